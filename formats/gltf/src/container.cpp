#include "container.hpp"

#include "pdeface/core/bytes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace pdeface::gltf {
namespace {

constexpr std::string_view kMagic = "glTF";
constexpr std::uint32_t kJsonChunk = 0x4E4F534A; // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;  // "BIN\0"
constexpr std::uint64_t kHeaderSize = 12;
constexpr std::uint64_t kChunkHeaderSize = 8;

// \pre offset + 4 <= bytes.size() (checked by the callers against the header's and chunks' sizes)
std::uint32_t u32_at(std::string_view bytes, std::uint64_t offset) {
  return load_le<std::uint32_t>(bytes, static_cast<std::size_t>(offset));
}

// A chunk type as text for messages ("JSON", "BIN", or hex when not printable).
std::string chunk_name(std::uint32_t type) {
  std::string name;
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<unsigned char>(type >> (8 * i));
    if (c == 0) break;
    if (!std::isprint(c)) return fmt::format("0x{:08x}", type);
    name += static_cast<char>(c);
  }
  return name;
}

Result<Container> split_glb(std::string_view bytes, std::string_view source, Notes* notes) {
  auto error = [&](ErrorCode code, std::string message, std::uint64_t at) {
    return make_error(code, std::move(message), std::string(source), Location::at_byte(at));
  };
  if (bytes.size() < kHeaderSize)
    return error(ErrorCode::Truncated,
                 fmt::format("the GLB header is 12 bytes, the data ends after {}", bytes.size()),
                 bytes.size());
  if (const std::uint32_t version = u32_at(bytes, 4); version != 2)
    return error(ErrorCode::UnsupportedVersion,
                 fmt::format("GLB version {}: we read glTF 2.0 (version 2)", version), 4);
  const std::uint64_t length = u32_at(bytes, 8);
  if (length > bytes.size())
    return error(ErrorCode::Truncated,
                 fmt::format("the GLB header says {} bytes, the data ends after {}", length, bytes.size()),
                 bytes.size());
  if (length < kHeaderSize + kChunkHeaderSize)
    return error(
        ErrorCode::Malformed,
        fmt::format("the GLB header says {} bytes, less than a header and a chunk header (20)", length), 8);
  if (length < bytes.size() && notes)
    notes->push_back(
        fmt::format("{}: {} bytes after the end of the GLB ignored", source, bytes.size() - length));

  Container c;
  c.bytes = bytes.substr(0, length);
  c.glb = true;
  const std::uint64_t json_length = u32_at(bytes, 12);
  if (const std::uint32_t type = u32_at(bytes, 16); type != kJsonChunk)
    return error(ErrorCode::Malformed,
                 fmt::format("the first chunk is '{}', expected 'JSON'", chunk_name(type)), 16);
  if (json_length == 0) return error(ErrorCode::Malformed, "the JSON chunk is empty", 12);
  c.json_offset = kHeaderSize + kChunkHeaderSize;
  if (c.json_offset + json_length > length)
    return error(ErrorCode::Malformed,
                 fmt::format("the JSON chunk claims {} bytes, but the GLB ends {} bytes after its start",
                             json_length, length - c.json_offset),
                 12);
  c.json = bytes.substr(c.json_offset, json_length);

  const std::uint64_t next = c.json_offset + json_length;
  if (next == length) return c; // no BIN chunk
  if (length - next < kChunkHeaderSize)
    return error(
        ErrorCode::Malformed,
        fmt::format("{} stray bytes after the JSON chunk, less than a chunk header (8)", length - next),
        next);
  if (const std::uint32_t type = u32_at(bytes, next + 4); type != kBinChunk)
    return error(ErrorCode::Malformed,
                 fmt::format("the chunk after JSON is '{}', expected 'BIN' (tinygltf reads no other)",
                             chunk_name(type)),
                 next + 4);
  const std::uint64_t bin_length = u32_at(bytes, next);
  c.bin_offset = next + kChunkHeaderSize;
  if (c.bin_offset + bin_length > length)
    return error(ErrorCode::Malformed,
                 fmt::format("the BIN chunk claims {} bytes, but the GLB ends {} bytes after its start",
                             bin_length, length - c.bin_offset),
                 next);
  if (bin_length == 0 || bin_length % 4 != 0)
    return error(ErrorCode::Malformed,
                 fmt::format("the BIN chunk length {} is not a positive multiple of 4", bin_length), next);
  c.bin = bytes.substr(c.bin_offset, bin_length);
  return c; // chunks after BIN are ignored, as the specification asks
}

} // namespace

Location Container::json_location(std::uint64_t offset) const {
  offset = std::min<std::uint64_t>(offset, json.size());
  if (glb) return Location::at_byte(json_offset + offset);
  const std::string_view before = json.substr(0, offset);
  const std::size_t line_start = before.rfind('\n');
  const auto line = static_cast<std::uint64_t>(std::ranges::count(before, '\n')) + 1;
  const std::uint64_t column = line_start == std::string_view::npos ? offset + 1 : offset - line_start;
  return Location::at_line(line, column);
}

Result<Container> split_container(std::string_view bytes, std::string_view source, Notes* notes) {
  if (bytes.empty())
    return make_error(ErrorCode::Empty, "no data: a .glb starts with \"glTF\", a .gltf with '{'",
                      std::string(source), Location::at_byte(0));
  if (bytes.substr(0, std::min(bytes.size(), kMagic.size())) ==
      kMagic.substr(0, std::min(bytes.size(), kMagic.size())))
    return split_glb(bytes, source, notes);
  std::string_view text = bytes;
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3); // a UTF-8 byte order mark
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos || text[first] != '{')
    return make_error(ErrorCode::BadMagic,
                      "not glTF: a .glb starts with \"glTF\", a .gltf with a JSON object",
                      std::string(source), Location::at_byte(0));
  Container c;
  c.bytes = c.json = bytes;
  return c;
}

} // namespace pdeface::gltf
