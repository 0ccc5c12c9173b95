// The VRML writer, and round trips through the reader.

#include "vrml_test_support.hpp"

#include "test_meshes.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include <cmath>
#include <limits>

namespace pdeface::test {
namespace {

Mesh round_trip(const Mesh& mesh, const vrml::WriteOptions& options = {}, Notes* notes = nullptr) {
  Result<std::string> bytes = vrml::write(mesh, options, notes);
  EXPECT_TRUE(bytes.ok()) << bytes.error().to_string();
  if (!bytes) return {};
  Result<Mesh> back = vrml::read(*bytes, "round-trip.wrl", notes);
  EXPECT_TRUE(back.ok()) << back.error().to_string();
  return back ? std::move(back).value() : Mesh{};
}

//! The sample face with its coordinates rounded to floats, as a float format would hold them.
Mesh float_sample_face() {
  Mesh mesh = sample_face();
  for (Vec3& p : mesh.positions)
    p = p.cast<float>().cast<double>();
  return mesh;
}

TEST(VrmlWrite, SampleFaceRoundTripIsExactForFloatData) {
  const Mesh mesh = float_sample_face();
  ASSERT_TRUE(mesh.has_colors() && mesh.has_normals());
  const Mesh back = round_trip(mesh);
  ASSERT_EQ(back.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(back.triangles, mesh.triangles);
  // 9 significant digits name each float exactly: read back and rounded to float, nothing changed.
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
    ASSERT_EQ(back.positions[i].cast<float>(), mesh.positions[i].cast<float>()) << "vertex " << i;
  EXPECT_EQ(back.normals, mesh.normals);
  EXPECT_EQ(back.colors, mesh.colors); // RGB exact, alpha 1 as the sample has
  EXPECT_EQ(back.units, Units::Millimetres);
  EXPECT_EQ(back.name, mesh.name);
}

TEST(VrmlWrite, SeventeenDigitsRoundTripDoublesBitForBit) {
  const Mesh mesh = sample_face();
  const Mesh back = round_trip(mesh, {.precision = 17});
  ASSERT_EQ(back.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(back.positions, mesh.positions);
}

TEST(VrmlWrite, FewerDigitsStayWithinTheirRounding) {
  const Mesh mesh = sample_face();
  const Mesh back = round_trip(mesh, {.precision = 5});
  ASSERT_EQ(back.vertex_count(), mesh.vertex_count());
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_LE(std::abs(back.positions[i][k] - mesh.positions[i][k]), 5e-5 * std::abs(mesh.positions[i][k]))
          << "vertex " << i;
}

TEST(VrmlWrite, PointCloudBecomesAPointSet) {
  Mesh cloud = sample_face();
  cloud.triangles.clear();
  Notes notes;
  Result<std::string> bytes = vrml::write(cloud, {}, &notes);
  ASSERT_TRUE(bytes.ok());
  EXPECT_NE(bytes->find("geometry PointSet {"), std::string::npos);
  EXPECT_TRUE(has_note(notes, "normals dropped: a VRML PointSet cannot hold them"));
  const Mesh back = round_trip(cloud);
  EXPECT_TRUE(back.is_point_cloud());
  EXPECT_EQ(back.vertex_count(), cloud.vertex_count());
  EXPECT_EQ(back.colors, cloud.colors);
  EXPECT_FALSE(back.has_normals());
}

TEST(VrmlWrite, TextureCoordinatesRoundTrip) {
  Mesh mesh = unit_square();
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0.25F, 0.75F}};
  EXPECT_EQ(round_trip(mesh).texcoords, mesh.texcoords);
}

TEST(VrmlWrite, SeamsAndAppearanceRoundTrip) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0.5F, 0.5F}};
  mesh.texcoord_triangles = {{0, 1, 2}, {3, 2, 0}};
  mesh.material = Material{.name = "m", .base_color = Vec4f(0.5F, 0.25F, 1, 1), .base_color_image = {}};
  const Result<std::string> text = vrml::write(mesh, {.precision = 9, .texture_url = "face.jpg"});
  ASSERT_TRUE(text.ok()) << text.error().to_string();
  EXPECT_NE(text->find("texture ImageTexture { url \"face.jpg\" }"), std::string::npos) << *text;
  Notes notes;
  const Result<Mesh> back = vrml::read(*text, "t.wrl", &notes);
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back->triangles, mesh.triangles);
  EXPECT_EQ(corner_texcoords(*back), corner_texcoords(mesh));
  ASSERT_TRUE(back->material && back->material->base_color_image);
  EXPECT_EQ(back->material->base_color_image->uri, "face.jpg");
  EXPECT_TRUE(test::has_note(notes, "texture image 'face.jpg' not read"));
}

TEST(VrmlWrite, AlphaIsDroppedWithANote) {
  Mesh mesh = unit_square();
  mesh.colors.assign(4, Vec4f(1, 0.5F, 0, 0.5F));
  Notes notes;
  const Mesh back = round_trip(mesh, {}, &notes);
  EXPECT_TRUE(has_note(notes, "colour alpha dropped"));
  EXPECT_EQ(back.colors, std::vector<Vec4f>(4, Vec4f(1, 0.5F, 0, 1)));
}

TEST(VrmlWrite, WritesAVrml2ShapeAndStatesOnlyWhatIsKnown) {
  Mesh mesh = unit_square();
  Result<std::string> bytes = vrml::write(mesh);
  ASSERT_TRUE(bytes.ok());
  EXPECT_TRUE(bytes->starts_with("#VRML V2.0 utf8\n"));
  EXPECT_NE(bytes->find("solid FALSE"), std::string::npos);
  EXPECT_NE(bytes->find("      0 1 2 -1,\n      0 2 3 -1,\n"), std::string::npos);
  EXPECT_EQ(bytes->find("WorldInfo"), std::string::npos); // no name, no units: nothing to state
  EXPECT_EQ(round_trip(mesh).units, Units::Unknown);

  mesh.name = "a \"quoted\" \\ name";
  mesh.units = Units::Inches;
  const Mesh back = round_trip(mesh);
  EXPECT_EQ(back.name, mesh.name);
  EXPECT_EQ(back.units, Units::Inches);
}

TEST(VrmlWrite, RejectsBadOptionsAndBadMeshes) {
  EXPECT_EQ(vrml::write(unit_square(), {.precision = 0}).error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(vrml::write(unit_square(), {.precision = 18}).error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(vrml::write(Mesh{}).error().code, ErrorCode::Empty);
  Mesh bad = unit_square();
  bad.triangles.push_back({0, 1, 4});
  EXPECT_EQ(vrml::write(bad).error().code, ErrorCode::IndexOutOfRange);
  bad = unit_square();
  bad.positions[1].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(vrml::write(bad).error().code, ErrorCode::NonFinite);
}

TEST(VrmlWrite, ThroughTheFormatsDispatcher) {
  const Mesh mesh = float_sample_face();
  Result<std::string> bytes = formats::encode_mesh(mesh, "face.wrl");
  ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
  Result<formats::LoadedMesh> loaded = formats::read_mesh(*bytes, "face.wrl");
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  EXPECT_EQ(loaded->format, formats::Format::Vrml);
  EXPECT_EQ(loaded->mesh.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(loaded->mesh.triangle_count(), mesh.triangle_count());
}

} // namespace
} // namespace pdeface::test
