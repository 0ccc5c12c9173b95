#pragma once
// What the benchmarks share: where the real scans are, the allocator pinned to fresh or reused memory, and a
// page-fault counter.

#include <benchmark/benchmark.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__unix__)
#include <sys/resource.h>
#endif

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace pdeface::bench {

//! A scan of the faces folder: `$PDEFACE_DATA`, else the folder the build was configured with
//! (default ../shared/faces). The benchmarks that need it say so and skip when it is missing.
inline std::filesystem::path face(std::string_view name) {
  const char* env = std::getenv("PDEFACE_DATA");
  const std::filesystem::path dir = env && *env ? env : PDEFACE_DEFAULT_FACES;
  return dir / name;
}

//! On a VM a page fault costs ~1-13 µs, so whether a step's output lands on fresh pages can change its time
//! many-fold; a case says which it measures:
//!   Fresh:  every block of 64 KiB or more is mapped anew, as in one command's run, where each step first
//!           touches its output (page faults included);
//!   Reused: freed memory stays in the heap, so after the first iteration only arithmetic and copying
//!           remain (a long-running process converting many faces; "warm").
enum class Memory { Fresh, Reused };

//! Pins glibc's allocator as `memory` says for what follows. Without glibc it is left as it is.
inline void pin_allocator(Memory memory) {
#if defined(__GLIBC__)
  // Setting either threshold also turns off glibc's adjusting of them to the sizes freed so far.
  if (memory == Memory::Fresh) {
    mallopt(M_MMAP_THRESHOLD, 64 * 1024);
    mallopt(M_TRIM_THRESHOLD, 128 * 1024);
  } else {
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024); // glibc's largest: blocks up to 32 MiB come from the heap
    mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
  }
#else
  (void)memory;
#endif
}

//! Counts the page faults of the timed loop (the counter "faults", per iteration), where the system says.
class FaultCounter {
public:
  explicit FaultCounter(benchmark::State& state) : state_(state), start_(faults()) {}
  FaultCounter(const FaultCounter&) = delete;
  FaultCounter& operator=(const FaultCounter&) = delete;
  ~FaultCounter() {
    if (start_ >= 0)
      state_.counters["faults"] = benchmark::Counter(static_cast<double>(faults() - start_ - excluded_),
                                                     benchmark::Counter::kAvgIterations);
  }
  //! Runs `untimed` (between PauseTiming and ResumeTiming) without counting its faults.
  template <class F> void exclude(F&& untimed) {
    const long before = faults();
    untimed();
    excluded_ += faults() - before;
  }

private:
  static long faults() {
#if defined(__unix__)
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) == 0) return usage.ru_minflt + usage.ru_majflt;
#endif
    return -1;
  }

  benchmark::State& state_;
  long start_;
  long excluded_ = 0;
};

} // namespace pdeface::bench
