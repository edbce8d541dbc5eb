// Per-triangle boxes: the exact double box of the three corners, rounded outward to float, so that
// a float box always contains the double triangle (ARCHITECTURE.md, "BVH boxes may be float").
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <bit>
#include <cstdint>
#include <limits>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "build_internal.h"
#include "interfere/bvh/bvh.h"

namespace interfere {
namespace detail {
void advise_huge_pages(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t lo = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t hi = (begin + bytes) & ~(kHuge - 1);
  if (p != nullptr && hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

Buffer<PrimRef> make_prim_refs(const TriMesh& mesh) {
  const std::size_t n = mesh.num_triangles();
  Buffer<PrimRef> refs(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      refs[i].box = triangle_box_f(mesh, i);
      refs[i].idx = static_cast<std::uint32_t>(i);
      refs[i].pad = 0;
    }
  });
  return refs;
}

AabbF centroid_bounds_parallel(const PrimRef* refs, std::size_t n) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 1 << 14), AabbF{},
      [&](const auto& r, AabbF c) {
        c.expand(centroid_bounds(refs, r.begin(), r.end()));
        return c;
      },
      [](AabbF x, const AabbF& y) {
        x.expand(y);
        return x;
      });
}

}  // namespace detail

std::vector<AabbF> triangle_boxes(const TriMesh& mesh) {
  const std::size_t n = mesh.num_triangles();
  std::vector<AabbF> boxes;
  detail::resize_output(boxes, n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) boxes[i] = detail::triangle_box_f(mesh, i);
  });
  return boxes;
}

}  // namespace interfere
