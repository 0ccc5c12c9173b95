#include "bitstream.hpp"

#include "pdeface/core/bytes.hpp"
#include "pdeface/draco/draco.hpp"

#include <fmt/format.h>

#include <cstring>

namespace pdeface::drc::bitstream {
namespace {

constexpr std::string_view kMagic = "DRACO";
constexpr std::uint32_t kMetadataFlag = 0x8000;
constexpr int kMaxMetadataDepth = 32; // Draco writes one level; its decoder recurses without a limit

// Reads the fields of untrusted bytes; a read that would pass the end returns a `Truncated` error
// (located where the data ends) naming what was being read.
class Reader {
public:
  Reader(std::string_view bytes, const Origin& origin) : bytes_(bytes), origin_(origin) {}

  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }
  [[nodiscard]] std::size_t size() const { return bytes_.size(); }
  [[nodiscard]] const Origin& origin() const { return origin_; }

  std::optional<Error> u8(std::uint32_t& value, std::string_view what) {
    return little_endian(value, 1, what);
  }
  std::optional<Error> u16(std::uint32_t& value, std::string_view what) {
    return little_endian(value, 2, what);
  }
  std::optional<Error> u32(std::uint32_t& value, std::string_view what) {
    return little_endian(value, 4, what);
  }

  // Draco's varint: 7 bits per byte, least significant first, at most 5 bytes for 32 bits (libdraco
  // keeps the low 32 bits of a 5-byte value, and so do we).
  std::optional<Error> varint(std::uint32_t& value, std::string_view what) {
    const std::size_t start = pos_;
    std::uint64_t v = 0;
    for (int i = 0; i < 5; ++i) {
      if (remaining() == 0) return truncated(what);
      const auto b = static_cast<std::uint8_t>(bytes_[pos_++]);
      v |= std::uint64_t{b & 0x7fu} << (7 * i);
      if ((b & 0x80u) == 0) {
        value = static_cast<std::uint32_t>(v);
        return std::nullopt;
      }
    }
    return origin_.error(ErrorCode::Malformed, fmt::format("{} is a varint longer than 5 bytes", what),
                         start);
  }

  std::optional<Error> skip(std::size_t n, std::string_view what) {
    if (remaining() < n) return truncated(what);
    pos_ += n;
    return std::nullopt;
  }

  [[nodiscard]] Error truncated(std::string_view what) const {
    return origin_.error(ErrorCode::Truncated,
                         fmt::format("the Draco data ends ({} bytes) inside {}", bytes_.size(), what),
                         bytes_.size());
  }

private:
  std::optional<Error> little_endian(std::uint32_t& value, int n, std::string_view what) {
    if (remaining() < static_cast<std::size_t>(n)) return truncated(what);
    value = n == 1   ? load_le<std::uint8_t>(bytes_, pos_)
            : n == 2 ? load_le<std::uint16_t>(bytes_, pos_)
                     : load_le<std::uint32_t>(bytes_, pos_);
    pos_ += static_cast<std::size_t>(n);
    return std::nullopt;
  }

  std::string_view bytes_;
  const Origin& origin_;
  std::size_t pos_ = 0;
};

// An element count of the geometry: libdraco allocates for it before reading a single element.
std::optional<Error> check_elements(const Reader& r, std::uint64_t count, std::string_view what,
                                    std::size_t at) {
  if (count <= kMaxElementsPerByte * r.size()) return std::nullopt;
  return r.origin().error(ErrorCode::CountTooLarge,
                          fmt::format("the data claims {} {}, more than {} bytes of Draco data can hold (at "
                                      "most {} per byte)",
                                      count, what, r.size(), kMaxElementsPerByte),
                          at);
}

std::optional<Error> name(Reader& r) {
  std::uint32_t length = 0;
  if (auto e = r.u8(length, "a metadata name")) return e;
  return r.skip(length, "a metadata name");
}

// One metadata node: entries (name, size, value) then named children.
std::optional<Error> metadata(Reader& r, int depth) {
  if (depth > kMaxMetadataDepth)
    return r.origin().error(ErrorCode::Malformed,
                            fmt::format("metadata nested deeper than {} levels", kMaxMetadataDepth),
                            r.offset());
  // Every loop below reads at least a byte per turn, so a hostile count ends at the end of the data.
  std::uint32_t entries = 0;
  if (auto e = r.varint(entries, "a metadata entry count")) return e;
  for (std::uint32_t i = 0; i < entries; ++i) {
    if (auto e = name(r)) return e;
    std::uint32_t size = 0;
    const std::size_t at = r.offset();
    if (auto e = r.varint(size, "a metadata value size")) return e;
    if (size == 0) return r.origin().error(ErrorCode::Malformed, "a metadata value of 0 bytes", at);
    if (auto e = r.skip(size, "a metadata value")) return e;
  }
  std::uint32_t children = 0;
  if (auto e = r.varint(children, "a metadata child count")) return e;
  for (std::uint32_t i = 0; i < children; ++i) {
    if (auto e = name(r)) return e;
    if (auto e = metadata(r, depth + 1)) return e;
  }
  return std::nullopt;
}

// The geometry's metadata: per-attribute nodes (each after its attribute's unique id), then its own.
std::optional<Error> geometry_metadata(Reader& r) {
  std::uint32_t attributes = 0;
  if (auto e = r.varint(attributes, "the attribute metadata count")) return e;
  for (std::uint32_t i = 0; i < attributes; ++i) {
    std::uint32_t unique_id = 0;
    if (auto e = r.varint(unique_id, "an attribute metadata id")) return e;
    if (auto e = metadata(r, 1)) return e;
  }
  return metadata(r, 1);
}

// The counts that open the geometry data (bitstream 2.2/2.3 layouts of libdraco's decoders).
std::optional<Error> counts(Reader& r, const Header& header) {
  std::uint32_t value = 0;
  std::size_t at = r.offset();
  if (!header.mesh) { // sequential and k-d tree: an int32 point count
    if (auto e = r.u32(value, "the point count")) return e;
    return check_elements(r, value, "points", at);
  }
  if (header.method == 0) { // sequential: face count, point count
    if (auto e = r.varint(value, "the face count")) return e;
    if (auto e = check_elements(r, value, "faces", at)) return e;
    at = r.offset();
    if (auto e = r.varint(value, "the point count")) return e;
    return check_elements(r, value, "points", at);
  }
  // Edgebreaker: traversal type, vertices, faces, attribute data count, symbols, split symbols.
  if (auto e = r.u8(value, "the edgebreaker traversal type")) return e;
  std::uint32_t vertices = 0;
  at = r.offset();
  if (auto e = r.varint(vertices, "the vertex count")) return e;
  if (auto e = check_elements(r, vertices, "vertices", at)) return e;
  at = r.offset();
  if (auto e = r.varint(value, "the face count")) return e;
  if (auto e = check_elements(r, value, "faces", at)) return e;
  if (auto e = r.u8(value, "the attribute data count")) return e;
  if (auto e = r.varint(value, "the symbol count")) return e;
  at = r.offset();
  if (auto e = r.varint(value, "the split symbol count")) return e;
  // libdraco allocates a vertex for each split symbol too.
  return check_elements(r, std::uint64_t{vertices} + value, "vertices and split symbols", at);
}

} // namespace

Result<Header> check(std::string_view bytes, const Origin& origin) {
  if (bytes.empty()) return origin.error(ErrorCode::Empty, "no data: Draco data starts with \"DRACO\"", 0);
  const std::size_t n = std::min(bytes.size(), kMagic.size());
  if (bytes.substr(0, n) != kMagic.substr(0, n))
    return origin.error(ErrorCode::BadMagic, "not Draco data: it does not start with \"DRACO\"", 0);

  Reader r(bytes, origin);
  std::uint32_t major = 0, minor = 0, type = 0, method = 0, flags = 0;
  if (auto e = r.skip(kMagic.size(), "the 11-byte header")) return std::move(*e);
  if (auto e = r.u8(major, "the 11-byte header")) return std::move(*e);
  if (auto e = r.u8(minor, "the 11-byte header")) return std::move(*e);
  if (auto e = r.u8(type, "the 11-byte header")) return std::move(*e);
  if (auto e = r.u8(method, "the 11-byte header")) return std::move(*e);
  if (auto e = r.u16(flags, "the 11-byte header")) return std::move(*e);

  if (type > 1)
    return origin.error(ErrorCode::Malformed,
                        fmt::format("unknown geometry type {} (0 = point cloud, 1 = triangle mesh)", type),
                        7);
  const Header header{.mesh = type == 1, .method = static_cast<int>(method)};
  const std::uint32_t supported_minor = header.mesh ? 2 : 3;
  if (major != 2 || minor != supported_minor)
    return origin.error(ErrorCode::UnsupportedVersion,
                        fmt::format("Draco bitstream {}.{}: we read {} written by Draco 1.4 or later "
                                    "(bitstream 2.2 for meshes, 2.3 for point clouds)",
                                    major, minor, header.mesh ? "meshes" : "point clouds"),
                        5);
  if (method > 1)
    return origin.error(ErrorCode::Malformed,
                        fmt::format("unknown encoding method {} (0 = sequential, 1 = {})", method,
                                    header.mesh ? "edgebreaker" : "k-d tree"),
                        8);
  if (flags & kMetadataFlag)
    if (auto e = geometry_metadata(r)) return std::move(*e);
  if (auto e = counts(r, header)) return std::move(*e);
  return header;
}

} // namespace pdeface::drc::bitstream
