// Writing PLY and reading it back: counts, float32 positions, attributes and units survive.

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/ply/ply.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace pdeface;
using namespace pdeface::test;

namespace {

Mesh round_trip(const Mesh& mesh, bool binary, std::string* bytes_out = nullptr) {
  Result<std::string> bytes = ply::write(mesh, {.binary = binary});
  EXPECT_TRUE(bytes.ok()) << bytes.error().to_string();
  if (!bytes) return {};
  if (bytes_out) *bytes_out = *bytes;
  Result<Mesh> read = ply::read(*bytes, "round-trip.ply");
  EXPECT_TRUE(read.ok()) << read.error().to_string();
  return read ? std::move(read).value() : Mesh{};
}

std::string header_of(const std::string& bytes) { return bytes.substr(0, bytes.find("end_header")); }

// The sample face written and read back: geometry, normals, colours (to 8 bits) and units (mm) survive.
// Returns the bytes written.
std::string expect_sample_face_round_trip(const Mesh& mesh, bool binary) {
  std::string bytes;
  const Mesh read = round_trip(mesh, binary, &bytes);
  expect_same_geometry(mesh, read);
  EXPECT_EQ(read.normals, mesh.normals);
  EXPECT_EQ(read.colors, byte_rounded(mesh.colors));
  EXPECT_EQ(read.units, Units::Millimetres);
  return bytes;
}

} // namespace

// The sample face states its units (mm), has normals and colours.
TEST(PlyWrite, SampleFaceBinaryRoundTrip) {
  const Mesh mesh = sample_face();
  const std::string bytes = expect_sample_face_round_trip(mesh, true);
  const std::string header = header_of(bytes);
  EXPECT_NE(header.find("format binary_little_endian 1.0\ncomment units mm\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property float x\n"), std::string::npos) << "float32 positions, not double";
  EXPECT_NE(header.find("property float nx\n"), std::string::npos);
  EXPECT_NE(header.find("property uchar red\n"), std::string::npos);
  EXPECT_EQ(header.find("alpha"), std::string::npos) << "every alpha is 1: none written";
  // float xyz + float normal + uchar rgb per vertex; uchar count + 3 ints per triangle
  EXPECT_EQ(bytes.size(),
            bytes.find("end_header\n") + 11 + mesh.vertex_count() * 27 + mesh.triangle_count() * 13);
}

TEST(PlyWrite, SampleFaceAsciiRoundTrip) {
  const std::string bytes = expect_sample_face_round_trip(sample_face(), false);
  EXPECT_NE(bytes.find("format ascii 1.0\ncomment units mm\n"), std::string::npos);
}

TEST(PlyWrite, TexcoordsAndAlphaRoundTrip) {
  Mesh mesh = sample_face({.spacing_mm = 5.0});
  for (const Vec3& p : mesh.positions)
    mesh.texcoords.emplace_back(static_cast<float>(p.x() / 200 + 0.5), static_cast<float>(p.y() / 200 + 0.5));
  mesh.colors[7].w() = 0.5f;
  mesh.units = Units::Unknown;
  for (bool binary : {true, false}) {
    std::string bytes;
    const Mesh read = round_trip(mesh, binary, &bytes);
    expect_same_geometry(mesh, read);
    EXPECT_EQ(read.texcoords, mesh.texcoords) << binary;
    EXPECT_EQ(read.colors, byte_rounded(mesh.colors)) << binary;
    EXPECT_NE(header_of(bytes).find("property float s\nproperty float t\n"), std::string::npos);
    EXPECT_NE(header_of(bytes).find("property uchar alpha\n"), std::string::npos);
    EXPECT_EQ(read.units, Units::Unknown) << "no units stated, none read";
  }
}

TEST(PlyWrite, PointCloudRoundTrip) {
  Mesh cloud = to_mesh(to_point_cloud(sample_face()));
  for (bool binary : {true, false}) {
    const Mesh read = round_trip(cloud, binary);
    expect_same_geometry(cloud, read);
    EXPECT_TRUE(read.is_point_cloud());
  }
}

TEST(PlyWrite, RealScanRoundTripKeepsTheFileExactly) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_m46.ply");
  const Result<Mesh> scan = ply::read(*read_file(path), "facefuns_m46.ply");
  ASSERT_TRUE(scan.ok());
  for (bool binary : {true, false}) {
    const Mesh read = round_trip(*scan, binary);
    EXPECT_EQ(read.positions, scan->positions) << "float32 data written as float32 is exact";
    EXPECT_EQ(read.triangles, scan->triangles);
  }
}

TEST(PlyWrite, InvalidMeshIsRefused) {
  Mesh mesh = sample_face({.spacing_mm = 5.0});
  mesh.triangles.push_back({0, 1, static_cast<std::uint32_t>(mesh.vertex_count())});
  const Result<std::string> bytes = ply::write(mesh);
  ASSERT_FALSE(bytes.ok());
  EXPECT_EQ(bytes.error().code, ErrorCode::IndexOutOfRange);
}
