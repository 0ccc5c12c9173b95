// Reading speed of the formats on a paper-scale scan: a 1.1 MB facefuns PLY (30,204 vertices), and the
// same scan converted to VRML 2.0, OBJ, GLB and Draco in memory. Parsing is from bytes in memory, so
// the figures are the readers', not the disk's.
//
//   build/benchmarks/formats_bench [--benchmark_filter=Read]      (PDEFACE_DATA=/path/to/faces)
//
// Without the real scans it measures the built-in sample face instead, and says so.

#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

namespace {

using namespace pdeface;

struct Corpus {
  Mesh mesh;
  std::string origin;
  std::map<std::string, std::string> bytes; // extension -> encoded scan
};

const Corpus& corpus() {
  static const Corpus c = [] {
    Corpus out;
    const auto ply = bench::face("facefuns_f18.ply");
    if (auto bytes = read_file(ply); bytes.ok()) {
      out.bytes[".ply"] = std::move(bytes).value();
      out.mesh = formats::read_mesh(out.bytes[".ply"], "scan.ply").value().mesh;
      out.origin = ply.string();
    } else {
      std::fprintf(stderr, "formats_bench: %s not found; measuring the built-in sample face\n", ply.c_str());
      out.mesh = sample_face({.spacing_mm = 0.9});
      out.origin = "sample face";
    }
    for (const char* ext : {".ply", ".wrl", ".obj", ".glb", ".drc"})
      if (!out.bytes.contains(ext))
        out.bytes[ext] = formats::encode_mesh(out.mesh, std::string("scan") + ext).value();
    std::fprintf(stderr, "formats_bench: %s, %zu vertices, %zu triangles\n", out.origin.c_str(),
                 out.mesh.vertex_count(), out.mesh.triangle_count());
    return out;
  }();
  return c;
}

void read_format(benchmark::State& state, const char* ext) {
  const std::string& bytes = corpus().bytes.at(ext);
  const std::string source = std::string("scan") + ext;
  for (auto _ : state) {
    auto loaded = formats::read_mesh(bytes, source);
    if (!loaded) state.SkipWithError(loaded.error().to_string().c_str());
    benchmark::DoNotOptimize(loaded);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
}

void write_format(benchmark::State& state, const char* ext) {
  const Mesh& mesh = corpus().mesh;
  const std::string target = std::string("scan") + ext;
  std::size_t size = 0;
  for (auto _ : state) {
    auto bytes = formats::encode_mesh(mesh, target);
    if (!bytes) state.SkipWithError(bytes.error().to_string().c_str());
    size = bytes->size();
    benchmark::DoNotOptimize(bytes);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * size));
  state.counters["file_bytes"] = static_cast<double>(size);
}

// The scan as MeshLab wrote it (facefuns_example.obj, 3.8 MB: 6-digit text, normals), when present.
void read_real_obj(benchmark::State& state) {
  auto bytes = read_file(bench::face("facefuns_example.obj"));
  if (!bytes) return state.SkipWithError(bytes.error().to_string().c_str());
  for (auto _ : state) {
    auto loaded = formats::read_mesh(*bytes, "facefuns_example.obj");
    if (!loaded) state.SkipWithError(loaded.error().to_string().c_str());
    benchmark::DoNotOptimize(loaded);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes->size()));
  state.counters["file_bytes"] = static_cast<double>(bytes->size());
}

BENCHMARK(read_real_obj)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, ply, ".ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, vrml2, ".wrl")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, obj, ".obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, glb, ".glb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, draco, ".drc")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, ply, ".ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, vrml2, ".wrl")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, obj, ".obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, glb, ".glb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, draco, ".drc")->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
