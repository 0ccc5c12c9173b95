// Reading PLY: the real scans, every attribute, and every class of bad input with its exact location.

#include "format_test_support.hpp"
#include "pdeface/ply/ply.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace pdeface;
using namespace pdeface::test;

namespace {

Result<Mesh> read_ply(std::string_view bytes, Notes* notes = nullptr) {
  return ply::read(bytes, "t.ply", notes);
}

// A small binary PLY: 4 coloured vertices, a quad and a triangle; `records` holds where each vertex and
// face starts, then the end of the data.
struct SmallPly {
  std::string bytes;
  std::size_t data_offset = 0;
  std::vector<std::size_t> records;
};

SmallPly small_binary_ply() {
  SmallPly ply;
  ply.bytes =
      "ply\nformat binary_little_endian 1.0\ncomment units mm\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  ply.data_offset = ply.bytes.size();
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& corner : corners) {
    ply.records.push_back(ply.bytes.size());
    for (float c : corner)
      put(ply.bytes, c);
    for (std::uint8_t c : {std::uint8_t{255}, std::uint8_t{0}, std::uint8_t{128}})
      put(ply.bytes, c);
  }
  for (const std::vector<std::int32_t>& face : {std::vector<std::int32_t>{0, 1, 2, 3}, {0, 2, 3}}) {
    ply.records.push_back(ply.bytes.size());
    put(ply.bytes, static_cast<std::uint8_t>(face.size()));
    for (std::int32_t v : face)
      put(ply.bytes, v);
  }
  ply.records.push_back(ply.bytes.size());
  return ply;
}

// An ASCII triangle whose data lines (from line 10) can be replaced.
std::string ascii_ply(std::string_view data, std::string_view vertex_count = "3") {
  return fmt::format(
      "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n{}",
      vertex_count, data);
}
constexpr std::string_view kTriangle = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::string with_header_line(std::string_view line) {
  return fmt::format("ply\nformat ascii 1.0\n{}\nend_header\n", line);
}

} // namespace

// ---- real scans ---------------------------------------------------------------------------------------

TEST(PlyRead, EveryFacefunsScanHasTheManifestCounts) {
  for (const char* name : {"facefuns_f18.ply", "facefuns_f36.ply", "facefuns_f56.ply", "facefuns_m26.ply",
                           "facefuns_m46.ply", "facefuns_m66.ply"}) {
    PDEFACE_FACE_OR_SKIP(path, name);
    const Result<std::string> bytes = read_file(path);
    ASSERT_TRUE(bytes.ok());
    Notes notes;
    const Result<Mesh> mesh = ply::read(*bytes, name, &notes);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->vertex_count(), 30204u) << name;
    EXPECT_EQ(mesh->triangle_count(), 59697u) << name;
    EXPECT_FALSE(mesh->has_normals() || mesh->has_colors() || mesh->has_texcoords()) << name;
    EXPECT_EQ(mesh->units, Units::Unknown) << name << ": the file does not state its units";
    EXPECT_TRUE(notes.empty()) << notes.front();
  }
}

// The values OpenMesh hands over are the file's own floats and ints, in order.
TEST(PlyRead, RealScanValuesMatchTheRawBytes) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  const std::string bytes = *read_file(path);
  const Result<Mesh> mesh = read_ply(bytes);
  ASSERT_TRUE(mesh.ok());
  std::size_t at = bytes.find("end_header\n") + 11;
  auto next = [&]<class T>(T) {
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof value);
    at += sizeof value;
    return value;
  };
  for (const Vec3& p : mesh->positions)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(p[k], static_cast<double>(next(float{})));
  for (const Triangle& t : mesh->triangles) {
    ASSERT_EQ(next(std::uint8_t{}), 3);
    for (std::uint32_t v : t)
      ASSERT_EQ(v, static_cast<std::uint32_t>(next(std::int32_t{})));
  }
  EXPECT_EQ(at, bytes.size());
}

TEST(PlyRead, VertexOnlyScanIsAPointCloud) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f56_points.ply");
  const Result<Mesh> mesh = read_ply(*read_file(path));
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 30204u);
  EXPECT_TRUE(mesh->is_point_cloud());
}

// ---- attributes and layouts ---------------------------------------------------------------------------

TEST(PlyRead, SmallBinaryWithColoursAndUnits) {
  const Result<Mesh> mesh = read_ply(small_binary_ply().bytes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->units, Units::Millimetres);
  EXPECT_EQ(mesh->positions[2], Vec3(1, 1, 0));
  ASSERT_EQ(mesh->colors.size(), 4u);
  EXPECT_EQ(mesh->colors[0], Vec4f(1.0f, 0.0f, 128.0f / 255.0f, 1.0f));
  // The quad is fan-triangulated from its first corner.
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}}));
}

TEST(PlyRead, AsciiFixtureWithEveryAttribute) {
  Notes notes;
  const Result<Mesh> mesh = ply::read(fixture("ply", "attributes_ascii.ply"), "attributes_ascii.ply", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4u);
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(mesh->units, Units::Millimetres);
  ASSERT_TRUE(mesh->has_normals() && mesh->has_colors() && mesh->has_texcoords());
  EXPECT_EQ(mesh->normals[3], Vec3f(0, 0, 1));
  EXPECT_EQ(mesh->texcoords[2], Vec2f(1, 1)) << "texture_u/texture_v (MeshLab's names) are read";
  EXPECT_EQ(mesh->colors[2], Vec4f(0, 0, 1, 128.0f / 255.0f));
  EXPECT_TRUE(has_note(notes, "vertex properties ignored: quality"));
  EXPECT_TRUE(has_note(notes, "elements ignored: edge (2 items)"));
  EXPECT_TRUE(has_note(notes, "face colours dropped"));
}

TEST(PlyRead, BigEndianBinary) {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  auto put_be = [&](auto value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    std::reverse(raw, raw + sizeof value);
    bytes.append(raw, sizeof value);
  };
  for (double c : {0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, -3.0})
    put_be(c);
  put_be(std::uint8_t{3});
  for (std::uint32_t v : {2u, 1u, 0u})
    put_be(v);
  Notes notes;
  const Result<Mesh> mesh = read_ply(bytes, &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->positions[2], Vec3(0, 2, -3));
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{2, 1, 0}}));
  EXPECT_TRUE(has_note(notes, "double coordinates are read as float32"));
}

// OpenMesh finds binary data by assuming "\nend_header\n" right after the last property: a comment there,
// CRLF line ends or trailing blanks would shift it. We hand OpenMesh a canonical header instead.
TEST(PlyRead, HeaderLayoutDoesNotShiftBinaryData) {
  const SmallPly ply = small_binary_ply();
  std::string header = ply.bytes.substr(0, ply.data_offset);
  header.replace(header.find("end_header"), 10, "comment last words  \nend_header");
  for (std::size_t at = header.find('\n'); at != std::string::npos; at = header.find('\n', at + 4))
    header.replace(at, 1, "  \r\n");
  const Result<Mesh> mesh = read_ply(header + ply.bytes.substr(ply.data_offset));
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(mesh->triangle_count(), 3u);
}

// Faces may come first: OpenMesh would stop after them, so vertices are handed over first.
TEST(PlyRead, FacesBeforeVertices) {
  const Result<Mesh> mesh =
      read_ply("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
               "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "end_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 3u);
  EXPECT_EQ(mesh->triangle_count(), 1u);
}

TEST(PlyRead, LargePolygonIsFanTriangulated) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 255\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 255; ++i)
    for (float c :
         {std::cos(0.0246f * static_cast<float>(i)), std::sin(0.0246f * static_cast<float>(i)), 0.0f})
      put(bytes, c);
  put(bytes, std::uint8_t{255});
  for (std::int32_t v = 0; v < 255; ++v)
    put(bytes, v);
  const Result<Mesh> mesh = read_ply(bytes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_EQ(mesh->triangle_count(), 253u);
  EXPECT_EQ(mesh->triangles.back(), (Triangle{0, 253, 254}));
}

TEST(PlyRead, ShortFacesAreSkippedWithANote) {
  Notes notes;
  const Result<Mesh> mesh = read_ply(ascii_ply("0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangle_count(), 0u);
  EXPECT_TRUE(has_note(notes, "1 faces with fewer than 3 corners skipped"));
}

TEST(PlyRead, TrailingDataIsNoted) {
  Notes notes;
  ASSERT_TRUE(read_ply(small_binary_ply().bytes + "xyz", &notes).ok());
  EXPECT_TRUE(has_note(notes, "3 bytes after the last element ignored"));
}

// ---- bad input: the header ----------------------------------------------------------------------------

TEST(PlyReadErrors, EmptyInput) { EXPECT_EQ(error_of(read_ply("")).code, ErrorCode::Empty); }

TEST(PlyReadErrors, WrongMagic) {
  const Error e = error_of(read_ply("plx\nformat ascii 1.0\n"));
  EXPECT_EQ(e.code, ErrorCode::BadMagic);
  EXPECT_EQ(e.where.line, 1u);
  EXPECT_EQ(e.source, "t.ply");
  EXPECT_EQ(error_of(read_ply("plyfoo\n")).code, ErrorCode::BadMagic);
}

// OpenMesh loops forever on this.
TEST(PlyReadErrors, HeaderWithoutEndHeader) {
  const Error e =
      error_of(read_ply("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"));
  EXPECT_EQ(e.code, ErrorCode::Truncated);
  EXPECT_EQ(e.where.line, 5u);
}

// OpenMesh crashes on this.
TEST(PlyReadErrors, PropertyBeforeAnyElement) {
  const Error e =
      error_of(read_ply("ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n1\n"));
  EXPECT_EQ(e.code, ErrorCode::Malformed);
  EXPECT_EQ(e.where.line, 3u);
  EXPECT_EQ(e.where.column, 1u);
}

TEST(PlyReadErrors, HeaderStatements) {
  struct Case {
    std::string_view line;
    ErrorCode code;
    std::uint64_t column;
  };
  for (const Case& c :
       {Case{"element vertex 1\nproperty foo x", ErrorCode::Malformed, 10},
        Case{"element vertex -1", ErrorCode::Malformed, 16},
        Case{"element vertex many", ErrorCode::Malformed, 16},
        Case{"element vertex 1 2", ErrorCode::Malformed, 18},
        Case{"elephant vertex 1", ErrorCode::Malformed, 1},
        Case{"element vertex 1\nproperty list float int vertex_indices", ErrorCode::Malformed, 1},
        Case{"element vertex 1\nproperty float", ErrorCode::Malformed, 15}}) {
    const Error e = error_of(read_ply(with_header_line(c.line)));
    EXPECT_EQ(e.code, c.code) << c.line;
    EXPECT_EQ(e.where.line, std::ranges::count(c.line, '\n') + 3u) << c.line;
    EXPECT_EQ(e.where.column, c.column) << c.line;
  }
}

TEST(PlyReadErrors, FormatAndVersion) {
  Error e = error_of(read_ply("ply\nformat binary_middle_endian 1.0\nend_header\n"));
  EXPECT_EQ(e.code, ErrorCode::UnsupportedFormat);
  EXPECT_EQ(e.where.line, 2u);
  EXPECT_EQ(e.where.column, 8u);
  e = error_of(read_ply("ply\nformat ascii 2.0\nend_header\n"));
  EXPECT_EQ(e.code, ErrorCode::UnsupportedVersion);
  EXPECT_EQ(e.where.column, 14u);
  e = error_of(read_ply("ply\nelement vertex 0\nend_header\n"));
  EXPECT_EQ(e.code, ErrorCode::Malformed);
  EXPECT_EQ(e.where.line, 3u);
}

// What OpenMesh's reader would misread, print to stderr about, or crash on is refused up front.
TEST(PlyReadErrors, LayoutsOpenMeshCannotRead) {
  const std::string_view xyz = "element vertex 1\nproperty float x\nproperty float y\nproperty float z";
  struct Case {
    std::string header;
    ErrorCode code;
    std::uint64_t line;
  };
  const std::vector<Case> cases{
      {"element vertex 1\nproperty int x\nproperty float y\nproperty float z", ErrorCode::UnsupportedFormat,
       4},
      {fmt::format("{}\nproperty ushort red", xyz), ErrorCode::UnsupportedFormat, 7},
      {fmt::format("{}\nproperty list uchar float weights", xyz), ErrorCode::UnsupportedFormat, 7},
      {fmt::format(
           "{}\nelement face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord",
           xyz),
       ErrorCode::UnsupportedFormat, 9},
      {fmt::format("{}\nelement face 1\nproperty list uint int vertex_indices", xyz),
       ErrorCode::UnsupportedFormat, 8},
      {fmt::format("{}\nelement face 1\nproperty int vertex_indices", xyz), ErrorCode::Malformed, 8},
      {fmt::format("{}\nelement face 1\nproperty uchar flags", xyz), ErrorCode::Malformed, 7},
      {"element vertex 1\nproperty float x\nproperty float y", ErrorCode::Malformed, 3},
      {"element face 1\nproperty list uchar int vertex_indices", ErrorCode::Malformed, 5},
      {fmt::format("{}\n{}", xyz, xyz), ErrorCode::Malformed, 7},
  };
  for (const Case& c : cases) {
    const Error e = error_of(read_ply(with_header_line(c.header)));
    EXPECT_EQ(e.code, c.code) << c.header;
    EXPECT_EQ(e.where.line, c.line) << c.header;
  }
}

// ---- bad input: counts and binary data ----------------------------------------------------------------

TEST(PlyReadErrors, CountBeyondIntFailsAtTheCount) {
  const Error e = error_of(read_ply(ascii_ply(kTriangle, "2147483648")));
  EXPECT_EQ(e.code, ErrorCode::CountTooLarge);
  EXPECT_EQ(e.where.line, 3u);
  EXPECT_EQ(e.where.column, 16u);
}

// A count the file cannot hold fails before anything is read or allocated.
TEST(PlyReadErrors, CountLargerThanTheFile) {
  std::string bytes = small_binary_ply().bytes;
  bytes.replace(bytes.find("vertex 4"), 8, "vertex 2147483647");
  Error e = error_of(read_ply(bytes));
  EXPECT_EQ(e.code, ErrorCode::CountTooLarge);
  EXPECT_EQ(e.where.line, 4u);
  EXPECT_NE(e.message.find("2147483647 items of at least 15 bytes"), std::string::npos) << e.message;
  e = error_of(read_ply(ascii_ply(kTriangle, "2147483647")));
  EXPECT_EQ(e.code, ErrorCode::CountTooLarge);
  EXPECT_EQ(e.where.line, 3u);
}

TEST(PlyReadErrors, EveryTruncationOfABinaryFile) {
  const SmallPly ply = small_binary_ply();
  for (std::size_t n = 0; n < ply.bytes.size(); ++n) {
    const Result<Mesh> mesh = read_ply(std::string_view(ply.bytes).substr(0, n));
    ASSERT_FALSE(mesh.ok()) << "length " << n;
    const Error& e = mesh.error();
    if (n == 0) {
      EXPECT_EQ(e.code, ErrorCode::Empty);
    } else if (n < 3) {
      EXPECT_EQ(e.code, ErrorCode::BadMagic) << n;
    } else if (n < ply.data_offset) {
      EXPECT_EQ(e.code, ErrorCode::Truncated) << n;
      EXPECT_NE(e.where.line, 0u) << n;
    } else {
      // The error points at the record the data ends in.
      const auto record = std::ranges::upper_bound(ply.records, n) - 1;
      EXPECT_EQ(e.code, ErrorCode::Truncated) << n;
      EXPECT_EQ(e.where.byte, *record) << n << ": " << e.message;
    }
  }
}

TEST(PlyReadErrors, ListCountBeyondTheData) {
  SmallPly ply = small_binary_ply();
  const std::size_t face = ply.records[5];
  ply.bytes[face] = static_cast<char>(255); // the last face claims 255 corners
  const Error e = error_of(read_ply(ply.bytes));
  EXPECT_EQ(e.code, ErrorCode::Truncated);
  EXPECT_EQ(e.where.byte, face);
}

TEST(PlyReadErrors, FaceIndexOutOfRange) {
  SmallPly ply = small_binary_ply();
  const std::size_t third_corner = ply.records[5] + 1 + 2 * 4;
  ply.bytes.replace(third_corner, 4, std::string("\x07\x00\x00\x00", 4));
  const Error e = error_of(read_ply(ply.bytes));
  EXPECT_EQ(e.code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(e.where.byte, third_corner);
  EXPECT_EQ(e.message, "face 1 refers to vertex 7, but there are 4 vertices");
}

TEST(PlyReadErrors, NaNCoordinateInBinary) {
  SmallPly ply = small_binary_ply();
  const std::size_t y_of_vertex_2 = ply.records[2] + 4;
  const float nan = std::nanf("");
  std::memcpy(ply.bytes.data() + y_of_vertex_2, &nan, 4);
  const Error e = error_of(read_ply(ply.bytes));
  EXPECT_EQ(e.code, ErrorCode::NonFinite);
  EXPECT_EQ(e.where.byte, y_of_vertex_2);
}

TEST(PlyReadErrors, GarbageAfterTheHeader) {
  const SmallPly ply = small_binary_ply();
  const std::string header = ply.bytes.substr(0, ply.data_offset);
  // 0xFF bytes: the first coordinate is a NaN.
  Error e = error_of(read_ply(header + std::string(200, '\xFF')));
  EXPECT_EQ(e.code, ErrorCode::NonFinite);
  EXPECT_EQ(e.where.byte, ply.data_offset);
  // 'A' bytes: finite coordinates, then a face of 65 corners whose first index is 0x41414141.
  e = error_of(read_ply(header + std::string(200, 'A')));
  EXPECT_EQ(e.code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(e.where.byte, ply.records[4] + 1);
}

// ---- bad input: ASCII data ----------------------------------------------------------------------------

TEST(PlyReadErrors, AsciiValues) {
  struct Case {
    std::string_view data;
    ErrorCode code;
    std::uint64_t line;
    std::uint64_t column;
  };
  for (const Case& c : {Case{"0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", ErrorCode::NonFinite, 11, 3},
                        Case{"0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", ErrorCode::NonFinite, 11, 5},
                        Case{"0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n", ErrorCode::NonFinite, 11, 3},
                        Case{"0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", ErrorCode::Malformed, 11, 3},
                        Case{"0 0 0\n1 0.5.5 0\n0 1 0\n3 0 1 2\n", ErrorCode::Malformed, 11, 3},
                        Case{"0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", ErrorCode::Malformed, 13, 5},
                        Case{"0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", ErrorCode::Malformed, 13, 1},
                        Case{"0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ErrorCode::IndexOutOfRange, 13, 7},
                        Case{"0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", ErrorCode::IndexOutOfRange, 13, 5},
                        Case{"0 0 0\n1 0 0\n0 1", ErrorCode::Truncated, 12, 4},
                        Case{"0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ErrorCode::Truncated, 14, 1}}) {
    const Error e = error_of(read_ply(ascii_ply(c.data)));
    EXPECT_EQ(e.code, c.code) << c.data;
    EXPECT_EQ(e.where.line, c.line) << c.data;
    EXPECT_EQ(e.where.column, c.column) << c.data << ": " << e.message;
  }
}

// OpenMesh prints some complaints straight to stderr; we refuse those inputs before it sees them.
TEST(PlyReadErrors, NothingIsPrinted) {
  const SmallPly ply = small_binary_ply();
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  for (std::size_t n = 0; n < ply.bytes.size(); ++n)
    (void)read_ply(std::string_view(ply.bytes).substr(0, n));
  (void)read_ply(with_header_line("element vertex 1\nproperty int x\nproperty float y\nproperty float z"));
  (void)read_ply(with_header_line("element vertex 1\nproperty foo x"));
  (void)read_ply(ascii_ply("0 0 0\n1 0 0\n0 1 0\n2 0 1\n"));
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}
