// What we write passes the Khronos glTF validator with no errors; the test skips, saying why, when node
// or the validator is missing (tests/support/gltf_validator.hpp).

#include "gltf_validator.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/gltf/gltf.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace pdeface {
namespace {

TEST(GltfValidator, WrittenFilesHaveNoErrors) {
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);

  Mesh face = sample_face();
  face.units = Units::Millimetres;
  Mesh bytes_colors = sample_face({.spacing_mm = 4.0});
  for (Vec4f& c : bytes_colors.colors)
    c = (c * 255.0f).array().round() / 255.0f; // written as bytes
  bytes_colors.texcoords.assign(bytes_colors.vertex_count(), Vec2f(0.25f, 0.75f));
  Mesh plain = sample_face({.colors = false});
  plain.normals.clear();                   // computed by the writer
  plain.positions.emplace_back(0, 0, 200); // a vertex on no triangle: its normal must still be a unit vector
  Mesh cloud = face;
  cloud.triangles.clear();
  const drc::WriteOptions draco{};
  const std::vector<std::pair<std::string, Result<std::string>>> files = {
      {"face.glb", gltf::write(face)},
      {"plain.glb", gltf::write(plain)},
      {"byte_colors.glb", gltf::write(bytes_colors)},
      {"cloud.glb", gltf::write(cloud)},
      {"face_draco.glb", gltf::write(face, {.draco = draco})},
      {"colors16_draco.glb", gltf::write(bytes_colors, {.draco = drc::WriteOptions{.color_bits = 16}})},
      {"face.gltf", gltf::write(face, {.binary = false, .draco = std::nullopt})},
      {"face_draco.gltf", gltf::write(face, {.binary = false, .draco = draco})},
  };
  test::TempDir dir;
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    ASSERT_TRUE(write_file_atomic(dir / name, *bytes).ok());
    test::expect_valid_gltf(*node, *validator, dir / name);
  }
}

// The case: a textured scan with seams (james.obj, its material library and photo) as a GLB that
// the validator passes, the photo embedded.
TEST(GltfValidator, JamesWithItsPhotoHasNoErrors) {
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  test::TempDir dir;
  Notes notes;
  const Result<formats::ConvertReport> done = formats::convert(path, dir / "james.glb", {}, {}, &notes);
  ASSERT_TRUE(done.ok()) << done.error().to_string();
  test::expect_valid_gltf(*node, *validator, dir / "james.glb");
}

// The GLB in a real viewer: three.js in headless Chromium (tools/gltf_viewer). The picture's pixels must be
// the photo's (saturated, warmer than grey); the same scan without its material is grey, which shows the
// statistic can fail. Skips, saying why, without node, Chromium or the viewer's packages.
TEST(GltfViewer, JamesShowsItsPhoto) {
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  const auto node = test::find_node();
  if (!node) GTEST_SKIP() << "node is not on PATH";
  if (!std::filesystem::exists("/usr/bin/chromium"))
    GTEST_SKIP() << "no /usr/bin/chromium (apt-get install chromium)";
  const std::filesystem::path viewer = test::fixtures().parent_path().parent_path() / "tools" / "gltf_viewer";
  if (!std::filesystem::exists(viewer / "node_modules" / "three"))
    GTEST_SKIP() << "the viewer's packages are missing: cd tools/gltf_viewer && npm install";
  test::TempDir dir;
  auto render = [&](const std::string& name, bool companions) {
    const Result<formats::ConvertReport> done =
        formats::convert(path, dir / (name + ".glb"), {.companions = companions}, {}, nullptr);
    EXPECT_TRUE(done.ok()) << done.error().to_string();
    const std::filesystem::path stats = dir / (name + ".json");
    const std::string command = test::quoted(*node) + test::quoted(viewer / "screenshot.mjs") +
                                test::quoted(dir / (name + ".glb")) + test::quoted(dir / (name + ".png")) +
                                "> " + test::quoted(stats) + "2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    const Result<std::string> text = read_file(stats);
    return nlohmann::json::parse(text ? *text : std::string("{}"), nullptr, false);
  };
  const nlohmann::json photo = render("james", true), grey = render("plain", false);
  ASSERT_TRUE(photo.is_object() && grey.is_object()) << photo.dump() << grey.dump();
  EXPECT_EQ(photo["textured"], nlohmann::json::array({true})) << photo.dump();
  EXPECT_GT(photo["covered"].get<double>(), 0.15) << "the face fills the frame";
  EXPECT_GT(photo["mean_saturation"].get<double>(), 20.0) << photo.dump();
  const auto rgb = photo["mean_rgb"];
  EXPECT_GT(rgb[0].get<double>(), rgb[2].get<double>() + 20.0)
      << "skin: more red than blue, " << photo.dump();
  EXPECT_LT(grey["mean_saturation"].get<double>(), 2.0) << grey.dump();
}

TEST(GltfValidator, TexturedMeshesHaveNoErrors) {
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);
  Mesh face = sample_face({.spacing_mm = 4.0});
  face.texcoords.clear();
  for (const Vec3& p : face.positions)
    face.texcoords.emplace_back(static_cast<float>(p.x() / 200 + 0.5), static_cast<float>(p.y() / 200 + 0.5));
  Result<std::string> png = read_file(test::fixtures() / "obj" / "texture.png");
  ASSERT_TRUE(png.ok());
  face.material =
      Material{.name = "skin",
               .base_color = Vec4f(1, 0.9F, 0.8F, 1),
               .base_color_image = Image{.bytes = *png, .mime_type = "image/png", .uri = "t.png"}};
  // A seam: the first triangle's first corner gets a coordinate of its own.
  face.texcoord_triangles = face.triangles;
  face.texcoords.emplace_back(0.0F, 0.0F);
  face.texcoord_triangles[0][0] = static_cast<std::uint32_t>(face.texcoords.size() - 1);
  test::TempDir dir;
  for (const auto& [name, bytes] : std::vector<std::pair<std::string, Result<std::string>>>{
           {"textured.glb", gltf::write(face)},
           {"textured.gltf", gltf::write(face, {.binary = false, .draco = std::nullopt})},
           {"textured_draco.glb", gltf::write(face, {.draco = drc::WriteOptions{}})}}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    ASSERT_TRUE(write_file_atomic(dir / name, *bytes).ok());
    test::expect_valid_gltf(*node, *validator, dir / name);
  }
}

} // namespace
} // namespace pdeface
