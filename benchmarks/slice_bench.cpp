// Slicing a paper-scale scan (facefuns_f18.ply, 30,204 vertices) into all its profiles, against reading
// it from disk, in the same process: the slicing stage should cost a small fraction of the read.
//
//   build/benchmarks/slice_bench          (PDEFACE_DATA=/path/to/faces)

#include "pdeface/align/detect.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/slice/intersect.hpp"
#include "pdeface/slice/profiles.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace {

using namespace pdeface;

std::filesystem::path scan_path() { return bench::face("facefuns_f18.ply"); }

// The scan in the canonical frame with its landmarks (detected once; not what is measured).
struct Aligned {
  Mesh canonical;
  align::Landmarks landmarks;
  align::FaceFrame frame;
};

const Aligned* aligned() {
  static const std::optional<Aligned> a = []() -> std::optional<Aligned> {
    auto loaded = formats::read_mesh(scan_path());
    if (!loaded) {
      std::fprintf(stderr, "slice_bench: %s\n", loaded.error().to_string().c_str());
      return std::nullopt;
    }
    auto found = align::detect_landmarks(loaded->mesh);
    if (!found) return std::nullopt;
    return Aligned{align::to_canonical(loaded->mesh, found->frame),
                   align::to_canonical(found->landmarks, found->frame), found->frame};
  }();
  return a ? &*a : nullptr;
}

void read_from_disk(benchmark::State& state) {
  for (auto _ : state) {
    auto loaded = formats::read_mesh(scan_path());
    if (!loaded) return state.SkipWithError(loaded.error().to_string().c_str());
    benchmark::DoNotOptimize(loaded);
  }
}

void extract_all_profiles(benchmark::State& state) {
  const Aligned* a = aligned();
  if (!a) return state.SkipWithError("scan not available");
  slice::ProfileOptions options;
  options.ratio = static_cast<double>(state.range(0)) / 100.0;
  for (auto _ : state) {
    auto set = slice::extract_profiles(a->canonical, a->landmarks, a->frame, options);
    if (!set) return state.SkipWithError(set.error().to_string().c_str());
    benchmark::DoNotOptimize(set);
  }
}

void intersect_28_planes(benchmark::State& state) {
  const Aligned* a = aligned();
  if (!a) return state.SkipWithError("scan not available");
  const auto set = slice::extract_profiles(a->canonical, a->landmarks, a->frame);
  std::vector<double> xs;
  for (const auto& c : set->curves)
    xs.push_back(c.x);
  for (auto _ : state)
    benchmark::DoNotOptimize(slice::intersect(a->canonical, Vec3::UnitX(), xs));
}

void extract_from_point_cloud(benchmark::State& state) {
  const Aligned* a = aligned();
  if (!a) return state.SkipWithError("scan not available");
  const Mesh cloud = to_mesh(to_point_cloud(a->canonical));
  for (auto _ : state) {
    auto set = slice::extract_profiles(cloud, a->landmarks, a->frame);
    if (!set) return state.SkipWithError(set.error().to_string().c_str());
    benchmark::DoNotOptimize(set);
  }
}

} // namespace

BENCHMARK(read_from_disk)->Unit(benchmark::kMillisecond);
BENCHMARK(extract_all_profiles)->Arg(10)->Arg(60)->Unit(benchmark::kMillisecond);
BENCHMARK(intersect_28_planes)->Unit(benchmark::kMillisecond);
BENCHMARK(extract_from_point_cloud)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
