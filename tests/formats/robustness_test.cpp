// Every reader and writer on hostile input (issue 22, docs/robustness.md): messages quote at most ~60 bytes
// of a file, expansions are bounded by the file's size, what libdraco is handed is checked, an empty mesh
// is neither read nor written, and names are written as valid UTF-8.
#include "pdeface/core/file.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface_test.hpp"
#include "test_meshes.hpp"

#include <cfloat>
#include <string>
#include <vector>

namespace pdeface::formats {
namespace {

// ---- messages quote at most ~60 bytes of the input ------------------------------------------------------

struct LongToken {
  const char* name; // the file's name: its extension picks the reader
  std::string bytes;
};

const std::string kToken(1 << 20, 'x'); // a 1 MB word

std::vector<LongToken> long_tokens() {
  const std::string ply = "ply\nformat ascii 1.0\n";
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  return {
      {"number.obj", "v 1 2 " + kToken + "\n"},
      {"corner.obj", "v 0 0 0\nf 1 " + kToken + "\n"},
      {"count.off", "OFF\n" + kToken + " 1 0\n"},
      {"coordinate.off", "OFF\n1 0 0\n0 " + kToken + " 0\n"},
      {"number.wrl", "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [ 1 " +
                         kToken + " ] } } }\n"},
      {"use.wrl", "#VRML V2.0 utf8\nShape { geometry USE " + kToken + " }\n"},
      {"version.wrl", "#VRML V" + kToken + " utf8\n"},
      {"keyword.stl", "solid x\n" + kToken + "\n"},
      {"keyword.ply", ply + kToken + "\nend_header\n"},
      {"type.ply", ply + "element vertex 1\nproperty " + kToken + " x\nend_header\n"},
      {"value.ply", ply + "element vertex 1\n" + xyz + "end_header\n0 0 " + kToken + "\n"},
      {"element.ply", ply + "element " + kToken + " 99999999999\nend_header\n"},
      {"version.gltf", R"({"asset": {"version": ")" + kToken + R"("}})"},
  };
}

TEST(Robustness, MessagesQuoteAtMostSixtyBytesOfTheInput) {
  for (const LongToken& t : long_tokens()) {
    const Result<LoadedMesh> read = read_mesh(t.bytes, t.name);
    ASSERT_FALSE(read.ok()) << t.name;
    const std::string& message = read.error().message;
    EXPECT_LT(message.size(), 200U) << t.name << ": " << message.substr(0, 300);
    EXPECT_NE(message.find("xxx..."), std::string::npos) << t.name << ": " << message.substr(0, 300);
  }
}

TEST(Robustness, NotesNameAFewThingsAndQuoteThemShort) {
  // A PLY with 1000 extra elements and properties of long names, an OBJ with 1000 kinds of statements.
  std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\n";
  for (int i = 0; i < 1000; ++i)
    ply += "property float " + std::string(100, 'p') + std::to_string(i) + "\n";
  for (int i = 0; i < 1000; ++i)
    ply += "element " + std::string(100, 'e') + std::to_string(i) + " 0\n";
  ply += "end_header\n";
  for (int v = 0; v < 3; ++v) {
    ply += std::to_string(v) + " 0 0";
    for (int i = 0; i < 1000; ++i)
      ply += " 0";
    ply += "\n";
  }
  std::string obj = "v 0 0 0\n";
  for (int i = 0; i < 1000; ++i)
    obj += std::string(100, 'w') + std::to_string(i) + "\n";
  for (const auto& [name, bytes] : {std::pair{"notes.ply", ply}, std::pair{"notes.obj", obj}}) {
    Notes notes;
    const Result<LoadedMesh> read = read_mesh(bytes, name, {}, &notes);
    ASSERT_TRUE(read.ok()) << read.error().to_string();
    std::size_t total = 0;
    for (const std::string& n : notes)
      total += n.size();
    EXPECT_LT(total, 2000U) << name << ": " << notes.front().substr(0, 300);
    EXPECT_NE(notes.front().find(" more"), std::string::npos) << notes.front();
  }
}

// ---- expansions bounded by the file's size --------------------------------------------------------------

// An 11 KB VRML file whose nested USEs draw a 1000-point face set 32 x 32 x 31 times: 32.8 million
// vertices (4 GB) within the reader's absolute limits, refused by the one on what its size justifies.
TEST(Robustness, NestedUseExpandsNoFurtherThanTheFileJustifies) {
  std::string points, index;
  for (int i = 0; i < 1000; ++i)
    points +=
        std::to_string(i % 10) + " " + std::to_string(i / 10 % 10) + " " + std::to_string(i / 100) + " ";
  for (int i = 0; i + 2 < 1000; i += 3)
    index += std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + " -1 ";
  std::string wrl = "#VRML V2.0 utf8\nDEF A Group { children [ Shape { geometry IndexedFaceSet { coord "
                    "Coordinate { point [ " +
                    points + "] } coordIndex [ " + index + "] } } ] }\n";
  auto uses = [](const char* name, int n) {
    std::string out;
    for (int i = 0; i < n; ++i)
      out += std::string(" USE ") + name;
    return out;
  };
  wrl += "DEF B Group { children [" + uses("A", 32) + " ] }\n";
  wrl += "DEF C Group { children [" + uses("B", 32) + " ] }\n";
  wrl += "DEF D Group { children [" + uses("C", 31) + " ] }\n";
  ASSERT_LT(wrl.size(), 12000U);
  const Result<LoadedMesh> read = read_mesh(wrl, "nested.wrl");
  ASSERT_FALSE(read.ok()) << read->mesh.vertex_count() << " vertices";
  EXPECT_EQ(read.error().code, ErrorCode::CountTooLarge);
  EXPECT_NE(read.error().message.find("justifies"), std::string::npos) << read.error().message;

  // Instancing a file's size justifies still reads: the face set drawn 32 times.
  const std::string small = wrl.substr(0, wrl.find("DEF C"));
  const Result<LoadedMesh> ok = read_mesh(small, "instanced.wrl");
  ASSERT_TRUE(ok.ok()) << ok.error().to_string();
  EXPECT_EQ(ok->mesh.vertex_count(), 33U * 1000U);
}

TEST(Robustness, ReadFileStopsAtItsLimit) {
  const test::TempDir dir;
  const auto big = dir / "big.obj";
  std::ofstream(big) << std::string(4096, ' ');
  const Result<std::string> capped = read_file(big, 1000);
  ASSERT_FALSE(capped.ok());
  EXPECT_EQ(capped.error().code, ErrorCode::CountTooLarge);
  EXPECT_NE(capped.error().message.find("4096 bytes"), std::string::npos) << capped.error().message;
  EXPECT_TRUE(read_file(big, 4096).ok());
  // A device that never ends: read up to the limit, then refused (without a limit: until bad_alloc).
  const Result<std::string> zero = read_file("/dev/zero", 1 << 20);
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.error().code, ErrorCode::CountTooLarge);
  EXPECT_EQ(zero.error().source, "/dev/zero");
}

// ---- what libdraco is handed ----------------------------------------------------------------------------

// The 39-byte OBJ of the issue: x from -3e38 to 3e38, a span no float holds. libdraco's encoder crashed on
// it (signal 11); the writer now refuses it.
TEST(Robustness, DracoRefusesASpanWiderThanAFloat) {
  const Result<LoadedMesh> wide =
      read_mesh(std::string("v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n"), "wide.obj");
  ASSERT_TRUE(wide.ok()) << wide.error().to_string();
  for (const auto& [name, options] :
       {std::pair{"wide.drc", WriteOptions{}}, std::pair{"wide.glb", WriteOptions{.draco_in_gltf = true}},
        std::pair{"wide0.drc", WriteOptions{.draco_level = 0}}}) {
    const Result<std::string> out = encode_mesh(wide->mesh, name, options);
    ASSERT_FALSE(out.ok()) << name;
    EXPECT_EQ(out.error().code, ErrorCode::NonFinite) << out.error().to_string();
    EXPECT_NE(out.error().message.find("along x"), std::string::npos) << out.error().message;
  }
  // Every lossless writer holds it.
  for (const char* name : {"wide.obj", "wide.ply", "wide.glb", "wide.wrl", "wide.stl", "wide.off"})
    EXPECT_TRUE(encode_mesh(wide->mesh, name).ok()) << name;
  // Texture coordinates are quantised over their range too.
  Mesh uv = test::unit_square();
  uv.texcoords = {{-3e38F, 0}, {3e38F, 0}, {0, 1}, {0, 0}};
  const Result<std::string> out = encode_mesh(uv, "uv.drc");
  ASSERT_FALSE(out.ok());
  EXPECT_NE(out.error().message.find("texture coordinates"), std::string::npos) << out.error().message;
}

// A position attribute of data type BOOL (tests/data/draco/make_fixtures.cpp): libdraco's converter loads
// its bytes as bools (undefined behaviour; UBSan: invalid bool load). Refused before.
TEST(Robustness, DracoRefusesAttributesThatAreNotNumbers) {
  const Result<std::string> bytes = read_file(test::fixtures() / "draco" / "bool_position.drc");
  ASSERT_TRUE(bytes.ok());
  const Result<LoadedMesh> read = read_mesh(*bytes, "bool_position.drc");
  ASSERT_FALSE(read.ok()) << read->mesh.vertex_count();
  EXPECT_EQ(read.error().code, ErrorCode::Malformed);
  EXPECT_NE(read.error().message.find("not a number type"), std::string::npos) << read.error().message;
}

// ---- an empty mesh: read from no file, written by no writer ---------------------------------------------

TEST(Robustness, NoReaderReadsAndNoWriterWritesAnEmptyMesh) {
  const std::vector<std::pair<const char*, std::string>> empty{
      {"empty.off", "OFF\n0 0 0\n"},
      {"empty.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n"},
      {"empty.obj", "# nothing\n"},
      {"empty.wrl", "#VRML V2.0 utf8\nShape { geometry PointSet { coord Coordinate { point [ ] } } }\n"},
      {"empty.stl", "solid x\nendsolid x\n"},
  };
  for (const auto& [name, bytes] : empty) {
    const Result<LoadedMesh> read = read_mesh(bytes, name);
    ASSERT_FALSE(read.ok()) << name;
    EXPECT_EQ(read.error().code, ErrorCode::Empty) << read.error().to_string();
  }
  for (const FormatInfo& f : all_formats()) {
    if (!f.writable) continue;
    const Result<std::string> out = encode_mesh(Mesh{}, "empty" + std::string(f.extensions.front()));
    ASSERT_FALSE(out.ok()) << f.name;
    EXPECT_EQ(out.error().code, ErrorCode::Empty) << f.name << ": " << out.error().to_string();
  }
}

// ---- names are written as valid UTF-8 -------------------------------------------------------------------

TEST(Robustness, NamesAreWrittenAsValidUtf8) {
  // An OBJ object name with bytes that are not UTF-8, a newline and a '#' (which would end the name).
  Mesh mesh = test::unit_square();
  mesh.name = "bad\xff\xfe name\nv 9 9 9 # not a comment";
  for (const FormatInfo& f : all_formats()) {
    if (!f.writable) continue;
    const std::string file = "named" + std::string(f.extensions.front());
    const Result<std::string> out = encode_mesh(mesh, file);
    ASSERT_TRUE(out.ok()) << f.name << ": " << out.error().to_string(); // glTF threw a json type_error
    const Result<LoadedMesh> back = read_mesh(*out, file);
    ASSERT_TRUE(back.ok()) << f.name << ": " << back.error().to_string();
    EXPECT_EQ(back->mesh.vertex_count(), 4U) << f.name;
    EXPECT_TRUE(is_valid_utf8(back->mesh.name)) << f.name;
  }
}

} // namespace
} // namespace pdeface::formats
