#include "pdeface/pdef/mesh.hpp"

#include "pdeface/pde/displacement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pdeface::pdef {
namespace {

// Points spread over `length` about `spacing` apart: at least 2; lengths that are not positive and finite
// (a hostile file's curves may run downwards or not at all) get 2, absurd ones more than any grid may have.
std::size_t points_over(double length, double spacing) {
  const double intervals = std::ceil(length / spacing);
  if (!(intervals >= 1)) return 2;
  if (!(intervals < static_cast<double>(kMaxGridVertices))) return kMaxGridVertices + 1;
  return std::max<std::size_t>(2, static_cast<std::size_t>(intervals) + 1);
}

} // namespace

Resolution grid_for(double width_mm, double height_mm, double spacing_mm) {
  return {points_over(width_mm, spacing_mm), points_over(height_mm, spacing_mm)};
}

Resolution grid_for(double width_mm, double height_mm, std::size_t v) {
  v = std::max<std::size_t>(v, 2);
  const double spacing = height_mm / static_cast<double>(v - 1);
  return {points_over(width_mm, spacing), v};
}

Resolution grid_for(double width_mm, double height_mm, std::optional<Resolution> asked) {
  Resolution grid = asked ? *asked : grid_for(width_mm, height_mm, kDefaultGridSpacing);
  if (grid.u == 0) grid = grid_for(width_mm, height_mm, grid.v);
  return {std::max<std::size_t>(grid.u, 2), std::max<std::size_t>(grid.v, 2)};
}

std::array<double, 2> face_size(const Face& face) {
  double bottom = 0, top = 0;
  for (std::size_t j = 0; j < face.curve_count(); ++j) {
    const std::array<double, 2> e = face.extent(j);
    bottom = j == 0 ? e[0] : std::min(bottom, e[0]);
    top = j == 0 ? e[1] : std::max(top, e[1]);
  }
  const double width = face.planes.empty() ? 0.0 : face.planes.back() - face.planes.front();
  return {width, top - bottom};
}

pde::AffineMap scan_map(const Frame& frame) {
  const Eigen::Matrix3d back = frame.rotation.transpose() / frame.scale;
  return {back, -(back * frame.translation)};
}

Result<pde::GridMesher> mesher(const pde::Surface& surface, Resolution grid, const pde::AffineMap& map,
                               std::string_view source) {
  grid = {std::max<std::size_t>(grid.u, 2), std::max<std::size_t>(grid.v, 2)};
  if (grid.u > kMaxGridVertices / grid.v || grid.v > kMaxGridVertices / 2)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("a {} x {} grid has more than {} vertices: ask for a coarser resolution",
                                  grid.u, grid.v, kMaxGridVertices),
                      std::string(source));
  if (!map.linear.allFinite() || !map.offset.allFinite()) // a file's frame: a tiny scale
    return make_error(ErrorCode::NonFinite,
                      "the frame maps the surface beyond the range of double: its scale is too small",
                      std::string(source));
  return pde::GridMesher(surface, grid.u, grid.v, {.map = map});
}

Result<SurfaceMesh> surface_mesh(const pde::Surface& surface, Resolution grid, const Frame& frame,
                                 std::string_view source) {
  Result<pde::GridMesher> canonical = mesher(surface, grid, {}, source);
  if (!canonical) return std::move(canonical).error();
  Result<pde::GridMesher> scan = mesher(surface, grid, scan_map(frame), source);
  return SurfaceMesh{canonical->mesh(surface.units()), scan->mesh(frame.scan_units)};
}

Result<pde::Surface> surface_of(const Face& face, std::string_view source) {
  return pde::Surface::build(face.curves, face.pde, source);
}

Result<pde::GridMesher> scan_mesher(const Face& face, const pde::Surface& surface,
                                    std::optional<Resolution> resolution, std::string_view source) {
  if (!resolution && has_offsets(face)) // the layer's own grid: its offsets exactly, nothing interpolated
    resolution = Resolution{face.residual->field.width, face.residual->field.height};
  const std::array<double, 2> size = face_size(face);
  return mesher(surface, grid_for(size[0], size[1], resolution), scan_map(face.frame), source);
}

Result<Mesh> to_mesh(const Face& face, std::optional<Resolution> resolution, std::string_view source) {
  Result<pde::Surface> surface = surface_of(face, source);
  if (!surface) return std::move(surface).error();
  Result<pde::GridMesher> scan = scan_mesher(face, *surface, resolution, source);
  if (!scan) return std::move(scan).error();
  Mesh mesh;
  if (has_offsets(face)) { // moved along the normals the mesher makes, then given the moved grid's
    const pde::Displacement& field = face.residual->field;
    std::vector<double> resampled;
    std::span<const double> offsets = field.values; // the layer's own grid: its values as they are
    if (field.width != scan->u_count() || field.height != scan->v_count()) {
      resampled = pde::resample(field, scan->u_count(), scan->v_count());
      offsets = resampled;
    }
    mesh = scan->displaced_mesh(offsets, 1.0 / face.frame.scale, face.frame.scan_units);
  } else {
    mesh = scan->mesh(face.frame.scan_units);
  }
  mesh.name = face.name;
  if (face.texture) with_texture(mesh, scan->u_count(), scan->v_count(), *face.texture);
  if (has_offsets(face) && !face.residual->trimmed.empty()) { // cells with no scan under them go
    const pde::Displacement& field = face.residual->field;
    const std::vector<std::uint8_t> cells = pde::resample_trim(
        face.residual->trimmed, field.width, field.height, scan->u_count(), scan->v_count());
    pde::trim_grid(mesh, scan->u_count(), scan->v_count(), cells);
    if (mesh.triangles.empty())
      return make_error(ErrorCode::Empty, "the residual layer's trim leaves no surface", std::string(source));
  }
  return mesh;
}

void with_texture(Mesh& mesh, std::size_t u_count, std::size_t v_count, const Image& texture) {
  if (mesh.vertex_count() != u_count * v_count || u_count < 2 || v_count < 2)
    throw std::invalid_argument(
        "pdef::with_texture: a mesh that is not a grid of u_count × v_count vertices");
  mesh.texcoord_triangles.clear();
  mesh.texcoords.resize(mesh.vertex_count());
  const double du = 1.0 / static_cast<double>(u_count - 1), dv = 1.0 / static_cast<double>(v_count - 1);
  for (std::size_t k = 0; k < v_count; ++k)
    for (std::size_t i = 0; i < u_count; ++i)
      mesh.texcoords[k * u_count + i] = Vec2f(static_cast<float>(static_cast<double>(i) * du),
                                              static_cast<float>(static_cast<double>(k) * dv));
  mesh.material = Material{"face", Vec4f::Ones(), texture};
}

bool has_offsets(const Face& face) { return face.residual && !face.residual->field.empty(); }

} // namespace pdeface::pdef
