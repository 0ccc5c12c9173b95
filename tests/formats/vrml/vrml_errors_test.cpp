// The VRML reader on bad input: every class of error with its code and line:column, truncation at every
// byte, and random damage. Offending tokens are put at the start of a line where that helps reading.

#include "vrml_test_support.hpp"

#include <random>

namespace pdeface::test {
namespace {

const std::string kV2 = "#VRML V2.0 utf8\n";

// --- the header --------------------------------------------------------------------------------------------

TEST(VrmlErrors, EmptyFile) { EXPECT_TRUE(fails_at(read_vrml(""), ErrorCode::Empty, 1, 1)); }

TEST(VrmlErrors, MissingHeader) {
  EXPECT_TRUE(fails_at(read_vrml("Shape { }\n"), ErrorCode::BadMagic, 1, 1));
  EXPECT_TRUE(fails_at(read_vrml("\n#VRML V2.0 utf8\n"), ErrorCode::BadMagic, 1, 1));
  EXPECT_TRUE(fails_at(read_vrml("#X3D V3.0 utf8\n"), ErrorCode::BadMagic, 1, 1));
  EXPECT_TRUE(fails_at(read_vrml(std::string("\x89PNG\r\n\x1a\n\0\0", 10)), ErrorCode::BadMagic, 1, 1));
}

TEST(VrmlErrors, OtherVersionsAndEncodings) {
  EXPECT_TRUE(fails_at(read_vrml("#VRML V3.0 utf8\n"), ErrorCode::UnsupportedVersion, 1, 7));
  EXPECT_TRUE(fails_at(read_vrml("#VRML V2.0 ascii\n"), ErrorCode::UnsupportedVersion, 1, 12));
  EXPECT_TRUE(fails_at(read_vrml("#VRML V1.0 utf8\n"), ErrorCode::UnsupportedVersion, 1, 12));
  EXPECT_TRUE(fails_at(read_vrml("#VRML\n"), ErrorCode::UnsupportedVersion, 1, 6));
}

TEST(VrmlErrors, ByteOrderMarkIsAcceptedAndColumnsCountFromAfterIt) {
  EXPECT_TRUE(
      read_vrml(
          "\xEF\xBB\xBF#VRML V2.0 utf8\nShape { geometry PointSet { coord Coordinate { point 0 0 0 } } }")
          .ok());
  EXPECT_TRUE(fails_at(read_vrml("\xEF\xBB\xBF#VRML V9.0 utf8\n"), ErrorCode::UnsupportedVersion, 1, 7));
}

// --- structure ---------------------------------------------------------------------------------------------

TEST(VrmlErrors, UnclosedBraceIsReportedWhereItWasOpened) {
  const Result<Mesh> r = read_vrml(kV2 + "Shape {\n"
                                         "  geometry IndexedFaceSet {\n"
                                         "    coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n");
  EXPECT_TRUE(fails_at(r, ErrorCode::Truncated, 3, 27));
  EXPECT_NE(r.error().message.find("the file ends (at 5:1) before this '{' is closed"), std::string::npos)
      << r.error().message;
}

TEST(VrmlErrors, FileEndingInsideAListNamesItsBracket) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Shape { geometry PointSet { coord Coordinate { point\n"
                                       "[ 0 0 0, 1 0"),
                       ErrorCode::Truncated, 3, 1));
}

TEST(VrmlErrors, FileEndingBetweenStatements) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "DEF"), ErrorCode::Truncated, 2, 4));
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "DEF X\n"), ErrorCode::Truncated, 3, 1));
}

TEST(VrmlErrors, UnterminatedString) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "WorldInfo { title\n\"abc\n}\n"), ErrorCode::Truncated, 3, 1));
}

TEST(VrmlErrors, StrayCloser) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Group { }\n}\n"), ErrorCode::Malformed, 3, 1));
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "]"), ErrorCode::Malformed, 2, 1));
}

TEST(VrmlErrors, MismatchedCloser) {
  const Result<Mesh> r = read_vrml(kV2 + "Group { children [ Shape { }\n}\n");
  EXPECT_TRUE(fails_at(r, ErrorCode::Malformed, 3, 1));
  EXPECT_NE(r.error().message.find("does not close the '[' opened at 2:18"), std::string::npos)
      << r.error().message;
}

TEST(VrmlErrors, NodeTypeWithoutBody) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Shape\ngeometry"), ErrorCode::Malformed, 3, 1));
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "[ ]"), ErrorCode::Malformed, 2, 1));
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Group { children [\n\"text\" ] }"), ErrorCode::Malformed, 3, 1));
}

TEST(VrmlErrors, GarbageBytes) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "\x01\x02 \xff\xfe {"), ErrorCode::Malformed, 2, 4));
}

TEST(VrmlErrors, MalformedRoute) {
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "ROUTE a.b\nFROM c.d\n"), ErrorCode::Malformed, 3, 1));
}

TEST(VrmlErrors, NestingDepthIsLimited) {
  // Each "Group { children [ " opens two levels; the 1001st level is the '{' of the 501st Group.
  std::string deep = kV2;
  for (int i = 0; i < 600; ++i)
    deep += "Group { children [ ";
  const Result<Mesh> r = read_vrml(deep);
  EXPECT_TRUE(fails_at(r, ErrorCode::Malformed, 2, 500 * 19 + 7));
}

TEST(VrmlErrors, NestingUpToTheLimitIsRead) {
  // The deepest input accepted, in the two shapes that use the most stack per level.
  std::string v1 = "#VRML V1.0 ascii\n";
  for (int i = 0; i < 999; ++i)
    v1 += "Separator { ";
  v1 += "Coordinate3 { point 0 0 0 } PointSet { }" + std::string(999, '}');
  const Result<Mesh> r1 = read_vrml(v1);
  ASSERT_TRUE(r1.ok()) << r1.error().to_string();
  EXPECT_EQ(r1->vertex_count(), 1U);

  std::string v2 = kV2;
  for (int i = 0; i < 497; ++i)
    v2 += "Transform { translation 1 0 0 children [ ";
  v2 += "Shape { geometry PointSet { coord Coordinate { point 0 0 0 } } }";
  for (int i = 0; i < 497; ++i)
    v2 += " ] }";
  const Result<Mesh> r2 = read_vrml(v2);
  ASSERT_TRUE(r2.ok()) << r2.error().to_string();
  EXPECT_EQ(r2->positions.front(), Vec3(497, 0, 0));
}

TEST(VrmlErrors, UseChainDepthIsLimited) {
  // Groups nest only through USE here: A<i> holds A<i-1>, and every A<i> is drawn (a top-level node).
  // A999 is the first whose chain is too deep: it puts A0's geometry, the PointSet, at depth 1001.
  std::string text = kV2 + "DEF A0 Shape { geometry PointSet { coord Coordinate { point 0 0 0 } } }\n";
  for (int i = 1; i <= 1200; ++i)
    text += "DEF A" + std::to_string(i) + " Group { children USE A" + std::to_string(i - 1) + " }\n";
  EXPECT_TRUE(fails_at(read_vrml(text), ErrorCode::Malformed, 2, 25));
}

TEST(VrmlErrors, InstancingBombFailsBeforeAllocating) {
  // 16^8 instances of a 100-point face set: far beyond the limit, refused by the counting pass, quickly.
  std::string text = kV2 + "DEF L0 Shape { geometry\nIndexedFaceSet { coord Coordinate { point [";
  for (int i = 0; i < 100; ++i)
    text += " 0 0 " + std::to_string(i);
  text += " ] } coordIndex [ 0 1 2 ] } }\n";
  for (int level = 1; level <= 8; ++level) {
    text += "DEF L" + std::to_string(level) + " Group { children [";
    for (int k = 0; k < 16; ++k)
      text += " USE L" + std::to_string(level - 1);
    text += " ] }\n";
  }
  EXPECT_TRUE(fails_at(read_vrml(text), ErrorCode::CountTooLarge, 3, 1));
}

// --- values ------------------------------------------------------------------------------------------------

const std::string kPoints = kV2 + "Shape { geometry PointSet { coord Coordinate { point [\n";

//! Two points, the second one's y (at 4:3) written as `y`.
Result<Mesh> read_second_y(std::string_view y) {
  return read_vrml(kPoints + "0 0 0,\n1 " + std::string(y) + " 0 ] } } }");
}

TEST(VrmlErrors, NumberThatDoesNotParse) {
  for (std::string_view y : {"0.5.5", "2e", "abc", "0x10", "\"2\""})
    EXPECT_TRUE(fails_at(read_second_y(y), ErrorCode::Malformed, 4, 3)) << y;
}

TEST(VrmlErrors, ListEndingInsideAVector) {
  EXPECT_TRUE(fails_at(read_vrml(kPoints + "0 0 0, 1 0\n] } } }"), ErrorCode::Malformed, 4, 1));
}

TEST(VrmlErrors, NonFiniteCoordinates) {
  for (std::string_view y : {"nan", "-inf", "1e999"})
    EXPECT_TRUE(fails_at(read_second_y(y), ErrorCode::NonFinite, 4, 3)) << y;
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Transform { translation 0\nNaN 0 }"), ErrorCode::NonFinite, 3, 1));
}

TEST(VrmlErrors, BadIntegersAndBooleans) {
  const std::string faces =
      kV2 + "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n";
  EXPECT_TRUE(fails_at(read_vrml(faces + "coordIndex [ 0 1\n4294967296 ] } }"), ErrorCode::Malformed, 4, 1));
  EXPECT_TRUE(fails_at(read_vrml(faces + "coordIndex [ 0 1\n2.0 ] } }"), ErrorCode::Malformed, 4, 1));
  EXPECT_TRUE(fails_at(read_vrml(faces + "ccw\nmaybe } }"), ErrorCode::Malformed, 4, 1));
}

// --- references --------------------------------------------------------------------------------------------

TEST(VrmlErrors, CoordIndexOutOfRangePointsAtTheIndex) {
  const std::string faces =
      kV2 + "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
            "  coordIndex [ 0 1 2 -1\n";
  EXPECT_TRUE(fails_at(read_vrml(faces + "    0 2 3 -1 ] } }"), ErrorCode::IndexOutOfRange, 4, 9));
  EXPECT_TRUE(fails_at(read_vrml(faces + "  # a comment\n  0 -2 1 ] } }"), ErrorCode::IndexOutOfRange, 5, 5));
  // coordIndex before coord: the same place.
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Shape { geometry IndexedFaceSet { coordIndex [ 0 1\n5 ]\n"
                                       "coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } } }"),
                       ErrorCode::IndexOutOfRange, 3, 1));
}

TEST(VrmlErrors, AttributeIndexOutOfRange) {
  EXPECT_TRUE(fails_at(
      read_vrml(kV2 + "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
                      "coordIndex [ 0 1 2 -1 ] color Color { color [ 1 0 0 ] } colorIndex [ 0 0\n"
                      "1 -1 ] } }"),
      ErrorCode::IndexOutOfRange, 4, 1));
}

TEST(VrmlErrors, Vrml1IndexOutOfRange) {
  const std::string v1 = "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n";
  EXPECT_TRUE(fails_at(read_vrml(v1 + "IndexedFaceSet { coordIndex [ 0, 1,\n3, -1 ] } }"),
                       ErrorCode::IndexOutOfRange, 4, 1));
  EXPECT_TRUE(fails_at(read_vrml(v1 + "PointSet { startIndex\n4 } }"), ErrorCode::IndexOutOfRange, 4, 1));
  // A count the data cannot hold fails at once, allocating nothing.
  EXPECT_TRUE(fails_at(read_vrml(v1 + "PointSet { startIndex 1 numPoints\n2147483647 } }"),
                       ErrorCode::IndexOutOfRange, 4, 1));
}

TEST(VrmlErrors, UseOfAnUndefinedName) {
  EXPECT_TRUE(
      fails_at(read_vrml(kV2 + "Transform { children USE\nNobody }"), ErrorCode::UndefinedName, 3, 1));
  // A DEF inside a PROTO body belongs to the PROTO, not to the file.
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "PROTO P [ ] { DEF Inner Shape { } }\nGroup { children USE Inner }"),
                       ErrorCode::UndefinedName, 3, 22));
  // A node cannot USE itself: its name is defined only once it is complete.
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "DEF Me Group { children USE Me }"), ErrorCode::UndefinedName, 2, 29));
}

TEST(VrmlErrors, NodeOfTheWrongTypeWhereACoordinateIsNeeded) {
  const Result<Mesh> r =
      read_vrml(kV2 + "DEF M Material { }\nShape { geometry IndexedFaceSet {\ncoord USE M } }");
  EXPECT_TRUE(fails_at(r, ErrorCode::Malformed, 4, 7));
  EXPECT_EQ(r.error().message, "coord must be a Coordinate node, found Material");
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Shape { geometry IndexedFaceSet {\ncoord Color { color 1 0 0 } } }"),
                       ErrorCode::Malformed, 3, 7));
}

TEST(VrmlErrors, FileWithoutGeometry) {
  const Result<Mesh> r = read_vrml(kV2 + "Viewpoint { position 0 0 10 }\n");
  EXPECT_TRUE(fails_at(r, ErrorCode::Empty, 1, 1));
  EXPECT_EQ(r.error().message, "no IndexedFaceSet or PointSet with coordinates in the file");
  EXPECT_TRUE(fails_at(read_vrml(kV2 + "Shape { geometry IndexedFaceSet { coordIndex [ 0 1 2 ] } }"),
                       ErrorCode::Empty, 1, 1));
  EXPECT_TRUE(fails_at(read_vrml("#VRML V1.0 ascii\nSeparator { Info { } }"), ErrorCode::Empty, 1, 1));
}

// --- damage anywhere ---------------------------------------------------------------------------------------

//! Reading `bytes` gives a valid mesh or an error that says where; it never crashes (run under ASan).
void expect_graceful(std::string_view bytes, std::string_view what) {
  const Result<Mesh> r = read_vrml(bytes);
  if (r.ok()) {
    EXPECT_TRUE(validate(*r).ok()) << what;
    return;
  }
  EXPECT_EQ(r.error().source, "test.wrl") << what;
  EXPECT_GT(r.error().where.line, 0U) << what << ": " << r.error().to_string();
}

TEST(VrmlErrors, TruncationAtEveryByteNeverCrashes) {
  for (const char* name : {"v2_skipped.wrl", "v2_attributes.wrl", "v1_separators.wrl", "v1_attributes.wrl"}) {
    const std::string bytes = vrml_fixture(name);
    for (std::size_t n = 0; n < bytes.size(); ++n)
      expect_graceful(std::string_view(bytes).substr(0, n),
                      std::string(name) + " cut at " + std::to_string(n));
  }
}

TEST(VrmlErrors, TruncationInsideTheGeometryIsAnError) {
  const std::string bytes = vrml_fixture("v2_polygons.wrl");
  const std::size_t points = bytes.find("point [");
  for (std::size_t n = points; n < bytes.find("}\nShape"); ++n) { // up to the first Shape's last '}'
    const std::string_view cut = std::string_view(bytes).substr(0, n);
    const Result<Mesh> r = read_vrml(cut);
    ASSERT_FALSE(r.ok()) << "cut at " << n;
    // Truncated, unless the cut leaves half a token outside a comment: "-1" cut to "-" is not a number.
    const std::string_view last_line = cut.substr(cut.rfind('\n') + 1);
    const bool half_token = last_line.ends_with('-') && last_line.find('#') == std::string_view::npos;
    EXPECT_EQ(r.error().code, half_token ? ErrorCode::Malformed : ErrorCode::Truncated)
        << r.error().to_string();
  }
}

TEST(VrmlErrors, RandomDamageNeverCrashes) {
  const std::string original = vrml_fixture("v2_skipped.wrl");
  std::mt19937 random(12345);
  const std::string alphabet = "{}[]\"#,. -+0123456789eEaxDEFUSE\n\\";
  std::uniform_int_distribution<std::size_t> position(16, original.size() - 1); // keep the header
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  for (int round = 0; round < 3000; ++round) {
    std::string damaged = original;
    for (int k = 0; k < 1 + round % 4; ++k)
      damaged[position(random)] = alphabet[pick(random)];
    expect_graceful(damaged, "round " + std::to_string(round));
  }
}

} // namespace
} // namespace pdeface::test
