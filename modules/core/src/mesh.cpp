#include "pdeface/core/mesh.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>

namespace pdeface {

std::string_view to_string(Units units) noexcept {
  switch (units) {
  case Units::Unknown: return "unknown";
  case Units::Millimetres: return "mm";
  case Units::Centimetres: return "cm";
  case Units::Metres: return "m";
  case Units::Inches: return "in";
  }
  return "unknown";
}

std::optional<Units> units_from_string(std::string_view word) noexcept {
  static constexpr std::pair<std::string_view, Units> kNames[] = {{"mm", Units::Millimetres},
                                                                  {"millimetres", Units::Millimetres},
                                                                  {"millimeters", Units::Millimetres},
                                                                  {"cm", Units::Centimetres},
                                                                  {"centimetres", Units::Centimetres},
                                                                  {"centimeters", Units::Centimetres},
                                                                  {"m", Units::Metres},
                                                                  {"metres", Units::Metres},
                                                                  {"meters", Units::Metres},
                                                                  {"in", Units::Inches},
                                                                  {"inch", Units::Inches},
                                                                  {"inches", Units::Inches}};
  for (const auto& [name, units] : kNames)
    if (word == name) return units;
  return std::nullopt;
}

double millimetres_per(Units units) noexcept {
  switch (units) {
  case Units::Unknown: return 0.0;
  case Units::Millimetres: return 1.0;
  case Units::Centimetres: return 10.0;
  case Units::Metres: return 1000.0;
  case Units::Inches: return 25.4;
  }
  return 0.0;
}

PointCloud to_point_cloud(const Mesh& mesh) { return {mesh.positions, mesh.units, mesh.name}; }

Mesh to_mesh(PointCloud cloud) {
  Mesh mesh;
  mesh.positions = std::move(cloud.positions);
  mesh.units = cloud.units;
  mesh.name = std::move(cloud.name);
  return mesh;
}

Box bounding_box(std::span<const Vec3> points) {
  Box box;
  for (const Vec3& p : points)
    box.extend(p);
  return box;
}

std::vector<Vec3f> vertex_normals(const Mesh& mesh) {
  std::vector<Vec3> sum(mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a); // |n| = 2 * area
    for (std::uint32_t v : t)
      sum[v] += n;
  }
  std::vector<Vec3f> normals(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = sum[i].norm();
    normals[i] = len > 0.0 ? Vec3f((sum[i] / len).cast<float>()) : Vec3f::Zero();
  }
  return normals;
}

Result<void> validate(const Mesh& mesh, std::string_view source) {
  const std::size_t n = mesh.positions.size();
  auto fail = [&](ErrorCode code, std::string message) {
    return make_error(code, std::move(message), std::string(source));
  };
  auto check_size = [n](std::size_t size) { return size == 0 || size == n; };
  if (!check_size(mesh.normals.size()))
    return fail(ErrorCode::Malformed, fmt::format("{} normals for {} vertices", mesh.normals.size(), n));
  if (!check_size(mesh.colors.size()))
    return fail(ErrorCode::Malformed, fmt::format("{} colours for {} vertices", mesh.colors.size(), n));
  if (!check_size(mesh.texcoords.size()))
    return fail(ErrorCode::Malformed,
                fmt::format("{} texture coordinates for {} vertices", mesh.texcoords.size(), n));
  for (std::size_t i = 0; i < n; ++i)
    if (!mesh.positions[i].allFinite())
      return fail(ErrorCode::NonFinite, fmt::format("vertex {} has a non-finite coordinate", i));
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (std::uint32_t v : mesh.triangles[f])
      if (v >= n)
        return fail(ErrorCode::IndexOutOfRange,
                    fmt::format("triangle {} refers to vertex {} of {}", f, v, n));
  return {};
}

Result<void> check_writable(const Mesh& mesh) {
  if (Result<void> valid = validate(mesh, mesh.name); !valid) return valid;
  if (mesh.positions.empty())
    return make_error(ErrorCode::Empty, "nothing to write: the mesh has no vertices", mesh.name);
  return {};
}

} // namespace pdeface
