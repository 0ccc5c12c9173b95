// What we write passes the Khronos glTF validator with no errors. The validator is an npm package run
// with node; the test skips, saying why, when either is missing. Install it with
//   npm install --prefix build/tools gltf-validator
// or point PDEFACE_GLTF_VALIDATOR_DIR at a folder holding node_modules/gltf-validator.
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

namespace fs = std::filesystem;

std::optional<fs::path> find_node() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && fs::exists(fs::path(dir) / "node")) return fs::path(dir) / "node";
  return std::nullopt;
}

// $PDEFACE_GLTF_VALIDATOR_DIR, else <build>/tools (this program runs from <build>/tests).
std::optional<fs::path> find_validator() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("PDEFACE_GLTF_VALIDATOR_DIR"); env && *env) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(self.parent_path().parent_path() / "tools");
  for (const fs::path& dir : candidates)
    if (fs::exists(dir / "node_modules" / "gltf-validator" / "package.json")) return dir;
  return std::nullopt;
}

struct Validation {
  int status = -1;
  std::string report;
};

std::string quoted(const fs::path& path) {
  std::string out = "'";
  out += path.string();
  out += "' ";
  return out;
}

Validation validate_file(const fs::path& node, const fs::path& validator, const fs::path& file) {
  const fs::path report = file.string() + ".report.json";
  std::string command = quoted(node);
  command += quoted(fs::path(PDEFACE_TEST_TOOLS) / "validate_gltf.js");
  command += quoted(file);
  command += quoted(validator);
  command += "> " + quoted(report) + "2>&1";
  const int raw = std::system(command.c_str());
  Validation v;
  v.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  v.report = read_file(report).ok() ? *read_file(report) : std::string();
  return v;
}

TEST(GltfValidator, WrittenFilesHaveNoErrors) {
  const std::optional<fs::path> node = find_node();
  if (!node) GTEST_SKIP() << "node is not on PATH: cannot run the Khronos glTF validator";
  const std::optional<fs::path> validator = find_validator();
  if (!validator)
    GTEST_SKIP() << "gltf-validator is not installed: npm install --prefix build/tools gltf-validator "
                    "(or set PDEFACE_GLTF_VALIDATOR_DIR)";

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
  const draco::WriteOptions draco{};
  const std::vector<std::pair<std::string, Result<std::string>>> files = {
      {"face.glb", gltf::write(face)},
      {"plain.glb", gltf::write(plain)},
      {"byte_colors.glb", gltf::write(bytes_colors)},
      {"cloud.glb", gltf::write(cloud)},
      {"face_draco.glb", gltf::write(face, {.draco = draco})},
      {"colors16_draco.glb", gltf::write(bytes_colors, {.draco = draco::WriteOptions{.color_bits = 16}})},
      {"face.gltf", gltf::write(face, {.binary = false, .draco = std::nullopt})},
      {"face_draco.gltf", gltf::write(face, {.binary = false, .draco = draco})},
  };
  test::TempDir dir;
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
    ASSERT_TRUE(write_file_atomic(dir / name, *bytes).ok());
    const Validation v = validate_file(*node, *validator, dir / name);
    ASSERT_NE(v.status, 2) << "the validator could not run: " << v.report;
    EXPECT_EQ(v.status, 0) << v.report;
    EXPECT_NE(v.report.find("\"numErrors\": 0"), std::string::npos) << v.report;
  }
}

} // namespace
} // namespace pdeface
