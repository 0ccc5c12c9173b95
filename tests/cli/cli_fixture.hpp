#pragma once
// The CLI driven as a user drives it (the fixture of the CLI tests): runs pdeface in a shell, captures its
// exit code, stdout and stderr, and gives a folder for outputs in which nothing else may appear.

#include "pdeface_test.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace pdeface::test {

struct Outcome {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::size_t lines(const std::string& s) {
  return static_cast<std::size_t>(std::ranges::count(s, '\n'));
}

// Runs pdeface with `args` (each quoted for the shell) in a temporary folder of its own.
class Cli : public ::testing::Test {
protected:
  Outcome run(const std::vector<std::string>& args) {
    std::string cmd = quote(PDEFACE_EXE);
    for (const auto& a : args)
      cmd += " " + quote(a);
    const auto out = io_ / "stdout";
    const auto err = io_ / "stderr";
    cmd += " >" + quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  }
  // The same, run from the folder of outputs (for commands that write into the current folder).
  Outcome run_in_work(const std::vector<std::string>& args) {
    const std::filesystem::path previous = std::filesystem::current_path();
    std::filesystem::current_path(work_.path());
    Outcome r = run(args);
    std::filesystem::current_path(previous);
    return r;
  }
  std::string path(std::string_view name) const { return (work_ / name).string(); }
  // `command` + `args` fails on the data: exit 1, one line on stderr naming `file` and saying `expect`.
  void expect_data_error(std::vector<std::string> command, const std::vector<std::string>& args,
                         std::string_view expect, std::string_view file) {
    command.insert(command.end(), args.begin(), args.end());
    const Outcome r = run(command);
    EXPECT_EQ(r.exit_code, 1) << args[0];
    EXPECT_EQ(lines(r.err), 1U) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  }
  std::size_t files() const { return work_.entries(); }

  test::TempDir work_; // where outputs go: nothing else may appear here
  test::TempDir io_;
};

} // namespace pdeface::test
