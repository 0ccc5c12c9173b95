#include "pdeface/core/summary.hpp"

namespace pdeface {

MeshSummary summarize(const Mesh& mesh) {
  return {mesh.vertex_count(), mesh.triangle_count(), mesh.has_normals(),
          mesh.has_colors(),   mesh.has_texcoords(),  mesh.units,
          bounding_box(mesh),  topology(mesh)};
}

} // namespace pdeface
