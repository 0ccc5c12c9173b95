// OBJ: the real scans, every corner form and attribute mapping, round trips, every bad input with its
// line and column.

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/obj/obj.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

using namespace pdeface;
using namespace pdeface::test;
using namespace std::string_literals;

namespace {

Result<Mesh> read_obj(std::string_view text, Notes* notes = nullptr) {
  return obj::read(text, "t.obj", notes);
}

std::string fixture(std::string_view name) { return pdeface::test::fixture("obj", name); }

Result<Mesh> read_with_notes(std::string_view text, std::string_view source, Notes* notes) {
  return obj::read(text, source, notes);
}

Mesh round_trip(const Mesh& mesh, const obj::WriteOptions& options = {}) {
  const Result<std::string> text = obj::write(mesh, options);
  EXPECT_TRUE(text.ok()) << text.error().to_string();
  Result<Mesh> read = read_obj(text ? *text : std::string());
  EXPECT_TRUE(read.ok()) << read.error().to_string();
  return read ? std::move(read).value() : Mesh{};
}

constexpr std::string_view kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

} // namespace

// ---- real scans ---------------------------------------------------------------------------------------

TEST(ObjRead, FacefunsExampleHasTheManifestCounts) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_example.obj");
  Notes notes;
  const Result<Mesh> mesh = obj::read(*read_file(path), "facefuns_example.obj", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 30204u);
  EXPECT_EQ(mesh->triangle_count(), 59697u);
  EXPECT_TRUE(mesh->has_texcoords()) << "one vt per v, used 1:1";
  EXPECT_FALSE(mesh->has_colors() || mesh->has_normals());
  EXPECT_EQ(mesh->positions[0], Vec3(-75.124207f, 43.292213f, -23.553007f));
  EXPECT_EQ(mesh->texcoords[0], Vec2f(0.0f, 0.5f));
  EXPECT_TRUE(notes.empty()) << notes.front();
}

TEST(ObjRead, JamesHasTheManifestCountsAndSeams) {
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  Notes notes;
  const Result<Mesh> mesh = obj::read(*read_file(path), "james.obj", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 6393u);
  EXPECT_EQ(mesh->triangle_count(), 12228u);
  ASSERT_TRUE(mesh->has_corner_texcoords()) << "6393 v, 6680 vt, 636 corners on seams: kept per corner";
  EXPECT_EQ(mesh->texcoords.size(), 6680u);
  EXPECT_EQ(mesh->texcoord_triangles.size(), mesh->triangle_count());
  EXPECT_TRUE(has_note(notes, "material library './james.obj.mtl' not read")) << "no resolver";
  EXPECT_FALSE(mesh->material);
  EXPECT_EQ(mesh->units, Units::Unknown);
}

TEST(ObjRead, JamesWithItsMaterialAndPhoto) {
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  Notes notes;
  const Resolver beside = [dir = path.parent_path()](std::string_view name) {
    return read_file(dir / std::string(name));
  };
  const Result<Mesh> mesh = obj::read(*read_file(path), "james.obj", &notes, beside);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_TRUE(mesh->material && mesh->material->base_color_image);
  EXPECT_EQ(mesh->material->name, "material_0");
  EXPECT_EQ(mesh->material->base_color, Vec4f::Ones()) << "Kd is the colour only without a map_Kd";
  const Image& image = *mesh->material->base_color_image;
  EXPECT_EQ(image.uri, "james.jpg");
  EXPECT_EQ(image.mime_type, "image/jpeg");
  EXPECT_EQ(image.bytes, *read_file(path.parent_path() / "james.jpg"));
  EXPECT_TRUE(notes.empty()) << notes.front();
}

// ---- fixtures -----------------------------------------------------------------------------------------

TEST(ObjRead, AttributesThatMapOneToOneAreKept) {
  Notes notes;
  const Result<Mesh> mesh = obj::read(fixture("attributes.obj"), "attributes.obj", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
  ASSERT_TRUE(mesh->has_colors() && mesh->has_normals() && mesh->has_texcoords());
  EXPECT_EQ(mesh->colors[1], Vec4f(0, 1, 0, 1));
  EXPECT_EQ(mesh->normals[3], Vec3f(0, 0, 1));
  EXPECT_EQ(mesh->texcoords[0], Vec2f(0, 0));
  EXPECT_EQ(mesh->texcoords[3], Vec2f(0, 1));
  EXPECT_EQ(mesh->units, Units::Millimetres);
  EXPECT_EQ(mesh->name, "handmade square");
  EXPECT_EQ(notes,
            (Notes{"attributes.obj: material library 'never_opened.mtl' not read: reading from memory, no "
                   "folder to find it in"}));
}

TEST(ObjRead, PolygonsRelativeIndicesAndMixedCorners) {
  Notes notes;
  const Result<Mesh> mesh = obj::read(fixture("polygons.obj"), "polygons.obj", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->triangles,
            (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {0, 4, 2}, {0, 2, 3}, {0, 1, 4}}));
  EXPECT_FALSE(mesh->has_texcoords() || mesh->has_normals());
  EXPECT_TRUE(has_note(notes, "texture coordinates dropped: 7 face corners have none"));
  EXPECT_TRUE(has_note(notes, "normals dropped: 9 face corners have none"));
  EXPECT_TRUE(has_note(notes, "statements not read: l, vp"));
}

TEST(ObjRead, SeamsKeepTextureCoordinatesPerCorner) {
  Notes notes;
  const Result<Mesh> mesh = obj::read(fixture("seams.obj"), "seams.obj", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 4u) << "counts kept: no vertex is split";
  ASSERT_TRUE(mesh->has_corner_texcoords());
  EXPECT_EQ(mesh->texcoord_triangles, (std::vector<Triangle>{{0, 1, 2}, {2, 2, 3}}));
  EXPECT_EQ(mesh->texcoords.size(), 4u);
  EXPECT_EQ(corner_texcoords(*mesh)[3], Vec2f(1, 1)) << "vertex 1 on the second face";
  EXPECT_TRUE(notes.empty()) << notes.front();
}

TEST(ObjWrite, SeamsRoundTripPerCorner) {
  const Mesh mesh = *obj::read(fixture("seams.obj"), "seams.obj");
  const Mesh back = round_trip(mesh);
  EXPECT_EQ(back.positions, mesh.positions);
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_EQ(corner_texcoords(back), corner_texcoords(mesh));
}

TEST(ObjRead, MaterialLibraryAndImageThroughTheResolver) {
  const std::string png = fixture("texture.png");
  std::vector<std::string> asked;
  const Resolver resolve = [&](std::string_view name) -> Result<std::string> {
    asked.emplace_back(name);
    if (name == "lib/m.mtl")
      return std::string("newmtl other\nKd 1 0 0\nnewmtl skin\nKd 0.5 0.25 0.125\nd 0.5\n"
                         "map_Kd -s 1 1 1 -clamp on photo 1.png\n");
    if (name == "lib/photo 1.png") return png;
    return make_error(ErrorCode::Io, "no such file", std::string(name));
  };
  Notes notes;
  const Result<Mesh> mesh =
      obj::read("mtllib lib/m.mtl\n"s + std::string(kTriangle) + "vt 0 0\nusemtl skin\nf 1/1 2/1 3/1\n",
                "t.obj", &notes, resolve);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_EQ(asked, (std::vector<std::string>{"lib/m.mtl", "lib/photo 1.png"}));
  ASSERT_TRUE(mesh->material);
  EXPECT_EQ(mesh->material->name, "skin");
  EXPECT_EQ(mesh->material->base_color, Vec4f(1, 1, 1, 0.5F)) << "with a map_Kd the photo is the colour";
  ASSERT_TRUE(mesh->material->base_color_image);
  EXPECT_EQ(mesh->material->base_color_image->bytes, png);
  EXPECT_EQ(mesh->material->base_color_image->mime_type, "image/png");
  EXPECT_TRUE(notes.empty()) << notes.front();
}

TEST(ObjRead, MissingLibraryOrImageIsANoteNotAFailure) {
  const Resolver nothing = [](std::string_view name) -> Result<std::string> {
    return make_error(ErrorCode::Io, "no such file", std::string(name));
  };
  Notes notes;
  Result<Mesh> mesh =
      obj::read("mtllib m.mtl\n"s + std::string(kTriangle) + "f 1 2 3\n", "t.obj", &notes, nothing);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_FALSE(mesh->material);
  EXPECT_TRUE(has_note(notes, "material library 'm.mtl' not read (no such file)"));

  const Resolver library_only = [](std::string_view name) -> Result<std::string> {
    if (name == "m.mtl") return std::string("newmtl a\nKd 0.5 0.5 0.5\nmap_Kd gone.jpg\n");
    return make_error(ErrorCode::Io, "no such file", std::string(name));
  };
  notes.clear();
  mesh = obj::read("mtllib m.mtl\n"s + std::string(kTriangle) + "f 1 2 3\n", "t.obj", &notes, library_only);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  ASSERT_TRUE(mesh->material && mesh->material->base_color_image);
  EXPECT_TRUE(mesh->material->base_color_image->bytes.empty());
  EXPECT_EQ(mesh->material->base_color_image->uri, "gone.jpg");
  EXPECT_TRUE(has_note(notes, "texture image 'gone.jpg' not read (no such file)"));
}

TEST(ObjRead, CorruptOrHugeImageIsAnErrorNamingIt) {
  std::string bomb = fixture("texture.png");
  bomb[16] = '\x7f'; // width 0x7f0000xx: two billion pixels wide
  for (const auto& [image, code] :
       {std::pair{bomb, ErrorCode::CountTooLarge},
        std::pair{std::string("\xFF\xD8\xFF\xE0\x00\x10JFIF"), ErrorCode::Truncated}}) {
    const std::string& bytes = image; // clang 14 does not capture structured bindings
    const Resolver resolve = [&](std::string_view name) -> Result<std::string> {
      if (name == "m.mtl") return std::string("newmtl a\nmap_Kd face.png\n");
      return bytes;
    };
    const Error e = error_of(
        obj::read("mtllib m.mtl\n"s + std::string(kTriangle) + "f 1 2 3\n", "t.obj", nullptr, resolve));
    EXPECT_EQ(e.code, code) << e.to_string();
    EXPECT_EQ(e.source, "face.png");
    EXPECT_TRUE(e.where.byte.has_value()) << e.to_string();
  }
}

TEST(ObjWrite, MaterialLibraryNamesTheImage) {
  Mesh mesh = *read_obj(std::string(kTriangle) + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  mesh.material =
      Material{.name = "skin tone", .base_color = Vec4f(0.5F, 0.25F, 1, 1), .base_color_image = {}};
  Notes notes;
  const Result<std::string> text = obj::write(mesh, {.material_library = "out.mtl"}, &notes);
  ASSERT_TRUE(text.ok()) << text.error().to_string();
  EXPECT_NE(text->find("mtllib out.mtl\n"), std::string::npos);
  EXPECT_NE(text->find("usemtl skin_tone\n"), std::string::npos);
  EXPECT_EQ(obj::write_material_library(mesh, "out.jpg"),
            "# written by pdeface\nnewmtl skin_tone\nKd 0.5 0.25 1\nd 1\nillum 1\nmap_Kd out.jpg\n");
  EXPECT_TRUE(notes.empty()) << notes.front();
  ASSERT_TRUE(obj::write(mesh, {}, &notes).ok());
  EXPECT_TRUE(has_note(notes, "material dropped: no material library"));
}

TEST(ObjRead, TextureIndexOutOfRangeIsAnError) {
  expect_errors_at(read_with_notes, "t.obj",
                   {{std::string(kTriangle) + "vt 0 0\nf 1/1 2/1 3/2\n", ErrorCode::IndexOutOfRange, 5, 11}});
}

TEST(ObjRead, PointCloudWithOneNormalPerVertex) {
  const Result<Mesh> mesh = read_obj("v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 1 0\n");
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_TRUE(mesh->is_point_cloud());
  ASSERT_TRUE(mesh->has_normals());
  EXPECT_EQ(mesh->normals[1], Vec3f(0, 1, 0));
}

TEST(ObjRead, PartialColoursAndShortFacesAreNoted) {
  Notes notes;
  const Result<Mesh> mesh = read_obj("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n", &notes);
  ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
  EXPECT_FALSE(mesh->has_colors());
  EXPECT_EQ(mesh->triangle_count(), 1u);
  EXPECT_TRUE(has_note(notes, "vertex colours dropped: only 1 of 3 vertices have them"));
  EXPECT_TRUE(has_note(notes, "1 faces with fewer than 3 corners skipped"));
}

// ---- round trips --------------------------------------------------------------------------------------

TEST(ObjWrite, SampleFaceRoundTrip) {
  Mesh mesh = sample_face();
  mesh.name = "sample";
  for (const Vec3& p : mesh.positions)
    mesh.texcoords.emplace_back(static_cast<float>(p.x() / 200), static_cast<float>(p.y() / 200));
  const Mesh read = round_trip(mesh);
  const Mesh expected = float_rounded(mesh);
  EXPECT_EQ(read.positions, expected.positions);
  EXPECT_EQ(read.triangles, expected.triangles);
  EXPECT_EQ(read.normals, mesh.normals);
  EXPECT_EQ(read.texcoords, mesh.texcoords);
  EXPECT_EQ(read.colors, mesh.colors);
  EXPECT_EQ(read.units, Units::Millimetres);
  EXPECT_EQ(read.name, "sample");
}

TEST(ObjWrite, EveryCornerForm) {
  const Mesh full = sample_face({.spacing_mm = 6.0});
  for (int form = 0; form < 4; ++form) {
    Mesh mesh = full;
    if (form & 1) mesh.normals.clear();
    if (form & 2)
      mesh.texcoords.clear();
    else
      mesh.texcoords.assign(mesh.vertex_count(), Vec2f(0.25f, 0.5f));
    const Mesh read = round_trip(mesh);
    EXPECT_EQ(read.triangles, mesh.triangles) << form;
    EXPECT_EQ(read.normals, mesh.normals) << form;
    EXPECT_EQ(read.texcoords, mesh.texcoords) << form;
  }
}

TEST(ObjWrite, PointCloudRoundTrip) {
  const Mesh cloud = to_mesh(to_point_cloud(sample_face({.spacing_mm = 4.0})));
  const Mesh read = round_trip(cloud);
  EXPECT_EQ(read.positions, float_rounded(cloud).positions);
  EXPECT_TRUE(read.is_point_cloud());
}

TEST(ObjWrite, RealScanRoundTripIsExact) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_example.obj");
  const Result<Mesh> scan = obj::read(*read_file(path), "facefuns_example.obj");
  ASSERT_TRUE(scan.ok());
  const Mesh read = round_trip(*scan);
  EXPECT_EQ(read.positions, scan->positions);
  EXPECT_EQ(read.triangles, scan->triangles);
  EXPECT_EQ(read.texcoords, scan->texcoords);
}

TEST(ObjWrite, PrecisionAndAlpha) {
  Mesh mesh;
  mesh.positions = {{1.0 / 3.0, 2.0, 1e-7}};
  mesh.colors = {{1.0f, 0.5f, 0.25f, 0.5f}};
  Notes notes;
  const Result<std::string> text = obj::write(mesh, {.precision = 4}, &notes);
  ASSERT_TRUE(text.ok());
  EXPECT_NE(text->find("\nv 0.3333 2 1e-07 1 0.5 0.25\n"), std::string::npos) << *text;
  EXPECT_TRUE(has_note(notes, "alpha dropped"));
  EXPECT_NE(obj::write(mesh)->find("\nv 0.33333334 2 1e-07 1 0.5 0.25\n"), std::string::npos)
      << *obj::write(mesh);
  const Result<std::string> bad = obj::write(mesh, {.precision = 0});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::InvalidArgument);
}

// ---- bad input ----------------------------------------------------------------------------------------

TEST(ObjReadErrors, EveryClassWithItsLineAndColumn) {
  const std::string t(kTriangle);
  const std::vector<ErrorCase> cases{
      {"", ErrorCode::Empty, 0, 0},
      {"# nothing\ng empty\n", ErrorCode::Empty, 0, 0},
      {"v 1 abc 3\n", ErrorCode::Malformed, 1, 5},
      {"v 1 2 3\nv 1.5.5 2 3\n", ErrorCode::Malformed, 2, 3},
      {"v 0x10 2 3\n", ErrorCode::Malformed, 1, 3},
      {"v 1 nan 3\n", ErrorCode::NonFinite, 1, 5},
      {"v 1 2 inf\n", ErrorCode::NonFinite, 1, 7},
      {"v 1 2 1e39\n", ErrorCode::NonFinite, 1, 7},
      {"v 1 2\n", ErrorCode::Malformed, 1, 1},
      {"v 1 2 3 4 5\n", ErrorCode::Malformed, 1, 1},
      {"v 1 2 3 4 5 6 7\n", ErrorCode::Malformed, 1, 1},
      {t + "vn 0 1\n", ErrorCode::Malformed, 4, 1},
      {t + "vt 0 1 0 1\n", ErrorCode::Malformed, 4, 1},
      {t + "f 1 2 0\n", ErrorCode::Malformed, 4, 7},
      {t + "f 1 2 x\n", ErrorCode::Malformed, 4, 7},
      {t + "f 1 2 3/\n", ErrorCode::Malformed, 4, 7},
      {t + "f 1 2 3/1/1/1\n", ErrorCode::Malformed, 4, 7},
      {t + "f 1 2 4\nf 1 2 9\nf 1 2 3\n", ErrorCode::IndexOutOfRange, 5, 7},
      {t + "f 1 2 -4\n", ErrorCode::IndexOutOfRange, 4, 7},
      {"v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", ErrorCode::IndexOutOfRange, 5, 9},
      {t + "vt 0 0\nf 1/1 2/2 3/1\n", ErrorCode::IndexOutOfRange, 5, 7},
      {t + "f 1//1 2//1 3//1\n", ErrorCode::IndexOutOfRange, 4, 3},
      {t + "v 1 1 \0 0\n"s, ErrorCode::Malformed, 4, 7},
  };
  expect_errors_at(read_with_notes, "t.obj", cases);
}

TEST(ObjReadErrors, FaceWithMoreCornersThanTinyobjloaderCounts) {
  std::string text;
  for (int i = 0; i < 256; ++i)
    text += fmt::format("v {} {} 0\n", std::cos(i * 0.0245), std::sin(i * 0.0245));
  std::string face = "f";
  for (int i = 1; i <= 256; ++i)
    face += fmt::format(" {}", i);
  const Result<Mesh> mesh = read_obj(text + face + "\n");
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().code, ErrorCode::UnsupportedFormat);
  EXPECT_EQ(mesh.error().where.line, 257u);
  // 255 corners are fine: fan-triangulated into 253 triangles.
  const Result<Mesh> ok = read_obj(text + face.substr(0, face.rfind(' ')) + "\n");
  ASSERT_TRUE(ok.ok()) << ok.error().to_string();
  EXPECT_EQ(ok->triangle_count(), 253u);
}

// Every prefix of a document is an error or a valid mesh, never a crash.
TEST(ObjReadErrors, EveryTruncation) {
  const std::string text = fixture("attributes.obj");
  for (std::size_t n = 0; n < text.size(); ++n) {
    const Result<Mesh> mesh = read_obj(std::string_view(text).substr(0, n));
    if (!mesh) {
      EXPECT_TRUE(mesh.error().where.known() || mesh.error().code == ErrorCode::Empty) << n;
    }
  }
}

TEST(ObjReadErrors, NothingIsPrinted) {
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  (void)read_obj(std::string(kTriangle) + "f 1 2 9\nmtllib /nonexistent/x.mtl\nusemtl y\n");
  (void)read_obj("v 1 2 3\nf 1 2\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(ObjThreads, ConcurrentReadsGiveTheSameMeshes) {
  const std::string text = *obj::write(sample_face());
  const Mesh expected = *read_obj(text);
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t)
    threads.emplace_back([&] {
      for (int round = 0; round < 4; ++round) {
        const Result<Mesh> mesh = read_obj(text);
        if (!mesh || mesh->positions != expected.positions || mesh->triangles != expected.triangles)
          ++mismatches;
      }
    });
  for (std::thread& t : threads)
    t.join();
  EXPECT_EQ(mismatches.load(), 0);
}
