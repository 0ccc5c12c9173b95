// The Draco reader and writer: a real scan, round trips within the quantisation step, option checks and
// every class of bad input, with codes and byte offsets.
#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/draco/draco.hpp"
#include "pdeface_test.hpp"
#include "quantisation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace pdeface {

using test::half_step;
using test::max_vertex_error;
using test::sorted_axis_error;

void PrintTo(ErrorCode code, std::ostream* os) { *os << to_string(code); }

namespace {

std::string fixture(std::string_view name) {
  Result<std::string> bytes = read_file(test::fixtures() / "draco" / name);
  EXPECT_TRUE(bytes.ok()) << name;
  return bytes.ok() ? *bytes : std::string();
}

Mesh small_face() {
  return sample_face({.spacing_mm = 8.0}); // ~400 vertices: small enough to truncate at every length
}

// The vertex block of a binary little-endian PLY whose vertices are three floats (the facefuns scans).
std::vector<Vec3> read_ply_positions(const std::filesystem::path& path) {
  const std::string bytes = *read_file(path);
  const std::string_view end = "end_header\n";
  const std::size_t body = bytes.find(end) + end.size();
  const std::string header = bytes.substr(0, body);
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("property float x\nproperty float y\nproperty float z\nelement face"),
            std::string::npos);
  const std::size_t at = header.find("element vertex ") + 15;
  const std::size_t n = std::stoul(header.substr(at));
  std::vector<Vec3> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    float p[3];
    std::memcpy(p, bytes.data() + body + 12 * i, sizeof p);
    points[i] = Vec3(p[0], p[1], p[2]);
  }
  return points;
}

void expect_error(const Result<Mesh>& result, ErrorCode code, std::optional<std::uint64_t> byte) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, code) << result.error().to_string();
  EXPECT_EQ(result.error().where.byte, byte) << result.error().to_string();
  EXPECT_EQ(result.error().source, "bad.drc");
}

std::string varint(std::uint32_t v) {
  std::string out;
  do {
    const auto b = static_cast<char>(v & 0x7f);
    v >>= 7;
    out += v ? static_cast<char>(b | 0x80) : b;
  } while (v);
  return out;
}

// A Draco header: magic, version, geometry type, method, flags.
std::string header(int major, int minor, int type, int method, std::uint16_t flags = 0) {
  std::string h = "DRACO";
  for (int b : {major, minor, type, method, flags & 0xff, flags >> 8})
    h += static_cast<char>(b);
  return h;
}

// ---- real scan -----------------------------------------------------------------------------------------

TEST(DracoRead, RealScanWithinQuantisationStepOfItsPly) {
  PDEFACE_FACE_OR_SKIP(drc_path, "facefuns_m46.drc");
  PDEFACE_FACE_OR_SKIP(ply_path, "facefuns_m46.ply");
  Notes notes;
  Result<Mesh> mesh = drc::read(*read_file(drc_path), "facefuns_m46.drc", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 30204u);
  EXPECT_EQ(mesh->triangle_count(), 59697u);
  EXPECT_FALSE(mesh->has_normals());
  EXPECT_EQ(mesh->units, Units::Unknown); // draco_encoder writes no units
  EXPECT_TRUE(notes.empty());

  const std::vector<Vec3> original = read_ply_positions(ply_path);
  ASSERT_EQ(original.size(), mesh->vertex_count());
  Mesh reference;
  reference.positions = original;
  const double tolerance = half_step(reference, 14); // draco_encoder -qp 14
  const Box a = bounding_box(*mesh), b = bounding_box(reference);
  EXPECT_LE((a.min - b.min).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_LE((a.max - b.max).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_LE(sorted_axis_error(mesh->positions, original), tolerance);
  EXPECT_GT(sorted_axis_error(mesh->positions, original), 0.0); // it is quantised
}

// ---- round trips ---------------------------------------------------------------------------------------

TEST(DracoRoundTrip, SampleFaceAtSeveralBitDepthsKeepsOrderAtLevel0) {
  Mesh face = sample_face();
  face.units = Units::Millimetres;
  for (int bits : {8, 11, 14, 18, 24}) {
    SCOPED_TRACE(bits);
    Notes notes;
    Result<std::string> bytes = drc::write(face, {.position_bits = bits, .level = 0}, &notes);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find(std::to_string(bits) + " bits"), std::string::npos) << notes[0];
    Result<Mesh> back = drc::read(*bytes, "face.drc");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_EQ(back->vertex_count(), face.vertex_count());
    EXPECT_EQ(back->triangles, face.triangles); // level 0: same vertex order, same triangles
    const double error = max_vertex_error(back->positions, face.positions);
    EXPECT_LE(error, half_step(face, bits));
    EXPECT_GT(error, half_step(face, bits) / 20); // really quantised at that depth, not finer
    EXPECT_EQ(back->units, Units::Millimetres);
    ASSERT_TRUE(back->has_normals());
    ASSERT_TRUE(back->has_colors());
    for (std::size_t i = 0; i < face.vertex_count(); ++i) {
      ASSERT_GT(back->normals[i].dot(face.normals[i]), 0.999f) << i; // 10-bit octahedral normals
      ASSERT_LE((back->colors[i] - face.colors[i]).cwiseAbs().maxCoeff(), 0.5f / 255 + 1e-6f) << i;
    }
  }
}

TEST(DracoRoundTrip, Level7ReordersVerticesButKeepsTheShape) {
  const Mesh face = sample_face();
  Result<std::string> bytes = drc::write(face, {.level = 7});
  ASSERT_TRUE(bytes.ok());
  Result<Mesh> back = drc::read(*bytes, "face.drc");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  ASSERT_EQ(back->vertex_count(), face.vertex_count());
  EXPECT_EQ(back->triangle_count(), face.triangle_count());
  EXPECT_NE(back->triangles, face.triangles);
  EXPECT_LE(sorted_axis_error(back->positions, face.positions), half_step(face, 14));
  EXPECT_LT(bytes->size(), drc::write(face, {.level = 0})->size() / 4);
}

TEST(DracoRoundTrip, PointCloudAtLevels0And7) {
  Mesh cloud = sample_face();
  cloud.triangles.clear();
  cloud.units = Units::Metres;
  for (int level : {0, 7}) {
    SCOPED_TRACE(level);
    Result<std::string> bytes = drc::write(cloud, {.level = level});
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    EXPECT_EQ((*bytes)[7], 0) << "a point cloud, not a mesh";
    Result<Mesh> back = drc::read(*bytes, "cloud.drc");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_TRUE(back->is_point_cloud());
    ASSERT_EQ(back->vertex_count(), cloud.vertex_count());
    EXPECT_EQ(back->units, Units::Metres);
    EXPECT_TRUE(back->has_colors());
    if (level == 0) {
      EXPECT_LE(max_vertex_error(back->positions, cloud.positions), half_step(cloud, 14));
    }
    EXPECT_LE(sorted_axis_error(back->positions, cloud.positions), half_step(cloud, 14));
  }
}

TEST(DracoRoundTrip, TexcoordsAnd16BitColours) {
  Mesh face = small_face();
  for (std::size_t i = 0; i < face.vertex_count(); ++i) {
    face.texcoords.emplace_back(static_cast<float>(i % 17) / 16, static_cast<float>(i % 5) / 4);
    face.colors[i].w() = static_cast<float>(i % 3) / 2;
  }
  Result<std::string> bytes = drc::write(face, {.color_bits = 16, .texcoord_bits = 12, .level = 0});
  ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
  Result<Mesh> back = drc::read(*bytes, "face.drc");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  ASSERT_TRUE(back->has_texcoords());
  for (std::size_t i = 0; i < face.vertex_count(); ++i) {
    ASSERT_LE((back->texcoords[i] - face.texcoords[i]).cwiseAbs().maxCoeff(), 0.5f / 4095 + 1e-6f) << i;
    ASSERT_LE((back->colors[i] - face.colors[i]).cwiseAbs().maxCoeff(), 0.5f / 65535 + 1e-6f) << i;
  }
}

TEST(DracoWrite, NotesVerticesOnNoTriangleThatEdgebreakerDrops) {
  Mesh face = small_face();
  face.positions.emplace_back(0, 0, 500);
  face.normals.emplace_back(0, 0, 1);
  face.colors.emplace_back(1, 1, 1, 1);
  Notes notes;
  Result<Mesh> back = drc::read(*drc::write(face, {.level = 7}, &notes), "face.drc");
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->vertex_count(), face.vertex_count() - 1);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[1].find("1 vertex on no triangle"), std::string::npos) << notes[1];
  back = drc::read(*drc::write(face, {.level = 0}), "face.drc");
  EXPECT_EQ(back->vertex_count(), face.vertex_count());
}

TEST(DracoWrite, RefusesEmptyAndInvalidMeshes) {
  Result<std::string> empty = drc::write(Mesh{});
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().code, ErrorCode::Empty);
  Mesh bad = small_face();
  bad.triangles[3][1] = 100000;
  Result<std::string> out = drc::write(bad);
  ASSERT_FALSE(out.ok());
  EXPECT_EQ(out.error().code, ErrorCode::IndexOutOfRange);
}

TEST(DracoWrite, CheckRefusesOptionsOutOfRange) {
  EXPECT_TRUE(drc::check({}).ok());
  EXPECT_TRUE(drc::check({.position_bits = 1, .normal_bits = 2, .texcoord_bits = 1, .level = 0}).ok());
  EXPECT_TRUE(
      drc::check({.position_bits = 24, .normal_bits = 24, .color_bits = 16, .texcoord_bits = 24, .level = 10})
          .ok());
  struct Case {
    drc::WriteOptions options;
    std::string_view message;
  };
  for (const Case& c : {Case{{.position_bits = 0}, "position_bits = 0 is outside 1..24"},
                        Case{{.position_bits = 25}, "position_bits = 25 is outside 1..24"},
                        Case{{.position_bits = 30}, "position_bits = 30 is outside 1..24"},
                        Case{{.normal_bits = 1}, "normal_bits = 1 is outside 2..24"},
                        Case{{.color_bits = 10}, "color_bits = 10 is neither 8 nor 16"},
                        Case{{.texcoord_bits = 31}, "texcoord_bits = 31 is outside 1..24"},
                        Case{{.level = -1}, "level = -1 is outside 0..10"},
                        Case{{.level = 11}, "level = 11 is outside 0..10"}}) {
    const Result<void> result = drc::check(c.options);
    ASSERT_FALSE(result.ok()) << c.message;
    EXPECT_EQ(result.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(result.error().message.substr(0, c.message.size()), c.message);
    Result<std::string> written = drc::write(small_face(), c.options);
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().code, ErrorCode::InvalidArgument);
  }
}

// ---- bad input -----------------------------------------------------------------------------------------

TEST(DracoBadInput, EmptyWrongMagicAndShortHeader) {
  expect_error(drc::read("", "bad.drc"), ErrorCode::Empty, 0);
  expect_error(drc::read("PLY\nformat", "bad.drc"), ErrorCode::BadMagic, 0);
  expect_error(drc::read("DRACX\x02\x02", "bad.drc"), ErrorCode::BadMagic, 0);
  expect_error(drc::read("DRA", "bad.drc"), ErrorCode::Truncated, 3);
  expect_error(drc::read(header(2, 2, 1, 1).substr(0, 9), "bad.drc"), ErrorCode::Truncated, 9);
}

TEST(DracoBadInput, VersionsGeometryTypesAndMethods) {
  expect_error(drc::read(header(3, 0, 1, 1) + "\x00\x00", "bad.drc"), ErrorCode::UnsupportedVersion, 5);
  expect_error(drc::read(header(2, 1, 1, 1) + "\x00\x00", "bad.drc"), ErrorCode::UnsupportedVersion, 5);
  expect_error(drc::read(header(2, 2, 0, 0) + "\x00\x00", "bad.drc"), ErrorCode::UnsupportedVersion, 5);
  expect_error(drc::read(header(2, 2, 2, 0) + "\x00\x00", "bad.drc"), ErrorCode::Malformed, 7);
  expect_error(drc::read(header(2, 2, 1, 2) + "\x00\x00", "bad.drc"), ErrorCode::Malformed, 8);
  Result<Mesh> version = drc::read(header(1, 3, 1, 1), "bad.drc");
  EXPECT_NE(version.error().message.find("bitstream 1.3"), std::string::npos) << version.error().message;
}

TEST(DracoBadInput, HugeCountsFailBeforeLibdracoAllocates) {
  const std::string padding(100, '\x55');
  // Sequential mesh: 2^31 faces (at byte 11), then 2^31 points (at byte 12 after a 1-byte face count).
  expect_error(drc::read(header(2, 2, 1, 0) + varint(1u << 31) + varint(3) + padding, "bad.drc"),
               ErrorCode::CountTooLarge, 11);
  expect_error(drc::read(header(2, 2, 1, 0) + varint(3) + varint(1u << 31) + padding, "bad.drc"),
               ErrorCode::CountTooLarge, 12);
  // Edgebreaker: traversal type at 11, vertices at 12, faces after them.
  expect_error(drc::read(header(2, 2, 1, 1) + '\x02' + varint(1u << 31) + padding, "bad.drc"),
               ErrorCode::CountTooLarge, 12);
  expect_error(drc::read(header(2, 2, 1, 1) + '\x02' + varint(9) + varint(100'000'000) + padding, "bad.drc"),
               ErrorCode::CountTooLarge, 13);
  // Split symbols add vertices: 9 + 2^30 of them.
  expect_error(drc::read(header(2, 2, 1, 1) + '\x02' + varint(9) + varint(8) + '\x00' + varint(8) +
                             varint(1u << 30) + padding,
                         "bad.drc"),
               ErrorCode::CountTooLarge, 16);
  // Point clouds (sequential and k-d tree): an int32 count at byte 11.
  for (int method : {0, 1}) {
    const std::string count("\x00\x00\x00\x80", 4);
    Result<Mesh> result = drc::read(header(2, 3, 0, method) + count + padding, "bad.drc");
    expect_error(result, ErrorCode::CountTooLarge, 11);
    EXPECT_NE(result.error().message.find("2147483648 points"), std::string::npos) << result.error().message;
  }
}

TEST(DracoBadInput, HostileMetadata) {
  const std::string mesh = header(2, 2, 1, 0, 0x8000);
  const std::string tail = varint(8) + varint(9) + std::string(100, '\0');
  // 4 GB claimed for one value (after 0 attributes, 1 entry, name "u"): the data ends first.
  const std::string huge_value = mesh + varint(0) + varint(1) + "\x01u" + varint(0xffffffff) + tail;
  expect_error(drc::read(huge_value, "bad.drc"), ErrorCode::Truncated, huge_value.size());
  // 2^31 attribute metadata nodes (libdraco would loop over them 2^31 times, even past the end) or entries:
  // valid ones follow until the data ends.
  std::string attributes = mesh + varint(1u << 31), entries = mesh + varint(0) + varint(1u << 31);
  for (int i = 0; i < 40; ++i) {
    attributes += std::string("\x00\x00\x00", 3); // id 0, no entries, no children
    entries += std::string("\x00\x01\x00", 3);    // no name, a 1-byte value
  }
  expect_error(drc::read(attributes, "bad.drc"), ErrorCode::Truncated, attributes.size());
  expect_error(drc::read(entries, "bad.drc"), ErrorCode::Truncated, entries.size());
  // A value of 0 bytes (libdraco refuses it too), size at byte 15.
  expect_error(drc::read(mesh + varint(0) + varint(1) + "\x01u" + varint(0) + tail, "bad.drc"),
               ErrorCode::Malformed, 15);
  // Children nested 40 deep: each is (name "", 0 entries, 1 child); libdraco would recurse without limit.
  std::string nested = varint(0) + varint(0) + varint(1);
  for (int i = 0; i < 40; ++i)
    nested += std::string("\x00", 1) + varint(0) + varint(1);
  Result<Mesh> deep = drc::read(mesh + nested + tail, "bad.drc");
  ASSERT_FALSE(deep.ok());
  EXPECT_EQ(deep.error().code, ErrorCode::Malformed);
  EXPECT_NE(deep.error().message.find("nested deeper than 32"), std::string::npos);
  // A varint of more than 5 bytes.
  expect_error(drc::read(mesh + std::string(6, '\x80') + tail, "bad.drc"), ErrorCode::Malformed, 11);
}

TEST(DracoBadInput, HandMadeFixtures) {
  Result<Mesh> square = drc::read(fixture("square.drc"), "square.drc");
  ASSERT_TRUE(square.ok()) << square.error().to_string();
  EXPECT_EQ(square->vertex_count(), 9u);
  EXPECT_EQ(square->triangle_count(), 8u);

  Notes notes;
  Result<Mesh> generic = drc::read(fixture("square_generic16.drc"), "generic.drc", &notes);
  ASSERT_TRUE(generic.ok()) << generic.error().to_string();
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "generic.drc: Draco attribute 1 (generic) dropped");

  Result<Mesh> nan = drc::read(fixture("nan_position.drc"), "bad.drc");
  expect_error(nan, ErrorCode::NonFinite, std::nullopt);
  EXPECT_NE(nan.error().message.find("point 4"), std::string::npos) << nan.error().message;

  // square.drc stores its faces as raw bytes from byte 14; make the third index of face 0 point past the
  // 9 points. libdraco checks this itself; either way it must be refused.
  std::string out_of_range = fixture("square.drc");
  out_of_range[16] = 0x20;
  const Result<Mesh> index = drc::read(out_of_range, "bad.drc");
  ASSERT_FALSE(index.ok());
  EXPECT_TRUE(index.error().code == ErrorCode::Malformed || index.error().code == ErrorCode::IndexOutOfRange)
      << index.error().to_string();
}

TEST(DracoBadInput, GarbageAfterAValidHeader) {
  std::mt19937 random(7);
  for (const std::string& h :
       {header(2, 2, 1, 0), header(2, 2, 1, 1), header(2, 3, 0, 0), header(2, 3, 0, 1)}) {
    std::string bytes = h;
    for (int i = 0; i < 200; ++i)
      bytes += static_cast<char>(random() % 7); // small values: plausible counts
    const Result<Mesh> result = drc::read(bytes, "bad.drc");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().source, "bad.drc");
    EXPECT_TRUE(result.error().where.byte.has_value()) << result.error().to_string();
  }
}

// Every prefix of a small valid file, mesh or point cloud, sequential or not, with metadata: an error or a
// valid mesh, never a crash (run under the sanitizers too).
TEST(DracoBadInput, EveryTruncationLengthFailsCleanly) {
  Mesh face = small_face();
  face.units = Units::Millimetres;
  Mesh cloud = face;
  cloud.triangles.clear();
  for (const Mesh* mesh : {&face, &cloud})
    for (int level : {0, 7}) {
      const std::string bytes = *drc::write(*mesh, {.level = level});
      for (std::size_t n = 0; n < bytes.size(); ++n) {
        const Result<Mesh> result = drc::read(std::string_view(bytes).substr(0, n), "bad.drc");
        if (result.ok()) {
          EXPECT_TRUE(validate(*result).ok());
          continue;
        }
        ASSERT_EQ(result.error().source, "bad.drc");
        if (n < 11) {
          EXPECT_EQ(result.error().code, n == 0 ? ErrorCode::Empty : ErrorCode::Truncated);
        }
      }
    }
}

// Random byte changes of small valid files: never a crash, never a hang.
TEST(DracoBadInput, RandomMutationsFailCleanly) {
  Mesh face = small_face();
  Mesh cloud = face;
  cloud.triangles.clear();
  std::mt19937 random(42);
  for (const Mesh* mesh : {&face, &cloud})
    for (int level : {0, 7}) {
      const std::string original = *drc::write(*mesh, {.level = level});
      for (int trial = 0; trial < 300; ++trial) {
        std::string bytes = original;
        for (int k = 0; k < 1 + trial % 4; ++k)
          bytes[random() % bytes.size()] = static_cast<char>(random());
        const Result<Mesh> result = drc::read(bytes, "bad.drc");
        if (result.ok()) {
          EXPECT_TRUE(validate(*result).ok());
        }
      }
    }
}

} // namespace
} // namespace pdeface
