// The glTF reader and writer: the real scan, scenes, transforms, modes and encodings, round trips plain
// and with Draco, and every class of bad input with its code and location.
#include "../draco/quantisation.hpp"
#include "format_test_support.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/gltf/gltf.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

namespace pdeface {

using test::half_step;
using test::sorted_axis_error;

void PrintTo(ErrorCode code, std::ostream* os) { *os << to_string(code); }

namespace {

using json = nlohmann::json;

std::string fixture(std::string_view name) {
  Result<std::string> bytes = read_file(test::fixtures() / "gltf" / name);
  EXPECT_TRUE(bytes.ok()) << name;
  return bytes.ok() ? *bytes : std::string();
}

Mesh small_face() { return sample_face({.spacing_mm = 8.0}); } // ~400 vertices

std::uint32_t u32_at(std::string_view bytes, std::size_t offset) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

void put_u32(std::string& bytes, std::size_t offset, std::uint32_t v) {
  std::memcpy(bytes.data() + offset, &v, 4);
}

// A GLB of `doc` and `bin`, padded as the specification asks.
std::string make_glb(const json& doc, std::string bin) {
  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string out = "glTF" + std::string(8, '\0');
  auto chunk = [&](const std::string& data, std::uint32_t type) {
    std::string header(8, '\0');
    put_u32(header, 0, static_cast<std::uint32_t>(data.size()));
    put_u32(header, 4, type);
    out += header + data;
  };
  chunk(text, 0x4E4F534A);
  if (!bin.empty()) chunk(bin, 0x004E4942);
  put_u32(out, 4, 2);
  put_u32(out, 8, static_cast<std::uint32_t>(out.size()));
  return out;
}

// The JSON and BIN chunks of a GLB we wrote.
std::pair<json, std::string> split_glb(std::string_view glb) {
  const std::uint32_t json_length = u32_at(glb, 12);
  json doc = json::parse(glb.substr(20, json_length));
  std::string bin;
  if (20 + json_length < glb.size())
    bin = std::string(glb.substr(28 + json_length, u32_at(glb, 20 + json_length)));
  return {doc, bin};
}

template <class T> std::string bytes_of(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// A document of `bin` as buffer 0, with one buffer view per (offset, length) and the given accessors.
json document(const std::string& bin, const std::vector<std::pair<std::size_t, std::size_t>>& views,
              const json& accessors, const json& meshes, const json& nodes, const json& scenes = json()) {
  json doc = {{"asset", {{"version", "2.0"}}},
              {"buffers", {{{"byteLength", bin.size()}}}},
              {"bufferViews", json::array()},
              {"accessors", accessors},
              {"meshes", meshes}};
  for (const auto& [offset, length] : views)
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
  if (!nodes.is_null()) doc["nodes"] = nodes;
  if (!scenes.is_null()) {
    doc["scenes"] = scenes;
    doc["scene"] = 0;
  }
  return doc;
}

json accessor(int view, int component_type, std::size_t count, std::string_view type,
              bool normalized = false) {
  json a = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (normalized) a["normalized"] = true;
  return a;
}

// The unit square in the z = 0 plane: 4 positions, normals +z.
const std::vector<float> kSquare{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<float> kUp{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};

void expect_error(const Result<Mesh>& result, ErrorCode code, Location where,
                  std::string_view source = "bad.glb") {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, code) << result.error().to_string();
  EXPECT_EQ(result.error().where.byte, where.byte) << result.error().to_string();
  EXPECT_EQ(result.error().where.line, where.line) << result.error().to_string();
  EXPECT_EQ(result.error().where.column, where.column) << result.error().to_string();
  EXPECT_EQ(result.error().source, source);
}

void expect_message(const Result<Mesh>& result, std::string_view text) {
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find(text), std::string::npos) << result.error().to_string();
}

bool has_note(const Notes& notes, std::string_view text) {
  return std::ranges::any_of(notes, [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// ---- reading -------------------------------------------------------------------------------------------

TEST(GltfRead, RealScanMatchesItsPly) {
  PDEFACE_FACE_OR_SKIP(glb, "facefuns_f36.glb");
  Notes notes;
  Result<Mesh> mesh = gltf::read(*read_file(glb), "facefuns_f36.glb", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_TRUE(notes.empty());
  EXPECT_EQ(mesh->vertex_count(), 30204u);
  EXPECT_EQ(mesh->triangle_count(), 59697u);
  EXPECT_EQ(mesh->units, Units::Unknown); // it has no pdeface units marker
  // Figures of facefuns_f36.ply, printed once with Python (its float32 values, exactly).
  const Box box = bounding_box(*mesh);
  EXPECT_EQ(box.min, Vec3(-85.52855682373047, -124.45348358154297, -68.29451751708984));
  EXPECT_EQ(box.max, Vec3(82.62286376953125, 89.3740234375, 64.76822662353516));
  EXPECT_EQ(mesh->positions.front(), Vec3(-77.3948974609375, 40.9913330078125, -23.24306297302246));
  EXPECT_EQ(mesh->positions.back(), Vec3(11.809102058410645, -123.0659408569336, -25.03916358947754));
  EXPECT_EQ(mesh->triangles.front(), (Triangle{11774, 11647, 11537}));
  EXPECT_EQ(mesh->triangles.back(), (Triangle{10852, 417, 11023}));
}

TEST(GltfRead, SquareAsGltfAndGlb) {
  for (const char* name : {"square.gltf", "square.glb"}) {
    SCOPED_TRACE(name);
    Result<Mesh> mesh = gltf::read(fixture(name), name);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->vertex_count(), 4u);
    ASSERT_EQ(mesh->triangle_count(), 2u);
    EXPECT_EQ(mesh->triangles[1], (Triangle{0, 2, 3}));
    EXPECT_EQ(mesh->positions[2], Vec3(1, 1, 0));
    EXPECT_EQ(mesh->units, Units::Millimetres);
    EXPECT_EQ(mesh->name, "square");
  }
}

TEST(GltfRead, NodeTransformsAreComposedParentChild) {
  const std::string bin =
      bytes_of(kSquare) + bytes_of(kUp) + bytes_of(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
  const json accessors = {accessor(0, 5126, 4, "VEC3"), accessor(1, 5126, 4, "VEC3"),
                          accessor(2, 5123, 6, "SCALAR")};
  const json meshes = {
      {{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}}}}}};
  const double s = std::sin(std::numbers::pi / 4), c = std::cos(std::numbers::pi / 4);
  const json nodes = {// Root: translate by (10, 0, 0), scale by 2; its child turns 90 degrees about x.
                      {{"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}},
                      {{"rotation", {s, 0, 0, c}}, {"mesh", 0}},
                      // A second root mirrors x with a column-major matrix.
                      {{"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}, {"mesh", 0}}};
  const json doc =
      document(bin, {{0, 48}, {48, 48}, {96, 12}}, accessors, meshes, nodes, {{{"nodes", {0, 2}}}});
  Result<Mesh> mesh = gltf::read(make_glb(doc, bin), "nodes.glb");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_EQ(mesh->vertex_count(), 8u);
  // (1, 1, 0) turned about x is (1, 0, 1), scaled (2, 0, 2), moved (12, 0, 2).
  EXPECT_TRUE(mesh->positions[2].isApprox(Vec3(12, 0, 2))) << mesh->positions[2].transpose();
  EXPECT_TRUE(mesh->normals[0].isApprox(Vec3f(0, -1, 0), 1e-6f)) << mesh->normals[0].transpose();
  EXPECT_NEAR(mesh->normals[0].norm(), 1.0f, 1e-6f); // unit again after the scale
  EXPECT_EQ(mesh->triangles[0], (Triangle{0, 1, 2}));
  // The mirrored copy: x negated, and its winding flipped to stay counter-clockwise from outside.
  EXPECT_TRUE(mesh->positions[6].isApprox(Vec3(-1, 1, 0)));
  EXPECT_EQ(mesh->triangles[2], (Triangle{4, 6, 5}));
  EXPECT_TRUE(mesh->normals[4].isApprox(Vec3f(0, 0, 1)));
}

TEST(GltfRead, ModesIndexTypesAndMixedPoints) {
  const std::string bin = bytes_of(kSquare) + bytes_of(std::vector<std::uint8_t>{0, 1, 3, 2}) +
                          bytes_of(std::vector<std::uint32_t>{0, 1, 2, 3});
  const json accessors = {accessor(0, 5126, 4, "VEC3"), accessor(1, 5121, 4, "SCALAR"),
                          accessor(2, 5125, 4, "SCALAR")};
  const json primitives = {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 5}}, // strip, u8
                           {{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"mode", 6}}, // fan, u32
                           {{"attributes", {{"POSITION", 0}}}, {"mode", 4}},                 // no indices
                           {{"attributes", {{"POSITION", 0}}}, {"mode", 0}},                 // points
                           {{"attributes", {{"POSITION", 0}}}, {"mode", 1}}};                // lines
  const json doc =
      document(bin, {{0, 48}, {48, 4}, {52, 16}}, accessors, {{{"primitives", primitives}}}, {{{"mesh", 0}}});
  Notes notes;
  Result<Mesh> mesh = gltf::read(make_glb(doc, bin), "modes.glb", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_EQ(mesh->vertex_count(), 16u);
  ASSERT_EQ(mesh->triangle_count(), 2u + 2u + 1u);
  EXPECT_EQ(mesh->triangles[0], (Triangle{0, 1, 3})); // strip: v0 v1 v2
  EXPECT_EQ(mesh->triangles[1], (Triangle{1, 2, 3})); // then v1 v3 v2: the winding is kept
  EXPECT_EQ(mesh->triangles[2], (Triangle{5, 6, 4})); // fan: v1 v2 v0
  EXPECT_EQ(mesh->triangles[3], (Triangle{6, 7, 4}));
  EXPECT_EQ(mesh->triangles[4], (Triangle{8, 9, 10})); // non-indexed: 4 vertices, 1 triangle
  EXPECT_TRUE(has_note(notes, "1 indices left over"));
  EXPECT_TRUE(has_note(notes, "mixes points and triangles: its 4 points"));
  EXPECT_TRUE(has_note(notes, "line primitives skipped"));
}

TEST(GltfRead, AttributeEncodings) {
  const std::string bin = bytes_of(kSquare) +
                          bytes_of(std::vector<std::uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 255, 51, 51, 51}) +
                          bytes_of(std::vector<std::uint16_t>{0, 65535, 0, 65535, 65535, 0, 0, 0}) +
                          bytes_of(std::vector<std::int16_t>{0, 0, 32767, 0, 32767, 32767, 0, -32768});
  const json accessors = {accessor(0, 5126, 4, "VEC3"), accessor(1, 5121, 4, "VEC3", true),
                          accessor(2, 5123, 2, "VEC4", true), accessor(3, 5122, 4, "VEC2", true)};
  const json primitives = {
      {{"attributes", {{"POSITION", 0}, {"COLOR_0", 1}, {"TEXCOORD_0", 3}}}, {"mode", 0}}};
  json doc = document(bin, {{0, 48}, {48, 12}, {60, 16}, {76, 16}}, accessors, {{{"primitives", primitives}}},
                      {{{"mesh", 0}}});
  Result<Mesh> mesh = gltf::read(make_glb(doc, bin), "attributes.glb");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->colors[0], Vec4f(1, 0, 0, 1)); // RGB gets alpha 1
  EXPECT_EQ(mesh->colors[3], Vec4f(0.2f, 0.2f, 0.2f, 1));
  EXPECT_EQ(mesh->texcoords[2], Vec2f(1, 0)); // (1, 1) with glTF's v turned into ours: 1 - v
  EXPECT_EQ(mesh->texcoords[3], Vec2f(0, 2)); // -32768 clamps to -1
  // Unsigned short RGBA colours, two elements only: a count that does not match POSITION.
  doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 2;
  Result<Mesh> bad = gltf::read(make_glb(doc, bin), "bad.glb");
  expect_error(bad, ErrorCode::Malformed, {});
  expect_message(bad, "COLOR_0 has 2 elements, POSITION 4");
}

TEST(GltfRead, ScenesRootsAndUnits) {
  const std::string bin = bytes_of(kSquare);
  const json accessors = json::array({accessor(0, 5126, 4, "VEC3")});
  const json meshes = {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 0}}}}}};
  // No scenes: every root node (node 1 is node 0's child, so read once, moved by both).
  json doc =
      document(bin, {{0, 48}}, accessors, meshes,
               {{{"children", {1}}, {"translation", {0, 0, 5}}}, {{"mesh", 0}, {"translation", {1, 0, 0}}}});
  Result<Mesh> mesh = gltf::read(make_glb(doc, bin), "roots.glb");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->positions[0], Vec3(1, 0, 5));
  // No nodes at all: the meshes, untransformed, with a note.
  doc.erase("nodes");
  Notes notes;
  mesh = gltf::read(make_glb(doc, bin), "meshes.glb", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->positions[1], Vec3(1, 0, 0));
  EXPECT_TRUE(has_note(notes, "no nodes"));
  // Units: ours, or unknown with a note.
  doc["asset"]["extras"] = {{"units", "cm"}};
  EXPECT_EQ(gltf::read(make_glb(doc, bin), "cm.glb")->units, Units::Centimetres);
  doc["asset"]["extras"] = {{"units", "furlongs"}};
  notes.clear();
  EXPECT_EQ(gltf::read(make_glb(doc, bin), "furlongs.glb", &notes)->units, Units::Unknown);
  EXPECT_TRUE(has_note(notes, "units unknown"));
}

TEST(GltfRead, ImagesAreIgnoredNeverLoaded) {
  json doc = json::parse(fixture("square.gltf"));
  doc["images"] = {{{"uri", "/etc/passwd"}}, {{"uri", "data:image/png;base64,iVBORw0KGgo="}}};
  Result<Mesh> mesh = gltf::read(doc.dump(), "images.gltf");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4u);
}

// ---- round trips ---------------------------------------------------------------------------------------

TEST(GltfRoundTrip, SampleFacePlainIsExactAsFloat32) {
  Mesh face = sample_face();
  face.units = Units::Millimetres;
  face.name = "sample";
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary);
    Notes notes;
    Result<std::string> bytes = gltf::write(face, {.binary = binary, .draco = std::nullopt}, &notes);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    EXPECT_EQ(bytes->starts_with("glTF"), binary);
    EXPECT_TRUE(has_note(notes, "rounded to float32"));
    Result<Mesh> back = gltf::read(*bytes, binary ? "face.glb" : "face.gltf");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_EQ(back->vertex_count(), face.vertex_count());
    EXPECT_EQ(back->triangles, face.triangles);
    EXPECT_EQ(back->units, Units::Millimetres);
    EXPECT_EQ(back->name, "sample");
    for (std::size_t i = 0; i < face.vertex_count(); ++i) {
      ASSERT_EQ(back->positions[i], face.positions[i].cast<float>().cast<double>()) << i;
      ASSERT_TRUE(back->normals[i].isApprox(face.normals[i], 1e-6f)) << i;
      ASSERT_EQ(back->colors[i], face.colors[i]) << i; // not 8-bit: written as floats
    }
  }
}

TEST(GltfRoundTrip, EightBitColoursAndTexcoords) {
  Mesh face = small_face();
  for (std::size_t i = 0; i < face.vertex_count(); ++i) {
    face.colors[i] = Vec4f(static_cast<float>(i % 256), 17, 255, 128) / 255.0f;
    face.texcoords.emplace_back(static_cast<float>(i) / 1000, 0.25f);
  }
  Result<std::string> bytes = gltf::write(face);
  ASSERT_TRUE(bytes.ok());
  const json doc = split_glb(*bytes).first;
  const int color = doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"];
  EXPECT_EQ(doc["accessors"][color]["componentType"], 5121);
  EXPECT_EQ(doc["accessors"][color]["normalized"], true);
  Result<Mesh> back = gltf::read(*bytes, "face.glb");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back->colors, face.colors);
  ASSERT_EQ(back->texcoords.size(), face.texcoords.size());
  for (std::size_t i = 0; i < face.texcoords.size(); ++i) // v' = 1 - v twice: within half a float ulp of 1
    ASSERT_TRUE((back->texcoords[i] - face.texcoords[i]).cwiseAbs().maxCoeff() <= 0x1p-24F) << i;
}

// The case: james.obj (6393 vertices, 636 corners on texture seams, a material library and a
// 2400 × 1600 JPEG) as a GLB keeps every corner's texture coordinate and the photo's bytes.
TEST(GltfRoundTrip, JamesKeepsItsSeamsAndPhoto) {
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  Notes notes;
  const Result<formats::LoadedMesh> james = formats::read_mesh(path, {}, &notes);
  ASSERT_TRUE(james.ok()) << james.error().to_string();
  const Mesh& mesh = james->mesh;
  ASSERT_TRUE(mesh.has_corner_texcoords());
  std::size_t split = 0;
  (void)with_vertex_texcoords(mesh, &split);
  EXPECT_GT(split, 0u) << "seam vertices";
  const Result<std::string> glb = formats::encode_mesh(mesh, "james.glb", {}, &notes);
  ASSERT_TRUE(glb.ok()) << glb.error().to_string();
  EXPECT_TRUE(has_note(notes, "vertices on texture seams written once per texture coordinate"));

  const json doc = split_glb(*glb).first;
  ASSERT_EQ(doc["images"].size(), 1u);
  EXPECT_EQ(doc["images"][0]["mimeType"], "image/jpeg");
  EXPECT_EQ(doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
  const Result<Mesh> back = gltf::read(*glb, "james.glb");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back->vertex_count(), mesh.vertex_count()) << "the seams welded again";
  EXPECT_EQ(back->triangles, mesh.triangles);
  const std::vector<Vec2f> before = corner_texcoords(mesh), after = corner_texcoords(*back);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i)
    ASSERT_TRUE((after[i] - before[i]).cwiseAbs().maxCoeff() <= 0x1p-24F) << "corner " << i;
  ASSERT_TRUE(back->material && back->material->base_color_image);
  EXPECT_EQ(back->material->base_color_image->bytes, *read_file(path.parent_path() / "james.jpg"))
      << "the JPEG embedded unchanged";
}

TEST(GltfRead, ExternalImagesThroughTheResolverAndBadImages) {
  json doc = json::parse(fixture("square.gltf"));
  doc["images"] = {{{"uri", "skin%20photo.png"}}};
  doc["textures"] = {{{"source", 0}}};
  doc["materials"] = {{{"name", "skin"},
                       {"pbrMetallicRoughness",
                        {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"baseColorTexture", {{"index", 0}}}}}}};
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  const std::string png = *read_file(test::fixtures() / "obj" / "texture.png");
  Notes notes;
  // Without a resolver: a note, the uri kept.
  Result<Mesh> mesh = gltf::read(doc.dump(), "t.gltf", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_TRUE(mesh->material && mesh->material->base_color_image);
  EXPECT_EQ(mesh->material->name, "skin");
  EXPECT_EQ(mesh->material->base_color, Vec4f(0.5F, 0.5F, 0.5F, 1));
  EXPECT_TRUE(mesh->material->base_color_image->bytes.empty());
  EXPECT_TRUE(has_note(notes, "texture image 'skin%20photo.png' not read"));
  // With one.
  const Resolver resolve = [&](std::string_view) -> Result<std::string> { return png; };
  mesh = gltf::read(doc.dump(), "t.gltf", nullptr, resolve);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->material->base_color_image->bytes, png);
  // A corrupt image that is there: an error naming it.
  const Resolver corrupt = [&](std::string_view) -> Result<std::string> { return png.substr(0, 20); };
  const Error e = test::error_of(gltf::read(doc.dump(), "t.gltf", nullptr, corrupt));
  EXPECT_EQ(e.code, ErrorCode::Truncated) << e.to_string();
  // A texture index out of range.
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3;
  EXPECT_EQ(test::error_of(gltf::read(doc.dump(), "t.gltf")).code, ErrorCode::IndexOutOfRange);
}

TEST(GltfBadInput, EmbeddedImageBombIsRefusedAtItsByte) {
  Mesh face = small_face();
  face.texcoords.assign(face.vertex_count(), Vec2f(0.5F, 0.5F));
  std::string png = *read_file(test::fixtures() / "obj" / "texture.png");
  face.material = Material{.name = "m",
                           .base_color = Vec4f::Ones(),
                           .base_color_image = Image{.bytes = png, .mime_type = "image/png", .uri = {}}};
  Result<std::string> glb = gltf::write(face);
  ASSERT_TRUE(glb.ok()) << glb.error().to_string();
  const std::size_t at = glb->find(png);
  ASSERT_NE(at, std::string::npos);
  (*glb)[at + 16] = '\x7f'; // the width: 2 billion pixels
  const Error e = test::error_of(gltf::read(*glb, "bomb.glb"));
  EXPECT_EQ(e.code, ErrorCode::CountTooLarge) << e.to_string();
  EXPECT_EQ(e.where.byte, at + 16) << e.to_string();
}

TEST(GltfRoundTrip, DracoWithinHalfAQuantisationStep) {
  Mesh face = sample_face();
  face.units = Units::Millimetres;
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary);
    Notes notes;
    Result<std::string> bytes = gltf::write(face, {.binary = binary, .draco = drc::WriteOptions{}}, &notes);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    EXPECT_TRUE(has_note(notes, "quantises positions to 14 bits"));
    Result<Mesh> back = gltf::read(*bytes, binary ? "face.glb" : "face.gltf");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_EQ(back->vertex_count(), face.vertex_count());
    EXPECT_EQ(back->triangle_count(), face.triangle_count());
    EXPECT_EQ(back->units, Units::Millimetres);
    ASSERT_TRUE(back->has_normals());
    ASSERT_TRUE(back->has_colors());
    EXPECT_LE(sorted_axis_error(back->positions, face.positions), half_step(face, 14));
    EXPECT_GT(sorted_axis_error(back->positions, face.positions), 0.0);
  }
  // Level 0 keeps the order, so vertices compare one by one.
  Result<Mesh> ordered = gltf::read(
      *gltf::write(face, {.draco = drc::WriteOptions{.position_bits = 11, .level = 0}}), "face.glb");
  ASSERT_TRUE(ordered.ok()) << ordered.error().to_string();
  const double tolerance = half_step(face, 11);
  for (std::size_t i = 0; i < face.vertex_count(); ++i) {
    ASSERT_LE((ordered->positions[i] - face.positions[i]).cwiseAbs().maxCoeff(), tolerance) << i;
    ASSERT_GT(ordered->normals[i].dot(face.normals[i]), 0.999f) << i;
    ASSERT_LE((ordered->colors[i] - face.colors[i]).cwiseAbs().maxCoeff(), 0.5f / 255 + 1e-6f) << i;
  }
}

TEST(GltfRoundTrip, PointCloudsAsPoints) {
  Mesh cloud = small_face();
  cloud.triangles.clear();
  cloud.normals.clear();
  Notes notes;
  Result<std::string> bytes = gltf::write(cloud, {.draco = drc::WriteOptions{}}, &notes);
  ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
  EXPECT_TRUE(has_note(notes, "point cloud is written uncompressed"));
  EXPECT_EQ(split_glb(*bytes).first["meshes"][0]["primitives"][0]["mode"], 0);
  Result<Mesh> back = gltf::read(*bytes, "cloud.glb");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_TRUE(back->is_point_cloud());
  EXPECT_EQ(back->vertex_count(), cloud.vertex_count());
  EXPECT_FALSE(back->has_normals()); // none computed for points
}

TEST(GltfWrite, NormalsAreComputedAndUnit) {
  Mesh face = small_face();
  face.normals.clear();
  face.positions.emplace_back(0, 0, 100); // on no triangle: no normal of its own
  face.colors.emplace_back(1, 1, 1, 1);
  Notes notes;
  Result<Mesh> back = gltf::read(*gltf::write(face, {}, &notes), "face.glb");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  for (const Vec3f& n : back->normals)
    ASSERT_NEAR(n.norm(), 1.0f, 1e-6f);
  EXPECT_EQ(back->normals.back(), Vec3f(0, 0, 1));
  EXPECT_TRUE(has_note(notes, "1 vertex without a usable normal"));
  const std::vector<Vec3f> expected = vertex_normals(face);
  EXPECT_TRUE(back->normals[10].isApprox(expected[10], 1e-6f));
}

TEST(GltfWrite, DracoJsonIsWhatTheExtensionAsks) {
  Mesh face = small_face();
  face.texcoords.assign(face.vertex_count(), Vec2f(0.5f, 0.5f));
  const auto [doc, bin] = split_glb(*gltf::write(face, {.draco = drc::WriteOptions{.color_bits = 16}}));
  EXPECT_EQ(doc["extensionsUsed"], json::array({"KHR_draco_mesh_compression"}));
  EXPECT_EQ(doc["extensionsRequired"], json::array({"KHR_draco_mesh_compression"}));
  EXPECT_TRUE(doc["asset"]["generator"].get<std::string>().starts_with("pdeface "));
  const json& primitive = doc["meshes"][0]["primitives"][0];
  const json& draco = primitive["extensions"]["KHR_draco_mesh_compression"];
  const json& view = doc["bufferViews"][draco["bufferView"].get<int>()];
  EXPECT_FALSE(view.contains("target"));
  EXPECT_EQ(view["byteLength"], doc["buffers"][0]["byteLength"]);
  EXPECT_TRUE(bin.starts_with("DRACO"));
  EXPECT_EQ(draco["attributes"].size(), 4u);
  for (const auto& [name, index] : primitive["attributes"].items()) {
    const json& a = doc["accessors"][index.get<int>()];
    EXPECT_FALSE(a.contains("bufferView")) << name;
    EXPECT_EQ(a["count"], face.vertex_count()) << name;
    EXPECT_TRUE(draco["attributes"].contains(name)) << name;
  }
  const json& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(position["min"].size(), 3u);
  EXPECT_EQ(position["max"].size(), 3u);
  const json& color = doc["accessors"][primitive["attributes"]["COLOR_0"].get<int>()];
  EXPECT_EQ(color["componentType"], 5123); // 16-bit colours
  EXPECT_EQ(color["normalized"], true);
  EXPECT_EQ(doc["accessors"][primitive["indices"].get<int>()]["count"], 3 * face.triangle_count());
}

TEST(GltfWrite, RefusesBadOptionsAndMeshes) {
  Result<std::string> bits = gltf::write(small_face(), {.draco = drc::WriteOptions{.position_bits = 30}});
  ASSERT_FALSE(bits.ok());
  EXPECT_EQ(bits.error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(gltf::write(Mesh{}).error().code, ErrorCode::Empty);
  Mesh nan = small_face();
  nan.positions[5].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(gltf::write(nan).error().code, ErrorCode::NonFinite);
}

// ---- bad input -----------------------------------------------------------------------------------------

TEST(GltfBadInput, HandMadeFixtures) {
  const std::string bin_chunk = fixture("bin_chunk_past_end.glb");
  const std::string square = fixture("square.glb");
  const std::uint64_t bin = 28 + u32_at(square, 12); // where square.glb's BIN data starts
  struct Case {
    const char* file;
    ErrorCode code;
    Location where;
    std::string_view message;
  };
  for (const Case& c : {
           Case{"bad_magic.glb", ErrorCode::BadMagic, Location::at_byte(0), "not glTF"},
           Case{"bad_version.glb", ErrorCode::UnsupportedVersion, Location::at_byte(4), "GLB version 1"},
           Case{"json_chunk_past_end.glb", ErrorCode::Malformed, Location::at_byte(12),
                "claims 100000 bytes"},
           Case{"bin_chunk_past_end.glb", ErrorCode::Malformed, Location::at_byte(20 + u32_at(bin_chunk, 12)),
                "the BIN chunk claims 64 bytes"},
           Case{"truncated.glb", ErrorCode::Truncated, Location::at_byte(646), "says 656 bytes"},
           Case{"syntax_error.gltf", ErrorCode::Malformed, Location::at_line(4, 10),
                "invalid JSON: syntax error"},
           Case{"external_buffer.gltf",
                ErrorCode::UnsupportedFormat,
                {},
                "external buffer 'square.bin' not supported: use .glb or embedded data URIs"},
           Case{"missing_position.gltf", ErrorCode::Malformed, {}, "has no POSITION attribute"},
           Case{"accessor_past_end.gltf",
                ErrorCode::Malformed,
                {},
                "run past the end of bufferView 0 (48 bytes)"},
           Case{"index_out_of_range.glb", ErrorCode::IndexOutOfRange, Location::at_byte(bin + 48 + 5 * 2),
                "index 5 is 7, but the primitive has 4 vertices"},
           Case{"nan_position.glb", ErrorCode::NonFinite, Location::at_byte(bin + 2 * 12 + 4),
                "element 2 of accessor 0 is not finite"},
       }) {
    SCOPED_TRACE(c.file);
    const Result<Mesh> result = gltf::read(fixture(c.file), c.file);
    expect_error(result, c.code, c.where, c.file);
    expect_message(result, c.message);
  }
}

TEST(GltfBadInput, EmptyAndTinyInputs) {
  expect_error(gltf::read("", "bad.glb"), ErrorCode::Empty, Location::at_byte(0));
  expect_error(gltf::read("gl", "bad.glb"), ErrorCode::Truncated, Location::at_byte(2));
  expect_error(gltf::read(std::string("glTF\x02\0\0\0", 8), "bad.glb"), ErrorCode::Truncated,
               Location::at_byte(8));
  expect_error(gltf::read("solid cube", "bad.glb"), ErrorCode::BadMagic, Location::at_byte(0));
  expect_error(gltf::read("[1, 2]", "bad.glb"), ErrorCode::BadMagic, Location::at_byte(0));
  // The JSON ends after the '{': the error is where the data ends.
  expect_error(gltf::read("  {", "bad.gltf"), ErrorCode::Malformed, Location::at_line(1, 4), "bad.gltf");
}

TEST(GltfBadInput, GlbHeaderAndChunks) {
  const std::string good = fixture("square.glb");
  const std::uint32_t json_length = u32_at(good, 12);
  const std::size_t bin_header = 20 + json_length;
  auto edited = [&](std::size_t offset, std::uint32_t value) {
    std::string bytes = good;
    put_u32(bytes, offset, value);
    return gltf::read(bytes, "bad.glb");
  };
  expect_error(edited(8, 16), ErrorCode::Malformed, Location::at_byte(8));           // length < 20
  expect_error(edited(16, 0x12345678), ErrorCode::Malformed, Location::at_byte(16)); // not JSON
  expect_error(edited(12, 0), ErrorCode::Malformed, Location::at_byte(12));          // empty JSON
  expect_error(edited(bin_header + 4, 0x41414141), ErrorCode::Malformed, Location::at_byte(bin_header + 4));
  expect_error(edited(bin_header, 58), ErrorCode::Malformed, Location::at_byte(bin_header)); // not 4n
  // A BIN chunk ending exactly at the end of the file, its 8-byte header forgotten: tinygltf would read 8
  // bytes past the end of the data.
  expect_error(edited(bin_header, static_cast<std::uint32_t>(good.size() - bin_header)), ErrorCode::Malformed,
               Location::at_byte(bin_header));
  // Stray bytes after the JSON chunk, too few for a chunk header.
  std::string stray = good.substr(0, bin_header) + "abc";
  put_u32(stray, 8, static_cast<std::uint32_t>(stray.size()));
  expect_error(gltf::read(stray, "bad.glb"), ErrorCode::Malformed, Location::at_byte(bin_header));
  // Bytes after the declared length: ignored, with a note.
  Notes notes;
  EXPECT_TRUE(gltf::read(good + "trailing", "square.glb", &notes).ok());
  EXPECT_TRUE(has_note(notes, "8 bytes after the end of the GLB ignored"));
}

TEST(GltfBadInput, JsonProblemsAreLocated) {
  const std::string good = fixture("square.glb");
  // A syntax error in a GLB's JSON: located by byte in the file.
  std::string bytes = good;
  const std::size_t brace = good.find("\"scene\"");
  bytes[brace] = '?';
  expect_error(gltf::read(bytes, "bad.glb"), ErrorCode::Malformed, Location::at_byte(brace));
  // Nesting deeper than 64 levels (tinygltf converts extras recursively): the root object is level 1, so
  // the 64th '[' (after `{"extras":`) is the first too deep.
  json doc = json::parse(fixture("square.gltf"));
  std::string deep = std::string(100, '[') + std::string(100, ']');
  std::string text = doc.dump();
  text.insert(1, "\"extras\":" + deep + ",");
  expect_error(gltf::read(text, "bad.gltf"), ErrorCode::Malformed, Location::at_line(1, 10 + 64), "bad.gltf");
  expect_error(gltf::read("{\"asset\": 1} 2", "bad.gltf"), ErrorCode::Malformed, Location::at_line(1, 14),
               "bad.gltf");
  // Versions and extensions.
  doc["asset"]["version"] = "1.0";
  const Result<Mesh> version = gltf::read(doc.dump(), "bad.gltf");
  expect_error(version, ErrorCode::UnsupportedVersion, {}, "bad.gltf");
  expect_message(version, "glTF 1.0: we read glTF 2.0");
  doc["asset"]["version"] = "2.0";
  doc["extensionsRequired"] = {"KHR_materials_unlit", "EXT_meshopt_compression"};
  const Result<Mesh> extension = gltf::read(doc.dump(), "bad.gltf");
  expect_error(extension, ErrorCode::UnsupportedFormat, {}, "bad.gltf");
  expect_message(extension, "requires the extension EXT_meshopt_compression");
}

TEST(GltfBadInput, BuffersAndViews) {
  const json square = json::parse(fixture("square.gltf"));
  auto read = [](const json& doc) { return gltf::read(doc.dump(), "bad.gltf"); };
  json doc = square;
  doc["buffers"][0].erase("uri");
  expect_message(read(doc), "buffers[0] has no uri");
  doc = square;
  doc["buffers"][0]["byteLength"] = 64;
  expect_message(read(doc), "buffers[0]: its data URI holds 60 bytes, its byteLength says 64");
  doc = square;
  doc["bufferViews"][1]["byteOffset"] = 52;
  expect_message(read(doc), "bufferViews[1] covers bytes 52..64 of buffers[0], which has 60");
  doc = square;
  doc["buffers"][0]["uri"] = "data:text/html,<p>hello</p>";
  expect_message(read(doc), "not base64");
  doc = square;
  doc["accessors"][0]["sparse"] = {{"count", 1},
                                   {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
                                   {"values", {{"bufferView", 0}}}};
  expect_message(read(doc), "is sparse");
  doc = square;
  doc["bufferViews"][0]["byteStride"] = 8;
  expect_message(read(doc), "stride 8 is shorter than an element (12 bytes)");
  // GLB: buffer 0 longer than the BIN chunk.
  auto [glb_doc, bin] = split_glb(fixture("square.glb"));
  glb_doc["buffers"][0]["byteLength"] = 100;
  const std::string glb = make_glb(glb_doc, bin);
  expect_error(gltf::read(glb, "bad.glb"), ErrorCode::Malformed, Location::at_byte(20 + u32_at(glb, 12)));
}

TEST(GltfBadInput, HostileNodeHierarchies) {
  const json square = json::parse(fixture("square.gltf"));
  auto read = [](const json& doc) { return gltf::read(doc.dump(), "bad.gltf"); };
  json doc = square;
  doc["nodes"][0]["children"] = {0};
  expect_message(read(doc), "node 0 is reached twice");
  doc = square;
  doc["scenes"][0]["nodes"] = {5};
  expect_message(read(doc), "node 5 does not exist");
  doc = square;
  doc["nodes"][0]["mesh"] = 3;
  expect_message(read(doc), "mesh 3 does not exist");
  doc = square;
  doc["scene"] = 4;
  expect_message(read(doc), "the default scene 4 does not exist");
  doc = square;
  doc["nodes"][0]["matrix"] = std::vector<double>(15, 1.0);
  expect_message(read(doc), "a matrix needs 16 numbers");
  // A chain of 50000 nodes (recursion would take more than the 8 MB stack): walked without recursion.
  doc = square;
  doc["nodes"] = json::array();
  for (int i = 0; i < 100000; ++i)
    doc["nodes"].push_back({{"children", {i + 1}}});
  doc["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, 1}}});
  Result<Mesh> chain = read(doc);
  ASSERT_TRUE(chain.ok()) << chain.error().to_string();
  EXPECT_EQ(chain->positions[0], Vec3(0, 0, 1));
}

TEST(GltfBadInput, InstancingIsBounded) {
  // 1000 points, placed by k nodes.
  std::vector<float> points;
  for (int i = 0; i < 3000; ++i)
    points.push_back(static_cast<float>(i));
  const std::string bin = bytes_of(points);
  const json meshes = {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 0}}}}}};
  auto placed = [&](int k) {
    json nodes = json::array(), roots = json::array();
    for (int i = 0; i < k; ++i) {
      nodes.push_back({{"mesh", 0}, {"translation", {i, 0, 0}}});
      roots.push_back(i);
    }
    return make_glb(document(bin, {{0, bin.size()}}, json::array({accessor(0, 5126, 1000, "VEC3")}), meshes,
                             nodes, {{{"nodes", roots}}}),
                    bin);
  };
  Result<Mesh> few = gltf::read(placed(20), "few.glb");
  ASSERT_TRUE(few.ok()) << few.error().to_string();
  EXPECT_EQ(few->vertex_count(), 20000u);
  const std::string many = placed(2000); // ~50 KB placing 2 million points
  expect_error(gltf::read(many, "bad.glb"), ErrorCode::CountTooLarge, {});
}

// KHR_draco_mesh_compression primitives that would crash or mislead tinygltf's unchecked decoding.
TEST(GltfBadInput, HostileDracoPrimitives) {
  // Not a structured binding: clang 14 (the sanitizer build) cannot capture one in a lambda.
  const auto split = split_glb(*gltf::write(small_face(), {.draco = drc::WriteOptions{}}));
  const json& good = split.first;
  const std::string& bin = split.second;
  auto read = [&](const json& doc, std::string data) {
    return gltf::read(make_glb(doc, std::move(data)), "bad.glb");
  };
  const std::string ext = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";
  auto with = [&](const std::string& pointer, const json& value) {
    json doc = good;
    doc[json::json_pointer(pointer)] = value;
    return doc;
  };
  expect_message(read(with(ext + "/bufferView", 7), bin), "needs a bufferView that exists");
  expect_message(read(with(ext + "/bufferView", -1), bin), "needs a bufferView that exists");
  expect_message(read(with(ext + "/attributes/NORMAL", 9), bin),
                 "the Draco data has no attribute 9 (for NORMAL)");
  expect_message(read(with(ext + "/attributes/NORMAL", -3), bin), "is not a Draco attribute id");
  expect_message(read(with("/meshes/0/primitives/0/attributes/NORMAL", 40), bin), "not an accessor index");
  expect_message(read(with("/accessors/1/type", "VEC4"), bin), "NORMAL has 3 components in the Draco data");
  expect_message(read(with("/accessors/3/componentType", 5121), bin),
                 "do not fit its indices' component type");
  expect_message(read(with("/accessors/3/componentType", 5126), bin), "unsigned byte, short or int");
  expect_message(read(with("/meshes/0/primitives/0/mode", 0), bin), "TRIANGLES (4) or TRIANGLE_STRIP (5)");
  json no_indices = good;
  no_indices["meshes"][0]["primitives"][0].erase("indices");
  expect_message(read(no_indices, bin), "needs an indices accessor");
  // Damaged Draco data: located in the file (the BIN chunk starts after the JSON chunk).
  std::string damaged = bin;
  damaged[5] = 7; // bitstream version 7.2
  const std::string glb = make_glb(good, damaged);
  expect_error(gltf::read(glb, "bad.glb"), ErrorCode::UnsupportedVersion,
               Location::at_byte(28 + u32_at(glb, 12) + 5));
  // A Draco point cloud where a mesh is due.
  Mesh cloud = small_face();
  cloud.triangles.clear();
  const std::string points = *drc::write(cloud);
  json doc = with("/buffers/0/byteLength", points.size());
  doc["bufferViews"][0]["byteLength"] = points.size();
  expect_message(read(doc, points), "holds no triangles");
  // An attribute of 16 components (tinygltf would copy it into a 4-element array on the stack).
  const Result<std::string> wide = read_file(test::fixtures() / "draco" / "square_generic16.drc");
  ASSERT_TRUE(wide.ok());
  const json wide_doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", wide->size()}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", wide->size()}}}},
      {"accessors",
       {{{"componentType", 5126}, {"count", 9}, {"type", "VEC3"}},
        {{"componentType", 5126}, {"count", 9}, {"type", "MAT4"}},
        {{"componentType", 5123}, {"count", 24}, {"type", "SCALAR"}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"_WIDE", 1}}},
            {"indices", 2},
            {"extensions",
             {{"KHR_draco_mesh_compression",
               {{"bufferView", 0}, {"attributes", {{"POSITION", 0}, {"_WIDE", 1}}}}}}}}}}}}}};
  expect_message(read(wide_doc, *wide), "_WIDE has 16 components in the Draco data, at most 4 are allowed");
  // Two primitives sharing one Draco stream with accessors of their own: tinygltf decodes the stream once,
  // for the first, and leaves the second's accessors without data.
  doc = good;
  json second = doc["meshes"][0]["primitives"][0];
  for (auto& [name, index] : second["attributes"].items()) {
    doc["accessors"].push_back(doc["accessors"][index.get<int>()]);
    index = doc["accessors"].size() - 1;
  }
  doc["meshes"][0]["primitives"].push_back(second);
  expect_message(read(doc, bin), "has no data (no bufferView)");
}

// Every prefix of small valid files: an error or a valid mesh, never a crash (run under the sanitizers).
TEST(GltfBadInput, EveryTruncationLengthFailsCleanly) {
  Mesh face = small_face();
  face.units = Units::Millimetres;
  std::vector<std::string> files = {*gltf::write(face), *gltf::write(face, {.draco = drc::WriteOptions{}}),
                                    fixture("square.gltf")};
  for (const std::string& bytes : files)
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      const Result<Mesh> result = gltf::read(std::string_view(bytes).substr(0, n), "bad.glb");
      if (result.ok()) {
        EXPECT_TRUE(validate(*result).ok());
      } else {
        ASSERT_EQ(result.error().source, "bad.glb");
        ASSERT_TRUE(result.error().where.known()) << n << ": " << result.error().to_string();
      }
    }
}

// Random byte changes of small valid files, binary and text: never a crash.
TEST(GltfBadInput, RandomMutationsFailCleanly) {
  Mesh face = small_face();
  const std::vector<std::string> files = {*gltf::write(face),
                                          *gltf::write(face, {.draco = drc::WriteOptions{}}),
                                          fixture("square.gltf"), fixture("square.glb")};
  std::mt19937 random(11);
  for (const std::string& original : files)
    for (int trial = 0; trial < 400; ++trial) {
      std::string bytes = original;
      for (int k = 0; k < 1 + trial % 3; ++k) {
        const std::size_t at =
            trial % 2 ? random() % std::min<std::size_t>(bytes.size(), 2000) : random() % bytes.size();
        bytes[at] = static_cast<char>(trial % 4 ? random() : "0123456789{}[],:\"-"[random() % 18]);
      }
      const Result<Mesh> result = gltf::read(bytes, "bad.glb");
      if (result.ok()) {
        EXPECT_TRUE(validate(*result).ok());
      }
    }
}

} // namespace
} // namespace pdeface
