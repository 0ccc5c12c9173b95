// The PDE surface: solving 28 curves, evaluating a 316 × 316 grid (99,856 vertices), triangulating it
// (with normals), and writing the same mesh out, all in one process so that the ratios mean something.
//
// Real curves (real_*, argument: the sampling ratio in %): facefuns_f18.ply aligned (align::align_scan),
// sliced at 10 % (K = 27) and 60 % (K = 162), the curves solved as `pdeface reconstruct` does (spline,
// physical spacing); the mesh encoded as GLB and as binary PLY in memory (formats::encode_mesh) and
// written atomically to a file in the temporary folder (formats::write_mesh). The scan is read, aligned
// and sliced once, outside the timed loops; without it these cases are skipped, saying why.
// Synthetic curves (solve/*, evaluate/*, argument: K): the face of tests/pde/synthetic_face.hpp.
//
// Memory: every case pins glibc's allocator first, because on a VM a page fault costs ~10 µs and whether
// a step's output lands on fresh pages changes its time up to 30-fold:
//   fresh:  every block of 64 KiB or more is mapped anew, as in one `pdeface reconstruct` run, where each
//           step first touches its output (page faults included);
//   reused: freed memory stays in the heap, so after the first iteration only arithmetic and copying
//           remain (a long-running process converting many faces).
//
//   build/benchmarks/pde_bench [--benchmark_filter=real_]          (PDEFACE_DATA=/path/to/faces)

#include "pdeface/align/detect.hpp"
#include "pdeface/align/frame.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pde/mesher.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/slice/profiles.hpp"

#include "../tests/pde/synthetic_face.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>

namespace {

using namespace pdeface;
using namespace pdeface::pde;

constexpr std::size_t grid_side = 316;

using bench::FaultCounter;
using bench::Memory;
using bench::pin_allocator;

// --- Real curves ------------------------------------------------------------------------------------

std::filesystem::path scan_path() { return bench::face("facefuns_f18.ply"); }

struct AlignedScan {
  Mesh scan;
  align::Alignment alignment;
};

// The scan read and aligned once; the reason in `why` when it cannot be.
const AlignedScan* aligned_scan(std::string& why) {
  static std::string error;
  static const std::optional<AlignedScan> scan = []() -> std::optional<AlignedScan> {
    auto loaded = formats::read_mesh(scan_path());
    if (!loaded) {
      error = loaded.error().to_string() + " (set PDEFACE_DATA to the faces folder)";
      return std::nullopt;
    }
    auto alignment = align::align_scan(loaded->mesh, std::nullopt, scan_path().string());
    if (!alignment) {
      error = alignment.error().to_string();
      return std::nullopt;
    }
    return AlignedScan{std::move(loaded->mesh), std::move(alignment).value()};
  }();
  why = error;
  return scan ? &*scan : nullptr;
}

const pde::Options& reconstruct_options() {
  static const pde::Options options = pipeline::ReconstructOptions{}.pde; // spline, physical spacing
  return options;
}

// What the timed steps start from, at one sampling ratio: the curves, their surface and its mesh.
struct RealCase {
  Curves curves;
  Surface surface;
  Mesh mesh;
};

std::optional<RealCase> make_real_case(std::int64_t percent, std::string& why) {
  const AlignedScan* a = aligned_scan(why);
  if (!a) return std::nullopt;
  slice::ProfileOptions options;
  options.ratio = static_cast<double>(percent) / 100.0;
  auto profiles = pipeline::extract_profiles(pipeline::canonical_scan(a->scan, a->alignment), options);
  if (!profiles) {
    why = profiles.error().to_string();
    return std::nullopt;
  }
  Curves curves = pipeline::to_curves(*profiles);
  auto surface = Surface::build(curves, reconstruct_options());
  if (!surface) {
    why = surface.error().to_string();
    return std::nullopt;
  }
  Mesh mesh = surface->mesh(grid_side, grid_side);
  return RealCase{std::move(curves), std::move(surface).value(), std::move(mesh)};
}

// The case for the ratio in state.range(0) (made once, with fresh memory), or nullptr after skipping
// the benchmark with the reason. Sets the counter K, and pins the allocator as `memory` says for what
// follows.
const RealCase* real_case(benchmark::State& state, Memory memory) {
  static std::map<std::int64_t, std::pair<std::optional<RealCase>, std::string>> cache;
  const std::int64_t percent = state.range(0);
  auto it = cache.find(percent);
  if (it == cache.end()) {
    pin_allocator(Memory::Fresh);
    std::string why;
    std::optional<RealCase> made = make_real_case(percent, why);
    it = cache.emplace(percent, std::pair{std::move(made), std::move(why)}).first;
  }
  if (!it->second.first) {
    state.SkipWithError(("skipped, no real curves: " + it->second.second).c_str());
    return nullptr;
  }
  state.counters["K"] = static_cast<double>(it->second.first->surface.sample_count());
  pin_allocator(memory);
  return &*it->second.first;
}

void real_solve(benchmark::State& state, Memory memory) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const FaultCounter faults(state);
  for (auto _ : state) {
    auto s = Surface::build(c->curves, reconstruct_options());
    if (!s) return state.SkipWithError(s.error().to_string().c_str());
    benchmark::DoNotOptimize(s);
  }
}

// Times `step(c)` on the real case `c`, keeping what it makes, with the page faults counted.
template <class Step> void time_real(benchmark::State& state, Memory memory, Step step) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const FaultCounter faults(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(step(*c));
}

void real_evaluate(benchmark::State& state, Memory memory) {
  time_real(state, memory, [](const RealCase& c) { return c.surface.evaluate(grid_side, grid_side); });
}

void real_triangulate(benchmark::State& state, Memory memory) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const Grid grid = c->surface.evaluate(grid_side, grid_side);
  FaultCounter faults(state);
  for (auto _ : state) {
    state.PauseTiming(); // triangulate takes the grid by value: copying it is not what is measured
    Grid copy;
    faults.exclude([&] { copy = grid; });
    state.ResumeTiming();
    benchmark::DoNotOptimize(triangulate(std::move(copy), Units::Millimetres));
  }
}

void real_evaluate_triangulate(benchmark::State& state, Memory memory) {
  state.counters["vertices"] = static_cast<double>(grid_side * grid_side);
  time_real(state, memory, [](const RealCase& c) { return c.surface.mesh(grid_side, grid_side); });
}

// The floor under producing the mesh: its three arrays allocated and filled with zeros.
void real_mesh_memory(benchmark::State& state, Memory memory) {
  time_real(state, memory, [](const RealCase& c) {
    Mesh m;
    m.positions.assign(c.mesh.positions.size(), Vec3::Zero());
    m.triangles.assign(c.mesh.triangles.size(), Triangle{});
    m.normals.assign(c.mesh.normals.size(), Vec3f::Zero());
    return m;
  });
}

void real_encode(benchmark::State& state, Memory memory, const char* name) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const FaultCounter faults(state);
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto encoded = formats::encode_mesh(c->mesh, name);
    if (!encoded) return state.SkipWithError(encoded.error().to_string().c_str());
    bytes = encoded->size();
    benchmark::DoNotOptimize(encoded);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}

void real_write(benchmark::State& state, Memory memory, const char* name) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const FaultCounter faults(state);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto written = formats::write_mesh(c->mesh, path);
    if (!written) return state.SkipWithError(written.error().to_string().c_str());
    bytes = *written;
  }
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  state.counters["bytes"] = static_cast<double>(bytes);
}

// Curves to a GLB file: solve, evaluate, triangulate, write (what `pdeface reconstruct` does after slicing).
void real_curves_to_glb(benchmark::State& state, Memory memory) {
  const RealCase* c = real_case(state, memory);
  if (!c) return;
  const FaultCounter faults(state);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "pdeface_pde_bench_all.glb";
  for (auto _ : state) {
    auto s = Surface::build(c->curves, reconstruct_options());
    if (!s) return state.SkipWithError(s.error().to_string().c_str());
    auto written = formats::write_mesh(s->mesh(grid_side, grid_side), path);
    if (!written) return state.SkipWithError(written.error().to_string().c_str());
  }
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

void real_encode_glb(benchmark::State& state, Memory memory) { real_encode(state, memory, "surface.glb"); }
void real_encode_ply(benchmark::State& state, Memory memory) { real_encode(state, memory, "surface.ply"); }
void real_write_glb(benchmark::State& state, Memory memory) {
  real_write(state, memory, "pdeface_pde_bench.glb");
}
void real_write_ply(benchmark::State& state, Memory memory) {
  real_write(state, memory, "pdeface_pde_bench.ply");
}

#define PDEFACE_REAL_BENCHMARK(function, unit)                                                               \
  BENCHMARK_CAPTURE(function, fresh, Memory::Fresh)->Arg(10)->Arg(60)->Unit(unit);                           \
  BENCHMARK_CAPTURE(function, reused, Memory::Reused)->Arg(10)->Arg(60)->Unit(unit)

PDEFACE_REAL_BENCHMARK(real_solve, benchmark::kMicrosecond);
PDEFACE_REAL_BENCHMARK(real_evaluate, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_triangulate, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_evaluate_triangulate, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_mesh_memory, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_encode_glb, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_encode_ply, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_write_glb, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_write_ply, benchmark::kMillisecond);
PDEFACE_REAL_BENCHMARK(real_curves_to_glb, benchmark::kMillisecond);

// --- Synthetic curves -------------------------------------------------------------------------------

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
  (void)curves(samples);
  pin_allocator(Memory::Fresh);
  const FaultCounter faults(state);
  for (auto _ : state) {
    auto s = Surface::build(curves(samples), options);
    if (!s) return state.SkipWithError(s.error().to_string().c_str());
    benchmark::DoNotOptimize(s);
  }
}

void evaluate(benchmark::State& state, Memory memory) {
  const Surface& s = surface(static_cast<std::size_t>(state.range(0)));
  pin_allocator(memory);
  const FaultCounter faults(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(s.evaluate(grid_side, grid_side));
}

// The mesher's parts on the synthetic face, memory reused: what it holds (the coefficients at every u and
// the cosines of every v), the rows' positions alone, positions and normals, the triangles, and all of it.
void mesher_make(benchmark::State& state) {
  const Surface& s = surface(static_cast<std::size_t>(state.range(0)));
  pin_allocator(Memory::Reused);
  for (auto _ : state)
    benchmark::DoNotOptimize(GridMesher(s, grid_side, grid_side));
}

void mesher_rows(benchmark::State& state, bool normals) {
  const GridMesher mesher(surface(static_cast<std::size_t>(state.range(0))), grid_side, grid_side);
  pin_allocator(Memory::Reused);
  std::vector<Vec3> positions(mesher.vertex_count());
  std::vector<Vec3f> n(normals ? mesher.vertex_count() : 0);
  for (auto _ : state) {
    mesher.rows(0, grid_side, positions, n);
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(n.data());
  }
}

void mesher_triangles(benchmark::State& state) {
  const GridMesher mesher(surface(30), grid_side, grid_side);
  std::vector<Triangle> triangles(mesher.triangle_count());
  for (auto _ : state) {
    mesher.triangles(0, grid_side - 1, triangles);
    benchmark::DoNotOptimize(triangles.data());
  }
}

void mesher_mesh(benchmark::State& state) {
  const Surface& s = surface(static_cast<std::size_t>(state.range(0)));
  pin_allocator(Memory::Reused);
  for (auto _ : state)
    benchmark::DoNotOptimize(s.mesh(grid_side, grid_side));
}

BENCHMARK(mesher_make)->Arg(30)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(mesher_rows, positions, false)->Arg(30)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(mesher_rows, with_normals, true)->Arg(30)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(mesher_triangles)->Unit(benchmark::kMicrosecond);
BENCHMARK(mesher_mesh)->Arg(30)->Arg(300)->Unit(benchmark::kMicrosecond);

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
BENCHMARK_CAPTURE(evaluate, fresh, Memory::Fresh)->Arg(30)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(evaluate, reused, Memory::Reused)->Arg(30)->Arg(300)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
