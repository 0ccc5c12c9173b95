// What we write passes the Khronos glTF validator with no errors; the test skips, saying why, when node
// or the validator is missing (tests/support/gltf_validator.hpp).

#include "gltf_validator.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/gltf/gltf.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>

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

} // namespace
} // namespace pdeface
