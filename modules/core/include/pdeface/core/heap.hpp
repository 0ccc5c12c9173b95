#pragma once
//! \file
//! The C heap of a program that runs one command and exits.

//! PDEFACE_SANITIZED: defined in a build for a sanitizer, whose allocator is its own (GCC says so by
//! __SANITIZE_*__, clang 14 only by __has_feature).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PDEFACE_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define PDEFACE_SANITIZED 1
#endif
#endif

namespace pdeface {

//! Sets up glibc's heap for a program that runs one command and exits (the CLI, the benchmarks that stand
//! for it): fixed mmap (4 MB) and trim (64 MB) thresholds, so that freed blocks stay for reuse whatever the
//! order of the frees, and the heap's top made 60 MB long (virtual: nothing is touched) on transparent huge
//! pages where the system grants them on request (`madvise`, Debian's default), so that a fresh 2 MB costs
//! one page fault instead of 512 — what `GLIBC_TUNABLES=glibc.malloc.hugetlb=1` does for every block,
//! which a process cannot set for itself. Blocks of any size are carved from that top while it has room.
//! Process-wide: call it first thing in `main`, never from a library (a caller's process keeps its own
//! settings). Returns whether the huge pages were asked for, `madvise` accepting (false without glibc,
//! under sanitizers, whose allocators are their own, or when `madvise` refuses); the thresholds are set
//! either way.
bool prepare_command_heap();

} // namespace pdeface
