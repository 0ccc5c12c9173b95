// The PDE surface: solving 28 curves (K = 30 and 300 samples) by each scheme, evaluating a 316 × 316
// grid (99,856 vertices), triangulating it (with normals), and, for scale, encoding the same mesh as
// binary PLY in memory. Curves: the synthetic face of tests/pde/synthetic_face.hpp.
//
//   build/benchmarks/pde_bench [--benchmark_filter=Evaluate]

#include "pdeface/formats/formats.hpp"
#include "pdeface/pde/surface.hpp"

#include "../tests/pde/synthetic_face.hpp"

#include <benchmark/benchmark.h>

#include <map>

namespace {

using namespace pdeface;
using namespace pdeface::pde;

constexpr std::size_t grid_side = 316;

const Curves& curves(std::size_t samples) {
  static std::map<std::size_t, Curves> cache;
  auto [it, added] = cache.try_emplace(samples);
  if (added) it->second = face::profiles(samples);
  return it->second;
}

const Surface& surface(std::size_t samples) {
  static std::map<std::size_t, Surface> cache;
  auto it = cache.find(samples);
  if (it == cache.end()) it = cache.emplace(samples, Surface::build(curves(samples)).value()).first;
  return it->second;
}

void solve(benchmark::State& state, Options options) {
  const auto samples = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    auto s = Surface::build(curves(samples), options);
    if (!s) return state.SkipWithError(s.error().to_string().c_str());
    benchmark::DoNotOptimize(s);
  }
}

void evaluate(benchmark::State& state) {
  const Surface& s = surface(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(s.evaluate(grid_side, grid_side));
  state.counters["vertices"] = static_cast<double>(grid_side * grid_side);
}

void triangulate_grid(benchmark::State& state) {
  const Grid grid = surface(30).evaluate(grid_side, grid_side);
  for (auto _ : state)
    benchmark::DoNotOptimize(triangulate(grid));
}

void mesh_and_ply(benchmark::State& state) {
  const Surface& s = surface(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto ply = formats::encode_mesh(s.mesh(grid_side, grid_side), "surface.ply");
    bytes = ply->size();
    benchmark::DoNotOptimize(ply);
  }
  state.counters["ply_bytes"] = static_cast<double>(bytes);
}

void encode_ply(benchmark::State& state) {
  const Mesh mesh = surface(30).mesh(grid_side, grid_side);
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto ply = formats::encode_mesh(mesh, "surface.ply");
    bytes = ply->size();
    benchmark::DoNotOptimize(ply);
  }
  state.counters["ply_bytes"] = static_cast<double>(bytes);
}

BENCHMARK_CAPTURE(solve, spline, Options{})->Arg(30)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve, paper, Options{.scheme = Scheme::Paper})
    ->Arg(30)
    ->Arg(300)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve, patch4_13_modes, Options{.scheme = Scheme::Patch4, .modes = 13})
    ->Arg(30)
    ->Arg(300)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve, spline_13_modes_no_remainder, Options{.modes = 13, .remainder = false})
    ->Arg(30)
    ->Arg(300)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(evaluate)->Arg(30)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK(triangulate_grid)->Unit(benchmark::kMillisecond);
BENCHMARK(encode_ply)->Unit(benchmark::kMillisecond);
BENCHMARK(mesh_and_ply)->Arg(30)->Arg(300)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
