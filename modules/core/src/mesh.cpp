#include "pdeface/core/mesh.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>
#include <unordered_map>

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
  if (mesh.has_corner_texcoords()) {
    if (mesh.texcoord_triangles.size() != mesh.triangles.size())
      return fail(ErrorCode::Malformed, fmt::format("{} texture coordinate triangles for {} triangles",
                                                    mesh.texcoord_triangles.size(), mesh.triangles.size()));
    const std::size_t table = mesh.texcoords.size();
    for (std::size_t f = 0; f < mesh.texcoord_triangles.size(); ++f)
      for (std::uint32_t t : mesh.texcoord_triangles[f])
        if (t >= table)
          return fail(ErrorCode::IndexOutOfRange,
                      fmt::format("triangle {} refers to texture coordinate {} of {}", f, t, table));
  } else if (!check_size(mesh.texcoords.size())) {
    return fail(ErrorCode::Malformed,
                fmt::format("{} texture coordinates for {} vertices", mesh.texcoords.size(), n));
  }
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

std::vector<Vec2f> corner_texcoords(const Mesh& mesh) {
  std::vector<Vec2f> out;
  if (!mesh.has_texcoords()) return out;
  out.reserve(3 * mesh.triangles.size());
  const std::vector<Triangle>& index = mesh.has_corner_texcoords() ? mesh.texcoord_triangles : mesh.triangles;
  for (const Triangle& t : index)
    for (std::uint32_t i : t)
      out.push_back(mesh.texcoords[i]);
  return out;
}

namespace {

// The bytes of `value` appended to `key` at `at`: the maps below compare values bit for bit.
template <class T>
requires std::is_arithmetic_v<T>
void append_bits(std::span<char> key, std::size_t& at, T value) {
  std::memcpy(key.data() + at, &value, sizeof(T));
  at += sizeof(T);
}
template <class Derived>
void append_bits(std::span<char> key, std::size_t& at, const Eigen::MatrixBase<Derived>& value) {
  for (Eigen::Index i = 0; i < value.size(); ++i)
    append_bits(key, at, value(i));
}

// A vertex's position, normal and colour (or a vertex index and a texture coordinate) bit for bit, the
// absent ones zero: a fixed-size key, so that filling a map allocates no string per vertex.
using Key = std::array<char, sizeof(Vec3) + sizeof(Vec3f) + sizeof(Vec4f)>;
struct KeyHash {
  std::size_t operator()(const Key& k) const noexcept {
    return std::hash<std::string_view>{}(std::string_view(k.data(), k.size()));
  }
};

} // namespace

Mesh with_vertex_texcoords(Mesh mesh, std::size_t* split) {
  if (split) *split = 0;
  if (!mesh.has_corner_texcoords()) return mesh;
  const std::size_t n = mesh.positions.size();
  std::vector<bool> seen(n, false);
  std::vector<Vec2f> uv(n, Vec2f::Zero());
  // (vertex, coordinate's bits) → the vertex's copy with that coordinate.
  std::unordered_map<Key, std::uint32_t, KeyHash> copies;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t& v = mesh.triangles[f][k];
      const Vec2f t = mesh.texcoords[mesh.texcoord_triangles[f][k]];
      if (!seen[v]) {
        seen[v] = true;
        uv[v] = t;
        continue;
      }
      if (uv[v] == t) continue;
      Key key{};
      std::size_t at = 0;
      append_bits(key, at, v);
      append_bits(key, at, t);
      const auto [it, added] = copies.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
      if (added) {
        mesh.positions.push_back(Vec3(mesh.positions[v]));
        if (mesh.has_normals()) mesh.normals.push_back(Vec3f(mesh.normals[v]));
        if (mesh.has_colors()) mesh.colors.push_back(Vec4f(mesh.colors[v]));
        uv.push_back(t);
      }
      v = it->second;
    }
  }
  mesh.texcoords = std::move(uv);
  mesh.texcoord_triangles.clear();
  if (split) *split = mesh.positions.size() - n;
  return mesh;
}

Mesh weld_texcoord_seams(Mesh mesh, std::size_t* merged) {
  if (merged) *merged = 0;
  if (!mesh.has_texcoords() || mesh.has_corner_texcoords() || mesh.is_point_cloud()) return mesh;
  const std::size_t n = mesh.positions.size();
  std::unordered_map<Key, std::uint32_t, KeyHash> first;
  first.reserve(n);
  std::vector<std::uint32_t> index(n);
  std::uint32_t kept = 0;
  for (std::size_t v = 0; v < n; ++v) {
    Key key{};
    std::size_t at = 0;
    append_bits(key, at, mesh.positions[v]);
    if (mesh.has_normals()) append_bits(key, at, mesh.normals[v]);
    if (mesh.has_colors()) append_bits(key, at, mesh.colors[v]);
    const auto [it, added] = first.try_emplace(key, kept);
    index[v] = it->second;
    if (added) ++kept;
  }
  if (kept == n) return mesh;
  // The first vertex of each kind moves down to its new index (never above its old one); the texture
  // coordinates stay as they were, indexed per corner by the old triangles.
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (index[v] != next) continue; // a repeat: its kind's first came before it
    mesh.positions[next] = mesh.positions[v];
    if (mesh.has_normals()) mesh.normals[next] = mesh.normals[v];
    if (mesh.has_colors()) mesh.colors[next] = mesh.colors[v];
    ++next;
  }
  mesh.positions.resize(kept);
  if (mesh.has_normals()) mesh.normals.resize(kept);
  if (mesh.has_colors()) mesh.colors.resize(kept);
  mesh.texcoord_triangles = mesh.triangles;
  for (Triangle& t : mesh.triangles)
    t = {index[t[0]], index[t[1]], index[t[2]]};
  if (merged) *merged = n - kept;
  return mesh;
}

} // namespace pdeface
