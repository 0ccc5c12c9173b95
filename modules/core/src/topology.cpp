#include "pdeface/core/topology.hpp"

#include "pdeface/core/openmesh.hpp"

#include <vector>

namespace pdeface {

Topology topology(const Mesh& mesh) {
  const HalfedgeConversion conv = to_halfedge_mesh(mesh);
  const HalfedgeMesh& om = conv.mesh;
  Topology out;
  out.non_manifold_triangles = conv.rejected_triangles;
  for (auto v : om.vertices())
    if (om.is_isolated(v)) ++out.unreferenced_vertices;

  std::vector<char> seen(om.n_halfedges(), 0);
  for (auto h : om.halfedges()) {
    if (!h.is_boundary() || seen[h.idx()]) continue;
    ++out.boundary_loops;
    for (auto g = h; !seen[g.idx()]; g = g.next())
      seen[g.idx()] = 1;
  }

  std::vector<char> reached(om.n_faces(), 0);
  std::vector<OpenMesh::SmartFaceHandle> stack;
  for (auto f : om.faces()) {
    if (reached[f.idx()]) continue;
    ++out.components;
    reached[f.idx()] = 1;
    stack.push_back(f);
    while (!stack.empty()) {
      const auto g = stack.back();
      stack.pop_back();
      for (auto n : g.faces())
        if (!reached[n.idx()]) {
          reached[n.idx()] = 1;
          stack.push_back(n);
        }
    }
  }
  return out;
}

} // namespace pdeface
