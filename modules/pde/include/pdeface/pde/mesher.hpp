#pragma once
//! \file
//! A solved surface as a triangle mesh with normals on a regular grid: the one path from a `Surface` to
//! vertices (`Surface::mesh`, `pdef::to_mesh` and `pipeline::reconstruct` all take it), fast enough that
//! writing the mesh out costs more than making it.

#include "pdeface/core/mesh.hpp"
#include "pdeface/pde/surface.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <vector>

namespace pdeface::pde {

namespace detail {
struct MesherKernels; // the products and normals for one vector width (mesher.cpp)
} // namespace detail

//! An affine map p ↦ linear · p + offset, applied to the surface's points as they are made (e.g. a face's
//! canonical frame back into its scan's: linear = Rᵀ/scale, offset = −Rᵀt/scale). It is folded into the
//! surface's coefficients, so it costs nothing per vertex.
struct AffineMap {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Vec3 offset = Vec3::Zero();
};

//! How a `GridMesher` makes its mesh.
struct MesherOptions {
  AffineMap map; //!< applied to the points (default: none, the surface's own frame)
  //! At most this many doubles per vector in the products and normals (2: SSE2, 4: AVX2, 8: AVX-512F);
  //! 0: the widest the processor has. The mesh is the same whatever it is (for tests and benchmarks).
  std::size_t max_lanes = 0;
};

//! A surface on the grid of u_count × v_count points spread evenly over [0, u_max()] × [0, π] (the grid of
//! `Surface::evaluate(u_count, v_count)`), as a mesh: point (i, k) is vertex k·u_count + i, mapped by the
//! options' `AffineMap`; its normal is the unit X_u × X_v of the grid's central differences of the mapped
//! points (one-sided at the borders; reversed when the map reverses orientation, so that normals are the
//! mapped surface's); two triangles per cell, as `triangulate` makes them.
//!
//! It holds what every row shares: the coefficients of every cosine column at every u, already mapped, and
//! the cosines of every v. A row is then one small dense product (columns × 3·u_count by columns × 1; rows
//! v and π − v share it), so rows can be made in any order and in pieces (a writer can stream a mesh larger
//! than it wants to hold), and a row is the same to the bit however it is asked for, on every machine: the
//! product runs with the widest vectors the processor has (chosen at run time), each point summed in the
//! same order without fused multiply-adds.
class GridMesher {
public:
  //! \throw std::invalid_argument for fewer than 2 points either way or a map that is not finite
  GridMesher(const Surface& surface, std::size_t u_count, std::size_t v_count,
             const MesherOptions& options = {});

  [[nodiscard]] std::size_t u_count() const { return u_count_; }
  [[nodiscard]] std::size_t v_count() const { return v_count_; }
  [[nodiscard]] std::size_t vertex_count() const { return u_count_ * v_count_; }
  [[nodiscard]] std::size_t triangle_count() const { return 2 * (u_count_ - 1) * (v_count_ - 1); }

  //! Grid rows [first, first + count) (row k: the u_count points at v_k): their positions into
  //! `positions` (count · u_count of them) and, unless `normals` is empty, their unit normals.
  //! \throw std::invalid_argument for rows outside the grid or spans of another size
  void rows(std::size_t first, std::size_t count, std::span<Vec3> positions, std::span<Vec3f> normals) const;

  //! A block of rows for `rows(blocks)`: as the arguments of `rows(first, count, positions, normals)`.
  struct RowBlock {
    std::size_t first = 0;
    std::size_t count = 0;
    std::span<Vec3> positions;
    std::span<Vec3f> normals;
  };
  //! Several blocks of rows at once (none asked for twice): rows v and π − v share one product, so a
  //! block and its mirror image (rows v_count − first − count … v_count − first − 1) cost about one block.
  //! \throw std::invalid_argument as `rows`, and for a row in two blocks
  void rows(std::span<const RowBlock> blocks) const;

  //! The triangles of cell rows [first, first + count) (cell row k lies between grid rows k and k + 1),
  //! 2 (u_count − 1) each, in `triangulate`'s order.
  //! \throw std::invalid_argument for cell rows outside the grid or a span of another size
  void triangles(std::size_t first, std::size_t count, std::span<Triangle> out) const;

  //! The whole mesh, in `units`.
  [[nodiscard]] Mesh mesh(Units units = Units::Unknown) const;

  //! The whole mesh with every vertex moved along its normal by `offsets[vertex] · scale` (a `.pdef`
  //! residual layer's offsets, `scale` turning them into the mesh's units), then given the moved grid's
  //! normals, made as `mesh`'s are (central differences, one-sided at the borders, the same orientation).
  //! \throw std::invalid_argument unless there is one offset per vertex
  [[nodiscard]] Mesh displaced_mesh(std::span<const double> offsets, double scale,
                                    Units units = Units::Unknown) const;

private:
  // The unit normals of grid rows [first, first + count) into `out` (3 floats a point), each row r's
  // points at row[r] (3·u_count doubles; the rows beside them included).
  void normals_of(std::span<double* const> row, std::size_t first, std::size_t count, float* out) const;

  const detail::MesherKernels* kernels_ = nullptr;
  std::size_t u_count_ = 0;
  std::size_t v_count_ = 0;
  std::size_t columns_ = 0;          // cosine columns
  std::size_t stride_ = 0;           // doubles per column of coefficients_: 3·u_count, padded
  std::vector<double> coefficients_; // column n: A_n(u_i), mapped, at 3i + c (x, y, z); 0 in the padding
  std::vector<double> cosines_;      // row h < (v_count + 1)/2: cos(n v_h) for every column n
  bool reversed_ = false;            // the map reverses orientation: normals flipped
  double normal_scale_ = 1;          // a power of two that brings the grid's cross products near 1
};

} // namespace pdeface::pde
