#include "pdeface/core/openmesh.hpp"

namespace pdeface {

HalfedgeConversion to_halfedge_mesh(const Mesh& mesh) {
  HalfedgeConversion out;
  HalfedgeMesh& om = out.mesh;
  om.reserve(mesh.positions.size(), 3 * mesh.triangles.size() / 2, mesh.triangles.size());
  for (const Vec3& p : mesh.positions)
    om.add_vertex(HalfedgeMesh::Point(p.x(), p.y(), p.z()));
  for (const Triangle& t : mesh.triangles) {
    const auto face = om.add_face(om.vertex_handle(t[0]), om.vertex_handle(t[1]), om.vertex_handle(t[2]));
    if (!face.is_valid()) ++out.rejected_triangles;
  }
  return out;
}

Mesh from_halfedge_mesh(const HalfedgeMesh& om) {
  Mesh mesh;
  std::vector<std::uint32_t> index(om.n_vertices(), 0);
  mesh.positions.reserve(om.n_vertices());
  for (auto v : om.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(mesh.positions.size());
    const auto& p = om.point(v);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  mesh.triangles.reserve(om.n_faces());
  for (auto f : om.faces()) {
    Triangle t{};
    int i = 0;
    for (auto v : f.vertices())
      t[i++] = index[v.idx()];
    mesh.triangles.push_back(t);
  }
  return mesh;
}

} // namespace pdeface
