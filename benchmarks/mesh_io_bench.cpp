// Read and write speed of the OBJ, PLY, OFF and STL readers and writers, on real scans when present
// (facefuns_f18.ply 1.1 MB, facefuns_example.obj 3.8 MB) and on the built-in sample face.
// Run: build/benchmarks/mesh_io_bench [--benchmark_filter=Read]

#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

using namespace pdeface;

namespace {

std::filesystem::path faces_dir() {
  const char* env = std::getenv("PDEFACE_DATA");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(PDEFACE_DEFAULT_FACES);
}

void read_bytes(benchmark::State& state, const std::string& bytes, const std::string& source) {
  for (auto _ : state) {
    Result<formats::LoadedMesh> mesh = formats::read_mesh(bytes, source);
    if (!mesh) {
      state.SkipWithError(mesh.error().to_string().c_str());
      return;
    }
    benchmark::DoNotOptimize(mesh->mesh.positions.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
}

void read_scan(benchmark::State& state, const char* name) {
  const Result<std::string> bytes = read_file(faces_dir() / name);
  if (!bytes) {
    state.SkipWithError("real scan not found (set PDEFACE_DATA)");
    return;
  }
  read_bytes(state, *bytes, name);
}

// The sample face written in `name`'s format, then read.
void read_sample(benchmark::State& state, const char* name, bool ascii) {
  const Result<std::string> bytes = formats::encode_mesh(sample_face(), name, {.format = std::nullopt, .ascii = ascii});
  if (!bytes) {
    state.SkipWithError(bytes.error().to_string().c_str());
    return;
  }
  read_bytes(state, *bytes, name);
}

void write_sample(benchmark::State& state, const char* name, bool ascii) {
  const Mesh mesh = sample_face();
  std::size_t size = 0;
  for (auto _ : state) {
    Result<std::string> bytes = formats::encode_mesh(mesh, name, {.format = std::nullopt, .ascii = ascii});
    if (!bytes) {
      state.SkipWithError(bytes.error().to_string().c_str());
      return;
    }
    size = bytes->size();
    benchmark::DoNotOptimize(bytes->data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * size));
  state.counters["bytes"] = static_cast<double>(size);
}

} // namespace

BENCHMARK_CAPTURE(read_scan, ply_facefuns_f18, "facefuns_f18.ply")->Unit(benchmark::kMillisecond);
// Two threads reading at once: OpenMesh's readers are serialised by one mutex, our validators are not.
BENCHMARK_CAPTURE(read_scan, ply_facefuns_f18, "facefuns_f18.ply")->Unit(benchmark::kMillisecond)->Threads(2)->UseRealTime();
BENCHMARK_CAPTURE(read_scan, ply_points_f56, "facefuns_f56_points.ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_scan, obj_facefuns_example, "facefuns_example.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_scan, obj_facefuns_example, "facefuns_example.obj")->Unit(benchmark::kMillisecond)->Threads(2)->UseRealTime();
BENCHMARK_CAPTURE(read_scan, obj_james, "james.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_sample, ply_ascii, "sample.ply", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_sample, off, "sample.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_sample, stl_binary, "sample.stl", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_sample, stl_ascii, "sample.stl", true)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(write_sample, ply_binary, "sample.ply", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_sample, ply_ascii, "sample.ply", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_sample, obj, "sample.obj", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_sample, off, "sample.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_sample, stl_binary, "sample.stl", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_sample, stl_ascii, "sample.stl", true)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
