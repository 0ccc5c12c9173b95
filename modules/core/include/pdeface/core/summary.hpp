#pragma once
//! \file
//! What `pdeface info` says about a mesh: counts, attributes, extent and topology.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/topology.hpp"

namespace pdeface {

struct MeshSummary {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  bool normals = false;
  bool colors = false;
  bool texcoords = false;
  Units units = Units::Unknown;
  Box box;
  Topology topology;
};

[[nodiscard]] MeshSummary summarize(const Mesh& mesh);

} // namespace pdeface
