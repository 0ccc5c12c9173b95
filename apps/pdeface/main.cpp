// pdeface: the command line. Each command maps its arguments onto a library request, calls the library
// and prints the outcome (apps/pdeface/commands/); this file only lists them.

#include "commands/common.hpp"
#include "pdeface/core/heap.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <exception>
#include <string>

#if defined(__GLIBC__)
#include <sys/mman.h>
#endif

#include <cstdint>
#include <cstdlib>
#include <new>

// Blocks of 4 MB and more (a decoded mesh, its PLY bytes, a scan's BVH) on transparent huge pages where the
// system offers them on request (Debian's default, `madvise`): one page fault per 2 MB instead of 512. Page
// faults are what such a block costs most: `pdeface decode` of an 8 KB residual file (148k vertices) made
// 4,640 of them in 80-84 ms, now ~3,100-3,600 in 58-62 ms (docs/performance.md, "Writing PLY"). Smaller
// blocks, and Eigen's from malloc, are on huge pages in the heap's 60 MB top (prepare_command_heap). The
// blocks come from malloc and go back by free; not under the sanitizers, whose own operator new checks more.
#if defined(__GLIBC__) && !defined(PDEFACE_SANITIZED)
namespace {
constexpr std::size_t kHugeFrom = std::size_t{4} << 20; // mapped on their own once the heap's top is used
} // namespace

void* operator new(std::size_t size) {
  void* p = nullptr;
  while ((p = std::malloc(size == 0 ? 1 : size)) == nullptr) {
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
  if (size >= kHugeFrom) {
    constexpr std::uintptr_t kPage = 4096; // madvise takes a page-aligned start
    const std::size_t into_page = reinterpret_cast<std::uintptr_t>(p) % kPage;
    (void)madvise(static_cast<char*>(p) - into_page, size + into_page, MADV_HUGEPAGE);
  }
  return p;
}
// GCC takes any free() in an operator delete for a mismatch with operator new; this pair matches.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t /*size*/) noexcept { std::free(p); }
#pragma GCC diagnostic pop
#endif

namespace {

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
  // One command is one short process that allocates and frees maps, grids and meshes of 0.1-4 MB over and
  // over: freed blocks kept for reuse, fresh ones on huge pages (core/heap.hpp).
  (void)pdeface::prepare_command_heap();
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
