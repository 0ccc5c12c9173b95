// pdeface: the command line. Each command maps its arguments onto a library request, calls the library
// and prints the outcome (apps/pdeface/commands/); this file only lists them.

#include "commands/common.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <exception>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

// One command is one short process that allocates and frees maps, grids and meshes of 0.1-4 MB over and
// over (detection tries hypotheses, the self-check grids). glibc's defaults hand such blocks back to the
// system at every free, by munmap or by trimming the heap, and each reuse pays its page faults again;
// its dynamic threshold only sometimes saves that, depending on the order of the frees. Fixed thresholds
// keep freed blocks for reuse: encode on facefuns_f18 makes 6,100 -> 4,000 page faults, 8 % less time,
// for ~1 MB more peak memory (docs/performance.md, "Page faults").
void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
}

int run(int argc, char** argv) {
  using namespace pdeface::cli;
  CLI::App app{
      "pdeface: 3D face scans to compact PDE surfaces and back, and conversion between mesh formats"};
  app.set_version_flag("--version", std::string("pdeface ") + PDEFACE_VERSION);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
    return fmt::format("pdeface{}: error: {} (see --help)\n",
                       failed && failed->get_parent() ? " " + failed->get_name() : "", e.what());
  });

  int status = 0;
  constexpr std::array<Command, 10> kCommands{
      &info_command,        &convert_command, &sample_command,  &align_command,  &profiles_command,
      &reconstruct_command, &table_command,   &compare_command, &encode_command, &decode_command};
  for (Command add : kCommands)
    add(app, status);
  try {
    app.parse(argc, argv); // runs the command given
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kUsageError; // --help and --version exit 0
  }
  return status;
}

} // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    // A bug (bad data is a Result, never an exception): say so rather than abort.
    std::fputs("pdeface: internal error: ", stderr);
    std::fputs(e.what(), stderr);
    std::fputs("\n", stderr);
  } catch (...) {
    std::fputs("pdeface: internal error\n", stderr);
  }
  return pdeface::cli::kInternalError;
}
