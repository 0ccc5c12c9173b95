#pragma once
//! \file
//! Independent pieces of work spread over the cores (rows of a table, variants and scans of a comparison,
//! the hypotheses of a landmark search).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pdeface {

//! The machine's cores (at least 1).
[[nodiscard]] inline unsigned cores() { return std::max(1U, std::thread::hardware_concurrency()); }

//! Runs `work(i)` for every i in [0, n) on up to `threads` threads (0: every core), the calling thread
//! one of them; returns when all are done. An exception thrown by `work` does not stop the other items:
//! once all are done, the one thrown for the lowest i is thrown again on the calling thread.
template <class Work> void parallel_for(std::size_t n, unsigned threads, const Work& work) {
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::size_t failed_at = n;
  std::exception_ptr failure;
  const auto run = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        work(i);
      } catch (...) {
        const std::scoped_lock lock(failure_mutex);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
        }
      }
    }
  };
  {
    const std::size_t count = std::min<std::size_t>(n, threads == 0 ? cores() : threads);
    std::vector<std::jthread> workers(count > 1 ? count - 1 : 0);
    for (std::jthread& w : workers)
      w = std::jthread(run);
    run();
  } // the workers joined
  if (failure) std::rethrow_exception(failure);
}

} // namespace pdeface
