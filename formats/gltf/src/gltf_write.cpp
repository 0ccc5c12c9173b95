// glTF writer: a tinygltf model of one mesh, one primitive, one node and one scene, serialised by
// tinygltf as GLB or as .gltf with the buffer in a data URI.
#include "gltf_constants.hpp"

#include "pdeface/core/image.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/draco/detail.hpp"
#include "pdeface/gltf/gltf.hpp"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace pdeface::gltf {
namespace {

constexpr int kNoView = -1;
constexpr std::size_t kMaxShortVertices = 65535; // u16 indices below 65535, the primitive restart value

// The normals to write: the mesh's own, or area-weighted ones, each of unit length as the validator requires.
// A vertex on no triangle has no area-weighted normal: it gets +z, as does a zero normal of the mesh.
std::vector<Vec3f> unit_normals(const Mesh& mesh, Notes* notes) {
  std::vector<Vec3f> normals = mesh.has_normals() ? mesh.normals : vertex_normals(mesh);
  std::size_t replaced = 0;
  for (Vec3f& n : normals) {
    const float length = n.norm();
    if (length > 1e-12f && std::isfinite(length)) {
      n /= length;
    } else {
      n = Vec3f::UnitZ();
      ++replaced;
    }
  }
  if (replaced > 0 && notes)
    notes->push_back(fmt::format("{} {} without a usable normal (zero, or on no triangle) given +z: glTF "
                                 "normals must be unit vectors",
                                 replaced, replaced == 1 ? "vertex" : "vertices"));
  return normals;
}

// Colours that are all multiples of 1/255 lose nothing as normalised bytes (a quarter of the size).
bool eight_bit(const std::vector<Vec4f>& colors) {
  for (const Vec4f& c : colors)
    for (float x : c)
      if (std::round(x * 255.0f) / 255.0f != x) return false;
  return true;
}

void note_float_rounding(const Mesh& mesh, Notes* notes) {
  double worst = 0;
  for (const Vec3& p : mesh.positions)
    worst = std::max(worst, (p - p.cast<float>().cast<double>()).cwiseAbs().maxCoeff());
  if (worst > 0 && notes)
    notes->push_back(
        fmt::format("positions rounded to float32, as glTF stores them: by at most {:.3g}", worst));
}

// The tinygltf model, built up one buffer view and accessor at a time; everything in buffer 0.
class ModelBuilder {
public:
  ModelBuilder() {
    model_.buffers.emplace_back();
    model_.asset.version = "2.0";
    model_.asset.generator = std::string("pdeface ") + PDEFACE_VERSION;
  }

  // Appends `size` bytes as a new buffer view, 4-byte aligned as glTF requires of vertex attributes.
  int add_view(const void* bytes, std::size_t size, int target) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    data.resize((data.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    data.insert(data.end(), static_cast<const unsigned char*>(bytes),
                static_cast<const unsigned char*>(bytes) + size);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  template <class T> int add_view(const std::vector<T>& values, int target) {
    return add_view(values.data(), values.size() * sizeof(T), target);
  }

  int add_accessor(int view, int component_type, int type, std::size_t count, bool normalized = false,
                   std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view; // kNoView: the data is in a Draco stream, and tinygltf then writes no bufferView
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    a.normalized = normalized;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  // POSITION with the bounds the specification requires, computed from the float32 values written.
  int add_positions(int view, const std::vector<float>& xyz) {
    std::vector<double> min(3, std::numeric_limits<double>::infinity());
    std::vector<double> max(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      min[i % 3] = std::min<double>(min[i % 3], xyz[i]);
      max[i % 3] = std::max<double>(max[i % 3], xyz[i]);
    }
    return add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, xyz.size() / 3, false,
                        std::move(min), std::move(max));
  }

  // Mesh, node and scene around the primitive; units in asset.extras.
  Result<std::string> finish(tinygltf::Primitive primitive, const Mesh& mesh, bool binary) {
    tinygltf::Mesh m;
    m.name = clean_name(mesh.name); // JSON text must be UTF-8 (tinygltf throws on anything else)
    m.primitives.push_back(std::move(primitive));
    model_.meshes.push_back(std::move(m));
    tinygltf::Node node;
    node.mesh = 0;
    model_.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model_.scenes.push_back(scene);
    model_.defaultScene = 0;
    if (mesh.units != Units::Unknown)
      model_.asset.extras = tinygltf::Value(tinygltf::Value::Object{
          {std::string(kUnitsKey), tinygltf::Value(std::string(to_string(mesh.units)))}});
    std::ostringstream out;
    if (!tinygltf::TinyGLTF().WriteGltfSceneToStream(&model_, out, false, binary) || !out)
      return make_error(ErrorCode::Io, "tinygltf could not serialise the model", mesh.name);
    return std::move(out).str();
  }

  tinygltf::Model& model() { return model_; }

private:
  tinygltf::Model model_;
};

std::vector<float> flat_positions(const std::vector<Vec3>& positions) {
  std::vector<float> xyz;
  xyz.reserve(positions.size() * 3);
  for (const Vec3& p : positions)
    for (double c : p)
      xyz.push_back(static_cast<float>(c));
  return xyz;
}

template <int N, class V> std::vector<float> flat(const std::vector<V>& values) {
  std::vector<float> out;
  out.reserve(values.size() * N);
  for (const V& v : values)
    for (int c = 0; c < N; ++c)
      out.push_back(v[c]);
  return out;
}

// Indices as u16 when every vertex index fits below the restart value, else u32.
int add_indices(ModelBuilder& b, const std::vector<Triangle>& triangles, std::size_t vertices) {
  if (vertices <= kMaxShortVertices) {
    std::vector<std::uint16_t> v;
    v.reserve(triangles.size() * 3);
    for (const Triangle& t : triangles)
      for (std::uint32_t i : t)
        v.push_back(static_cast<std::uint16_t>(i));
    return b.add_accessor(b.add_view(v, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, v.size());
  }
  std::vector<std::uint32_t> v;
  v.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles)
    v.insert(v.end(), t.begin(), t.end());
  return b.add_accessor(b.add_view(v, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, v.size());
}

tinygltf::Primitive plain_primitive(ModelBuilder& b, const Mesh& mesh) {
  constexpr int kArray = TINYGLTF_TARGET_ARRAY_BUFFER;
  tinygltf::Primitive p;
  p.mode = mesh.is_point_cloud() ? TINYGLTF_MODE_POINTS : TINYGLTF_MODE_TRIANGLES;
  const std::size_t n = mesh.vertex_count();
  const std::vector<float> xyz = flat_positions(mesh.positions);
  p.attributes["POSITION"] = b.add_positions(b.add_view(xyz, kArray), xyz);
  if (mesh.has_normals())
    p.attributes["NORMAL"] = b.add_accessor(b.add_view(flat<3>(mesh.normals), kArray),
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  if (mesh.has_colors()) {
    if (eight_bit(mesh.colors)) {
      std::vector<std::uint8_t> rgba;
      for (const Vec4f& c : mesh.colors)
        for (float x : c)
          rgba.push_back(static_cast<std::uint8_t>(std::lround(x * 255.0f)));
      p.attributes["COLOR_0"] = b.add_accessor(
          b.add_view(rgba, kArray), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, n, true);
    } else {
      p.attributes["COLOR_0"] = b.add_accessor(b.add_view(flat<4>(mesh.colors), kArray),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n);
    }
  }
  if (mesh.has_texcoords())
    p.attributes["TEXCOORD_0"] = b.add_accessor(b.add_view(flat<2>(mesh.texcoords), kArray),
                                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
  if (!mesh.is_point_cloud()) p.indices = add_indices(b, mesh.triangles, n);
  return p;
}

int component_type(drc::detail::ValueType type) {
  switch (type) {
  case drc::detail::ValueType::UnsignedByte: return TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  case drc::detail::ValueType::UnsignedShort: return TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  case drc::detail::ValueType::Float: return TINYGLTF_COMPONENT_TYPE_FLOAT;
  }
  return TINYGLTF_COMPONENT_TYPE_FLOAT;
}

// A KHR_draco_mesh_compression primitive: the Draco stream in one buffer view, and accessors with no
// view that describe the decoded data. Draco reorders and may add or drop vertices, so counts and
// POSITION bounds come from decoding the stream, as the extension's implementation note advises.
Result<tinygltf::Primitive> draco_primitive(ModelBuilder& b, const Mesh& mesh,
                                            const drc::WriteOptions& options, Notes* notes) {
  Result<drc::detail::Encoded> encoded = drc::detail::encode(mesh, options, notes);
  if (!encoded) return std::move(encoded).error();
  Result<drc::detail::Decoded> decoded =
      drc::detail::decode(encoded->bytes, mesh.name, std::nullopt, nullptr);
  if (!decoded) return std::move(decoded).error();
  const Mesh& out = decoded->mesh;
  const std::size_t n = out.vertex_count();

  tinygltf::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Value::Object ids;
  auto attribute = [&](const char* name, const drc::detail::Attribute& a, int type) {
    if (!a.present()) return;
    p.attributes[name] =
        b.add_accessor(kNoView, component_type(a.type), type, n, a.type != drc::detail::ValueType::Float);
    ids[name] = tinygltf::Value(a.unique_id);
  };
  p.attributes["POSITION"] = b.add_positions(kNoView, flat_positions(out.positions));
  ids["POSITION"] = tinygltf::Value(encoded->position.unique_id);
  attribute("NORMAL", encoded->normal, TINYGLTF_TYPE_VEC3);
  attribute("COLOR_0", encoded->color, TINYGLTF_TYPE_VEC4);
  attribute("TEXCOORD_0", encoded->texcoord, TINYGLTF_TYPE_VEC2);
  p.indices = b.add_accessor(kNoView,
                             n <= kMaxShortVertices ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                                    : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                             TINYGLTF_TYPE_SCALAR, out.triangle_count() * 3);
  const int view = b.add_view(encoded->bytes.data(), encoded->bytes.size(), 0);
  p.extensions[std::string(kDracoExtension)] = tinygltf::Value(tinygltf::Value::Object{
      {"bufferView", tinygltf::Value(view)}, {"attributes", tinygltf::Value(std::move(ids))}});
  b.model().extensionsUsed = {std::string(kDracoExtension)};
  b.model().extensionsRequired = {std::string(kDracoExtension)};
  return p;
}

// The material, and its image embedded in buffer 0 (the GLB's BIN chunk, or the .gltf's data URI), as the
// primitive's: base colour factor and texture, not metallic (a face is not metal; glTF's default would be),
// fully rough.
void add_material(ModelBuilder& b, const Mesh& mesh, tinygltf::Primitive& p, Notes* notes) {
  if (!mesh.material) return;
  const Material& m = *mesh.material;
  tinygltf::Model& model = b.model();
  tinygltf::Material out;
  out.name = clean_name(m.name);
  out.pbrMetallicRoughness.baseColorFactor = {m.base_color[0], m.base_color[1], m.base_color[2],
                                              m.base_color[3]};
  for (double& c : out.pbrMetallicRoughness.baseColorFactor)
    c = std::isfinite(c) ? std::clamp(c, 0.0, 1.0) : 1.0;
  out.pbrMetallicRoughness.metallicFactor = 0.0;
  out.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (m.base_color[3] < 1.0F) out.alphaMode = "BLEND";
  auto note = [&](std::string text) {
    if (notes) notes->push_back(std::move(text));
  };
  if (m.base_color_image) {
    const Image& image = *m.base_color_image;
    const std::optional<std::string_view> mime = image_mime_type(image.bytes);
    if (image.bytes.empty()) {
      note(fmt::format("texture image '{}' not embedded: its bytes were not read", excerpt(image.uri)));
    } else if (!mime) {
      note("texture image not embedded: glTF holds JPEG and PNG images only");
    } else if (!mesh.has_texcoords()) {
      note("texture image not embedded: the mesh has no texture coordinates to map it");
    } else {
      tinygltf::Image gi;
      gi.name = clean_name(std::filesystem::path(image.uri).stem().string());
      gi.mimeType = std::string(*mime);
      gi.bufferView = b.add_view(image.bytes.data(), image.bytes.size(), 0);
      model.images.push_back(std::move(gi));
      tinygltf::Sampler sampler;
      sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
      sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
      model.samplers.push_back(sampler);
      tinygltf::Texture texture;
      texture.source = static_cast<int>(model.images.size()) - 1;
      texture.sampler = static_cast<int>(model.samplers.size()) - 1;
      model.textures.push_back(texture);
      out.pbrMetallicRoughness.baseColorTexture.index = static_cast<int>(model.textures.size()) - 1;
      out.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
    }
  }
  model.materials.push_back(std::move(out));
  p.material = static_cast<int>(model.materials.size()) - 1;
}

} // namespace

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (options.draco)
    if (Result<void> ok = drc::check(*options.draco); !ok) return std::move(ok).error();
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();

  Mesh out = mesh;
  if (!mesh.is_point_cloud() || mesh.has_normals()) out.normals = unit_normals(mesh, notes);
  // One texture coordinate per vertex: seam vertices written once per coordinate (normals computed before,
  // so both copies shade alike). glTF's (0, 0) is the image's top left, ours its bottom left (OBJ's).
  std::size_t split = 0;
  out = with_vertex_texcoords(std::move(out), &split);
  if (split > 0 && notes)
    notes->push_back(fmt::format("{} vertices on texture seams written once per texture coordinate ({} in "
                                 "all): glTF holds one per vertex",
                                 split, out.vertex_count()));
  for (Vec2f& t : out.texcoords)
    t.y() = 1.0F - t.y();
  ModelBuilder builder;
  tinygltf::Primitive primitive;
  if (options.draco && mesh.is_point_cloud() && notes)
    notes->push_back(
        "KHR_draco_mesh_compression holds triangle meshes only: the point cloud is written uncompressed");
  if (options.draco && !mesh.is_point_cloud()) {
    Result<tinygltf::Primitive> p = draco_primitive(builder, out, *options.draco, notes);
    if (!p) return std::move(p).error();
    primitive = std::move(p).value();
  } else {
    note_float_rounding(mesh, notes);
    primitive = plain_primitive(builder, out);
  }
  add_material(builder, out, primitive, notes);
  return builder.finish(std::move(primitive), mesh, options.binary);
}

} // namespace pdeface::gltf
