#include "pdeface/draco/detail.hpp"
#include "pdeface/draco/draco.hpp"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/geometry_metadata.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>
#include <optional>
#include <span>

namespace pdeface::drc {
namespace {

std::optional<Error> check_range(std::string_view what, int value, int lo, int hi,
                                 std::string_view why = {}) {
  if (value >= lo && value <= hi) return std::nullopt;
  return make_error(ErrorCode::InvalidArgument,
                    fmt::format("{} = {} is outside {}..{}{}", what, value, lo, hi, why));
}

// Adds a per-point attribute of N components of type T (identity mapping: value i belongs to point i)
// filled by `value_of(i)`; returns its description for glTF.
template <class T, int N, class ValueOf>
detail::Attribute add_attribute(draco::PointCloud& pc, draco::GeometryAttribute::Type type,
                                draco::DataType data_type, detail::ValueType value_type, std::size_t count,
                                ValueOf value_of) {
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, N, data_type, value_type != detail::ValueType::Float, sizeof(T) * N, 0);
  const int id = pc.AddAttribute(ga, true, static_cast<draco::PointIndex::ValueType>(count));
  draco::PointAttribute* attribute = pc.attribute(id);
  for (std::size_t i = 0; i < count; ++i) {
    const std::array<T, N> value = value_of(i);
    attribute->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)), value.data());
  }
  return {static_cast<int>(attribute->unique_id()), N, value_type};
}

template <class T> T to_unorm(float c) {
  constexpr float max = std::numeric_limits<T>::max();
  return static_cast<T>(std::lround(std::clamp(c, 0.0f, 1.0f) * max));
}

template <class T>
detail::Attribute add_colors(draco::PointCloud& pc, const Mesh& mesh, draco::DataType data_type,
                             detail::ValueType value_type) {
  return add_attribute<T, 4>(
      pc, draco::GeometryAttribute::COLOR, data_type, value_type, mesh.colors.size(), [&](std::size_t i) {
        const Vec4f& c = mesh.colors[i];
        return std::array<T, 4>{to_unorm<T>(c[0]), to_unorm<T>(c[1]), to_unorm<T>(c[2]), to_unorm<T>(c[3])};
      });
}

// The mesh as Draco geometry (a draco::Mesh, with no faces for a point cloud); fills the attribute ids.
std::unique_ptr<draco::Mesh> to_draco(const Mesh& mesh, const WriteOptions& options, detail::Encoded& out) {
  using Type = draco::GeometryAttribute::Type;
  auto dm = std::make_unique<draco::Mesh>();
  const std::size_t n = mesh.vertex_count();
  dm->set_num_points(static_cast<draco::PointIndex::ValueType>(n));
  out.position = add_attribute<float, 3>(*dm, Type::POSITION, draco::DT_FLOAT32, detail::ValueType::Float, n,
                                         [&](std::size_t i) {
                                           const Vec3f p = mesh.positions[i].cast<float>();
                                           return std::array<float, 3>{p.x(), p.y(), p.z()};
                                         });
  if (mesh.has_normals())
    out.normal = add_attribute<float, 3>(*dm, Type::NORMAL, draco::DT_FLOAT32, detail::ValueType::Float, n,
                                         [&](std::size_t i) {
                                           const Vec3f& v = mesh.normals[i];
                                           return std::array<float, 3>{v.x(), v.y(), v.z()};
                                         });
  if (mesh.has_colors())
    out.color =
        options.color_bits == 8
            ? add_colors<std::uint8_t>(*dm, mesh, draco::DT_UINT8, detail::ValueType::UnsignedByte)
            : add_colors<std::uint16_t>(*dm, mesh, draco::DT_UINT16, detail::ValueType::UnsignedShort);
  if (mesh.has_texcoords())
    out.texcoord = add_attribute<float, 2>(*dm, Type::TEX_COORD, draco::DT_FLOAT32, detail::ValueType::Float,
                                           n, [&](std::size_t i) {
                                             const Vec2f& t = mesh.texcoords[i];
                                             return std::array<float, 2>{t.x(), t.y()};
                                           });
  dm->SetNumFaces(mesh.triangle_count());
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    dm->SetFace(draco::FaceIndex(static_cast<std::uint32_t>(f)),
                {draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  }
  if (mesh.units != Units::Unknown) {
    auto metadata = std::make_unique<draco::GeometryMetadata>();
    metadata->AddEntryString("units", std::string(to_string(mesh.units)));
    dm->AddMetadata(std::move(metadata));
  }
  return dm;
}

draco::Encoder make_encoder(const WriteOptions& options, bool mesh) {
  using Type = draco::GeometryAttribute::Type;
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(Type::POSITION, options.position_bits);
  encoder.SetAttributeQuantization(Type::NORMAL, options.normal_bits);
  encoder.SetAttributeQuantization(Type::TEX_COORD, options.texcoord_bits);
  const int speed = 10 - options.level;
  encoder.SetSpeedOptions(speed, speed);
  // Speed 10 already picks the sequential methods; saying so keeps the vertex-order promise of level 0
  // independent of libdraco's heuristics (its edgebreaker and k-d tree reorder points).
  if (options.level == 0)
    encoder.SetEncodingMethod(mesh ? int{draco::MESH_SEQUENTIAL_ENCODING}
                                   : int{draco::POINT_CLOUD_SEQUENTIAL_ENCODING});
  return encoder;
}

// "positions quantised to 14 bits: step 0.0133 mm, error at most 0.0066 mm per axis".
std::string position_error_note(const Mesh& mesh, int bits) {
  const double step = bounding_box(mesh).size().maxCoeff() / static_cast<double>((1u << bits) - 1);
  const std::string_view units =
      mesh.units == Units::Unknown ? std::string_view("units") : to_string(mesh.units);
  return fmt::format("Draco quantises positions to {} bits: step {:.3g} {}, error at most {:.3g} {} per axis",
                     bits, step, units, step / 2, units);
}

// Draco's edgebreaker (every level but 0) encodes only the vertices of triangles.
std::optional<std::string> dropped_vertices_note(const Mesh& mesh, const WriteOptions& options) {
  if (mesh.is_point_cloud() || options.level == 0) return std::nullopt;
  std::vector<bool> used(mesh.vertex_count(), false);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t)
      used[v] = true;
  const auto unused = static_cast<std::size_t>(std::ranges::count(used, false));
  if (unused == 0) return std::nullopt;
  return fmt::format("{} {} on no triangle dropped: Draco's edgebreaker (level 1-10) keeps only the vertices "
                     "of triangles; level 0 keeps them",
                     unused, unused == 1 ? "vertex" : "vertices");
}

// libdraco quantises positions and texture coordinates over their range, computed in float: a range wider
// than the largest float (coordinates from -3e38 to 3e38) is infinite, and its encoder then crashes. What
// the writer hands libdraco is checked first.
template <class Vector>
std::optional<Error> check_span(std::span<const Vector> values, std::string_view what, const Mesh& mesh) {
  constexpr std::string_view kAxes = "xyzw";
  for (int k = 0; k < static_cast<int>(Vector::RowsAtCompileTime); ++k) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const Vector& v : values) {
      lo = std::min(lo, static_cast<float>(v[k]));
      hi = std::max(hi, static_cast<float>(v[k]));
    }
    if (values.empty() || std::isfinite(hi - lo)) continue;
    return make_error(ErrorCode::NonFinite,
                      fmt::format("the {} span {:.3g} to {:.3g} along {}, a range wider than a float holds: "
                                  "Draco cannot quantise them",
                                  what, lo, hi, kAxes[static_cast<std::size_t>(k)]),
                      mesh.name);
  }
  return std::nullopt;
}

} // namespace

Result<void> check(const WriteOptions& options) {
  constexpr std::string_view kMemory =
      " (more bits than float32 values hold; Draco's encoder would allocate 4 * 2^bits bytes)";
  for (const std::optional<Error>& e :
       {check_range("position_bits", options.position_bits, 1, kMaxQuantizationBits, kMemory),
        check_range("normal_bits", options.normal_bits, 2, kMaxQuantizationBits, kMemory),
        check_range("texcoord_bits", options.texcoord_bits, 1, kMaxQuantizationBits, kMemory),
        check_range("level", options.level, 0, 10)})
    if (e) return *e;
  if (options.color_bits != 8 && options.color_bits != 16)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("color_bits = {} is neither 8 nor 16 (colours are stored as normalised "
                                  "8- or 16-bit integers)",
                                  options.color_bits));
  return {};
}

namespace detail {

Result<Encoded> encode(const Mesh& input, const WriteOptions& options, Notes* notes) {
  if (Result<void> ok = check(options); !ok) return std::move(ok).error();
  if (Result<void> valid = check_writable(input); !valid) return std::move(valid).error();
  // One TEX_COORD value per point: seam vertices split (same position, so the edgebreaker's connectivity,
  // which follows positions, is the same; the reader welds them again).
  std::size_t split = 0;
  const Mesh split_mesh = input.has_corner_texcoords() ? with_vertex_texcoords(input, &split) : Mesh();
  const Mesh& mesh = input.has_corner_texcoords() ? split_mesh : input;
  if (split > 0 && notes)
    notes->push_back(fmt::format("{} vertices on texture seams written once per texture coordinate", split));
  if (auto e = check_span<Vec3>(mesh.positions, "positions", mesh)) return std::move(*e);
  if (auto e = check_span<Vec2f>(mesh.texcoords, "texture coordinates", mesh)) return std::move(*e);
  if (mesh.vertex_count() > std::numeric_limits<std::int32_t>::max())
    return make_error(ErrorCode::CountTooLarge,
                      fmt::format("{} vertices: Draco holds at most 2^31 - 1", mesh.vertex_count()),
                      mesh.name);

  Encoded out;
  try {
    const std::unique_ptr<draco::Mesh> dm = to_draco(mesh, options, out);
    draco::Encoder encoder = make_encoder(options, !mesh.is_point_cloud());
    draco::EncoderBuffer buffer;
    const draco::Status status = mesh.is_point_cloud() ? encoder.EncodePointCloudToBuffer(*dm, &buffer)
                                                       : encoder.EncodeMeshToBuffer(*dm, &buffer);
    if (!status.ok())
      return make_error(ErrorCode::Malformed,
                        "Draco cannot encode the mesh: " + detail::message_text(status.error_msg_string()),
                        mesh.name);
    out.bytes.assign(buffer.data(), buffer.size());
  } catch (const std::bad_alloc&) {
    return make_error(ErrorCode::CountTooLarge, "not enough memory to encode the mesh with Draco", mesh.name);
  }
  // What libdraco wrote must decode again: its sequential encoder (level 0) writes a mesh of one triangle as
  // data its own decoder refuses (found by path_fuzz; draco_decoder refuses it too).
  if (Result<Decoded> back = decode(out.bytes, mesh.name, std::nullopt, nullptr); !back)
    return make_error(ErrorCode::Malformed,
                      fmt::format("libdraco wrote data it cannot decode again ({}){}", back.error().message,
                                  options.level == 0 && mesh.triangle_count() == 1
                                      ? ": it cannot hold one triangle at level 0, use a level of 1 to 10"
                                      : ""),
                      mesh.name);
  if (notes) {
    notes->push_back(position_error_note(mesh, options.position_bits));
    if (std::optional<std::string> note = dropped_vertices_note(mesh, options)) notes->push_back(*note);
  }
  return out;
}

} // namespace detail

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  Result<detail::Encoded> encoded = detail::encode(mesh, options, notes);
  if (!encoded) return std::move(encoded).error();
  return std::move(encoded->bytes);
}

} // namespace pdeface::drc
