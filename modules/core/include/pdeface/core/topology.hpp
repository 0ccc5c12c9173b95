#pragma once
//! \file
//! Connected components and boundary loops of a mesh: what `pdeface info` reports.

#include "pdeface/core/mesh.hpp"

#include <cstddef>

namespace pdeface {

struct Topology {
  std::size_t components = 0;             //!< edge-connected pieces of triangles
  std::size_t boundary_loops = 0;         //!< closed chains of boundary edges (holes and outer borders)
  std::size_t unreferenced_vertices = 0;  //!< vertices on no triangle (all of them for a point cloud)
  std::size_t non_manifold_triangles = 0; //!< triangles the half-edge structure had to leave out
};

[[nodiscard]] Topology topology(const Mesh& mesh);

} // namespace pdeface
