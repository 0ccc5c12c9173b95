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
// The files a mesh file refers to are read beside it, and nowhere else.
TEST(FilesBeside, OnlyInsideTheFolderAndWithinTheCap) {
  const test::TempDir dir;
  const std::filesystem::path inner = dir.path() / "scan";
  std::filesystem::create_directories(inner / "sub");
  ASSERT_TRUE(write_file_atomic(inner / "m.mtl", "newmtl a\n").ok());
  ASSERT_TRUE(write_file_atomic(inner / "sub" / "skin photo.jpg", "jpeg").ok());
  ASSERT_TRUE(write_file_atomic(dir.path() / "secret.txt", "secret").ok());
  std::filesystem::create_symlink(dir.path() / "secret.txt", inner / "link.jpg");
  const Resolver resolve = files_beside(inner / "face.obj", 16);
  EXPECT_EQ(*resolve("m.mtl"), "newmtl a\n");
  EXPECT_EQ(*resolve("./sub/skin%20photo.jpg"), "jpeg");
  for (const char* outside : {"../secret.txt", "sub/../../secret.txt", "/etc/passwd", "file:///etc/passwd",
                              "http://example.org/a.jpg", "link.jpg", ""}) {
    const Result<std::string> bytes = resolve(outside);
    ASSERT_FALSE(bytes.ok()) << outside;
    EXPECT_EQ(bytes.error().code, ErrorCode::UnsupportedFormat)
        << outside << ": " << bytes.error().to_string();
  }
  EXPECT_EQ(resolve("missing.jpg").error().code, ErrorCode::Io);
  EXPECT_EQ(files_beside(inner / "face.obj", 4)("m.mtl").error().code, ErrorCode::CountTooLarge);
}

// An OBJ with its material library and image, written as one set of files and read back from them.
TEST(FilesBeside, ObjWithMaterialWritesAndReadsItsFiles) {
  const test::TempDir dir;
  Mesh mesh = sample_face({.spacing_mm = 8.0});
  mesh.texcoords.assign(mesh.vertex_count(), Vec2f(0.5F, 0.5F));
  const Result<std::string> png = read_file(test::fixtures() / "obj" / "texture.png");
  ASSERT_TRUE(png.ok());
  mesh.material =
      Material{.name = "skin",
               .base_color = Vec4f::Ones(),
               .base_color_image = Image{.bytes = *png, .mime_type = "image/png", .uri = "t.png"}};
  ASSERT_TRUE(write_mesh(mesh, dir.path() / "face.obj").ok());
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "face.mtl"));
  EXPECT_EQ(*read_file(dir.path() / "face.png"), *png);
  Notes notes;
  const Result<LoadedMesh> back = read_mesh(dir.path() / "face.obj", {}, &notes);
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  ASSERT_TRUE(back->mesh.material && back->mesh.material->base_color_image);
  EXPECT_EQ(back->mesh.material->base_color_image->bytes, *png);
  EXPECT_TRUE(notes.empty()) << notes.front();
  // Into a folder that does not exist: nothing is written, none of the three files.
  EXPECT_FALSE(write_mesh(mesh, dir.path() / "none" / "face.obj").ok());
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "none"));
}

} // namespace pdeface::formats
