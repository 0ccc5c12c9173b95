#pragma once
//! \file
//! Connected components and boundary loops of a mesh: what `pdeface info` reports.

#include "pdeface/core/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pdeface {

struct Topology {
  std::size_t components = 0;             //!< pieces of triangles (joined by an edge or a vertex)
  std::size_t boundary_loops = 0;         //!< closed chains of boundary edges (holes and outer borders)
  std::size_t unreferenced_vertices = 0;  //!< vertices on no triangle (all of them for a point cloud)
  std::size_t non_manifold_triangles = 0; //!< triangles the half-edge structure had to leave out
};

[[nodiscard]] Topology topology(const Mesh& mesh);

//! A label per vertex: vertices joined by triangles share a label, labels are 0..n-1 in order of first
//! appearance, and a vertex on no triangle has a label of its own. Works on non-manifold meshes.
[[nodiscard]] std::vector<std::uint32_t> component_labels(const Mesh& mesh);

//! Marks a vertex that `kept_component_vertices` drops.
inline constexpr std::uint32_t kDroppedVertex = UINT32_MAX;

//! Each vertex's index among the vertices of the pieces that hold at least `min_fraction` of the mesh's
//! vertices, or `kDroppedVertex`; empty when every vertex is kept (a point cloud's always are). What
//! `drop_small_components` keeps, for a caller that needs only some of the mesh's arrays.
[[nodiscard]] std::vector<std::uint32_t> kept_component_vertices(const Mesh& mesh, double min_fraction);

//! The mesh without the pieces that hold fewer than `min_fraction` of its vertices (loose fragments,
//! stray points); vertices re-indexed, attributes kept. A point cloud is returned unchanged.
[[nodiscard]] Mesh drop_small_components(const Mesh& mesh, double min_fraction);

} // namespace pdeface
