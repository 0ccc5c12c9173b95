#include "pdeface/core/topology.hpp"

#include "pdeface/core/openmesh.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <numeric>
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

  // Pieces joined by a vertex count as one, as in a scanner's view of "pieces" (and MANIFEST.md).
  const std::vector<std::uint32_t> label = component_labels(mesh);
  std::vector<char> has_triangle(mesh.vertex_count(), 0);
  for (const Triangle& t : mesh.triangles)
    has_triangle[label[t[0]]] = 1;
  out.components = static_cast<std::size_t>(std::ranges::count(has_triangle, 1));
  return out;
}

std::vector<std::uint32_t> component_labels(const Mesh& mesh) {
  // Union-find with path halving over the triangles' vertices.
  std::vector<std::uint32_t> parent(mesh.vertex_count());
  std::iota(parent.begin(), parent.end(), 0U);
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v)
      v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Triangle& t : mesh.triangles) {
    for (int i = 1; i < 3; ++i) {
      const std::uint32_t a = find(t[0]); // again each time: the first union may have moved t[0]'s root
      const std::uint32_t b = find(t[static_cast<std::size_t>(i)]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::uint32_t> label(mesh.vertex_count());
  std::vector<std::uint32_t> renumber(mesh.vertex_count(), UINT32_MAX);
  std::uint32_t next = 0;
  for (std::uint32_t v = 0; v < label.size(); ++v) {
    const std::uint32_t root = find(v);
    if (renumber[root] == UINT32_MAX) renumber[root] = next++;
    label[v] = renumber[root];
  }
  return label;
}

std::vector<std::uint32_t> kept_component_vertices(const Mesh& mesh, double min_fraction) {
  if (mesh.is_point_cloud()) return {};
  std::vector<std::uint32_t> label = component_labels(mesh);
  std::vector<std::size_t> size;
  for (std::uint32_t l : label) {
    if (l >= size.size()) size.resize(l + 1, 0);
    ++size[l];
  }
  const auto min_size = static_cast<std::size_t>(min_fraction * static_cast<double>(mesh.vertex_count()));
  if (std::ranges::all_of(size, [&](std::size_t n) { return n >= min_size; })) return {};
  std::uint32_t next = 0;
  for (std::uint32_t& l : label) // the labels become the new indices
    l = size[l] < min_size ? kDroppedVertex : next++;
  return label;
}

Mesh drop_small_components(const Mesh& mesh, double min_fraction) {
  const std::vector<std::uint32_t> index = kept_component_vertices(mesh, min_fraction);
  if (index.empty()) return mesh;
  Mesh out;
  out.units = mesh.units;
  out.name = mesh.name;
  out.material = mesh.material;
  // Per-corner texture coordinates keep their table; the corners of the triangles kept still index it.
  const bool per_vertex_uv = mesh.has_texcoords() && !mesh.has_corner_texcoords();
  if (mesh.has_corner_texcoords()) out.texcoords = mesh.texcoords;
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    if (index[v] == kDroppedVertex) continue;
    out.positions.push_back(mesh.positions[v]);
    if (mesh.has_normals()) out.normals.push_back(mesh.normals[v]);
    if (mesh.has_colors()) out.colors.push_back(mesh.colors[v]);
    if (per_vertex_uv) out.texcoords.push_back(mesh.texcoords[v]);
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (index[t[0]] == kDroppedVertex) continue;
    out.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    if (mesh.has_corner_texcoords()) out.texcoord_triangles.push_back(mesh.texcoord_triangles[f]);
  }
  return out;
}

} // namespace pdeface
