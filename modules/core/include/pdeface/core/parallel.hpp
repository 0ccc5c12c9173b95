#pragma once
//! \file
//! Independent pieces of work spread over the cores (rows of a table, variants and scans of a comparison,
//! the hypotheses of a landmark search).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace pdeface {

//! The machine's cores (at least 1).
[[nodiscard]] inline unsigned cores() { return std::max(1U, std::thread::hardware_concurrency()); }

//! Runs `work(i)` for every i in [0, n) on up to `threads` threads (0: every core), the calling thread
//! one of them; returns when all are done. `work` must not throw.
template <class Work> void parallel_for(std::size_t n, unsigned threads, const Work& work) {
  std::atomic<std::size_t> next{0};
  const auto run = [&] {
    for (std::size_t i = next++; i < n; i = next++)
      work(i);
  };
  const std::size_t count = std::min<std::size_t>(n, threads == 0 ? cores() : threads);
  std::vector<std::jthread> workers(count > 1 ? count - 1 : 0);
  for (std::jthread& w : workers)
    w = std::jthread(run);
  run();
}

} // namespace pdeface
