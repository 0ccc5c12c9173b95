// OFF: reading (comments, COFF/NOFF, every bad input with its line and column) and round trips.

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/off/off.hpp"
#include "pdeface/ply/ply.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace pdeface;
using namespace pdeface::test;

namespace {

Result<Mesh> read_off(std::string_view bytes, Notes* notes = nullptr) {
  return off::read(bytes, "t.off", notes);
}

constexpr std::string_view kSquare = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

} // namespace

TEST(OffRead, CommentsBlankLinesQuadsAndFaceColours) {
  Notes notes;
  const Result<Mesh> mesh = off::read(fixture("off", "pyramid_comments.off"), "pyramid_comments.off", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 5u);
  EXPECT_EQ(mesh->triangles,
            (std::vector<Triangle>{{0, 3, 2}, {0, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}));
  EXPECT_EQ(mesh->positions[4], Vec3(0.5, 0.5, 1));
  EXPECT_EQ(mesh->units, Units::Millimetres);
  EXPECT_TRUE(has_note(notes, "values after face indices (face colours?) ignored (line 11 and later)"));
}

// COFF colours are ours to read (OpenMesh reads OFF streams as plain OFF); NOFF normals are dropped.
TEST(OffRead, ColoursReadNormalsDropped) {
  Notes notes;
  const Result<Mesh> mesh = off::read(fixture("off", "colored_normals.off"), "colored_normals.off", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->positions[2], Vec3(0, 1, 0));
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_FALSE(mesh->has_normals());
  EXPECT_EQ(mesh->colors, (std::vector<Vec4f>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0.5F, 0.25F, 0.75F, 1}}));
  EXPECT_TRUE(has_note(notes, "NOFF normals dropped"));
  EXPECT_TRUE(has_note(notes, "values after face indices"));
}

TEST(OffWrite, SampleFaceRoundTrip) {
  const Mesh mesh = sample_face();
  Notes notes;
  const Result<std::string> bytes = off::write(mesh, &notes);
  ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
  EXPECT_TRUE(bytes->starts_with("COFF\n# units mm\n"));
  EXPECT_TRUE(has_note(notes, "normals dropped: OFF cannot store them"));
  const Result<Mesh> read = read_off(*bytes);
  ASSERT_TRUE(read.ok()) << read.error().to_string();
  expect_same_geometry(mesh, *read);
  EXPECT_EQ(read->colors, byte_rounded(mesh.colors)) << "COFF: 8-bit colours";
  EXPECT_EQ(read->units, Units::Millimetres);
}

TEST(OffWrite, PointCloudRoundTrip) {
  const Mesh cloud = to_mesh(to_point_cloud(sample_face({.spacing_mm = 4.0})));
  const Result<Mesh> read = read_off(*off::write(cloud));
  ASSERT_TRUE(read.ok()) << read.error().to_string();
  expect_same_geometry(cloud, *read);
}

TEST(OffWrite, RealScanRoundTrip) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f36.ply");
  const Result<Mesh> scan = ply::read(*read_file(path), "facefuns_f36.ply");
  ASSERT_TRUE(scan.ok());
  const Result<Mesh> read = read_off(*off::write(*scan));
  ASSERT_TRUE(read.ok()) << read.error().to_string();
  EXPECT_EQ(read->positions, scan->positions);
  EXPECT_EQ(read->triangles, scan->triangles);
}

// ---- bad input ----------------------------------------------------------------------------------------

TEST(OffReadErrors, EveryClassWithItsLocation) {
  const std::vector<ErrorCase> cases{
      {"", ErrorCode::Empty, 0, 0},
      {"  \n# only a comment\n", ErrorCode::Empty, 0, 0},
      {"PLY\n3 1 0\n", ErrorCode::BadMagic, 1, 1},
      {"\nOFF\n3 1 0\n", ErrorCode::BadMagic, 2, 1},
      {"OFF BINARY\n", ErrorCode::UnsupportedFormat, 1, 5},
      {"OFF 3 1 0\n", ErrorCode::UnsupportedFormat, 1, 5},
      {"4OFF\n3 1 0\n", ErrorCode::UnsupportedFormat, 1, 1},
      {"STOFF\n3 1 0\n", ErrorCode::UnsupportedFormat, 1, 1},
      {"OFF\n", ErrorCode::Truncated, 2, 1},
      {"OFF\n3 x 0\n0 0 0\n1 0 0\n0 1 0\n", ErrorCode::Malformed, 2, 3},
      {"OFF\n3 1 0 7\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", ErrorCode::Malformed, 2, 7},
      {"OFF\n2147483648 1 0\n", ErrorCode::CountTooLarge, 2, 1},
      {"OFF\n1000 1 0\n0 0 0\n", ErrorCode::CountTooLarge, 2, 1},
      {"OFF\n3 1000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", ErrorCode::CountTooLarge, 2, 3},
      {"OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", ErrorCode::NonFinite, 4, 3},
      {"OFF\n3 1 0\n0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n", ErrorCode::NonFinite, 4, 3},
      {"OFF\n3 1 0\n0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", ErrorCode::Malformed, 4, 3},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ErrorCode::IndexOutOfRange, 6, 7},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", ErrorCode::IndexOutOfRange, 6, 5},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", ErrorCode::Malformed, 6, 5},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", ErrorCode::Malformed, 6, 1},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1", ErrorCode::Truncated, 5, 4},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n", ErrorCode::Truncated, 7, 1},
  };
  expect_errors_at(off::read, "t.off", cases);
}

// Every prefix of a file is an error or a valid mesh, never a crash or a hang.
TEST(OffReadErrors, EveryTruncation) {
  for (std::size_t n = 0; n < kSquare.size(); ++n) {
    const Result<Mesh> mesh = read_off(kSquare.substr(0, n));
    if (mesh) {
      EXPECT_EQ(n, kSquare.size() - 1) << "only the final newline may be missing";
      EXPECT_EQ(mesh->triangle_count(), 2u);
    } else {
      EXPECT_TRUE(mesh.error().where.known() || mesh.error().code == ErrorCode::Empty) << n;
    }
  }
}

TEST(OffReadErrors, NothingIsPrinted) {
  testing::internal::CaptureStderr();
  for (std::size_t n = 0; n < kSquare.size(); ++n)
    (void)read_off(kSquare.substr(0, n));
  (void)read_off("COFF\n3 1 0\n0 0 0 1 2 3 4 5\n1 0 0\n0 1 0\n3 0 1 2 3 4 5 6\n");
  (void)read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}
