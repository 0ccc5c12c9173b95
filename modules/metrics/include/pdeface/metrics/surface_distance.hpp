#pragma once
//! \file
//! Distances between surfaces, as mesh-compression users measure them (Metro, MeshLab's Hausdorff
//! filter): points sampled on one mesh, their distance to the other mesh's surface, both ways.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/point_index.hpp"
#include "pdeface/core/result.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace pdeface::metrics {

//! Exact nearest-point queries on a triangle mesh's surface. Built once: a bounding-volume hierarchy of
//! axis-aligned boxes over the triangles (median splits, 4 triangles per leaf), searched nearest box first
//! and pruned by box distance, so a query tests a few dozen triangles whatever the mesh's size or its
//! longest edge. Queries are const and thread-safe.
//!
//! A point cloud has no surface between its points, so a point-to-point distance would count the cloud's
//! own spacing as error (a surface 0.1 mm from a cloud 1.4 mm apart would measure ~0.7 mm). Its surface is
//! taken as each point's tangent plane (the normal of its 10 nearest neighbours' best plane): the distance
//! is the query's offset along the nearest point's normal (MPEG point-cloud coding's point-to-plane "D2"),
//! or the distance to the point itself where the query lies beyond the neighbourhood the plane was fitted
//! to. A point of the cloud is at 0.
class SurfaceDistance {
public:
  //! \pre `mesh` stays alive and unchanged while this object is used.
  //! \throw std::invalid_argument for a mesh without vertices.
  //! `threads`: how many build the hierarchy (0: every core); the same hierarchy whatever their number.
  explicit SurfaceDistance(const Mesh& mesh, unsigned threads = 1);

  struct Nearest {
    Vec3 point;           //!< the nearest point of the surface
    double distance;      //!< to it
    std::size_t triangle; //!< the triangle holding it (for a point cloud: the point's index)
  };
  [[nodiscard]] Nearest nearest(const Vec3& query) const;
  [[nodiscard]] double distance(const Vec3& query) const { return nearest(query).distance; }

private:
  //! A box of the hierarchy, in float rounded outwards (it holds its triangles' box; a distance to it
  //! is never more than to them), 32 bytes: half a double box's, for a scan of a million triangles 16 MB.
  struct Node {
    std::array<float, 3> lo{}, hi{};
    std::uint32_t index = 0; //!< leaf: first index into order_; inner: the right child (the left is next)
    std::uint32_t count = 0; //!< leaf: number of triangles; inner: 0
  };
  void fit_tangent_planes();
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::uint32_t at,
                      const std::vector<Eigen::Vector3f>& centroids, unsigned threads);

  const Mesh* mesh_;
  std::optional<PointIndex> points_; //!< for a point cloud
  std::vector<Vec3> normals_;        //!< a point cloud's: each point's tangent plane
  std::vector<double> reach_;        //!< a point cloud's: how far across its plane stands for the surface
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_; //!< triangle indices, grouped by leaf
};

//! The point of triangle (a, b, c) nearest to p (Ericson, Real-Time Collision Detection, 5.1.5).
[[nodiscard]] Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

//! Points spread over a mesh's surface: every triangle gets points in proportion to its area, placed
//! on a deterministic low-discrepancy pattern (the same mesh gives the same points), about one per
//! `spacing`² of area; triangles' vertices are included. A point cloud gives its own points. With
//! `within`, only those inside that box (bounds included), in the same order: a triangle whose box misses
//! it is not sampled at all (a bust measured on its face).
[[nodiscard]] std::vector<Vec3> sample_surface(const Mesh& mesh, double spacing,
                                               const std::optional<Box>& within = std::nullopt);

struct DistanceStats {
  double mean = 0.0;
  double rms = 0.0;
  double p95 = 0.0; //!< 95th percentile
  double max = 0.0; //!< the one-sided Hausdorff distance
  std::size_t samples = 0;
};

struct DistanceOptions {
  double spacing = 0.5;      //!< sample spacing on each surface, in the meshes' units
  std::optional<Box> region; //!< only samples inside this box count (the face region), on both sides
  //! Further, only samples of `a` (of `b`) for which this holds count: a region that is not a box, or
  //! parts of a surface that should not be judged (a reconstruction's filled holes, where the scan had
  //! nothing to compare with).
  std::function<bool(const Vec3&)> keep_a, keep_b;
};

//! Both directions and their union (the symmetric figures report the worse of the two maxima).
struct TwoSidedDistance {
  DistanceStats a_to_b;
  DistanceStats b_to_a;
  DistanceStats both;
  double diagonal = 0.0; //!< bounding-box diagonal of `a` inside the region, to state errors as a fraction
};

//! Errors: `InvalidArgument` when a mesh is empty or no sample falls in the region.
[[nodiscard]] Result<TwoSidedDistance> surface_distance(const Mesh& a, const Mesh& b,
                                                        const DistanceOptions& options = {});

//! Statistics of a list of distances (sorted copy for the percentile).
[[nodiscard]] DistanceStats statistics(std::vector<double> distances);

} // namespace pdeface::metrics
