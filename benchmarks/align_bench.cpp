// Landmark detection and alignment on a paper-scale scan (facefuns_f18.ply, 30,204 vertices), its point
// cloud, and the built-in sample face (15,129 vertices).
//
//   build/benchmarks/align_bench          (PDEFACE_DATA=/path/to/faces)

#include "pdeface/align/detect.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace {

using namespace pdeface;

const Mesh& real_scan() {
  static const Mesh scan = [] {
    auto loaded = formats::read_mesh(bench::face("facefuns_f18.ply"));
    if (!loaded) {
      std::fprintf(stderr, "align_bench: %s; the real-scan cases are skipped\n",
                   loaded.error().to_string().c_str());
      return Mesh{};
    }
    return loaded->mesh;
  }();
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
BENCHMARK(to_canonical_frame)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
