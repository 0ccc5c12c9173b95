#include "pdeface/ply/binary.hpp"

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
  auto bits = std::bit_cast<std::uint32_t>(value);
  if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
  std::memcpy(out, &bits, 4);
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

std::size_t binary_size(const BinaryLayout& layout) {
  return binary_header(layout).size() + layout.vertices * vertex_record(layout.normals) +
         layout.triangles * kFaceRecord;
}

void append_binary_vertices(std::string& out, std::span<const Vec3> positions,
                            std::span<const Vec3f> normals) {
  const bool with_normals = !normals.empty();
  if (with_normals && normals.size() != positions.size())
    throw std::invalid_argument("ply: as many normals as positions, or none");
  const std::size_t record = vertex_record(with_normals), start = out.size();
  out.resize(start + positions.size() * record);
  char* at = out.data() + start;
  for (std::size_t i = 0; i < positions.size(); ++i, at += record) {
    for (std::size_t c = 0; c < 3; ++c)
      put32(at + 4 * c, static_cast<float>(positions[i][static_cast<Eigen::Index>(c)]));
    if (with_normals)
      for (std::size_t c = 0; c < 3; ++c)
        put32(at + 12 + 4 * c, normals[i][static_cast<Eigen::Index>(c)]);
  }
}

void append_binary_triangles(std::string& out, std::span<const Triangle> triangles) {
  const std::size_t start = out.size();
  out.resize(start + triangles.size() * kFaceRecord);
  char* at = out.data() + start;
  for (const Triangle& t : triangles) {
    *at = 3;
    for (std::size_t c = 0; c < 3; ++c)
      put32(at + 1 + 4 * c, static_cast<std::int32_t>(t[c]));
    at += kFaceRecord;
  }
}

} // namespace pdeface::ply
