// (c) Binned SAH builder (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// 2007): top-down; each node's centroids are binned into kBins slabs per axis, the surface-area
// cost A_L*N_L + A_R*N_R is swept over the kBins-1 bin boundaries of all three axes, and the
// triangles are partitioned at the cheapest one. Ranges of at most max_leaf_size triangles become
// leaves: the ray- tracing leaf-termination test (leaf cost vs split cost) makes smaller leaves,
// which measured slower for tree-vs-tree queries (more node pairs for the same triangle pairs).
//
// Parallel (oneTBB): nodes above kParallelSize bin with tbb::parallel_reduce and partition with a
// stable blocked partition; subtrees are built with tbb::parallel_invoke (TopDownBuilder). Bin
// merges are min/max and integer sums (exact) and both partitions are functions of the input alone,
// so the tree is the same for every thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "build_internal.h"

namespace interfere::detail {
namespace {

constexpr int kBins = 16;
constexpr std::size_t kParallelSize = std::size_t{1} << 16;
constexpr std::size_t kBlock = std::size_t{1} << 13;

// Maps doubled centroids to bins: bin = floor((c2 - lo) * scale), clamped to [0, kBins) (NaN -> 0).
struct BinMap {
  float lo[4] = {0, 0, 0, 0};
  float scale[4] = {0, 0, 0, 0};
  explicit BinMap(const AabbF& cb) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = cb.lo[k];
      const float ext = cb.hi[k] - cb.lo[k];
      scale[k] = ext > 0 ? (static_cast<float>(kBins) * 0.99999f) / ext : 0.0f;
    }
  }
  int bin(const PrimRef& r, int k) const {
    float v = (r.c2(k) - lo[k]) * scale[k];
    v = v >= 0 ? v : 0;
    v = v < static_cast<float>(kBins - 1) ? v : static_cast<float>(kBins - 1);
    return static_cast<int>(v);
  }
};

struct Bins {
  // Per axis and bin: box lo/hi (4 lanes, the 4th unused) and count.
  alignas(16) float lo[3][kBins][4];
  alignas(16) float hi[3][kBins][4];
  std::uint32_t count[3][kBins];

  Bins() {
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < kBins; ++i) {
        for (int l = 0; l < 4; ++l) {
          lo[k][i][l] = std::numeric_limits<float>::infinity();
          hi[k][i][l] = -std::numeric_limits<float>::infinity();
        }
        count[k][i] = 0;
      }
    }
  }
  AabbF box(int k, int i) const {
    AabbF b;
    for (int l = 0; l < 3; ++l) b.lo[l] = lo[k][i][l], b.hi[l] = hi[k][i][l];
    return b;
  }
  void merge(const Bins& o) {
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < kBins; ++i) {
        for (int l = 0; l < 4; ++l) {
          lo[k][i][l] = std::min(lo[k][i][l], o.lo[k][i][l]);
          hi[k][i][l] = std::max(hi[k][i][l], o.hi[k][i][l]);
        }
        count[k][i] += o.count[k][i];
      }
    }
  }
};

void bin_range(const PrimRef* refs, std::size_t b, std::size_t e, const BinMap& map, Bins& bins) {
#if defined(__SSE2__)
  const __m128 lo = _mm_loadu_ps(map.lo), scale = _mm_loadu_ps(map.scale);
  const __m128 zero = _mm_setzero_ps(), top = _mm_set1_ps(static_cast<float>(kBins - 1));
  for (std::size_t i = b; i < e; ++i) {
    const float* p = refs[i].box.lo;  // lo[0..2], then hi[0..2] (AabbF is 6 packed floats)
    const __m128 blo = _mm_setr_ps(p[0], p[1], p[2], 0.0f);
    const __m128 bhi = _mm_setr_ps(p[3], p[4], p[5], 0.0f);
    __m128 v = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(blo, bhi), lo), scale);
    v = _mm_min_ps(_mm_max_ps(v, zero), top);  // maxps(NaN, 0) returns 0: NaN maps to bin 0
    alignas(16) int j[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(j), _mm_cvttps_epi32(v));
    for (int k = 0; k < 3; ++k) {
      float* bl = bins.lo[k][j[k]];
      float* bh = bins.hi[k][j[k]];
      _mm_store_ps(bl, _mm_min_ps(_mm_load_ps(bl), blo));
      _mm_store_ps(bh, _mm_max_ps(_mm_load_ps(bh), bhi));
      ++bins.count[k][j[k]];
    }
  }
#else
  for (std::size_t i = b; i < e; ++i) {
    const PrimRef& r = refs[i];
    for (int k = 0; k < 3; ++k) {
      const int j = map.bin(r, k);
      for (int l = 0; l < 3; ++l) {
        bins.lo[k][j][l] = std::min(bins.lo[k][j][l], r.box.lo[l]);
        bins.hi[k][j][l] = std::max(bins.hi[k][j][l], r.box.hi[l]);
      }
      ++bins.count[k][j];
    }
  }
#endif
}

inline float half_area(const AabbF& b) {
  const float dx = b.hi[0] - b.lo[0], dy = b.hi[1] - b.lo[1], dz = b.hi[2] - b.lo[2];
  return dx * dy + dy * dz + dz * dx;
}

inline void grow_centroid(AabbF& c, const PrimRef& r) {
  for (int k = 0; k < 3; ++k) {
    const float v = r.c2(k);
    c.lo[k] = std::min(c.lo[k], v);
    c.hi[k] = std::max(c.hi[k], v);
  }
}

struct SahRule {
  using Info = AabbF;  // centroid bounds (doubled) of the node's triangles
  PrimRef* refs;
  PrimRef* scratch;  // as large as refs (stable parallel partition of the big nodes)
  Bvh* bvh;
  std::size_t max_leaf;

  AabbF leaf(std::size_t b, std::size_t e) const { return emit_ref_leaf(refs, *bvh, b, e); }

  Split<Info> split(std::size_t b, std::size_t e, const Info& cb, int depth, bool parallel) const {
    const std::size_t n = e - b;
    if (n <= max_leaf) return {};
    if (depth >= kMaxSplitDepth) return median(b, e, cb);
    const BinMap map(cb);
    const bool big = parallel && n > kParallelSize;
    Bins bins;
    if (big) {
      bins = tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(b, e, kBlock), Bins{},
          [&](const auto& r, Bins acc) {
            bin_range(refs, r.begin(), r.end(), map, acc);
            return acc;
          },
          [](Bins x, const Bins& y) {
            x.merge(y);
            return x;
          });
    } else {
      bin_range(refs, b, e, map, bins);
    }

    // Sweep over the non-empty bins only (a boundary next to an empty bin repeats its neighbour's
    // cost): right-to-left suffix costs, then left-to-right. Ties: lowest axis, then lowest bin.
    float best_cost = std::numeric_limits<float>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int k = 0; k < 3; ++k) {
      int used[kBins];
      int nu = 0;
      for (int i = 0; i < kBins; ++i) {
        if (bins.count[k][i] != 0) used[nu++] = i;
      }
      if (nu < 2) continue;
      std::array<float, kBins> right_cost{};  // indexed by position in `used`
      AabbF acc;
      std::uint32_t cnt = 0;
      for (int u = nu - 1; u > 0; --u) {
        acc.expand(bins.box(k, used[u]));
        cnt += bins.count[k][used[u]];
        right_cost[u] = half_area(acc) * static_cast<float>(cnt);
      }
      acc = AabbF{};
      cnt = 0;
      for (int u = 1; u < nu; ++u) {  // split between used[u-1] and used[u], at bin used[u-1]+1
        acc.expand(bins.box(k, used[u - 1]));
        cnt += bins.count[k][used[u - 1]];
        const float cost = half_area(acc) * static_cast<float>(cnt) + right_cost[u];
        if (cost < best_cost) best_cost = cost, best_axis = k, best_bin = used[u - 1] + 1;
      }
    }
    if (best_axis < 0) return median(b, e, cb);  // all centroids in one bin on every axis

    Split<Info> s;
    s.m = big ? partition_parallel(b, e, map, best_axis, best_bin, s.left, s.right)
              : partition_serial(b, e, map, best_axis, best_bin, s.left, s.right);
    return s;
  }

  Split<Info> median(std::size_t b, std::size_t e, const Info& cb) const {
    const std::size_t m = median_split(refs, b, e, longest_axis(cb));
    return {m, centroid_bounds(refs, b, m), centroid_bounds(refs, m, e)};
  }

  // Hoare partition; also returns the children's centroid bounds.
  std::size_t partition_serial(std::size_t b, std::size_t e, const BinMap& map, int k,
                               int split_bin, AabbF& lc, AabbF& rc) const {
    std::size_t i = b, j = e;
    while (true) {
      while (i < j && map.bin(refs[i], k) < split_bin) grow_centroid(lc, refs[i++]);
      while (i < j && map.bin(refs[j - 1], k) >= split_bin) grow_centroid(rc, refs[--j]);
      if (i >= j) break;
      std::swap(refs[i], refs[j - 1]);
      grow_centroid(lc, refs[i++]);
      grow_centroid(rc, refs[--j]);
    }
    return i;
  }

  // Stable partition in fixed blocks (independent of the thread count) through `scratch`.
  std::size_t partition_parallel(std::size_t b, std::size_t e, const BinMap& map, int k,
                                 int split_bin, AabbF& lc, AabbF& rc) const {
    const std::size_t n = e - b, nblocks = (n + kBlock - 1) / kBlock;
    std::vector<std::size_t> left(nblocks + 1, 0);
    std::vector<AabbF> lcb(nblocks), rcb(nblocks);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks, 1), [&](const auto& r) {
      for (std::size_t blk = r.begin(); blk < r.end(); ++blk) {
        const std::size_t lo = b + blk * kBlock, hi = std::min(e, lo + kBlock);
        std::size_t c = 0;
        for (std::size_t i = lo; i < hi; ++i) {
          if (map.bin(refs[i], k) < split_bin) {
            ++c;
            grow_centroid(lcb[blk], refs[i]);
          } else {
            grow_centroid(rcb[blk], refs[i]);
          }
        }
        left[blk + 1] = c;
      }
    });
    for (std::size_t blk = 0; blk < nblocks; ++blk) {
      left[blk + 1] += left[blk];
      lc.expand(lcb[blk]);
      rc.expand(rcb[blk]);
    }
    const std::size_t nl = left[nblocks];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks, 1), [&](const auto& r) {
      for (std::size_t blk = r.begin(); blk < r.end(); ++blk) {
        const std::size_t lo = b + blk * kBlock, hi = std::min(e, lo + kBlock);
        std::size_t li = b + left[blk], ri = b + nl + (lo - b - left[blk]);
        for (std::size_t i = lo; i < hi; ++i) {
          if (map.bin(refs[i], k) < split_bin) {
            scratch[li++] = refs[i];
          } else {
            scratch[ri++] = refs[i];
          }
        }
      }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(b, e, kBlock), [&](const auto& r) {
      std::copy(scratch + r.begin(), scratch + r.end(), refs + r.begin());
    });
    return b + nl;
  }
};

}  // namespace

Bvh build_sah(const TriMesh& mesh, std::uint32_t max_leaf_size) {
  Bvh bvh;
  const std::size_t n = mesh.num_triangles();
  if (n == 0) return bvh;
  Buffer<PrimRef> refs = make_prim_refs(mesh);
  const AabbF cb = centroid_bounds_parallel(refs.data(), n);
  Buffer<PrimRef> scratch(n > kParallelSize ? n : 0);
  resize_output(bvh.prims, n);
  resize_output(bvh.prim_boxes, n);
  const SahRule rule{refs.data(), scratch.data(), &bvh, std::max<std::uint32_t>(1, max_leaf_size)};
  TopDownBuilder<SahRule>(rule).build(n, cb, bvh.nodes);
  return bvh;
}

}  // namespace interfere::detail
