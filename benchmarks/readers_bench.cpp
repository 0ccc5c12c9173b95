// The readers on the shared scans themselves: every binary PLY, OBJ and VRML file of the faces folder read
// from memory (formats::read_mesh), and facefuns_f18.ply written as ASCII PLY (the folder has none), each
// a case with its bytes per second. scripts/bench.sh sums them per format (bytes over time) for issue 21's
// reader targets (binary PLY >= 1 GB/s; ASCII PLY, OBJ, VRML >= 300 MB/s). The process's heap is the CLI's
// (prepare_command_heap): freed blocks are kept, so a read after the first reuses warm pages and the rate
// is the reader's own; a fresh process also pays its first touches (docs/performance.md, "The heap on huge
// pages", times `pdeface convert` of an OBJ whole).
//
//   build/benchmarks/readers_bench      (PDEFACE_DATA=/path/to/faces; nothing to measure without it)

#include "pdeface/core/file.hpp"
#include "pdeface/core/heap.hpp"
#include "pdeface/formats/formats.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace pdeface;

void read_bytes(benchmark::State& state, const std::string& bytes, const std::string& source) {
  std::size_t vertices = 0;
  for (auto _ : state) {
    auto loaded = formats::read_mesh(bytes, source);
    if (!loaded) return state.SkipWithError(loaded.error().to_string().c_str());
    vertices = loaded->mesh.vertex_count();
    benchmark::DoNotOptimize(loaded);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// One case per scan in the folder (its name: the format, then the file), registered before the run.
void register_scans() {
  const std::filesystem::path folder = bench::face("");
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::ranges::sort(files);
  for (const std::filesystem::path& file : files) {
    const std::string ext = file.extension().string();
    if (ext != ".ply" && ext != ".obj" && ext != ".wrl") continue;
    Result<std::string> bytes = read_file(file);
    if (!bytes) continue;
    std::string format = ext == ".ply" ? "ply_binary" : ext.substr(1);
    if (ext == ".ply" && bytes->find("format ascii") < bytes->find("end_header")) format = "ply_ascii";
    if (file.filename() == "facefuns_f18.ply") { // the folder has no ASCII PLY: this scan written as one
      if (Result<formats::LoadedMesh> mesh = formats::read_mesh(*bytes, file.string()))
        if (Result<std::string> ascii = formats::encode_mesh(mesh->mesh, "scan.ply", {.ascii = true}))
          benchmark::RegisterBenchmark(("read/ply_ascii/facefuns_f18_ascii.ply"),
                                       [text = std::move(ascii).value()](benchmark::State& state) {
                                         read_bytes(state, text, "facefuns_f18_ascii.ply");
                                       })
              ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark(("read/" + format + "/" + file.filename().string()).c_str(),
                                 [data = std::move(bytes).value(), source = file.string()](
                                     benchmark::State& state) { read_bytes(state, data, source); })
        ->Unit(benchmark::kMillisecond);
  }
  if (files.empty()) std::fprintf(stderr, "readers_bench: no scans in %s\n", folder.c_str());
}

} // namespace

int main(int argc, char** argv) {
  (void)prepare_command_heap();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_scans();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
