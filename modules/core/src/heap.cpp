#include "pdeface/core/heap.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#endif

namespace pdeface {

bool prepare_command_heap() {
#if defined(__GLIBC__)
  // Setting either threshold alone turns glibc's dynamic threshold off and is far worse (encode: 31,000
  // page faults instead of 4,000; docs/performance.md, "Page faults").
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  bool huge = false;
#if !defined(PDEFACE_SANITIZED)
  // Two blocks of 30 MB taken from the heap (the mmap threshold raised to glibc's most, 32 MB, for them),
  // marked and given back: they become the heap's top, which later blocks are carved from and which stays
  // (below the trim threshold). madvise only marks the range; pages come on first touch, 2 MB at a time.
  constexpr std::size_t kBlock = std::size_t{30} << 20, kPage = 4096;
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  const std::array<void*, 2> blocks{std::malloc(kBlock), std::malloc(kBlock)};
  huge = true;
  for (void* b : blocks) {
    if (b == nullptr) {
      huge = false;
      continue;
    }
    // madvise takes a page-aligned range: the block's whole pages.
    const std::size_t skip = (kPage - reinterpret_cast<std::uintptr_t>(b) % kPage) % kPage;
    if (madvise(static_cast<char*>(b) + skip, (kBlock - skip) / kPage * kPage, MADV_HUGEPAGE) != 0)
      huge = false;
  }
  for (void* b : blocks)
    std::free(b);
#endif
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  return huge;
#else
  return false;
#endif
}

} // namespace pdeface
