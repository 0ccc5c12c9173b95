#pragma once
//! \file
//! Where a line meets a triangle mesh: every crossing of a segment with the mesh's triangles, through a
//! bounding-volume hierarchy, so that a residual layer's node finds the scan along its normal exactly,
//! also in folds and grooves where stepping towards the nearest point does not converge.

#include "pdeface/core/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace pdeface::residual {

//! A crossing of the line x + t·d with a triangle.
struct RayHit {
  double t = 0.0;
  std::size_t triangle = 0;
};

//! A triangle mesh's triangles in a hierarchy of axis-aligned boxes (median splits, 4 a leaf). Queries are
//! const and thread-safe. A class because it caches the hierarchy.
class RayCaster {
public:
  //! \pre `mesh` stays alive and unchanged while this object is used (a point cloud: no triangles).
  explicit RayCaster(const Mesh& mesh);

  //! The crossing of x + t·d (d need not be unit) with |t| ≤ `reach` nearest to t = 0 (the smaller t of
  //! two as near); nullopt when the segment meets no triangle.
  [[nodiscard]] std::optional<RayHit> nearest(const Vec3& x, const Vec3& d, double reach) const;
  //! Every crossing with |t| ≤ `reach`, by t ascending.
  [[nodiscard]] std::vector<RayHit> all(const Vec3& x, const Vec3& d, double reach) const;

private:
  struct Node {
    Box box;
    std::uint32_t first = 0; //!< leaf: first index into order_; inner: the left child
    std::uint32_t count = 0; //!< leaf: its triangles; inner: 0
    std::uint32_t right = 0; //!< inner: the right child
  };
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::vector<Vec3>& centroids);
  template <class Visit> void visit(const Vec3& x, const Vec3& d, double reach, Visit&& on_hit) const;

  const Mesh* mesh_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
};

} // namespace pdeface::residual
