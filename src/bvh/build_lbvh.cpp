// Linear BVH (Lauterbach et al. 2009, "Fast BVH Construction on GPUs"; Karras 2012): triangles are
// sorted along a 30-bit Morton curve of their centroids (10 bits per axis on the cube around the
// vertex bounds, so elongated parts are cut across their long axis first), and every node is
// split where its highest differing Morton bit flips (binary search in the sorted codes). Ranges
// whose codes are all equal fall back to the object-median split of the longest axis; ranges of at
// most max_leaf_size triangles become leaves.
//
// Sorting: keys (code << 32 | triangle index) are unique, so the parallel radix sort (one MSD pass
// in fixed blocks, then in-cache LSD passes per bucket) has one possible result, whatever the
// thread count. Passes: (1) vertex bounds, (2) triangle boxes in input order (sequential mesh access;
// the corners of a Morton-ordered sweep would be random accesses) and their keys in one sweep, then
// the sort, (3)
// boxes gathered into sorted order with software prefetch, (4) the tree (TopDownBuilder, binary
// searches over 32-bit codes). Scratch per triangle: 24 + 8 + 8 + 4 bytes; fresh pages are a large
// part of the cost at 10^6 triangles, hence few buffers.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include "build_internal.h"
#include "interfere/core/morton.h"

namespace interfere::detail {
namespace {

constexpr double kInfD = std::numeric_limits<double>::infinity();

// Radix sort of the 64-bit keys on their code bits [32, 62) (the keys are unique, so every correct
// sort gives the same order). One parallel MSD pass on the top 10 code bits (fixed blocks, stable
// scatter from `in` into `keys`), then each of the 1024 buckets, small enough to stay in cache, is
// finished independently in place: two LSD passes of 10 bits through `in` as scratch, or std::sort
// when tiny.
constexpr int kRadixBits = 10;
constexpr std::size_t kBuckets = std::size_t{1} << kRadixBits;

void sort_bucket(std::uint64_t* a, std::uint64_t* scratch, std::size_t n) {  // sorts a[0, n)
  if (n < 256) {
    std::sort(a, a + n);
    return;
  }
  std::uint32_t hist[kBuckets];
  std::uint64_t* src = a;
  std::uint64_t* dst = scratch;
  for (int pass = 0; pass < 2; ++pass) {  // a -> scratch -> a
    const int shift = 32 + pass * kRadixBits;
    std::fill(hist, hist + kBuckets, 0u);
    for (std::size_t i = 0; i < n; ++i) ++hist[(src[i] >> shift) & (kBuckets - 1)];
    std::uint32_t sum = 0;
    for (std::size_t d = 0; d < kBuckets; ++d) {
      const std::uint32_t c = hist[d];
      hist[d] = sum;
      sum += c;
    }
    for (std::size_t i = 0; i < n; ++i) dst[hist[(src[i] >> shift) & (kBuckets - 1)]++] = src[i];
    std::swap(src, dst);
  }
}

void radix_sort_codes(Buffer<std::uint64_t>& in, Buffer<std::uint64_t>& keys) {
  const std::size_t n = keys.size();
  const std::size_t block = std::max<std::size_t>(std::size_t{1} << 14, (n + 255) / 256);
  const std::size_t nblocks = (n + block - 1) / block;
  constexpr int kShift = 32 + 2 * kRadixBits;
  std::vector<std::uint32_t> hist(nblocks * kBuckets);
  const std::uint64_t* src = in.data();
  std::uint64_t* dst = keys.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks, 1), [&](const auto& r) {
    for (std::size_t blk = r.begin(); blk < r.end(); ++blk) {
      std::uint32_t* h = hist.data() + blk * kBuckets;
      const std::size_t lo = blk * block, hi = std::min(n, lo + block);
      for (std::size_t i = lo; i < hi; ++i) ++h[(src[i] >> kShift) & (kBuckets - 1)];
    }
  });
  std::vector<std::uint32_t> start(kBuckets + 1, 0);
  std::uint32_t sum = 0;
  for (std::size_t d = 0; d < kBuckets; ++d) {  // exclusive prefix in (bucket, block) order: stable
    start[d] = sum;
    for (std::size_t blk = 0; blk < nblocks; ++blk) {
      const std::uint32_t c = hist[blk * kBuckets + d];
      hist[blk * kBuckets + d] = sum;
      sum += c;
    }
  }
  start[kBuckets] = sum;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks, 1), [&](const auto& r) {
    for (std::size_t blk = r.begin(); blk < r.end(); ++blk) {
      std::uint32_t* h = hist.data() + blk * kBuckets;
      const std::size_t lo = blk * block, hi = std::min(n, lo + block);
      for (std::size_t i = lo; i < hi; ++i) dst[h[(src[i] >> kShift) & (kBuckets - 1)]++] = src[i];
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kBuckets, 1), [&](const auto& r) {
    for (std::size_t d = r.begin(); d < r.end(); ++d) {
      const std::size_t lo = start[d], len = start[d + 1] - lo;
      if (len > 1) sort_bucket(keys.data() + lo, in.data() + lo, len);
    }
  });
}

struct LbvhRule {
  struct Info {};
  const std::uint32_t* codes;  // sorted Morton codes, aligned with prims
  Bvh* bvh;                    // prims/prim_boxes already in sorted order
  std::size_t max_leaf;

  Split<Info> split(std::size_t b, std::size_t e, const Info&, int, bool) const {
    if (e - b <= max_leaf) return {};
    const std::uint32_t first = codes[b], last = codes[e - 1];
    if (first == last) return {median(b, e), {}, {}};
    if (e - b > 1024 && e - b <= 8192) {
      // Near the root of a serially built subtree: pull its codes into cache once, so that the
      // dependent loads of the many binary searches below hit L1/L2.
      for (std::size_t i = b; i < e; i += 16) __builtin_prefetch(codes + i);
    }
    const int bit = 31 - std::countl_zero(first ^ last);
    // First code with `bit` set (the codes in [b, e) share every higher bit): branch-free
    // lower_bound (the comparisons are unpredictable), finished by counting over the last 16.
    const std::uint32_t pivot = ((first >> bit) | 1u) << bit;
    const std::uint32_t* base = codes + b;
    std::size_t len = e - b;
    while (len > 16) {
      const std::size_t half = len / 2;
      base += static_cast<std::size_t>(base[half - 1] < pivot) * half;
      len -= half;
    }
    std::size_t below = 0;  // short tail: count (independent loads) instead of dependent steps
    for (std::size_t i = 0; i < len; ++i) below += base[i] < pivot ? 1 : 0;
    return {static_cast<std::size_t>(base - codes) + below, {}, {}};
  }

  AabbF leaf(std::size_t b, std::size_t e) const {
    AabbF box;
    for (std::size_t i = b; i < e; ++i) box.expand(bvh->prim_boxes[i]);
    return box;
  }

  // Equal codes: object median of the longest centroid axis, reordering prims/prim_boxes[b, e).
  std::size_t median(std::size_t b, std::size_t e) const {
    std::vector<PrimRef> refs(e - b);
    for (std::size_t i = b; i < e; ++i) refs[i - b] = {bvh->prim_boxes[i], bvh->prims[i], 0};
    const std::size_t m = median_split(refs.data(), 0, refs.size(),
                                       longest_axis(centroid_bounds(refs.data(), 0, refs.size())));
    for (std::size_t i = b; i < e; ++i)
      bvh->prim_boxes[i] = refs[i - b].box, bvh->prims[i] = refs[i - b].idx;
    return b + m;
  }
};

}  // namespace

Bvh build_lbvh(const TriMesh& mesh, std::uint32_t max_leaf_size) {
  Bvh bvh;
  const std::size_t n = mesh.num_triangles();
  if (n == 0) return bvh;
  // Pass 1: the bounds of the vertices (half the bytes of a pass over the triangles), which bound
  // every triangle's doubled centroid by [2 lo, 2 hi]; min/max are exact, so the result does not
  // depend on how the range is split.
  struct Bounds {
    Vec3 lo{kInfD, kInfD, kInfD}, hi{-kInfD, -kInfD, -kInfD};
  };
  const Bounds vb = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 1 << 15), Bounds{},
      [&](const auto& r, Bounds acc) {
        for (std::size_t v = r.begin(); v < r.end(); ++v) {
          acc.lo = min(acc.lo, mesh.positions[v]);
          acc.hi = max(acc.hi, mesh.positions[v]);
        }
        return acc;
      },
      [](Bounds x, const Bounds& y) {
        x.lo = min(x.lo, y.lo);
        x.hi = max(x.hi, y.hi);
        return x;
      });
  float lo2[3];
  float ext = 0;
  for (int k = 0; k < 3; ++k) {
    lo2[k] = static_cast<float>(2 * vb.lo[k]);
    ext = std::max(ext, static_cast<float>(2 * vb.hi[k]) - lo2[k]);
  }
  const float scale =
      ext > 0 && ext < std::numeric_limits<float>::infinity() ? 1024.0f / ext : 0.0f;

  // Pass 2: triangle boxes in input order (sequential mesh access) and their keys
  // (code << 32 | triangle) in the same sweep, then the sort.
  Buffer<AabbF> boxes(n);
  Buffer<std::uint64_t> keys(n);
  {
    Buffer<std::uint64_t> tmp(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const auto& r) {
      for (std::size_t t = r.begin(); t < r.end(); ++t) {
        const AabbF b = triangle_box_f(mesh, t);
        boxes[t] = b;
        std::uint32_t code = 0;
        for (int k = 0; k < 3; ++k) {
          float v = (b.lo[k] + b.hi[k] - lo2[k]) * scale;
          v = v >= 0 ? v : 0;  // also NaN -> 0
          v = v < 1023.0f ? v : 1023.0f;
          code |= morton_spread10(static_cast<std::uint32_t>(v)) << (2 - k);
        }
        tmp[t] = (static_cast<std::uint64_t>(code) << 32) | t;
      }
    });
    // The outputs' (serial) allocation and zero-fill overlaps the (parallel) sort.
    tbb::parallel_invoke([&] { radix_sort_codes(tmp, keys); },
                         [&] {
                           resize_output(bvh.prims, n);
                           resize_output(bvh.prim_boxes, n);
                         });
  }

  // Pass 3: outputs in sorted order (boxes gathered with prefetch), and the 32-bit codes.
  Buffer<std::uint32_t> codes(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const auto& r) {
    constexpr std::size_t kAhead = 16;
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
#if defined(__GNUC__)
      if (i + kAhead < r.end())
        __builtin_prefetch(&boxes[static_cast<std::uint32_t>(keys[i + kAhead])]);
#endif
      const auto t = static_cast<std::uint32_t>(keys[i]);
      bvh.prims[i] = t;
      bvh.prim_boxes[i] = boxes[t];
      codes[i] = static_cast<std::uint32_t>(keys[i] >> 32);
    }
  });
  keys = {};
  boxes = {};
  const LbvhRule rule{codes.data(), &bvh, std::max<std::uint32_t>(1, max_leaf_size)};
  TopDownBuilder<LbvhRule>(rule).build(n, {}, bvh.nodes);
  return bvh;
}

}  // namespace interfere::detail
