#include "preflight.hpp"

#include "pdeface/core/text.hpp"

#include "gltf_constants.hpp"
#include "pdeface/draco/detail.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>

namespace pdeface::gltf {
namespace {

using json = nlohmann::json;

constexpr int kMaxDepth = 64;

// The byte offset of the first '[' or '{' nested deeper than `limit`, outside strings.
std::optional<std::size_t> too_deep(std::string_view text, int limit) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::nullopt;
}

// "[json.exception.parse_error.101] parse error at line 1, column 7: syntax error ..." -> "syntax error ...".
std::string parse_error_text(const json::parse_error& e) {
  const std::string_view what = e.what();
  const std::size_t column = what.find("column ");
  const std::size_t colon = what.find(": ", column == std::string_view::npos ? 0 : column);
  return excerpt(colon == std::string_view::npos ? what : what.substr(colon + 2),
                 200); // nlohmann quotes the token
}

const json* member(const json* object, const char* key) {
  if (!object || !object->is_object()) return nullptr;
  const auto it = object->find(key);
  return it == object->end() ? nullptr : &*it;
}

std::optional<std::uint64_t> unsigned_of(const json* value) {
  if (!value || !value->is_number_unsigned()) return std::nullopt;
  return value->get<std::uint64_t>();
}

const json& array_of(const json& doc, const char* key) {
  static const json empty = json::array();
  const json* a = member(&doc, key);
  return a && a->is_array() ? *a : empty;
}

// The bytes tinygltf's base64 decoder makes of a data URI: it stops at the first '=' or other character
// outside the alphabet, and every 4 characters give 3 bytes.
std::uint64_t decoded_size(std::string_view uri) {
  const std::string_view payload = uri.substr(uri.find(',') + 1);
  const std::size_t n =
      std::min(payload.size(),
               payload.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"));
  return n / 4 * 3 + (n % 4 > 1 ? n % 4 - 1 : 0);
}

// A buffer's bytes: a slice of the GLB's BIN chunk, or a decoded data URI.
struct BufferData {
  std::vector<unsigned char> decoded;
  std::string_view bin;
  std::optional<std::uint64_t> base; // where the bytes start in the file

  [[nodiscard]] std::string_view bytes() const {
    return decoded.empty() ? bin
                           : std::string_view(reinterpret_cast<const char*>(decoded.data()), decoded.size());
  }
};

class Checker {
public:
  Checker(const Container& container, std::string_view source, const json& doc)
      : c_(container), source_(source), doc_(doc), buffers_(array_of(doc, "buffers")),
        views_(array_of(doc, "bufferViews")), accessors_(array_of(doc, "accessors")) {}

  std::optional<Error> run() {
    for (auto check : {&Checker::version, &Checker::required_extensions, &Checker::buffers,
                       &Checker::buffer_views, &Checker::draco_primitives})
      if (auto e = (this->*check)()) return e;
    return std::nullopt;
  }

private:
  [[nodiscard]] Error error(ErrorCode code, std::string message, Location where = {}) const {
    return make_error(code, std::move(message), std::string(source_), where);
  }

  std::optional<Error> version() const {
    const json* v = member(member(&doc_, "asset"), "version");
    if (!v || !v->is_string()) return error(ErrorCode::Malformed, "asset.version is missing");
    const std::string text = v->get<std::string>();
    if (!text.starts_with("2."))
      return error(ErrorCode::UnsupportedVersion, fmt::format("glTF {}: we read glTF 2.0", excerpt(text)));
    return std::nullopt;
  }

  // Extensions that change geometry must be understood; those of materials, textures and lights only
  // change looks, which we do not read.
  std::optional<Error> required_extensions() const {
    for (const json& e : array_of(doc_, "extensionsRequired")) {
      const std::string name = e.is_string() ? e.get<std::string>() : e.dump();
      constexpr std::array<std::string_view, 4> kLooks{"KHR_materials_", "KHR_texture_", "EXT_texture_",
                                                       "KHR_lights_"};
      if (name == kDracoExtension || name == kQuantizationExtension ||
          std::ranges::any_of(kLooks, [&](std::string_view prefix) { return name.starts_with(prefix); }))
        continue;
      return error(ErrorCode::UnsupportedFormat,
                   fmt::format("the file requires the extension {}, which we do not read", excerpt(name)));
    }
    return std::nullopt;
  }

  std::optional<Error> buffers() const {
    for (std::size_t i = 0; i < buffers_.size(); ++i) {
      const json& b = buffers_[i];
      const std::optional<std::uint64_t> length = unsigned_of(member(&b, "byteLength"));
      if (!length)
        return error(ErrorCode::Malformed, fmt::format("buffers[{}] has no unsigned byteLength", i));
      if (const json* uri = member(&b, "uri")) {
        const std::string text = uri->is_string() ? uri->get<std::string>() : uri->dump();
        if (tinygltf::IsDataURI(text)) {
          if (const std::uint64_t size = decoded_size(text); size != *length)
            return error(ErrorCode::Malformed,
                         fmt::format("buffers[{}]: its data URI holds {} bytes, its byteLength says {}", i,
                                     size, *length));
          continue;
        }
        if (text.starts_with("data:"))
          return error(
              ErrorCode::UnsupportedFormat,
              fmt::format("buffers[{}] has a data URI that is not base64 application/octet-stream or "
                          "application/gltf-buffer",
                          i));
        return error(
            ErrorCode::UnsupportedFormat,
            fmt::format("external buffer '{}' not supported: use .glb or embedded data URIs", excerpt(text)));
      }
      if (!c_.glb || i != 0)
        return error(
            ErrorCode::Malformed,
            fmt::format("buffers[{}] has no uri (only a GLB's first buffer may use its BIN chunk)", i));
      if (!c_.bin)
        return error(ErrorCode::Malformed, "buffers[0] refers to the GLB's BIN chunk, which is missing");
      if (*length > c_.bin->size())
        return error(
            ErrorCode::Malformed,
            fmt::format("buffers[0] claims {} bytes, the BIN chunk holds {}", *length, c_.bin->size()),
            Location::at_byte(c_.bin_offset - 8));
    }
    return std::nullopt;
  }

  // The declared length of buffer `index`, if that buffer exists.
  [[nodiscard]] std::optional<std::uint64_t> buffer_length(std::optional<std::uint64_t> index) const {
    if (!index || *index >= buffers_.size()) return std::nullopt;
    return unsigned_of(member(&buffers_[*index], "byteLength"));
  }

  std::optional<Error> buffer_views() const {
    for (std::size_t i = 0; i < views_.size(); ++i) {
      const json& v = views_[i];
      const std::optional<std::uint64_t> buffer = unsigned_of(member(&v, "buffer"));
      const std::optional<std::uint64_t> length = unsigned_of(member(&v, "byteLength"));
      const std::optional<std::uint64_t> offset =
          member(&v, "byteOffset") ? unsigned_of(member(&v, "byteOffset")) : std::uint64_t{0};
      const std::optional<std::uint64_t> size = buffer_length(buffer);
      if (!length || !offset || !size)
        return error(
            ErrorCode::Malformed,
            fmt::format("bufferViews[{}] needs a buffer that exists, an unsigned byteOffset and byteLength",
                        i));
      if (*offset > *size || *length > *size - *offset)
        return error(ErrorCode::Malformed,
                     fmt::format("bufferViews[{}] covers bytes {}..{} of buffers[{}], which has {}", i,
                                 *offset, *offset + *length, *buffer, *size));
    }
    return std::nullopt;
  }

  [[nodiscard]] Result<BufferData> buffer_data(std::uint64_t index) const {
    BufferData data;
    const json& b = buffers_[index];
    if (const json* uri = member(&b, "uri")) {
      std::string mime;
      if (!tinygltf::DecodeDataURI(&data.decoded, mime, uri->get<std::string>(),
                                   *unsigned_of(member(&b, "byteLength")), true))
        return error(ErrorCode::Malformed,
                     fmt::format("buffers[{}]: the data URI does not decode to byteLength bytes", index));
    } else {
      data.bin = *c_.bin;
      data.base = c_.bin_offset;
    }
    return data;
  }

  // The accessor an attribute or indices property names, with its component count.
  [[nodiscard]] Result<const json*> accessor(const json* index, std::string_view what) const {
    const std::optional<std::uint64_t> i = unsigned_of(index);
    if (!i || *i >= accessors_.size())
      return error(ErrorCode::Malformed,
                   fmt::format("{} is not an accessor index (the file has {})", what, accessors_.size()));
    return &accessors_[*i];
  }

  std::optional<Error> draco_primitives() const {
    const json& meshes = array_of(doc_, "meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const json* primitives = member(&meshes[m], "primitives");
      if (!primitives || !primitives->is_array()) continue;
      for (std::size_t p = 0; p < primitives->size(); ++p) {
        const json& primitive = (*primitives)[p];
        const json* draco = member(member(&primitive, "extensions"), kDracoExtension.data());
        if (!draco) continue;
        if (auto e = draco_primitive(primitive, *draco, fmt::format("meshes[{}].primitives[{}]", m, p)))
          return e;
      }
    }
    return std::nullopt;
  }

  std::optional<Error> draco_primitive(const json& primitive, const json& draco,
                                       const std::string& where) const {
    auto malformed = [&](std::string_view what) {
      return error(ErrorCode::Malformed, fmt::format("{} ({}): {}", where, kDracoExtension, what));
    };
    const std::optional<std::uint64_t> mode =
        member(&primitive, "mode") ? unsigned_of(member(&primitive, "mode")) : std::uint64_t{4};
    if (mode != 4u && mode != 5u) return malformed("the mode must be TRIANGLES (4) or TRIANGLE_STRIP (5)");
    const std::optional<std::uint64_t> view = unsigned_of(member(&draco, "bufferView"));
    const json* ids = member(&draco, "attributes");
    if (!view || *view >= views_.size() || !ids || !ids->is_object())
      return malformed("needs a bufferView that exists and an attributes object");

    // What the primitive claims about the decoded data.
    Result<const json*> indices = accessor(member(&primitive, "indices"), where + " indices");
    if (!indices) return malformed("needs an indices accessor");
    const std::optional<std::uint64_t> index_type = unsigned_of(member(*indices, "componentType"));
    if (index_type != 5121u && index_type != 5123u && index_type != 5125u)
      return malformed("its indices accessor must be of unsigned byte, short or int");
    const json* attributes = member(&primitive, "attributes");
    for (const auto& [name, id] : ids->items()) {
      if (!unsigned_of(&id) || id.get<std::uint64_t>() > std::numeric_limits<int>::max())
        return malformed(fmt::format("the id of {} is not a Draco attribute id", excerpt(name)));
      std::string what = where;
      what += " attribute ";
      what += excerpt(name);
      if (Result<const json*> a = accessor(member(attributes, name.c_str()), what); !a)
        return std::move(a).error();
    }

    // What the Draco data holds.
    const json& v = views_[*view];
    Result<BufferData> data = buffer_data(*unsigned_of(member(&v, "buffer")));
    if (!data) return std::move(data).error();
    const std::uint64_t offset = member(&v, "byteOffset") ? *unsigned_of(member(&v, "byteOffset")) : 0;
    const std::string_view bytes = data->bytes().substr(offset, *unsigned_of(member(&v, "byteLength")));
    const std::optional<std::uint64_t> base = data->base ? std::optional(*data->base + offset) : std::nullopt;
    Result<drc::detail::Decoded> decoded = drc::detail::decode(bytes, source_, base, nullptr);
    if (!decoded) {
      Error e = std::move(decoded).error();
      e.message = fmt::format("{} ({}): {}", where, kDracoExtension, e.message);
      return e;
    }
    if (decoded->mesh.triangles.empty()) return malformed("the Draco data holds no triangles");
    const std::uint64_t max_index = decoded->mesh.vertex_count() - 1;
    const std::uint64_t index_limit = *index_type == 5121u   ? 0xff
                                      : *index_type == 5123u ? 0xffff
                                                             : 0xffffffff;
    if (max_index > index_limit)
      return malformed(
          fmt::format("{} points do not fit its indices' component type", decoded->mesh.vertex_count()));
    for (const auto& [name, id] : ids->items()) {
      const auto found =
          std::ranges::find(decoded->attributes, id.get<int>(), &drc::detail::Attribute::unique_id);
      if (found == decoded->attributes.end())
        return malformed(
            fmt::format("the Draco data has no attribute {} (for {})", id.get<int>(), excerpt(name)));
      // tinygltf sizes the decoded buffer by the accessor's componentType: an unknown one counts -1 bytes,
      // and points x components x -1 asked for 4 GB (found by gltf_fuzz).
      const std::optional<std::uint64_t> component =
          unsigned_of(member(*accessor(member(attributes, name.c_str()), name), "componentType"));
      if (component != 5120u && component != 5121u && component != 5122u && component != 5123u &&
          component != 5125u && component != 5126u)
        return malformed(fmt::format("{}'s accessor has no glTF componentType", excerpt(name)));
      const json* type = member(*accessor(member(attributes, name.c_str()), name), "type");
      const int expected = type && type->is_string() ? components_of(type->get<std::string>()) : 0;
      // tinygltf copies each value into a 4-element array.
      if (found->components > 4)
        return malformed(fmt::format("{} has {} components in the Draco data, at most 4 are allowed",
                                     excerpt(name), found->components));
      if (found->components != expected)
        return malformed(fmt::format("{} has {} components in the Draco data, its accessor {}", excerpt(name),
                                     found->components, expected));
    }
    return std::nullopt;
  }

  const Container& c_;
  std::string_view source_;
  const json& doc_;
  const json& buffers_;
  const json& views_;
  const json& accessors_;
};

} // namespace

Result<Preflight> preflight(const Container& container, std::string_view source) {
  auto error = [&](ErrorCode code, std::string message, Location where) {
    return make_error(code, std::move(message), std::string(source), where);
  };
  if (const std::optional<std::size_t> at = too_deep(container.json, kMaxDepth))
    return error(ErrorCode::Malformed, fmt::format("JSON nested deeper than {} levels", kMaxDepth),
                 container.json_location(*at));
  json doc;
  try {
    doc = json::parse(container.json);
  } catch (const json::parse_error& e) {
    // nlohmann counts the bytes read, the failing one included.
    return error(ErrorCode::Malformed, "invalid JSON: " + parse_error_text(e),
                 container.json_location(e.byte == 0 ? 0 : e.byte - 1));
  } catch (const json::exception& e) { // out_of_range.406: a number beyond a double ("1e526")
    const std::string_view what = e.what();
    return error(ErrorCode::Malformed,
                 "invalid JSON: " + excerpt(what.substr(std::min(what.size(), what.find("] ") + 2)), 200),
                 Location{});
  }
  if (!doc.is_object())
    return error(ErrorCode::Malformed, "the glTF JSON is not an object", container.json_location(0));
  if (std::optional<Error> e = Checker(container, source, doc).run()) return std::move(*e);
  return Preflight{array_of(doc, "bufferViews").size()};
}

} // namespace pdeface::gltf
