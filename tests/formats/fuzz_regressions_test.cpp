// Every input a fuzz target found a fault with (fuzz/, docs/robustness.md), kept in tests/data/<format>/
// as fuzz_*: each now reads as it should, and what it reads writes and reads back in every format.
#include "pdeface/core/file.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface_test.hpp"

#include <algorithm>
#include <optional>
#include <string>

namespace pdeface::formats {
namespace {

struct Finding {
  const char* file;                    // tests/data/<file>
  std::optional<std::size_t> vertices; // read: that many; nullopt: refused with `code`
  ErrorCode code = ErrorCode::Malformed;
  const char* what; // what went wrong before the fix
};

const Finding kFindings[] = {
    {"obj/fuzz_vertical_tab.obj",
     1,
     {},
     "'v\\v1 0 0 ...': a vertex to the validator (VT is a blank), none to tinyobjloader: an empty mesh"},
    {"obj/fuzz_exponent.obj",
     1,
     {},
     "'0e801' (a colour): 0 to fast_float, 0 x inf = NaN to tinyobjloader; written as -nan, refused on read"},
    {"stl/fuzz_tiny_corners.stl",
     4,
     {},
     "corners 5e-39 apart: merged by OpenMesh's STL epsilon (FLT_MIN) into a degenerate facet on reading "
     "back"},
    {"draco/fuzz_denormal_corners.drc",
     9,
     {},
     "corners 9e-44 apart: OpenMesh's STL reader merged them (FLT_MIN apart is equal to it), 6 of 8 facets "
     "lost in an STL round trip"},
    {"off/fuzz_one_triangle.off",
     4,
     {},
     "one triangle: libdraco's sequential encoder (level 0) wrote data its own decoder refuses"},
    {"gltf/fuzz_component_type.glb",
     {},
     ErrorCode::Malformed,
     "a Draco attribute's accessor of componentType 5127: tinygltf sized its buffer as points x 3 x -1 "
     "bytes, "
     "a 4 GB allocation"},
    {"gltf/fuzz_control_character.glb",
     {},
     ErrorCode::Malformed,
     "a Draco attribute named 'TEPCOORD\\x7f0' was quoted as it is in the message: a control character"},
    {"gltf/fuzz_number_overflow.gltf",
     {},
     ErrorCode::Malformed,
     "\"componentTyp\":1e526: nlohmann's out_of_range.406 escaped the reader (exit 3, internal error)"},
};

void PrintTo(const Finding& f, std::ostream* os) { *os << f.file; }

class FuzzFinding : public ::testing::TestWithParam<Finding> {};

TEST_P(FuzzFinding, ReadsAsItShouldAndRoundTrips) {
  const Finding& f = GetParam();
  const Result<std::string> bytes = read_file(test::fixtures() / f.file);
  ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
  const Result<LoadedMesh> read = read_mesh(*bytes, f.file);
  if (!f.vertices) {
    ASSERT_FALSE(read.ok()) << f.what;
    EXPECT_EQ(read.error().code, f.code) << read.error().to_string();
    // One short line of UTF-8, as every message (fuzz/checks.hpp).
    const std::string& message = read.error().message;
    EXPECT_LT(message.size(), 512U);
    EXPECT_TRUE(is_valid_utf8(message)) << message;
    EXPECT_TRUE(std::ranges::none_of(message, [](char c) {
      return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    })) << message;
    return;
  }
  ASSERT_TRUE(read.ok()) << f.what << ": " << read.error().to_string();
  EXPECT_EQ(read->mesh.vertex_count(), *f.vertices) << f.what;
  for (const FormatInfo& format : all_formats()) {
    if (!format.writable) continue;
    const std::string name = "again" + std::string(format.extensions.front());
    const Result<std::string> out = encode_mesh(read->mesh, name);
    if (!out) continue; // refused cleanly (e.g. STL cannot hold a point cloud)
    const Result<LoadedMesh> back = read_mesh(*out, name);
    ASSERT_TRUE(back.ok()) << format.name << ": " << back.error().to_string();
    // As many triangles (STL: those whose corners are three different points; Draco may drop degenerate
    // ones), as fuzz/checks.hpp requires.
    const Mesh& m = read->mesh;
    std::size_t triangles = m.triangle_count();
    if (format.format == Format::Stl)
      triangles = static_cast<std::size_t>(std::ranges::count_if(m.triangles, [&](const Triangle& t) {
        const Vec3f a = m.positions[t[0]].cast<float>(), b = m.positions[t[1]].cast<float>(),
                    c = m.positions[t[2]].cast<float>();
        return a != b && b != c && a != c;
      }));
    if (format.format != Format::Draco) {
      EXPECT_EQ(back->mesh.triangle_count(), triangles) << format.name;
    }
  }
  // Draco at level 0 (vertex order kept) and inside a GLB: refused with a clear error, or read back.
  for (const auto& [name, options] : {std::pair{"again0.drc", WriteOptions{.draco_level = 0}},
                                      std::pair{"again.glb", WriteOptions{.draco_in_gltf = true}}}) {
    const Result<std::string> out = encode_mesh(read->mesh, name, options);
    if (!out) continue;
    const Result<LoadedMesh> back = read_mesh(*out, name);
    EXPECT_TRUE(back.ok()) << name << ": " << back.error().to_string();
  }
}

INSTANTIATE_TEST_SUITE_P(Fuzz, FuzzFinding, ::testing::ValuesIn(kFindings),
                         [](const auto& param) { return test::test_name(param.param.file); });

} // namespace
} // namespace pdeface::formats
