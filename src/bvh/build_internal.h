// Internals shared by the BVH builders (not installed): memory helpers, primitive references, and
// the top-down build framework that turns any split rule into the BvhNode layout deterministically.
//
// Layout (every builder): nodes[0] is the root; the children of an inner node are the adjacent pair
// (first, first + 1); a node's descendants follow it in depth-first order: the pair, then the first
// child's descendants, then the second child's. Children are therefore always stored after their
// parent, and a subtree's descendants are one contiguous range (refit relies on both).
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "interfere/bvh/bvh.h"

namespace interfere::detail {

// ---- memory ----
//
// First touches of fresh pages dominate a 10^6-triangle build (a 4 KiB page fault costs about as
// much as writing 100 KiB). Builders therefore allocate few, large buffers, touch them first inside
// the parallel loops that fill them, and ask for transparent huge pages on Linux (as Embree's
// allocator does), which cuts the fault count by 512.

/// madvise(MADV_HUGEPAGE) on the 2 MiB-aligned interior of [p, p + bytes) (no-op elsewhere).
void advise_huge_pages(void* p, std::size_t bytes);

/// Uninitialised storage for n objects of an implicit-lifetime type. Plain malloc (glibc then
/// reuses freed blocks of repeated builds without new page faults) plus huge-page advice.
template <class T>
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(std::size_t n) : n_(n) {
    if (n == 0) return;
    p_ = static_cast<T*>(std::malloc(n * sizeof(T)));
    if (!p_) throw std::bad_alloc();
    advise_huge_pages(p_, n * sizeof(T));
  }
  Buffer(Buffer&& o) noexcept : p_(o.p_), n_(o.n_) { o.p_ = nullptr, o.n_ = 0; }
  Buffer& operator=(Buffer&& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
    return *this;
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() { std::free(p_); }
  T* data() const { return p_; }
  T& operator[](std::size_t i) const { return p_[i]; }
  std::size_t size() const { return n_; }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

/// v.resize(n) after asking for huge pages for its new storage (outputs stay plain std::vectors).
template <class T>
void resize_output(std::vector<T>& v, std::size_t n) {
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.resize(n);
}

// ---- primitives ----

/// A primitive reference: its float box and triangle index, 32 bytes so partitions move whole refs.
struct PrimRef {
  AabbF box;
  std::uint32_t idx;
  std::uint32_t pad;
  /// Twice the centroid along axis k (no halving: only comparisons and affine bin maps use it).
  float c2(int k) const { return box.lo[k] + box.hi[k]; }
};
static_assert(sizeof(PrimRef) == 32);

#if defined(__SSE2__)
/// Largest floats <= each of the 4 doubles (a0, a1, b0, b1), i.e. round_down of core/aabb.h, in
/// SSE2: round to nearest, and where that went up, step the bit pattern one float toward -inf
/// (decrement for positive values, increment for negative ones; +0 is first mapped to -0).
inline __m128 round_down4(__m128d a, __m128d b) {
  const __m128 f = _mm_movelh_ps(_mm_cvtpd_ps(a), _mm_cvtpd_ps(b));
  const __m128d fa = _mm_cvtps_pd(f), fb = _mm_cvtps_pd(_mm_movehl_ps(f, f));
  const __m128 up = _mm_shuffle_ps(_mm_castpd_ps(_mm_cmpgt_pd(fa, a)),
                                   _mm_castpd_ps(_mm_cmpgt_pd(fb, b)), _MM_SHUFFLE(2, 0, 2, 0));
  const __m128 zero = _mm_setzero_ps();
  const __m128i is0 = _mm_castps_si128(_mm_cmpeq_ps(f, zero));
  __m128i u = _mm_castps_si128(f);
  u = _mm_or_si128(_mm_andnot_si128(is0, u), _mm_and_si128(is0, _mm_set1_epi32(INT32_MIN)));
  const __m128i step = _mm_or_si128(_mm_castps_si128(_mm_cmpgt_ps(f, zero)), _mm_set1_epi32(1));
  u = _mm_add_epi32(u, _mm_and_si128(step, _mm_castps_si128(up)));
  return _mm_or_ps(_mm_and_ps(up, _mm_castsi128_ps(u)), _mm_andnot_ps(up, f));
}
#endif

/// Scalar round_down (same result as core/aabb.h, without the libm call and branch-free).
inline float fast_round_down(double v) {
  const float f = static_cast<float>(v);
  std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  u = f == 0.0f ? 0x80000000u : u;
  const std::uint32_t step = f > 0.0f ? 0xFFFFFFFFu : 1u;  // -1 or +1 on the bit pattern
  u += static_cast<double>(f) > v ? step : 0u;
  return static_cast<double>(f) > v ? std::bit_cast<float>(u) : f;
}

/// The float box of triangle t, rounded outward: equal to to_float_outward(mesh.triangle_box(t))
/// (tests check it bit for bit), NaN coordinates included.
inline AabbF triangle_box_f(const TriMesh& mesh, std::size_t t) {
  const Tri& f = mesh.triangles[t];
  const double* p0 = &mesh.positions[f[0]].x;
  const double* p1 = &mesh.positions[f[1]].x;
  const double* p2 = &mesh.positions[f[2]].x;
  AabbF b;
#if defined(__SSE2__)
  // Same operand order as Aabb::expand (min(a, b) = a < b ? a : b), so NaNs propagate alike.
  const __m128d a0 = _mm_loadu_pd(p0), a1 = _mm_loadu_pd(p1), a2 = _mm_loadu_pd(p2);
  const __m128d z0 = _mm_load_sd(p0 + 2), z1 = _mm_load_sd(p1 + 2), z2 = _mm_load_sd(p2 + 2);
  const __m128d lxy = _mm_min_pd(_mm_min_pd(a0, a1), a2);
  const __m128d hxy = _mm_max_pd(_mm_max_pd(a0, a1), a2);
  const __m128d lz = _mm_min_sd(_mm_min_sd(z0, z1), z2);
  const __m128d hz = _mm_max_sd(_mm_max_sd(z0, z1), z2);
  // round_up(h) = -round_down(-h): one 4-wide and one 2-wide directed rounding.
  const __m128d sign = _mm_set1_pd(-0.0);
  const __m128d nhxy = _mm_xor_pd(hxy, sign), nhz = _mm_xor_pd(hz, sign);
  alignas(16) float r0[4], r1[4];
  _mm_store_ps(r0, round_down4(lxy, _mm_unpacklo_pd(lz, nhxy)));
  _mm_store_ps(r1, round_down4(_mm_shuffle_pd(nhxy, nhz, 1), _mm_setzero_pd()));
  b.lo[0] = r0[0], b.lo[1] = r0[1], b.lo[2] = r0[2];
  b.hi[0] = -r0[3], b.hi[1] = -r1[0], b.hi[2] = -r1[1];
#else
  auto mn = [](double x, double y) { return x < y ? x : y; };  // as Vec3 min/max, NaNs alike
  auto mx = [](double x, double y) { return x > y ? x : y; };
  for (int k = 0; k < 3; ++k) {
    const double lo = mn(mn(p0[k], p1[k]), p2[k]);
    const double hi = mx(mx(p0[k], p1[k]), p2[k]);
    b.lo[k] = fast_round_down(lo);
    b.hi[k] = -fast_round_down(-hi);
  }
#endif
  return b;
}

/// Boxes of triangles tri(i) for i in [b, e), out(i, box) receiving them: the loop of builders and
/// refit that visit triangles in a sorted order. Software prefetch two levels ahead (index, then
/// corners) hides most of the random access (measured 2x at 10^6 triangles: as fast as input
/// order).
template <class Index, class Out>
inline void triangle_boxes_gather(const TriMesh& mesh, std::size_t b, std::size_t e, Index&& tri,
                                  Out&& out) {
  constexpr std::size_t kFar = 32, kNear = 16;
  for (std::size_t i = b; i < e; ++i) {
#if defined(__GNUC__)
    if (i + kFar < e) __builtin_prefetch(&mesh.triangles[tri(i + kFar)]);
    if (i + kNear < e) {
      const auto& f = mesh.triangles[tri(i + kNear)];
      __builtin_prefetch(&mesh.positions[f[0]]);
      __builtin_prefetch(&mesh.positions[f[1]]);
      __builtin_prefetch(&mesh.positions[f[2]]);
    }
#endif
    out(i, triangle_box_f(mesh, tri(i)));
  }
}

/// PrimRefs of all triangles in input order (parallel; first touch in parallel).
Buffer<PrimRef> make_prim_refs(const TriMesh& mesh);

/// Bounds of the doubled centroids of refs[0, n) (parallel; min/max are exact, so the result does
/// not depend on how the range is split).
AabbF centroid_bounds_parallel(const PrimRef* refs, std::size_t n);

/// Centroid bounds (doubled, like PrimRef::c2) of refs[b, e).
inline AabbF centroid_bounds(const PrimRef* refs, std::size_t b, std::size_t e) {
  AabbF c;
  for (std::size_t i = b; i < e; ++i) {
    for (int k = 0; k < 3; ++k) {
      const float v = refs[i].c2(k);
      c.lo[k] = std::min(c.lo[k], v);
      c.hi[k] = std::max(c.hi[k], v);
    }
  }
  return c;
}

/// Longest axis of a box (ties: lowest axis; NaN extents lose).
inline int longest_axis(const AabbF& c) {
  int axis = 0;
  float best = -1;
  for (int k = 0; k < 3; ++k) {
    const float ext = c.hi[k] - c.lo[k];
    if (ext > best) best = ext, axis = k;
  }
  return axis;
}

/// Object-median split of refs[b, e) along `axis` (std::nth_element; equal centroids are ordered by
/// triangle index, so the result depends only on the set of refs, not on their order).
inline std::size_t median_split(PrimRef* refs, std::size_t b, std::size_t e, int axis) {
  const std::size_t m = b + (e - b) / 2;
  std::nth_element(refs + b, refs + m, refs + e, [axis](const PrimRef& x, const PrimRef& y) {
    const float cx = x.c2(axis), cy = y.c2(axis);
    return cx < cy || (!(cy < cx) && x.idx < y.idx);
  });
  return m;
}

// ---- top-down framework ----

/// out = a ∪ b (out may alias neither input: it is written after both are read).
inline void union_box(const AabbF& a, const AabbF& b, AabbF& out) {
  float lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = a.lo[k] < b.lo[k] ? a.lo[k] : b.lo[k];
    hi[k] = a.hi[k] > b.hi[k] ? a.hi[k] : b.hi[k];
  }
  for (int k = 0; k < 3; ++k) out.lo[k] = lo[k], out.hi[k] = hi[k];
}

/// Result of a split decision: split at m (b < m < e), or make a leaf (m == 0).
template <class Info>
struct Split {
  std::size_t m = 0;
  Info left{}, right{};
};

/// Depth beyond which rules must fall back to median splits (bounds recursion depth on adversarial
/// inputs, e.g. triangle sizes in geometric progression under SAH).
constexpr int kMaxSplitDepth = 48;

/// Top-down builder over primitives [0, n). `Rule` provides
///   using Info = ...;   // per-node state passed down
///   Split<Info> split(size_t b, size_t e, const Info&, int depth, bool parallel) const;
///   AabbF leaf(size_t b, size_t e) const;   // writes bvh.prims/prim_boxes[b, e), returns their
///   box
/// Phase 1 decides the splits: ranges above kBottomSize recurse with tbb::parallel_invoke (their
/// split work may itself be parallel), smaller "bottom" ranges recurse serially and record their
/// splits in pre-order in a shared array (region [2b, 2e) for range [b, e): a subtree over k
/// primitives has at most 2k - 1 nodes). Then every node's final position is known; phase 2 writes
/// the bottoms in parallel and the top part serially. Nothing depends on the thread count.
template <class Rule>
class TopDownBuilder {
 public:
  using Info = typename Rule::Info;
  static constexpr std::size_t kBottomSize = 4096;

  explicit TopDownBuilder(const Rule& rule) : rule_(rule) {}

  void build(std::size_t n, const Info& info, std::vector<BvhNode>& out) {
    std::vector<BvhNode>().swap(out);
    if (n == 0) return;
    splits_ = Buffer<std::uint32_t>(2 * n);
    Top root;
    root.b = 0, root.e = n;
    build_top(root, info, 0);
    resize_output(out, root.count);
    std::vector<Job> jobs;
    std::size_t next = 1;
    place(root, 0, next, jobs);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size(), 1), [&](const auto& r) {
      for (std::size_t j = r.begin(); j < r.end(); ++j) {
        Job& job = jobs[j];
        const std::uint32_t* list = splits_.data() + 2 * job.top->b;
        std::size_t next_slot = job.next;
        emit(list, job.top->b, job.top->e, job.slot, next_slot, out.data());
        job.top->box = out[job.slot].box;
      }
    });
    write_top(root, 0, out);
  }

 private:
  struct Top {
    std::size_t b = 0, e = 0;
    std::size_t count = 0;  // nodes in this subtree
    std::size_t pair = 0;   // inner top node: position of its child pair
    AabbF box;
    std::unique_ptr<Top> kid[2];
  };
  struct Job {
    Top* top;
    std::size_t slot, next;
  };

  void build_top(Top& t, const Info& info, int depth) {
    if (t.e - t.b <= kBottomSize) {
      std::uint32_t* list = splits_.data() + 2 * t.b;
      t.count = record(list, t.b, t.e, info, depth);
      return;
    }
    Split<Info> s = rule_.split(t.b, t.e, info, depth, true);
    if (s.m == 0) {
      splits_[2 * t.b] = 0;
      t.count = 1;
      return;
    }
    t.kid[0] = std::make_unique<Top>();
    t.kid[1] = std::make_unique<Top>();
    t.kid[0]->b = t.b, t.kid[0]->e = s.m;
    t.kid[1]->b = s.m, t.kid[1]->e = t.e;
    tbb::parallel_invoke([&] { build_top(*t.kid[0], s.left, depth + 1); },
                         [&] { build_top(*t.kid[1], s.right, depth + 1); });
    t.count = 1 + t.kid[0]->count + t.kid[1]->count;
  }

  // Phase 1 of a bottom range: pre-order split list (0 = leaf, else the split position, >= 1).
  std::size_t record(std::uint32_t*& list, std::size_t b, std::size_t e, const Info& info,
                     int depth) {
    const Split<Info> s = rule_.split(b, e, info, depth, false);
    *list++ = static_cast<std::uint32_t>(s.m);
    if (s.m == 0) return 1;
    const std::size_t l = record(list, b, s.m, s.left, depth + 1);
    return 1 + l + record(list, s.m, e, s.right, depth + 1);
  }

  // Phase 2 of a bottom range: node at `slot`, its descendants from `next` on.
  // Boxes travel through `out` (children are read back from it) rather than as return values: the
  // 24-byte aggregates returned through the stack cost store-forwarding stalls in this hot loop.
  void emit(const std::uint32_t*& list, std::size_t b, std::size_t e, std::size_t slot,
            std::size_t& next, BvhNode* out) const {
    const std::size_t m = *list++;
    if (m == 0) {
      out[slot].box = rule_.leaf(b, e);
      out[slot].first = static_cast<std::uint32_t>(b);
      out[slot].count = static_cast<std::uint32_t>(e - b);
      return;
    }
    const std::size_t pair = next;
    next += 2;
    emit(list, b, m, pair, next, out);
    emit(list, m, e, pair + 1, next, out);
    union_box(out[pair].box, out[pair + 1].box, out[slot].box);
    out[slot].first = static_cast<std::uint32_t>(pair);
    out[slot].count = 0;
  }

  void place(Top& t, std::size_t slot, std::size_t& next, std::vector<Job>& jobs) {
    if (!t.kid[0]) {
      jobs.push_back({&t, slot, next});
      next += t.count - 1;
      return;
    }
    t.pair = next;
    next += 2;
    place(*t.kid[0], t.pair, next, jobs);
    place(*t.kid[1], t.pair + 1, next, jobs);
  }

  // Top part, post-order (boxes of the bottoms are known by now).
  void write_top(Top& t, std::size_t slot, std::vector<BvhNode>& out) {
    if (!t.kid[0]) return;
    write_top(*t.kid[0], t.pair, out);
    write_top(*t.kid[1], t.pair + 1, out);
    t.box = t.kid[0]->box;
    t.box.expand(t.kid[1]->box);
    BvhNode& n = out[slot];
    n.box = t.box;
    n.first = static_cast<std::uint32_t>(t.pair);
    n.count = 0;
  }

  const Rule& rule_;
  Buffer<std::uint32_t> splits_;
};

/// Leaf emission shared by the PrimRef-based rules: copies refs[b, e) into bvh.prims/prim_boxes.
inline AabbF emit_ref_leaf(const PrimRef* refs, Bvh& bvh, std::size_t b, std::size_t e) {
  AabbF box;
  for (std::size_t i = b; i < e; ++i) {
    bvh.prims[i] = refs[i].idx;
    bvh.prim_boxes[i] = refs[i].box;
    box.expand(refs[i].box);
  }
  return box;
}

// Builders (one per source file).
Bvh build_insertion(const TriMesh& mesh);
Bvh build_median(const TriMesh& mesh, std::uint32_t max_leaf_size);
Bvh build_sah(const TriMesh& mesh, std::uint32_t max_leaf_size);
Bvh build_lbvh(const TriMesh& mesh, std::uint32_t max_leaf_size);

/// Treelet restructuring (build_treelet.cpp): `passes` bottom-up passes over a tree in the layout
/// above (every inner node's treelet of up to 7 subtrees rewired to its SAH-optimal topology), then
/// the nodes laid out again in that layout. Leaves and prims are kept.
void optimize_treelets(Bvh& bvh, std::uint32_t passes);

}  // namespace interfere::detail
