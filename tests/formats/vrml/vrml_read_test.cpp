// The VRML reader on well-formed input: the real scans, and one hand-made fixture per construct.

#include "vrml_test_support.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace pdeface::test {
namespace {

constexpr double kTight = 1e-12;

Mesh read_fixture(std::string_view name, Notes* notes = nullptr) {
  Result<Mesh> mesh = vrml::read(vrml_fixture(name), name, notes);
  EXPECT_TRUE(mesh.ok()) << (mesh ? "" : mesh.error().to_string());
  return mesh ? std::move(mesh).value() : Mesh{};
}

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance = kTight) {
  EXPECT_LT((actual - expected).norm(), tolerance)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// --- the real scans ----------------------------------------------------------------------------------------

TEST(VrmlRealScans, FranCutIsVrml1WithTheManifestCounts) {
  PDEFACE_FACE_OR_SKIP(path, "fran_cut.wrl");
  Result<std::string> bytes = read_file(path);
  ASSERT_TRUE(bytes.ok());
  Notes notes;
  Result<Mesh> mesh = vrml::read(*bytes, "fran_cut.wrl", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 2205U);
  EXPECT_EQ(mesh->triangle_count(), 4224U);
  EXPECT_EQ(mesh->units, Units::Unknown); // the file does not say
  // No transform in the file: the first point as written.
  EXPECT_EQ(mesh->positions.front(), Vec3(0.0, -0.2048, -0.090616));
  EXPECT_TRUE(notes.empty()) << notes.front();
}

TEST(VrmlRealScans, StfacesIsVrml2WithItsTransformApplied) {
  PDEFACE_FACE_OR_SKIP(path, "stfaces_neutral.wrl");
  Result<std::string> bytes = read_file(path);
  ASSERT_TRUE(bytes.ok());
  Result<Mesh> mesh = vrml::read(*bytes, "stfaces_neutral.wrl");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 7118U);
  EXPECT_EQ(mesh->triangle_count(), 14037U);
  EXPECT_EQ(mesh->units, Units::Unknown); // "units: see MANIFEST" names no unit

  // The file's Transform: rotation 0.7093073 -0.7048475 -0.0085472 -0.1904737, translation 12.5 -40 3.
  // Its first point, rotated by Rodrigues' formula written out here, then translated.
  const Vec3 p(106.26671, -52.83667, 1222.30080);
  const Vec3 axis = Vec3(0.7093073, -0.7048475, -0.0085472).normalized();
  const double angle = -0.1904737;
  const Vec3 rotated =
      p * std::cos(angle) + axis.cross(p) * std::sin(angle) + axis * axis.dot(p) * (1.0 - std::cos(angle));
  expect_near(mesh->positions.front(), rotated + Vec3(12.5, -40.0, 3.0), 1e-9);
}

// --- VRML 2.0 ----------------------------------------------------------------------------------------------

TEST(VrmlRead, NestedTransformsComposeWithCenterAndScaleOrientation) {
  const Mesh mesh = read_fixture("v2_transforms.wrl");
  ASSERT_EQ(mesh.vertex_count(), 3U);
  // Worked by hand (see the fixture): inner translation z+5, then minus center (1,0,0), y doubled (x
  // scaled along axes turned 90 degrees), rotated 90 degrees about z, plus center, plus (10,0,0).
  expect_near(mesh.positions[0], Vec3(9, 0, 5));   // (1,1,0)
  expect_near(mesh.positions[1], Vec3(11, -1, 5)); // (0,0,0)
  expect_near(mesh.positions[2], Vec3(11, 1, 5));  // (2,0,0)
  ASSERT_EQ(mesh.triangle_count(), 1U);
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 1, 2}));
}

TEST(VrmlRead, DefUseInstancesShapesAndSharesCoordinates) {
  const Mesh mesh = read_fixture("v2_instancing.wrl");
  ASSERT_EQ(mesh.vertex_count(), 24U);
  ASSERT_EQ(mesh.triangle_count(), 8U);
  const Vec3 corner(1, 0, 0);
  expect_near(mesh.positions[1], corner);                  // DEF Tri itself
  expect_near(mesh.positions[4], corner + Vec3(5, 0, 0));  // USE Tri under translation 5 0 0
  expect_near(mesh.positions[7], corner + Vec3(0, 5, 0));  // USE Tri in brackets
  expect_near(mesh.positions[10], corner);                 // USE TriCoords
  EXPECT_EQ(mesh.triangles[3], (Triangle{11, 10, 9}));     //   with its own coordIndex
  expect_near(mesh.positions[13], corner);                 // DEF Pair
  expect_near(mesh.positions[16], corner + Vec3(0, 0, 9)); // USE Pair under translation 0 0 9
  EXPECT_EQ(mesh.triangles[5], (Triangle{15, 16, 17}));
  expect_near(mesh.positions[19], corner + Vec3(0, 0, 20)); // DEF Lifted (a Transform)
  expect_near(mesh.positions[22], corner + Vec3(1, 0, 20)); // USE Lifted under translation 1 0 0
  EXPECT_EQ(mesh.triangles[7], (Triangle{21, 22, 23}));
}

TEST(VrmlRead, PolygonsAreFanTriangulatedAndCcwFalseFlips) {
  Notes notes;
  const Mesh mesh = read_fixture("v2_polygons.wrl", &notes);
  ASSERT_EQ(mesh.vertex_count(), 12U);
  const std::vector<Triangle> expected{{0, 1, 2},  {0, 2, 3},            // the quad
                                       {4, 5, 6},  {4, 6, 7}, {4, 7, 8}, // the pentagon
                                       {2, 5, 6},                        // the polygon without -1
                                       {9, 11, 10}};                     // ccw FALSE
  EXPECT_EQ(mesh.triangles, expected);
  EXPECT_TRUE(has_note(notes, "1 polygons with fewer than 3 vertices skipped"));
}

TEST(VrmlRead, SkipsProtosRoutesScriptsAndEverythingElseItDoesNotNeed) {
  Notes notes;
  const Mesh mesh = read_fixture("v2_skipped.wrl", &notes);
  ASSERT_EQ(mesh.vertex_count(), 3U);
  EXPECT_EQ(mesh.positions[1], Vec3(1, 0, 0)); // "1,0,0,0 1 0": commas are whitespace
  EXPECT_EQ(mesh.positions[2], Vec3(0, 1, 0));
  EXPECT_EQ(mesh.triangle_count(), 1U);
  EXPECT_EQ(mesh.units, Units::Millimetres);
  EXPECT_EQ(mesh.name, "skip \"everything\" {");
  EXPECT_TRUE(has_notes(notes, {"v2_skipped.wrl:25:1: Inline other.wrl not followed",
                                "v2_skipped.wrl:26:1: instance of PROTO Face skipped",
                                "v2_skipped.wrl:27:1: instance of PROTO Marker skipped",
                                "Shape geometry Sphere ignored"}));
}

TEST(VrmlRead, EveryGroupingNodeDrawsWhatItShould) {
  Notes notes;
  const Mesh mesh = read_fixture("v2_groups.wrl", &notes);
  ASSERT_EQ(mesh.triangle_count(), 7U);
  // One copy of T per height 0..6, in file order; nothing from the choices not taken.
  for (std::size_t i = 0; i < 7; ++i)
    expect_near(mesh.positions[3 * i], Vec3(0, 0, static_cast<double>(i)));
  EXPECT_TRUE(has_notes(notes, {"LOD: the first (finest) of its 2 levels is read",
                                "Billboard: its rotation towards the viewer is not applied"}));
}

TEST(VrmlRead, KeepsAttributesThatMapOneToOneOntoVertices) {
  Notes notes;
  const Mesh mesh = read_fixture("v2_attributes.wrl", &notes);
  ASSERT_EQ(mesh.vertex_count(), 4U);
  EXPECT_EQ(mesh.colors, (std::vector<Vec4f>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}}));
  EXPECT_EQ(mesh.normals, std::vector<Vec3f>(4, Vec3f(0, 0, 1)));
  EXPECT_EQ(mesh.texcoords, (std::vector<Vec2f>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_TRUE(notes.empty());
}

TEST(VrmlRead, NormalsFollowTheTransform) {
  const Result<Mesh> mesh = read_vrml(R"(#VRML V2.0 utf8
Transform { rotation 1 0 0 1.5707963267948966 scale 1 1 4
  children Shape { geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 -1 ]
    normal Normal { vector [ 0 0 1, 0 0 1, 0 0 1 ] } } } }
)");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_EQ(mesh->normals.size(), 3U);
  // z scaled by 4 keeps a z normal (unit again); the rotation about x takes +z to -y.
  EXPECT_LT((mesh->normals[0] - Vec3f(0, -1, 0)).norm(), 1e-6F);
}

struct DroppedAttribute {
  const char* name;
  const char* fields;
  const char* note;
};

class VrmlDroppedAttribute : public ::testing::TestWithParam<DroppedAttribute> {};

TEST_P(VrmlDroppedAttribute, IsDroppedWithANote) {
  const std::string text = std::string(R"(#VRML V2.0 utf8
Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }
  coordIndex [ 0 1 2 -1, 0 2 3 -1 ]
  )") + GetParam().fields + " } }\n";
  Notes notes;
  const Result<Mesh> mesh = read_vrml(text, &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangle_count(), 2U);
  EXPECT_FALSE(mesh->has_colors() || mesh->has_normals() || mesh->has_texcoords());
  EXPECT_TRUE(has_note(notes, GetParam().note));
}

INSTANTIATE_TEST_SUITE_P(
    VrmlRead, VrmlDroppedAttribute,
    ::testing::Values(
        DroppedAttribute{"PerFaceColours", "colorPerVertex FALSE color Color { color [ 1 0 0, 0 1 0 ] }",
                         "test.wrl:2:18: colours dropped: colorPerVertex FALSE gives one per face"},
        DroppedAttribute{"PerFaceNormals", "normalPerVertex FALSE normal Normal { vector [ 0 0 1, 0 0 1 ] }",
                         "normals dropped: normalPerVertex FALSE gives one per face"},
        DroppedAttribute{"TooFewColours", "color Color { color [ 1 0 0, 0 1 0 ] }",
                         "colours dropped: 2 of them for 4 points"},
        DroppedAttribute{"TexCoordIndexLength",
                         "texCoord TextureCoordinate { point [ 0 0, 1 0 ] } texCoordIndex [ 0 1 0 -1 ]",
                         "texture coordinates dropped: texCoordIndex has 4 entries where coordIndex has 8"},
        DroppedAttribute{"IndexLength", "color Color { color [ 1 0 0 ] } colorIndex [ 0 0 0 -1 ]",
                         "colours dropped: colorIndex has 4 entries where coordIndex has 8"},
        DroppedAttribute{"IndexSeparators",
                         "color Color { color [ 1 0 0 ] } colorIndex [ 0 0 -1 0 0 0 0 -1 ]",
                         "colorIndex and coordIndex do not end polygons at the same places"}),
    [](const auto& test) { return std::string(test.param.name); });

// A seam: vertex 2 has texture coordinate 0 on the first triangle and 1 on the second; kept per corner.
TEST(VrmlRead, SeamsKeepTextureCoordinatesPerCornerAndTheAppearance) {
  const std::string png = *read_file(test::fixtures() / "obj" / "texture.png");
  std::vector<std::string> asked;
  const Resolver resolve = [&](std::string_view name) -> Result<std::string> {
    asked.emplace_back(name);
    return png;
  };
  Notes notes;
  const Result<Mesh> mesh = vrml::read(R"(#VRML V2.0 utf8
Shape {
  appearance Appearance { material Material { diffuseColor 0.5 0.25 1 transparency 0.5 }
                          texture ImageTexture { url [ "skin.png" "http://example.org/skin.png" ] } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }
    coordIndex [ 0 1 2 -1, 0 2 3 -1 ]
    texCoord TextureCoordinate { point [ 0 0, 1 0 ] } texCoordIndex [ 0 1 0 -1 0 1 1 -1 ] } }
)",
                                       "seam.wrl", &notes, resolve);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4U);
  ASSERT_TRUE(mesh->has_corner_texcoords());
  EXPECT_EQ(mesh->texcoord_triangles, (std::vector<Triangle>{{0, 1, 0}, {0, 1, 1}}));
  ASSERT_TRUE(mesh->material && mesh->material->base_color_image);
  EXPECT_EQ(mesh->material->base_color, Vec4f(1, 1, 1, 0.5F)) << "an RGB texture replaces diffuseColor";
  EXPECT_EQ(mesh->material->base_color_image->bytes, png);
  EXPECT_EQ(asked, (std::vector<std::string>{"skin.png"}));
  EXPECT_TRUE(notes.empty()) << notes.front();
}

TEST(VrmlRead, TexCoordIndexOutOfRangeIsAnError) {
  const Result<Mesh> mesh = read_vrml(R"(#VRML V2.0 utf8
Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0 ] } coordIndex [ 0 1 2 -1 ]
  texCoord TextureCoordinate { point [ 0 0, 1 0 ] } texCoordIndex [ 0 1 2 -1 ] } }
)");
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(mesh.error().where.line, 3U);
  EXPECT_EQ(mesh.error().where.column, 73U);
}

TEST(VrmlRead, AttributesOnlySomeShapesHaveAreDroppedWithANote) {
  Notes notes;
  const Result<Mesh> mesh = read_vrml(R"(#VRML V2.0 utf8
Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 -1 ]
  color Color { color [ 1 0 0, 0 1 0, 0 0 1 ] } } }
Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 1, 1 0 1, 0 1 1 ] } coordIndex [ 0 1 2 -1 ] } }
)",
                                      &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 6U);
  EXPECT_FALSE(mesh->has_colors());
  EXPECT_TRUE(has_note(notes, "colours dropped: only 1 of the 2 geometries have them"));
}

TEST(VrmlRead, PointSetIsAPointCloudWithColours) {
  const Mesh mesh = read_fixture("v2_pointset.wrl");
  EXPECT_TRUE(mesh.is_point_cloud());
  ASSERT_EQ(mesh.vertex_count(), 4U);
  EXPECT_EQ(mesh.positions[3], Vec3(0, 0, 2));
  EXPECT_EQ(mesh.colors[3], Vec4f(1, 1, 0, 1));
}

TEST(VrmlRead, FieldsWithoutBracketsAndOtherLexicalForms) {
  // Single values without brackets, a '+' sign, hexadecimal and exponent numbers, CR LF line ends,
  // comments everywhere, '#' inside strings, TRUE/FALSE, NULL.
  const Result<Mesh> mesh =
      read_vrml("#VRML V2.0 utf8\r\n"
                "WorldInfo { info \"units: m # not a comment\" }\r\n"
                "Shape { appearance NULL geometry IndexedFaceSet { # comment\r\n"
                "  ccw TRUE coord Coordinate { point 1.5e1 +2 -.5 }\r\n"
                "  coordIndex 0 } }\r\n"
                "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0 1 0 0 0 1 0 ] }\r\n"
                "  coordIndex [ 0x0 0x1 0x2 ] } }\r\n");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_EQ(mesh->vertex_count(), 4U);
  EXPECT_EQ(mesh->positions[0], Vec3(15, 2, -0.5));
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{1, 2, 3}}));
  EXPECT_EQ(mesh->units, Units::Unknown); // "units: m # not a comment" is not a unit
}

TEST(VrmlRead, UnitsOnlyWhenStated) {
  const char* body = "Shape { geometry PointSet { coord Coordinate { point [ 0 0 0 ] } } }\n";
  auto units = [&](const std::string& info) {
    Result<Mesh> mesh = read_vrml("#VRML V2.0 utf8\n" + info + body);
    return mesh ? mesh->units : Units::Unknown;
  };
  EXPECT_EQ(units(""), Units::Unknown);
  EXPECT_EQ(units("WorldInfo { info [ \"units: mm\" ] }"), Units::Millimetres);
  EXPECT_EQ(units("WorldInfo { info [ \"x\" \"units: inches\" ] }"), Units::Inches);
  EXPECT_EQ(units("WorldInfo { info [ \"units: metres\" ] }"), Units::Metres);
  EXPECT_EQ(units("WorldInfo { info [ \"units: furlongs\" ] }"), Units::Unknown);
  EXPECT_EQ(units("WorldInfo { title \"units: mm\" }"), Units::Unknown); // only info entries
}

TEST(VrmlRead, ProtoInstanceAsCoordIsNotedAndItsFaceSetSkipped) {
  Notes notes;
  const Result<Mesh> mesh = read_vrml(R"(#VRML V2.0 utf8
PROTO MyCoords [ ] { Coordinate { point [ 0 0 0 ] } }
Shape { geometry IndexedFaceSet { coord MyCoords { } coordIndex [ 0 0 0 ] } }
Shape { geometry PointSet { coord Coordinate { point [ 1 2 3 ] } } }
)",
                                      &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 1U);
  EXPECT_TRUE(has_notes(
      notes, {"test.wrl:3:41: instance of PROTO MyCoords skipped", "IndexedFaceSet without coord skipped"}));
}

TEST(VrmlRead, DefInsideASkippedNodeCanBeUsedLater) {
  const Result<Mesh> mesh = read_vrml(R"(#VRML V2.0 utf8
Switch { choice [ Shape { geometry IndexedFaceSet { coord DEF C Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } } } ] }
SomeExtension { payload DEF C2 Coordinate { point [ 5 5 5 ] } }
Shape { geometry IndexedFaceSet { coord USE C coordIndex [ 0 1 2 ] } }
Shape { geometry IndexedFaceSet { coord USE C2 } }
)");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4U);
  EXPECT_EQ(mesh->positions[3], Vec3(5, 5, 5));
}

TEST(VrmlRead, ManyNotesAreCountedNotListed) {
  std::string text = "#VRML V2.0 utf8\n";
  for (int i = 0; i < 200; ++i)
    text += "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } "
            "coordIndex [ 0 1 2 -1 ] colorPerVertex FALSE color Color { color 1 0 0 } } }\n";
  Notes notes;
  const Result<Mesh> mesh = read_vrml(text, &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangle_count(), 200U);
  EXPECT_EQ(notes.size(), 51U);
  EXPECT_EQ(notes.back(), "test.wrl: 150 more notes like those above not shown");
}

// --- VRML 1.0 ----------------------------------------------------------------------------------------------

TEST(VrmlRead, Vrml1SeparatorsScopeTheState) {
  Notes notes;
  const Mesh mesh = read_fixture("v1_separators.wrl", &notes);
  EXPECT_EQ(mesh.units, Units::Centimetres);
  ASSERT_EQ(mesh.vertex_count(), 18U);
  ASSERT_EQ(mesh.triangle_count(), 6U);
  // Translation then Scale: the square at x 10..12.
  expect_near(mesh.positions[2], Vec3(12, 2, 0));
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (Triangle{0, 2, 3}));
  // Rotated half a turn, CLOCKWISE: the winding is flipped.
  expect_near(mesh.positions[6], Vec3(-1, -1, 0));
  EXPECT_EQ(mesh.triangles[2], (Triangle{4, 6, 5}));
  // The Separators undid both: DEF Tri at the origin, USE Tri after Transform z+1.
  expect_near(mesh.positions[9], Vec3(1, 0, 0));
  expect_near(mesh.positions[12], Vec3(1, 0, 1));
  // Tri's Coordinate3 stayed inside it: the last face uses Square again, also lifted, without the -1.
  expect_near(mesh.positions[16], Vec3(1, 1, 1));
  EXPECT_EQ(mesh.triangles[5], (Triangle{14, 15, 17}));
  EXPECT_TRUE(notes.empty());
}

TEST(VrmlRead, Vrml1PointSetTakesARangeOfTheCoordinates) {
  const Mesh mesh = read_fixture("v1_points.wrl");
  EXPECT_TRUE(mesh.is_point_cloud());
  ASSERT_EQ(mesh.vertex_count(), 4U);
  // MatrixTransform's last row is the translation (row vectors, as in Open Inventor).
  EXPECT_EQ(mesh.positions[0], Vec3(1, 0, 7));
  EXPECT_EQ(mesh.positions[1], Vec3(2, 0, 7));
  EXPECT_EQ(mesh.positions[3], Vec3(4, 0, 7));
}

TEST(VrmlRead, Vrml1PerVertexNormalsMaterialsAndTextureCoordinates) {
  const Mesh mesh = read_fixture("v1_attributes.wrl");
  ASSERT_EQ(mesh.vertex_count(), 3U);
  EXPECT_EQ(mesh.normals, std::vector<Vec3f>(3, Vec3f(0, 0, 1)));
  EXPECT_EQ(mesh.colors, (std::vector<Vec4f>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}}));
  EXPECT_EQ(mesh.texcoords, (std::vector<Vec2f>{{0, 0}, {1, 0}, {0, 1}}));
}

TEST(VrmlRead, Vrml1BindingsThatAreNotPerVertexAreDroppedWithANote) {
  Notes notes;
  const Result<Mesh> mesh = read_vrml(R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }
  Normal { vector [ 0 0 1 ] } NormalBinding { value PER_FACE }
  Material { diffuseColor [ 1 0 0 ] } MaterialBinding { value PER_FACE_INDEXED }
  IndexedFaceSet { coordIndex [ 0, 1, 2, -1 ] }
  Material { diffuseColor 0.5 0.5 0.5 } MaterialBinding { value OVERALL }
  IndexedFaceSet { coordIndex [ 0, 1, 2, -1 ] }
}
)",
                                      &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_FALSE(mesh->has_normals() || mesh->has_colors());
  EXPECT_TRUE(has_notes(notes, {"test.wrl:6:3: normals dropped: NormalBinding PER_FACE is not per vertex",
                                "colours dropped: MaterialBinding PER_FACE_INDEXED is not per vertex"}));
  EXPECT_EQ(notes.size(), 3U); // normals once per face set, nothing for the OVERALL material
}

} // namespace
} // namespace pdeface::test
