// parallel_for: every item runs once on any thread count, and an exception reaches the caller (the lowest
// item's) instead of ending the process.

#include "pdeface/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace pdeface {
namespace {

TEST(ParallelFor, RunsEveryItemOnceOnAnyThreadCount) {
  for (const unsigned threads : {0U, 1U, 2U, 7U}) {
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i)
      ASSERT_EQ(runs[i].load(), 1) << "item " << i << " on " << threads << " threads";
  }
  parallel_for(0, 2, [](std::size_t) { FAIL() << "no item to run"; });
}

TEST(ParallelFor, AnExceptionReachesTheCallerAfterTheOtherItems) {
  for (const unsigned threads : {1U, 2U, 4U}) {
    std::atomic<int> done{0};
    try {
      parallel_for(200, threads, [&](std::size_t i) {
        if (i == 37 || i == 150) throw std::runtime_error("item " + std::to_string(i));
        ++done;
      });
      ADD_FAILURE() << "nothing thrown on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "item 37") << threads << " threads"; // the lowest item's
    }
    EXPECT_EQ(done.load(), 198) << threads << " threads"; // the others all ran
  }
}

} // namespace
} // namespace pdeface
