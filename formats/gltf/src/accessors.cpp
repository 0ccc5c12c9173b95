#include "accessors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace pdeface::gltf {

static_assert(std::endian::native == std::endian::little, "glTF data is little-endian; we copy it as it is");

// Where an accessor's elements are, checked to lie inside their buffer.
struct Accessors::Span {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0, component_size = 0;
  int component_type = 0, components = 0;
  bool normalized = false;
  std::optional<std::uint64_t> file_offset; // of the first element, when in the GLB's BIN chunk

  [[nodiscard]] const unsigned char* at(std::size_t i, int c) const {
    return data + i * stride + c * component_size;
  }
  [[nodiscard]] std::optional<std::uint64_t> byte(std::size_t i, int c) const {
    return file_offset ? std::optional(*file_offset + i * stride + c * component_size) : std::nullopt;
  }
};

namespace {

std::size_t component_size(int type) {
  switch (type) {
  case TINYGLTF_COMPONENT_TYPE_BYTE:
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
  case TINYGLTF_COMPONENT_TYPE_SHORT:
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
  case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
  default: return 0; // int and double are not glTF 2.0 accessor types
  }
}

template <class T> T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// An integer component; normalised, the integer range maps to [0, 1] (unsigned) or [-1, 1] (signed, the
// lowest value clamped), as glTF defines it.
template <class Int> float integer_component(const unsigned char* p, bool normalized) {
  const auto v = static_cast<float>(load<Int>(p));
  return normalized ? std::max(v / static_cast<float>(std::numeric_limits<Int>::max()), -1.0f) : v;
}

// A component as glTF defines it.
float to_float(const unsigned char* p, int type, bool normalized) {
  switch (type) {
  case TINYGLTF_COMPONENT_TYPE_BYTE: return integer_component<std::int8_t>(p, normalized);
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return integer_component<std::uint8_t>(p, normalized);
  case TINYGLTF_COMPONENT_TYPE_SHORT: return integer_component<std::int16_t>(p, normalized);
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return integer_component<std::uint16_t>(p, normalized);
  default: return load<float>(p);
  }
}

std::uint32_t to_index(const unsigned char* p, int type) {
  switch (type) {
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p);
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
  default: return load<std::uint32_t>(p);
  }
}

} // namespace

Error Accessors::error(ErrorCode code, std::string message, std::optional<std::uint64_t> byte) const {
  return make_error(code, std::move(message), std::string(source_),
                    byte ? Location::at_byte(*byte) : Location{});
}

Result<Accessors::Span> Accessors::span(int index, std::string_view what) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
    return error(ErrorCode::Malformed, fmt::format("{}: accessor {} does not exist", what, index));
  const tinygltf::Accessor& a = model_.accessors[index];
  const std::string name = fmt::format("{}: accessor {}", what, index);
  if (a.sparse.isSparse)
    return error(ErrorCode::UnsupportedFormat, name + " is sparse, which we do not read");
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
    return error(ErrorCode::Malformed, name + " has no data (no bufferView)");
  const tinygltf::BufferView& view = model_.bufferViews[a.bufferView];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
    return error(ErrorCode::Malformed,
                 fmt::format("{}: its bufferView {} names no buffer", name, a.bufferView));
  const std::vector<unsigned char>& buffer = model_.buffers[view.buffer].data;

  Span s;
  s.count = a.count;
  s.component_type = a.componentType;
  s.component_size = component_size(a.componentType);
  s.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  s.normalized = a.normalized;
  if (s.component_size == 0 || s.components <= 0)
    return error(ErrorCode::Malformed,
                 fmt::format("{} has component type {}, type {}: not a glTF 2.0 accessor", name,
                             a.componentType, a.type));
  const std::size_t element = s.component_size * static_cast<std::size_t>(s.components);
  // The views tinygltf makes for decoded Draco data are tightly packed from byte 0, whatever they record.
  const bool decoded = static_cast<std::size_t>(a.bufferView) >= file_views_;
  const std::size_t view_offset = decoded ? 0 : view.byteOffset;
  s.stride = decoded || view.byteStride == 0 ? element : view.byteStride;
  if (view_offset > buffer.size() || view.byteLength > buffer.size() - view_offset)
    return error(ErrorCode::Malformed,
                 fmt::format("{}: bufferView {} lies outside its buffer", name, a.bufferView));
  if (s.stride < element)
    return error(ErrorCode::Malformed,
                 fmt::format("{}: stride {} is shorter than an element ({} bytes)", name, s.stride, element));
  const std::size_t length = view.byteLength;
  if (s.count > 0 && (a.byteOffset > length || element > length - a.byteOffset ||
                      s.count - 1 > (length - a.byteOffset - element) / s.stride))
    return error(ErrorCode::Malformed,
                 fmt::format("{}: {} elements of {} bytes (stride {}) from byte {} run past the end of "
                             "bufferView {} ({} bytes)",
                             name, s.count, element, s.stride, a.byteOffset, a.bufferView, length));
  s.data = buffer.data() + view_offset + a.byteOffset;
  const bool in_bin = container_.glb && !decoded && view.buffer == 0 && model_.buffers[0].uri.empty();
  if (in_bin) s.file_offset = container_.bin_offset + view_offset + a.byteOffset;
  return s;
}

Result<Floats> Accessors::floats(int index, std::string_view what) const {
  Result<Span> s = span(index, what);
  if (!s) return std::move(s).error();
  if (s->component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    return error(
        ErrorCode::Malformed,
        fmt::format("{}: accessor {} has unsigned int components, which glTF allows only for indices", what,
                    index));
  Floats out{std::vector<float>(s->count * s->components), s->components};
  float* v = out.values.data();
  for (std::size_t i = 0; i < s->count; ++i)
    for (int c = 0; c < s->components; ++c, ++v) {
      *v = to_float(s->at(i, c), s->component_type, s->normalized);
      if (!std::isfinite(*v))
        return error(ErrorCode::NonFinite,
                     fmt::format("{}: element {} of accessor {} is not finite", what, i, index),
                     s->byte(i, c));
    }
  return out;
}

Result<std::vector<std::uint32_t>> Accessors::indices(int index, std::size_t vertices,
                                                      std::string_view what) const {
  Result<Span> s = span(index, what);
  if (!s) return std::move(s).error();
  const int type = s->component_type;
  if (s->components != 1 ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    return error(ErrorCode::Malformed,
                 fmt::format("{}: accessor {} must hold unsigned byte, short or int scalars", what, index));
  std::vector<std::uint32_t> out(s->count);
  for (std::size_t i = 0; i < s->count; ++i) {
    out[i] = to_index(s->at(i, 0), type);
    if (out[i] >= vertices)
      return error(
          ErrorCode::IndexOutOfRange,
          fmt::format("{}: index {} is {}, but the primitive has {} vertices", what, i, out[i], vertices),
          s->byte(i, 0));
  }
  return out;
}

} // namespace pdeface::gltf
