#include "pdeface/align/crop.hpp"

#include "pdeface/core/topology.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pdeface::align {

Result<Mesh> crop_face(const Mesh& canonical, const Landmarks& landmarks, const CropOptions& options) {
  for (Landmark l :
       {Landmark::FaceTop, Landmark::FaceBottom, Landmark::EyeOuterLeft, Landmark::EyeOuterRight})
    if (!landmarks.has(l))
      return make_error(ErrorCode::InvalidArgument, fmt::format("cropping needs the {} landmark", name(l)),
                        canonical.name);
  const double top = landmarks[Landmark::FaceTop]->y();
  const double bottom = landmarks[Landmark::FaceBottom]->y();
  const double half_width = std::max(std::abs(landmarks[Landmark::EyeOuterLeft]->x()),
                                     std::abs(landmarks[Landmark::EyeOuterRight]->x())) +
                            options.side_margin_mm;
  auto inside = [&](const Vec3& p) {
    return p.y() >= bottom && p.y() <= top && std::abs(p.x()) <= half_width && p.z() >= -options.depth_mm;
  };

  Mesh cut;
  cut.units = canonical.units;
  cut.name = canonical.name;
  cut.material = canonical.material;
  // Per-corner texture coordinates keep their table; the corners of the triangles kept still index it.
  const bool per_vertex_uv = canonical.has_texcoords() && !canonical.has_corner_texcoords();
  if (canonical.has_corner_texcoords()) cut.texcoords = canonical.texcoords;
  std::vector<std::uint32_t> index(canonical.vertex_count(), UINT32_MAX);
  auto keep = [&](std::uint32_t v) {
    if (index[v] != UINT32_MAX) return index[v];
    index[v] = static_cast<std::uint32_t>(cut.positions.size());
    cut.positions.push_back(canonical.positions[v]);
    if (canonical.has_normals()) cut.normals.push_back(canonical.normals[v]);
    if (canonical.has_colors()) cut.colors.push_back(canonical.colors[v]);
    if (per_vertex_uv) cut.texcoords.push_back(canonical.texcoords[v]);
    return index[v];
  };
  if (canonical.is_point_cloud()) {
    for (std::uint32_t v = 0; v < canonical.vertex_count(); ++v)
      if (inside(canonical.positions[v])) keep(v);
  } else {
    for (std::size_t f = 0; f < canonical.triangles.size(); ++f) {
      const Triangle& t = canonical.triangles[f];
      if (!inside(canonical.positions[t[0]]) || !inside(canonical.positions[t[1]]) ||
          !inside(canonical.positions[t[2]]))
        continue;
      cut.triangles.push_back({keep(t[0]), keep(t[1]), keep(t[2])});
      if (canonical.has_corner_texcoords()) cut.texcoord_triangles.push_back(canonical.texcoord_triangles[f]);
    }
  }
  if (cut.vertex_count() == 0)
    return make_error(ErrorCode::NoFace, "no face found: nothing of the scan lies inside the face region",
                      canonical.name);
  return drop_small_components(cut, options.min_fragment);
}

} // namespace pdeface::align
