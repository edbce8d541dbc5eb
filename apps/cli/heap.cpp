// Heap preparation for large inputs (heap.h). Measured on two 1M-triangle binary STL files
// (docs/scene-benchmarks.md): 32,000 page faults and 0.9 s of CPU time without, 1,800 and 0.3 s
// with (the same as glibc's tunables glibc.malloc.hugetlb=1, mmap_max=0, trim_threshold).
#include "heap.h"

#include <climits>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace interfere::cli {

void prepare_heap(std::size_t bytes) {
  static bool done = false;
  if (done || bytes < (std::size_t{64} << 20)) return;
  done = true;
#if defined(__GLIBC__)
  // One heap, never trimmed: a freed buffer (the file bytes, the weld's scratch) is reused by the
  // next one (the trees) with its pages already present, not unmapped and faulted in again.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_ARENA_MAX, 1);  // worker threads' buffers from the same heap
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Grow the heap once by `bytes` (virtual only: nothing is touched) and advise it as huge pages,
  // then free it: it stays the heap's top (never trimmed), where the buffers come from, and each
  // 2 MiB page takes one fault instead of 512. Without transparent huge pages (or in "never"
  // mode) the advice is ignored.
  if (void* p = std::malloc(bytes)) {
    constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
    const auto lo = (reinterpret_cast<std::uintptr_t>(p) + huge - 1) & ~(huge - 1);
    const auto hi = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(huge - 1);
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
    std::free(p);
  }
#endif
#endif
}

}  // namespace interfere::cli
