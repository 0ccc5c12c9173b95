// The command line on hostile files (issue 22, docs/robustness.md): a clear one-line error and a non-zero
// exit in bounded time and memory, no output file (an existing one untouched), nothing amplified.

#include "cli_fixture.hpp"

#include "pdeface_test.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <random>

namespace pdeface {
namespace {

using test::Cli;
using test::lines;
using test::Outcome;
using test::slurp;

// The 39-byte OBJ of the issue: x from -3e38 to 3e38. libdraco's encoder died on it with signal 11.
TEST_F(Cli, DracoOutputOfASpanWiderThanAFloatFailsAndLeavesTheOldFile) {
  std::ofstream(work_ / "wide.obj") << "v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(work_ / "old.drc") << "the previous output";
  const std::size_t before = files();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{path("old.drc")}, {path("new.glb"), "--draco"}, {path("new.drc")}}) {
    std::vector<std::string> command{"convert", path("wide.obj")};
    command.insert(command.end(), args.begin(), args.end());
    const Outcome r = run(command);
    EXPECT_EQ(r.exit_code, 1) << args[0] << ": " << r.err; // was -1: killed by SIGSEGV
    EXPECT_EQ(lines(r.err), 1U) << r.err;
    EXPECT_NE(r.err.find("Draco cannot quantise them"), std::string::npos) << r.err;
  }
  EXPECT_EQ(files(), before) << "no output and no temporary file";
  EXPECT_EQ(slurp(work_ / "old.drc"), "the previous output");
}

TEST_F(Cli, ADeviceThatNeverEndsIsReadUpToALimit) {
  const Outcome r = run({"info", "/dev/zero"}); // was: read until std::bad_alloc
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1U) << r.err;
  EXPECT_NE(r.err.find("/dev/zero: count too large"), std::string::npos) << r.err;
}

TEST_F(Cli, AHugeTokenIsQuotedShort) {
  std::ofstream(work_ / "token.obj") << "v 1 2 " << std::string(std::size_t{8} << 20, 'x') << "\n";
  const Outcome r = run({"convert", path("token.obj"), path("token.ply")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.err.size(), 300U) << r.err.substr(0, 300); // was the whole 8 MB token
  EXPECT_FALSE(std::filesystem::exists(work_ / "token.ply"));
}

TEST_F(Cli, NamesThatAreNotUtf8AreWrittenAsUtf8) {
  // An OBJ object name, a file name and an --name that are not UTF-8: each was "internal error:
  // [json.exception.type_error.316]", exit 3.
  const std::string bad = "bad\xff\xfe";
  std::ofstream(work_ / "named.obj") << "o " << bad << "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  Outcome r = run({"convert", path("named.obj"), path("named.glb")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::filesystem::copy_file(work_ / "named.obj", work_ / (bad + ".obj"));
  r = run({"info", "--json", path(bad + ".obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;

  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  r = run({"encode", path("face.ply"), "-o", path("face.pdef"), "--name", "x\xffy\nz"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run({"decode", path("face.pdef"), "-o", path("face.glb"), "--resolution", "40"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run({"info", "--json", path("face.pdef")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(Cli, AnEmptyMeshIsNotWritten) {
  std::ofstream(work_ / "empty.off") << "OFF\n0 0 0\n";
  const Outcome r = run({"convert", path("empty.off"), path("empty.obj")}); // was an OBJ nothing reads
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(work_ / "empty.obj"));
}

// 100 random vertices in [0, 1e6]^3 and 300 triangles (5.5 KB): align, reconstruct and encode ran for
// more than 300 s and grew past 3 GB.
TEST_F(Cli, ARandomSoupAKilometreWideIsNoFaceQuickly) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1e6);
  std::uniform_int_distribution<int> pick(1, 100);
  std::ofstream soup(work_ / "soup.obj");
  for (int i = 0; i < 100; ++i)
    soup << "v " << u(rng) << " " << u(rng) << " " << u(rng) << "\n";
  for (int i = 0; i < 300; ++i)
    soup << "f " << pick(rng) << " " << pick(rng) << " " << pick(rng) << "\n";
  soup.close();
  const std::size_t before = files();
  for (const auto& [command, out] :
       {std::pair{"align", "a.ply"}, std::pair{"reconstruct", "r.ply"}, std::pair{"encode", "e.pdef"}}) {
    const Outcome r = run({command, path("soup.obj"), "-o", path(out)});
    EXPECT_EQ(r.exit_code, 1) << command << ": " << r.err;
    EXPECT_NE(r.err.find("no face found"), std::string::npos) << r.err;
  }
  EXPECT_EQ(files(), before);
}

} // namespace
} // namespace pdeface
