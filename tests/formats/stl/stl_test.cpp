// STL: binary and ASCII reading (corners merged into shared vertices), round trips, every bad input.

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/ply/ply.hpp"
#include "pdeface/stl/stl.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

using namespace pdeface;
using namespace pdeface::test;

namespace {

Result<Mesh> read_stl(std::string_view bytes, Notes* notes = nullptr) {
  return stl::read(bytes, "t.stl", notes);
}

// Two facets of a unit square, binary: 84 + 2 * 50 bytes.
std::string binary_square(std::string_view header = "two facets") {
  std::string bytes(header);
  bytes.resize(80, ' ');
  put(bytes, std::uint32_t{2});
  const float facets[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& facet : facets) {
    for (float v : facet)
      put(bytes, v);
    put(bytes, std::uint16_t{0});
  }
  return bytes;
}

// Each triangle's corners land on the float-rounded original corners (STL renumbers vertices).
void expect_same_corners(const Mesh& original, const Mesh& read) {
  const Mesh expected = float_rounded(original);
  ASSERT_EQ(read.triangle_count(), expected.triangle_count());
  for (std::size_t t = 0; t < expected.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(read.positions[read.triangles[t][k]], expected.positions[expected.triangles[t][k]]) << t;
}

std::size_t referenced_vertices(const Mesh& mesh) {
  std::set<std::uint32_t> used;
  for (const Triangle& t : mesh.triangles)
    used.insert(t.begin(), t.end());
  return used.size();
}

} // namespace

TEST(StlRead, BinaryCornersAreMerged) {
  const Result<Mesh> mesh = read_stl(binary_square());
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4u);
  EXPECT_EQ(mesh->triangle_count(), 2u);
  EXPECT_EQ(mesh->units, Units::Unknown);
}

TEST(StlRead, AsciiFixture) {
  const Result<Mesh> mesh = stl::read(fixture("stl", "square_ascii.stl"), "square_ascii.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4u);
  EXPECT_EQ(mesh->triangle_count(), 2u);
}

// Some exporters start a binary header with "solid": the size decides.
TEST(StlRead, BinaryWhoseHeaderSaysSolid) {
  const Result<Mesh> mesh = read_stl(binary_square("solid square, but binary"));
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangle_count(), 2u);
}

TEST(StlRead, TrailingBytesAreNoted) {
  Notes notes;
  ASSERT_TRUE(read_stl(binary_square() + "extra", &notes).ok());
  EXPECT_TRUE(has_note(notes, "5 bytes after the last facet ignored (from byte 184)"));
}

TEST(StlWrite, SampleFaceRoundTripBothEncodings) {
  const Mesh mesh = sample_face();
  ASSERT_EQ(referenced_vertices(mesh), mesh.vertex_count()) << "the sample has no loose vertices";
  for (bool binary : {true, false}) {
    Notes notes;
    const Result<std::string> bytes = stl::write(mesh, {.binary = binary}, &notes);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    EXPECT_TRUE(has_note(notes, "normals dropped: STL cannot store them"));
    if (binary) {
      EXPECT_EQ(bytes->size(), 84 + 50 * mesh.triangle_count());
    }
    const Result<Mesh> read = read_stl(*bytes);
    ASSERT_TRUE(read.ok()) << read.error().to_string();
    EXPECT_EQ(read->vertex_count(), mesh.vertex_count()) << "corners merge back into the same vertices";
    expect_same_corners(mesh, *read);
    EXPECT_EQ(read->units, Units::Millimetres) << "stated in the header or solid line";
  }
}

TEST(StlWrite, RealScanRoundTrip) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  const Result<Mesh> scan = ply::read(*read_file(path), "facefuns_f18.ply");
  ASSERT_TRUE(scan.ok());
  const Result<Mesh> read = read_stl(*stl::write(*scan));
  ASSERT_TRUE(read.ok()) << read.error().to_string();
  EXPECT_EQ(read->vertex_count(), referenced_vertices(*scan));
  expect_same_corners(*scan, *read);
}

TEST(StlWrite, PointCloudIsRefused) {
  const Result<std::string> bytes = stl::write(to_mesh(to_point_cloud(sample_face({.spacing_mm = 5.0}))));
  ASSERT_FALSE(bytes.ok());
  EXPECT_EQ(bytes.error().code, ErrorCode::InvalidArgument);
}

// ---- bad input ----------------------------------------------------------------------------------------

TEST(StlReadErrors, EveryTruncationOfABinaryFile) {
  const std::string bytes = binary_square();
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const Error e = error_of(read_stl(std::string_view(bytes).substr(0, n)));
    if (n == 0) {
      EXPECT_EQ(e.code, ErrorCode::Empty);
    } else if (n < 84) {
      EXPECT_EQ(e.code, ErrorCode::Truncated) << n;
      EXPECT_EQ(e.where.byte, n) << n;
    } else if (n < 100) { // not even the 2 x 50 facet bytes the count declares
      EXPECT_EQ(e.code, ErrorCode::CountTooLarge) << n;
      EXPECT_EQ(e.where.byte, 80u) << n;
    } else {
      EXPECT_EQ(e.code, ErrorCode::Truncated) << n;
      EXPECT_EQ(e.where.byte, n < 134 ? 84u : 134u) << n << ": the facet the file ends in";
    }
  }
}

TEST(StlReadErrors, FacetCountBeyondTheFile) {
  std::string bytes = binary_square();
  const std::uint32_t lie = 1u << 31;
  std::memcpy(bytes.data() + 80, &lie, 4);
  const Error e = error_of(read_stl(bytes));
  EXPECT_EQ(e.code, ErrorCode::CountTooLarge);
  EXPECT_EQ(e.where.byte, 80u);
  EXPECT_EQ(e.message,
            "2147483648 facets of 50 bytes declared (107374182400 bytes), but the whole file has 184 bytes");
}

TEST(StlReadErrors, NoFacets) {
  std::string bytes(80, ' ');
  put(bytes, std::uint32_t{0});
  EXPECT_EQ(error_of(read_stl(bytes)).code, ErrorCode::Empty);
  EXPECT_EQ(error_of(read_stl("solid empty\nendsolid empty\n")).code, ErrorCode::Empty);
}

TEST(StlReadErrors, NaNCornerInBinary) {
  std::string bytes = binary_square();
  const float nan = std::nanf("");
  const std::size_t y_of_second_corner = 84 + 50 + 12 + 12 + 4;
  std::memcpy(bytes.data() + y_of_second_corner, &nan, 4);
  const Error e = error_of(read_stl(bytes));
  EXPECT_EQ(e.code, ErrorCode::NonFinite);
  EXPECT_EQ(e.where.byte, y_of_second_corner);
}

TEST(StlReadErrors, AsciiWithItsLineAndColumn) {
  const std::string good = fixture("stl", "square_ascii.stl");
  auto replaced = [&](std::string_view from, std::string_view to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::vector<ErrorCase> cases{
      {replaced("vertex 1 0 0", "vertex 1 nan 0"), ErrorCode::NonFinite, 5, 16},
      {replaced("vertex 1 0 0", "vertex 1 1e39 0"), ErrorCode::NonFinite, 5, 16},
      {replaced("vertex 1 0 0", "vertex 1 abc 0"), ErrorCode::Malformed, 5, 16},
      {replaced("vertex 1 0 0", "vertex 1 0"), ErrorCode::Malformed, 6, 7},
      {replaced("outer loop", "outer space"), ErrorCode::Malformed, 3, 11},
      {replaced("endsolid square\n", ""), ErrorCode::Truncated, 16, 1},
      {good.substr(0, good.find("vertex 1 0 0") + 10), ErrorCode::Truncated, 5, 17},
      {"solid nothing\nfacet normal 0 0 1\n", ErrorCode::Truncated, 3, 1},
  };
  expect_errors_at(stl::read, "t.stl", cases);
}

TEST(StlReadErrors, NothingIsPrinted) {
  const std::string bytes = binary_square();
  const std::string text = fixture("stl", "square_ascii.stl");
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  for (std::size_t n = 0; n < bytes.size(); ++n)
    (void)read_stl(std::string_view(bytes).substr(0, n));
  for (std::size_t n = 0; n < text.size(); ++n)
    (void)read_stl(std::string_view(text).substr(0, n));
  (void)stl::write(sample_face({.spacing_mm = 5.0}));
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}
