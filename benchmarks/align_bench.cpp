// Landmark detection and alignment on a paper-scale scan (facefuns_f18.ply, 30,204 vertices), its point
// cloud, the built-in sample face (15,129 vertices), the hard cases (a bust in arbitrary units, a bust on a
// pedestal with its head turned, a coarse cut patch, a morphable model's face with eye holes in cm) and
// facefuns_f18 subdivided twice (482k vertices).
//
//   build/benchmarks/align_bench          (PDEFACE_DATA=/path/to/faces)

#include "pdeface/align/detect.hpp"
#include "pdeface/core/depth_map.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include "../tests/support/test_meshes.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

namespace {

using namespace pdeface;

// A scan of the faces folder, read once; empty (its cases are then skipped) when it cannot be read.
const Mesh& scan(const std::string& name) {
  static std::map<std::string, Mesh> read;
  const auto [it, fresh] = read.try_emplace(name);
  if (!fresh) return it->second;
  auto loaded = formats::read_mesh(bench::face(name));
  if (loaded)
    it->second = std::move(loaded->mesh);
  else
    std::fprintf(stderr, "align_bench: %s; the case is skipped\n", loaded.error().to_string().c_str());
  return it->second;
}

void detect(benchmark::State& state, const Mesh& mesh, unsigned threads = 1) {
  if (mesh.vertex_count() == 0) {
    state.SkipWithError("scan not available");
    return;
  }
  for (auto _ : state) {
    auto found = align::detect_landmarks(mesh, {.threads = threads});
    if (!found) state.SkipWithError(found.error().to_string().c_str());
    benchmark::DoNotOptimize(found);
  }
  state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
}

void detect_sample(benchmark::State& state) {
  static const Mesh face = sample_face();
  detect(state, face);
}
void detect_scan(benchmark::State& state, const char* name) { detect(state, scan(name)); }
// The same search on `state.range(0)` threads: its wall time (the landmarks are the same to the bit).
void detect_on_threads(benchmark::State& state, const char* name) {
  detect(state, scan(name), static_cast<unsigned>(state.range(0)));
}
void detect_facefuns_points(benchmark::State& state) {
  static const Mesh cloud = to_mesh(to_point_cloud(scan("facefuns_f18.ply")));
  detect(state, cloud);
}
void detect_half_a_million(benchmark::State& state) {
  const Mesh& real = scan("facefuns_f18.ply");
  static const Mesh fine = real.vertex_count() ? test::subdivided(test::subdivided(real)) : Mesh{};
  detect(state, fine);
}

// One depth map of the kind detection makes ~35 of (facefuns_f18 in its canonical frame, a cell of
// `state.range(0)` mm: the quick and the thorough searches'): rasterised, the see-through cells dropped,
// the holes filled.
void depth_map(benchmark::State& state) {
  const Mesh& real = scan("facefuns_f18.ply");
  if (real.vertex_count() == 0) return state.SkipWithError("scan not available");
  static const Mesh face = align::to_canonical(real, align::detect_landmarks(real).value().frame);
  const auto cell = static_cast<double>(state.range(0));
  for (auto _ : state) {
    DepthMap map(-100.0, 100.0, -140.0, 120.0, cell);
    map.rasterise(face.positions, face.triangles, 1.5 * cell);
    map.drop_pits(20.0, 25.0);
    map.fill_holes(std::max(1, static_cast<int>(std::lround(4.0 / cell))));
    benchmark::DoNotOptimize(map);
  }
}

void to_canonical_frame(benchmark::State& state) {
  const Mesh& real = scan("facefuns_f18.ply");
  if (real.vertex_count() == 0) return state.SkipWithError("scan not available");
  const align::FaceFrame frame = align::detect_landmarks(real).value().frame;
  for (auto _ : state)
    benchmark::DoNotOptimize(align::to_canonical(real, frame));
}

BENCHMARK(detect_sample)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_scan, facefuns, "facefuns_f18.ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_on_threads, facefuns, "facefuns_f18.ply")
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(detect_facefuns_points)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_scan, bust, "demosthenes.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_scan, bust_on_pedestal, "bust_man_wreath.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_scan, coarse_patch, "fran_cut.wrl")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(detect_scan, eye_holes, "ict_05.ply")->Unit(benchmark::kMillisecond);
BENCHMARK(detect_half_a_million)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(depth_map)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(to_canonical_frame)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
