#include "pdeface/formats/formats.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

namespace pdeface::formats {
namespace {

TEST(Formats, ExtensionsAreCaseInsensitive) {
  EXPECT_EQ(format_from_path("a/b/Face.WRL"), Format::Vrml);
  EXPECT_EQ(format_from_path("x.vrml"), Format::Vrml);
  EXPECT_EQ(format_from_path("x.glb"), Format::Glb);
  EXPECT_EQ(format_from_path("x.gltf"), Format::Gltf);
  EXPECT_EQ(format_from_path("x.drc"), Format::Draco);
  EXPECT_EQ(format_from_path("x.xyz"), std::nullopt);
  EXPECT_EQ(format_from_path("noextension"), std::nullopt);
}

TEST(Formats, EveryFormatKnowsItsOwnExtensions) {
  for (const FormatInfo& fi : all_formats()) {
    EXPECT_EQ(&info(fi.format), &fi);
    for (std::string_view ext : fi.extensions)
      EXPECT_EQ(format_from_path("f" + std::string(ext)), fi.format);
  }
}

TEST(Formats, ContentIsRecognisedByItsMagic) {
  EXPECT_EQ(format_from_content("#VRML V2.0 utf8\n"), Format::Vrml);
  EXPECT_EQ(format_from_content("ply\nformat ascii 1.0\n"), Format::Ply);
  EXPECT_EQ(format_from_content(std::string_view("glTF\x02\0\0\0", 8)), Format::Glb);
  EXPECT_EQ(format_from_content("DRACO\x02\x02"), Format::Draco);
  EXPECT_EQ(format_from_content("OFF\n3 1 0\n"), Format::Off);
  EXPECT_EQ(format_from_content("  {\"asset\": {\"version\": \"2.0\"}}"), Format::Gltf);
  EXPECT_EQ(format_from_content("solid x\n facet normal 0 0 1\n"), Format::Stl);
  EXPECT_EQ(format_from_content("# made by hand\nv 0 0 0\n"), Format::Obj);
  EXPECT_EQ(format_from_content("hello"), std::nullopt);
}

TEST(Formats, ContentWinsOverAMisleadingExtension) {
  const std::string ply = encode_mesh(sample_face({.spacing_mm = 5.0}), "x.ply").value();
  Notes notes;
  auto loaded = read_mesh(ply, "mislabelled.obj", {}, &notes);
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  EXPECT_EQ(loaded->format, Format::Ply);
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_EQ(notes[0], "mislabelled.obj: the content is PLY, not OBJ as the extension says");
}

TEST(Formats, UnknownAndEmptyInput) {
  auto unknown = read_mesh(std::string_view("12345"), "data.bin");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::UnsupportedFormat);
  EXPECT_EQ(unknown.error().source, "data.bin");
  auto empty = read_mesh(std::string_view(""), "nothing");
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().code, ErrorCode::Empty);
}

TEST(Formats, AttributesAFormatCannotHoldAreDroppedWithANote) {
  const Mesh face = sample_face({.spacing_mm = 5.0});
  ASSERT_TRUE(face.has_colors() && face.has_normals());
  Notes notes;
  auto stl = encode_mesh(face, "face.stl", {}, &notes);
  ASSERT_TRUE(stl.ok()) << stl.error().to_string();
  EXPECT_EQ(notes, (Notes{"normals dropped: STL cannot store them",
                          "vertex colours dropped: STL cannot store them"}));
  notes.clear();
  ASSERT_TRUE(encode_mesh(face, "face.ply", {}, &notes).ok());
  EXPECT_TRUE(notes.empty());
}

TEST(Formats, WriteRefusesWhatItCannotDoAndLeavesNoFile) {
  test::TempDir dir;
  Mesh cloud = to_mesh(to_point_cloud(sample_face({.spacing_mm = 5.0})));
  auto stl = write_mesh(cloud, dir / "cloud.stl");
  ASSERT_FALSE(stl);
  EXPECT_EQ(stl.error().code, ErrorCode::InvalidArgument);

  Mesh broken = sample_face({.spacing_mm = 5.0});
  broken.triangles.push_back({0, 1, 999999});
  auto bad = write_mesh(broken, dir / "broken.ply");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::IndexOutOfRange);

  auto draco_bits = write_mesh(sample_face({.spacing_mm = 5.0}), dir / "x.drc", {.draco_bits = 0});
  ASSERT_FALSE(draco_bits);
  EXPECT_EQ(draco_bits.error().code, ErrorCode::InvalidArgument);

  auto ext = write_mesh(sample_face({.spacing_mm = 5.0}), dir / "x.unknown");
  ASSERT_FALSE(ext);
  EXPECT_EQ(ext.error().code, ErrorCode::UnsupportedFormat);
  EXPECT_EQ(dir.entries(), 0U);
}

TEST(Formats, ConvertReportsBothSides) {
  test::TempDir dir;
  ASSERT_TRUE(write_mesh(sample_face({.spacing_mm = 4.0}), dir / "in.ply").ok());
  auto report = convert(dir / "in.ply", dir / "out.obj");
  ASSERT_TRUE(report.ok()) << report.error().to_string();
  EXPECT_EQ(report->from, Format::Ply);
  EXPECT_EQ(report->to, Format::Obj);
  EXPECT_EQ(report->bytes_out, std::filesystem::file_size(dir / "out.obj"));
  EXPECT_GT(report->triangles, 0U);
}

} // namespace
} // namespace pdeface::formats
