// Two-sided surface distance between two paper-scale scans (facefuns_f18 and facefuns_f36, 30,204
// vertices each), sampled every 0.5 mm: what a fidelity report costs per variant.

#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/surface_distance.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace {

using namespace pdeface;

Mesh load(const char* name) {
  auto loaded = formats::read_mesh(bench::face(name));
  return loaded ? loaded->mesh : Mesh{};
}

// Times the two-sided distance between `a` and `b` sampled every `spacing` mm; counts the samples.
void time_two_sided(benchmark::State& state, const Mesh& a, const Mesh& b, double spacing) {
  std::size_t samples = 0;
  for (auto _ : state) {
    auto d = metrics::surface_distance(a, b, {.spacing = spacing});
    samples = d->both.samples;
    benchmark::DoNotOptimize(d);
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsIterationInvariantRate);
}

void two_sided(benchmark::State& state) {
  static const Mesh a = load("facefuns_f18.ply"), b = load("facefuns_f36.ply");
  if (a.positions.empty() || b.positions.empty()) return state.SkipWithError("facefuns scans not found");
  time_two_sided(state, a, b, static_cast<double>(state.range(0)) / 10.0);
}

// A reconstruction-like case: the scan against itself moved 0.3 mm along its depth.
void two_sided_close(benchmark::State& state) {
  static const Mesh a = load("facefuns_f18.ply");
  if (a.positions.empty()) return state.SkipWithError("facefuns scan not found");
  static const Mesh b = [] {
    Mesh m = a;
    for (Vec3& p : m.positions)
      p.z() += 0.3;
    return m;
  }();
  time_two_sided(state, a, b, 0.5);
}

void build_index(benchmark::State& state) {
  static const Mesh a = load("facefuns_f18.ply");
  if (a.positions.empty()) return state.SkipWithError("facefuns scan not found");
  for (auto _ : state)
    benchmark::DoNotOptimize(metrics::SurfaceDistance(a));
}

BENCHMARK(two_sided)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond); // spacing 0.5 mm and 1 mm
BENCHMARK(two_sided_close)->Unit(benchmark::kMillisecond);
BENCHMARK(build_index)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
