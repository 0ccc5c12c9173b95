// Landmark detection and alignment on a paper-scale scan (facefuns_f18.ply, 30,204 vertices), its point
// cloud, the built-in sample face (15,129 vertices), the hard cases (a bust in arbitrary units, a bust on a
// pedestal with its head turned, a coarse cut patch, a morphable model's face with eye holes in cm) and
// facefuns_f18 subdivided twice (482k vertices).
//
//   build/benchmarks/align_bench          (PDEFACE_DATA=/path/to/faces)

#include "pdeface/align/detect.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include "../tests/support/test_meshes.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

namespace {

using namespace pdeface;

Mesh read_scan(const char* name) {
  auto loaded = formats::read_mesh(bench::face(name));
  if (!loaded) {
    std::fprintf(stderr, "align_bench: %s; the case is skipped\n", loaded.error().to_string().c_str());
    return Mesh{};
  }
  return loaded->mesh;
}

const Mesh& real_scan() {
  static const Mesh scan = read_scan("facefuns_f18.ply");
  return scan;
}

void detect(benchmark::State& state, const Mesh& scan) {
  if (scan.vertex_count() == 0) {
    state.SkipWithError("scan not available");
    return;
  }
  for (auto _ : state) {
    auto found = align::detect_landmarks(scan);
    if (!found) state.SkipWithError(found.error().to_string().c_str());
    benchmark::DoNotOptimize(found);
  }
  state.counters["vertices"] = static_cast<double>(scan.vertex_count());
}

void detect_sample(benchmark::State& state) {
  static const Mesh face = sample_face();
  detect(state, face);
}
void detect_facefuns(benchmark::State& state) { detect(state, real_scan()); }
void detect_facefuns_points(benchmark::State& state) {
  static const Mesh cloud = to_mesh(to_point_cloud(real_scan()));
  detect(state, cloud);
}

void detect_bust(benchmark::State& state) {
  static const Mesh scan = read_scan("demosthenes.obj");
  detect(state, scan);
}
void detect_bust_on_pedestal(benchmark::State& state) {
  static const Mesh scan = read_scan("bust_man_wreath.obj");
  detect(state, scan);
}
void detect_coarse_patch(benchmark::State& state) {
  static const Mesh scan = read_scan("fran_cut.wrl");
  detect(state, scan);
}
void detect_eye_holes(benchmark::State& state) {
  static const Mesh scan = read_scan("ict_05.ply");
  detect(state, scan);
}
void detect_half_a_million(benchmark::State& state) {
  static const Mesh fine =
      real_scan().vertex_count() ? test::subdivided(test::subdivided(real_scan())) : Mesh{};
  detect(state, fine);
}

void to_canonical_frame(benchmark::State& state) {
  const Mesh& scan = real_scan();
  if (scan.vertex_count() == 0) return state.SkipWithError("scan not available");
  const align::FaceFrame frame = align::detect_landmarks(scan).value().frame;
  for (auto _ : state)
    benchmark::DoNotOptimize(align::to_canonical(scan, frame));
}

BENCHMARK(detect_sample)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_facefuns)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_facefuns_points)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_bust)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_bust_on_pedestal)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_coarse_patch)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_eye_holes)->Unit(benchmark::kMillisecond);
BENCHMARK(detect_half_a_million)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(to_canonical_frame)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
