#pragma once
// Runs the Khronos glTF validator (an npm package, run with node) on a file. Install it with
//   npm install --prefix build/tools gltf-validator
// or point PDEFACE_GLTF_VALIDATOR_DIR at a folder holding node_modules/gltf-validator.

#include "pdeface/core/file.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace pdeface::test {

namespace fs = std::filesystem;

inline std::optional<fs::path> find_node() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && fs::exists(fs::path(dir) / "node")) return fs::path(dir) / "node";
  return std::nullopt;
}

// $PDEFACE_GLTF_VALIDATOR_DIR, else <build>/tools (this program runs from <build>/tests).
inline std::optional<fs::path> find_validator() {
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

inline std::string quoted(const fs::path& path) {
  std::string out = "'";
  out += path.string();
  out += "' ";
  return out;
}

inline Validation validate_file(const fs::path& node, const fs::path& validator, const fs::path& file) {
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

//! Skips the calling test (saying why) unless node and the validator are installed; sets `node` and
//! `validator` otherwise.
#define PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator)                                                      \
  const auto node = ::pdeface::test::find_node();                                                            \
  if (!node) GTEST_SKIP() << "node is not on PATH: cannot run the Khronos glTF validator";                   \
  const auto validator = ::pdeface::test::find_validator();                                                  \
  if (!validator)                                                                                            \
  GTEST_SKIP() << "gltf-validator is not installed: npm install --prefix build/tools gltf-validator "        \
                  "(or set PDEFACE_GLTF_VALIDATOR_DIR)"

//! Expects `file` to pass the validator with no errors.
inline void expect_valid_gltf(const fs::path& node, const fs::path& validator, const fs::path& file) {
  const Validation v = validate_file(node, validator, file);
  ASSERT_NE(v.status, 2) << "the validator could not run: " << v.report;
  EXPECT_EQ(v.status, 0) << v.report;
  EXPECT_NE(v.report.find("\"numErrors\": 0"), std::string::npos) << v.report;
}

} // namespace pdeface::test
