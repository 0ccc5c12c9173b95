#pragma once
// Helpers shared by the tests: fixture and real-scan paths, temporary folders.

#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::test {

//! tests/data: small fixtures we made ourselves.
inline std::filesystem::path fixtures() { return PDEFACE_TEST_FIXTURES; }

//! The rows of a table among the fixtures, tests/data/<folder>/<name>: its lines but the blank ones and the
//! comments ('#'); none when it cannot be read.
inline std::vector<std::string> fixture_rows(std::string_view folder, std::string_view name) {
  std::ifstream in(fixtures() / folder / name);
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') rows.push_back(line);
  return rows;
}

//! The folder of real scans: $PDEFACE_DATA, else the build's default (../shared/faces); nullopt if absent.
inline std::optional<std::filesystem::path> faces_dir() {
  const char* env = std::getenv("PDEFACE_DATA");
  std::filesystem::path dir =
      env && *env ? std::filesystem::path(env) : std::filesystem::path(PDEFACE_DEFAULT_FACES);
  if (!std::filesystem::is_directory(dir)) return std::nullopt;
  return dir;
}

//! The path of a real scan, or nullopt when the folder or the file is absent.
inline std::optional<std::filesystem::path> face(std::string_view name) {
  auto dir = faces_dir();
  if (!dir) return std::nullopt;
  auto path = *dir / name;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return path;
}

//! Every scan in ../shared/faces (MANIFEST.md): the facefuns averages and their copies in other formats,
//! the point cloud, the turned and cut VRMLs, a head with hair, a 3D photo with a neck, two busts and the
//! ICT faces with expressions, holes and capture defects.
inline constexpr const char* kSharedScans[] = {
    "facefuns_f18.ply",
    "facefuns_f36.ply",
    "facefuns_f56.ply",
    "facefuns_m26.ply",
    "facefuns_m46.ply",
    "facefuns_m66.ply",
    "facefuns_example.obj",
    "facefuns_f36.glb",
    "facefuns_m46.drc",
    "facefuns_f56_points.ply",
    "fran_cut.wrl",
    "stfaces_neutral.wrl",
    "james.obj",
    "meshmonk_demoface.obj",
    "demosthenes.obj",
    "bust_man_wreath.obj",
    "ict_00.obj",
    "ict_01.ply",
    "ict_02.glb",
    "ict_03.wrl",
    "ict_04.obj",
    "ict_05.ply",
    "ict_06.glb",
    "ict_07.wrl",
};

//! A fresh empty folder, removed with everything in it when the object dies.
class TempDir {
public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("pdeface-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(std::string_view name) const { return path_ / name; }
  //! Number of entries in the folder (to check that nothing was left behind).
  [[nodiscard]] std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(path_), {}));
  }

private:
  std::filesystem::path path_;
};

//! A test name from a file name ("facefuns_f18.ply" -> "facefuns_f18_ply"), for parameterised tests.
inline std::string test_name(std::string_view file) {
  std::string name(file);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

//! Names the instances of a test parameterised by file names.
struct FileParamName {
  template <class Info> std::string operator()(const Info& info) const { return test_name(info.param); }
};

//! `text` cut at every `by` (an empty last part dropped, as std::getline does).
inline std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, by);)
    out.push_back(part);
  return out;
}

} // namespace pdeface::test

//! Binds `var` to the real scan `name`, or skips the test (saying why) when ../shared/faces is absent.
#define PDEFACE_FACE_OR_SKIP(var, name)                                                                      \
  const auto var##_opt = ::pdeface::test::face(name);                                                        \
  if (!var##_opt) GTEST_SKIP() << "real scan " << (name) << " not found (set PDEFACE_DATA)";                 \
  const std::filesystem::path& var = *var##_opt
