#pragma once
//! \file
//! A scalar offset along a surface's normal over its whole (u, v) domain: the residual layer of a `.pdef`
//! file (docs/pdef-format.md, "The residual layer") is one, sampled on a regular grid. The displaced
//! surface is X(u, v) + d(u, v) · n(u, v), n the unit normal X_u × X_v / |X_u × X_v| of the PDE surface
//! and d the grid's bilinear interpolant.

#include "pdeface/core/mesh.hpp"
#include "pdeface/pde/surface.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pdeface::pde {

//! Offsets (mm, or the surface's units) on a width × height grid spread evenly over [0, u_max] × [0, π]:
//! node (i, k) at u = i · u_max / (width − 1), v = k · π / (height − 1), its value at `values[k·width + i]`.
struct Displacement {
  std::size_t width = 0;
  std::size_t height = 0;
  std::vector<double> values;

  [[nodiscard]] bool empty() const { return values.empty(); }
  //! The bilinear interpolant at s = u / u_max, t = v / π (each clamped to [0, 1]).
  [[nodiscard]] double at(double s, double t) const;
};

//! The surface's points and unit normals (X_u × X_v, normalised; (0, 0, 0) where the tangents are
//! parallel) at the nodes of a width × height grid over its domain, node (i, k) at k·width + i.
struct NormalGrid {
  std::size_t width = 0;
  std::size_t height = 0;
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
};
//! \throw std::invalid_argument for fewer than 2 nodes either way
[[nodiscard]] NormalGrid normal_grid(const Surface& surface, std::size_t width, std::size_t height);
//! The same at the nodes us × vs (node (i, k) at k·us.size() + i). \throw std::invalid_argument when either
//! is empty
[[nodiscard]] NormalGrid normal_grid(const Surface& surface, std::span<const double> us,
                                     std::span<const double> vs);

//! The offsets of `field` at the nodes of a u_count × v_count grid over the same domain (the grid's
//! own values where the grids are the same, the bilinear interpolant elsewhere), node (i, k) at
//! k·u_count + i. \throw std::invalid_argument for an empty field or fewer than 2 nodes either way
[[nodiscard]] std::vector<double> resample(const Displacement& field, std::size_t u_count,
                                           std::size_t v_count);

//! Moves every vertex of a grid mesh (u_count × v_count vertices, vertex (i, k) at k·u_count + i, with
//! unit normals, as `GridMesher` makes it) by `offsets[vertex] · scale` along its normal, then gives it
//! the normal of the moved grid (central differences, one-sided at the borders, oriented as before).
//! `scale` turns the offsets into the mesh's units (1 / the frame's scale for a mesh in a scan's frame).
//! \throw std::invalid_argument for sizes that do not match
void displace_grid(std::span<Vec3> positions, std::span<Vec3f> normals, std::size_t u_count,
                   std::size_t v_count, std::span<const double> offsets, double scale);

//! Which cells of a u_count × v_count grid (cell (i, k) between nodes (i, k) and (i + 1, k + 1), at
//! k·(u_count − 1) + i) lie in a trimmed cell of `trimmed`, the cells of a width × height grid over the same
//! domain (1 trimmed): each cell takes the value of the cell holding its centre (a grid the same as
//! `trimmed`'s: its own values). \throw std::invalid_argument for sizes that do not match or fewer than 2
//! nodes either way
[[nodiscard]] std::vector<std::uint8_t> resample_trim(std::span<const std::uint8_t> trimmed,
                                                      std::size_t width, std::size_t height,
                                                      std::size_t u_count, std::size_t v_count);

//! Drops from a grid mesh (u_count × v_count vertices, two triangles a cell in rows, as `GridMesher` makes
//! it) the triangles of the cells `trimmed` marks (1, one per cell, at k·(u_count − 1) + i), then the
//! vertices no triangle uses any more (their attributes with them; the others keep their order). Returns
//! for each vertex kept its index in the grid. \throw std::invalid_argument for sizes that do not match
std::vector<std::uint32_t> trim_grid(Mesh& mesh, std::size_t u_count, std::size_t v_count,
                                     std::span<const std::uint8_t> trimmed);

} // namespace pdeface::pde
