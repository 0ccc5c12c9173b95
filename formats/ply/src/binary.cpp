#include "pdeface/ply/binary.hpp"

#include "pdeface/core/bytes.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace pdeface::ply {
namespace {

// A little-endian 32-bit value at `out`.
template <class T> void put32(char* out, T value) {
  static_assert(sizeof(T) == 4);
  store_le(out, std::bit_cast<std::uint32_t>(value));
}

constexpr std::size_t kFaceRecord = 1 + 3 * 4;

std::size_t vertex_record(bool normals) { return std::size_t{normals ? 6U : 3U} * 4; }

} // namespace

std::string binary_header(const BinaryLayout& layout) {
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  if (layout.units != Units::Unknown) header += fmt::format("comment units {}\n", to_string(layout.units));
  header += fmt::format("element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
                        layout.vertices);
  if (layout.normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  header +=
      fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n", layout.triangles);
  return header;
}

std::size_t binary_vertex_bytes(std::size_t count, bool normals) { return count * vertex_record(normals); }

std::size_t binary_triangle_bytes(std::size_t count) { return count * kFaceRecord; }

std::size_t binary_size(const BinaryLayout& layout) {
  return binary_header(layout).size() + binary_vertex_bytes(layout.vertices, layout.normals) +
         binary_triangle_bytes(layout.triangles);
}

void put_binary_vertices(std::span<char> out, std::span<const Vec3> positions,
                         std::span<const Vec3f> normals) {
  const bool with_normals = !normals.empty();
  if (with_normals && normals.size() != positions.size())
    throw std::invalid_argument("ply: as many normals as positions, or none");
  if (out.size() < binary_vertex_bytes(positions.size(), with_normals))
    throw std::invalid_argument("ply: no room for the vertex records");
  const std::size_t record = vertex_record(with_normals);
  char* at = out.data();
  for (std::size_t i = 0; i < positions.size(); ++i, at += record) {
    for (std::size_t c = 0; c < 3; ++c)
      put32(at + 4 * c, static_cast<float>(positions[i][static_cast<Eigen::Index>(c)]));
    if (with_normals)
      for (std::size_t c = 0; c < 3; ++c)
        put32(at + 12 + 4 * c, normals[i][static_cast<Eigen::Index>(c)]);
  }
}

void put_binary_triangles(std::span<char> out, std::span<const Triangle> triangles) {
  if (out.size() < binary_triangle_bytes(triangles.size()))
    throw std::invalid_argument("ply: no room for the face records");
  char* at = out.data();
  for (const Triangle& t : triangles) {
    *at = 3;
    for (std::size_t c = 0; c < 3; ++c)
      put32(at + 1 + 4 * c, static_cast<std::int32_t>(t[c]));
    at += kFaceRecord;
  }
}

} // namespace pdeface::ply
