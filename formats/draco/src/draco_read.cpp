#include "bitstream.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/draco/detail.hpp"
#include "pdeface/draco/draco.hpp"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/geometry_metadata.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>

namespace pdeface::drc {
namespace {

using bitstream::Origin;
using draco::GeometryAttribute;

detail::ValueType value_type(draco::DataType type) {
  switch (type) {
  case draco::DT_UINT8: return detail::ValueType::UnsignedByte;
  case draco::DT_UINT16: return detail::ValueType::UnsignedShort;
  default: return detail::ValueType::Float;
  }
}

std::string_view attribute_name(GeometryAttribute::Type type) {
  switch (type) {
  case GeometryAttribute::POSITION: return "position";
  case GeometryAttribute::NORMAL: return "normal";
  case GeometryAttribute::COLOR: return "colour";
  case GeometryAttribute::TEX_COORD: return "texture coordinate";
  default: return "generic";
  }
}

// What the decoded data says, checked: libdraco maps points to values through an index map read from the
// data, so the map is checked before use; values must be finite. Errors here have no byte offset:
// libdraco does not say where in the data an attribute's values were.
class Converter {
public:
  Converter(const draco::PointCloud& pc, std::string_view source) : pc_(pc), source_(source) {}

  // Every attribute's data type and point map, not only those we read: glTF refers to any attribute by
  // unique id, and tinygltf reads them unchecked.
  [[nodiscard]] std::optional<Error> check_point_maps() const {
    const std::size_t points = pc_.num_points();
    for (int i = 0; i < pc_.num_attributes(); ++i) {
      const draco::PointAttribute& a = *pc_.attribute(i);
      const std::string_view what = attribute_name(a.attribute_type());
      // Numbers only: libdraco converts a BOOL attribute's bytes by loading them as bools (undefined for
      // any byte but 0 and 1), and has no conversion for the invalid types.
      if (a.data_type() < draco::DT_INT8 || a.data_type() > draco::DT_FLOAT64)
        return error(ErrorCode::Malformed, fmt::format("the {} attribute's data type {} is not a number type",
                                                       what, static_cast<int>(a.data_type())));
      if (!a.is_mapping_identity() && a.indices_map_size() < points)
        return error(ErrorCode::Malformed, fmt::format("the {} point map has {} entries for {} points", what,
                                                       a.indices_map_size(), points));
      for (std::uint32_t p = 0; p < points; ++p)
        if (const draco::AttributeValueIndex index = a.mapped_index(draco::PointIndex(p));
            index.value() >= a.size())
          return error(ErrorCode::IndexOutOfRange,
                       fmt::format("point {} refers to {} value {} of {}", p, what, index.value(), a.size()));
    }
    return std::nullopt;
  }

  // Calls put(point, values) with N components per point (missing components are 0); the point maps
  // must have been checked.
  template <int N, class Put>
  std::optional<Error> values(const draco::PointAttribute& attribute, Put put) const {
    const std::string_view what = attribute_name(attribute.attribute_type());
    std::array<float, N> v{};
    for (std::uint32_t p = 0; p < pc_.num_points(); ++p) {
      const draco::AttributeValueIndex index = attribute.mapped_index(draco::PointIndex(p));
      if (!attribute.ConvertValue<float>(index, static_cast<std::int8_t>(N), v.data()))
        return error(ErrorCode::Malformed,
                     fmt::format("{} value {} cannot be read as numbers", what, index.value()));
      if (!std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); }))
        return error(ErrorCode::NonFinite, fmt::format("the {} of point {} is not finite", what, p));
      put(p, v);
    }
    return std::nullopt;
  }

  [[nodiscard]] std::size_t points() const { return pc_.num_points(); }
  [[nodiscard]] Error error(ErrorCode code, std::string message) const {
    return make_error(code, std::move(message), std::string(source_));
  }

private:
  const draco::PointCloud& pc_;
  std::string_view source_;
};

// Integer colours stored without Draco's `normalized` flag still mean 0..max.
float color_scale(const draco::PointAttribute& attribute) {
  if (attribute.normalized()) return 1.0f;
  switch (attribute.data_type()) {
  case draco::DT_UINT8: return 1.0f / std::numeric_limits<std::uint8_t>::max();
  case draco::DT_UINT16: return 1.0f / std::numeric_limits<std::uint16_t>::max();
  default: return 1.0f;
  }
}

std::optional<Error> read_positions(const Converter& c, const draco::PointAttribute* attribute, Mesh& mesh) {
  if (!attribute) return c.error(ErrorCode::Malformed, "the Draco data has no position attribute");
  if (attribute->num_components() != 3)
    return c.error(ErrorCode::Malformed,
                   fmt::format("positions have {} components, expected 3", attribute->num_components()));
  mesh.positions.resize(c.points());
  return c.values<3>(*attribute, [&](std::uint32_t p, const std::array<float, 3>& v) {
    mesh.positions[p] = Vec3(v[0], v[1], v[2]);
  });
}

// The optional attributes: read when their shape is one we hold, else dropped with a note.
std::optional<Error> read_optional(const Converter& c, const draco::PointCloud& pc, Mesh& mesh,
                                   Notes* notes) {
  auto usable = [&](const draco::PointAttribute* attribute, std::initializer_list<int> components) {
    if (!attribute) return false;
    if (std::ranges::find(components, attribute->num_components()) != components.end()) return true;
    if (notes)
      notes->push_back(fmt::format("{} attribute with {} components dropped",
                                   attribute_name(attribute->attribute_type()), attribute->num_components()));
    return false;
  };
  const std::size_t n = pc.num_points();
  if (const auto* a = pc.GetNamedAttribute(GeometryAttribute::NORMAL); usable(a, {3})) {
    mesh.normals.resize(n);
    if (auto e = c.values<3>(
            *a, [&](std::uint32_t p, const auto& v) { mesh.normals[p] = Vec3f(v[0], v[1], v[2]); }))
      return e;
  }
  if (const auto* a = pc.GetNamedAttribute(GeometryAttribute::COLOR); usable(a, {3, 4})) {
    const float scale = color_scale(*a);
    const bool rgb = a->num_components() == 3;
    mesh.colors.resize(n);
    if (auto e = c.values<4>(*a, [&](std::uint32_t p, const auto& v) {
          mesh.colors[p] = Vec4f(v[0] * scale, v[1] * scale, v[2] * scale, rgb ? 1.0f : v[3] * scale);
        }))
      return e;
  }
  if (const auto* a = pc.GetNamedAttribute(GeometryAttribute::TEX_COORD); usable(a, {2})) {
    mesh.texcoords.resize(n);
    if (auto e =
            c.values<2>(*a, [&](std::uint32_t p, const auto& v) { mesh.texcoords[p] = Vec2f(v[0], v[1]); }))
      return e;
  }
  return std::nullopt;
}

// Notes the attributes beyond the first of each kind, and those of kinds we do not hold.
void note_unused(const draco::PointCloud& pc, Notes* notes) {
  if (!notes) return;
  for (int i = 0; i < pc.num_attributes(); ++i) {
    const draco::PointAttribute* a = pc.attribute(i);
    const GeometryAttribute::Type type = a->attribute_type();
    if (type == GeometryAttribute::GENERIC || type >= GeometryAttribute::NAMED_ATTRIBUTES_COUNT)
      notes->push_back(fmt::format("Draco attribute {} (generic) dropped", a->unique_id()));
    else if (pc.GetNamedAttribute(type) != a)
      notes->push_back(fmt::format("Draco attribute {}: a second {} attribute, dropped", a->unique_id(),
                                   attribute_name(type)));
  }
}

void read_units(const draco::PointCloud& pc, Mesh& mesh, Notes* notes) {
  std::string text;
  if (!pc.GetMetadata() || !pc.GetMetadata()->GetEntryString("units", &text)) return;
  if (const std::optional<Units> units = units_from_string(text)) {
    mesh.units = *units;
  } else if (notes) {
    notes->push_back(fmt::format("unknown units \"{}\" in the Draco metadata ignored", excerpt(text)));
  }
}

// libdraco's geometry as our mesh, checked.
Result<detail::Decoded> convert(const draco::PointCloud& pc, const draco::Mesh* dm, std::string_view source,
                                Notes* notes) {
  const Converter c(pc, source);
  detail::Decoded out;
  Mesh& mesh = out.mesh;
  if (pc.num_points() == 0) return c.error(ErrorCode::Empty, "the Draco data holds no points");
  if (auto e = c.check_point_maps()) return std::move(*e);
  if (auto e = read_positions(c, pc.GetNamedAttribute(GeometryAttribute::POSITION), mesh))
    return std::move(*e);
  if (auto e = read_optional(c, pc, mesh, notes)) return std::move(*e);
  note_unused(pc, notes);
  if (dm) {
    mesh.triangles.resize(dm->num_faces());
    for (draco::FaceIndex f(0); f < dm->num_faces(); ++f) {
      const draco::Mesh::Face& face = dm->face(f);
      mesh.triangles[f.value()] = {face[0].value(), face[1].value(), face[2].value()};
    }
  }
  read_units(pc, mesh, notes);
  if (Result<void> valid = validate(mesh, source); !valid) return std::move(valid).error();
  for (int i = 0; i < pc.num_attributes(); ++i) {
    const draco::PointAttribute* a = pc.attribute(i);
    out.attributes.push_back(
        {static_cast<int>(a->unique_id()), a->num_components(), value_type(a->data_type())});
  }
  return out;
}

} // namespace

namespace detail {

std::string message_text(std::string message) {
  constexpr std::size_t kMax = 200;
  std::ranges::replace(message, '\n', ' '); // tinygltf joins its errors with newlines
  while (!message.empty() && (message.back() == '.' || message.back() == ' '))
    message.pop_back();
  if (!message.empty()) message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
  return excerpt(message, kMax);
}

Result<Decoded> decode(std::string_view bytes, std::string_view source, std::optional<std::uint64_t> base,
                       Notes* notes) {
  const Origin origin{source, base};
  Result<bitstream::Header> header = bitstream::check(bytes, origin);
  if (!header) return std::move(header).error();

  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  // libdraco says what failed, not where: we locate the error where it stopped reading (it re-points the
  // buffer inside our bytes as it goes), and call it truncated only when that is the end of the data.
  auto failure = [&](const draco::Status& status) {
    const auto head = reinterpret_cast<std::uintptr_t>(buffer.data_head());
    const auto start = reinterpret_cast<std::uintptr_t>(bytes.data());
    const bool inside = head >= start && head - start <= bytes.size();
    const std::size_t stop = inside ? head - start : 0;
    const bool at_end = inside && stop == bytes.size();
    return make_error(at_end ? ErrorCode::Truncated : ErrorCode::Malformed,
                      fmt::format("the Draco decoder failed: {} (the data is {})",
                                  detail::message_text(status.error_msg_string()),
                                  at_end ? "truncated" : "corrupt or truncated"),
                      std::string(source), inside ? origin.at(stop) : Location{});
  };
  try {
    if (header->mesh) {
      auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
      if (!decoded.ok()) return failure(decoded.status());
      return convert(*decoded.value(), decoded.value().get(), source, notes);
    }
    auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
    if (!decoded.ok()) return failure(decoded.status());
    return convert(*decoded.value(), nullptr, source, notes);
  } catch (const std::bad_alloc&) {
    // The checked counts bound what libdraco allocates; this is the last line of defence.
    return make_error(ErrorCode::CountTooLarge, "the Draco data needs more memory than is available",
                      std::string(source));
  }
}

} // namespace detail

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
  Notes mine;
  Result<detail::Decoded> decoded = detail::decode(bytes, source, 0, notes ? &mine : nullptr);
  if (!decoded) return std::move(decoded).error();
  for (const std::string& note : mine)
    notes->push_back(fmt::format("{}: {}", source, note));
  if (!decoded->mesh.has_texcoords()) return std::move(decoded->mesh);
  // Points that repeat a position, normal and colour differ in their texture coordinate only (a seam the
  // writer split): one vertex again, the texture coordinates per corner.
  std::size_t merged = 0;
  Mesh mesh = weld_texcoord_seams(std::move(decoded->mesh), &merged);
  if (merged > 0 && notes)
    notes->push_back(
        fmt::format("{}: {} points on texture seams merged with their twins (texture coordinates "
                    "per corner)",
                    source, merged));
  return mesh;
}

} // namespace pdeface::drc
