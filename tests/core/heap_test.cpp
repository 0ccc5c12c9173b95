// prepare_command_heap: the heap's fresh blocks on huge pages.

#include "pdeface/core/heap.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace pdeface {
namespace {

// The VmFlags of the mapping that holds `p` (/proc/self/smaps), or "" when none does.
std::string flags_of_mapping(const void* p) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t from = 0, to = 0;
    char dash = 0;
    if (std::istringstream header(line); header >> std::hex >> from >> dash >> to && dash == '-') {
      inside = from <= at && at < to;
    } else if (inside && line.starts_with("VmFlags:")) {
      return line.substr(8) + " ";
    }
  }
  return "";
}

TEST(Heap, FreshBlocksAreOnHugePages) {
  if (!prepare_command_heap())
    GTEST_SKIP() << "no huge pages asked for here (not glibc, a sanitizer's allocator, or madvise refused)";
  // Blocks of 1 and 5 MB (the latter above the mmap threshold) come from the heap's top, marked for huge
  // pages but for the page where the marked range began (a block's first bytes may lie there).
  constexpr std::size_t kSmall = std::size_t{1} << 20, kBig = std::size_t{5} << 20;
  auto* small = static_cast<char*>(std::malloc(kSmall));
  auto* big = static_cast<char*>(std::malloc(kBig));
  ASSERT_NE(small, nullptr);
  ASSERT_NE(big, nullptr);
  const std::string small_flags = flags_of_mapping(small + kSmall - 1),
                    big_flags = flags_of_mapping(big + kBig / 2);
  std::free(small);
  std::free(big);
  EXPECT_NE(small_flags.find(" hg "), std::string::npos) << small_flags;
  EXPECT_NE(big_flags.find(" hg "), std::string::npos) << big_flags;
}

} // namespace
} // namespace pdeface
