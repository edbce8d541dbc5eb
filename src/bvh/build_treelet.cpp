// Treelet restructuring of the LBVH (Karras & Aila, "Fast Parallel Construction of High-Quality
// Bounding Volume Hierarchies", HPG 2013, §3 "Treelet restructuring"): a treelet is a node with up
// to 7 "treelet leaves" below it, grown by repeatedly expanding the treelet leaf of largest surface
// area; its SAH-optimal topology over those leaves is found by dynamic programming over the
// subsets of the leaves (c(S) = A(S) + min over partitions {P, S\P} of c(P) + c(S\P), each
// unordered partition enumerated once), and the treelet's inner nodes are rewired to it when that
// lowers the cost. Nodes are processed bottom-up (a node after its two children), so every treelet
// sees already optimised subtrees; a pass visits every inner node, and passes repeat (the paper
// uses 3; here BvhBuildOptions::treelet_passes, default 1).
//
// Differences from the paper: the LBVH leaves (up to max_leaf_size triangles) stay as they are:
// no collapsing of subtrees into leaves, so the leaf term of the SAH is constant and the DP only
// minimises the sum of the treelet's inner-node areas (c = 0 for a treelet leaf). Costs are float
// (areas within a few 1e-7, relative, of the exact ones), and a treelet is rewired only when its
// cost falls by more than 2^-16 (relative): ties keep the LBVH topology, and every rewiring
// strictly lowers the exact SAH cost (treelets whose areas overflow float, extents beyond ~1e19,
// are kept). Passes after the first skip the treelets whose input did not change since they were
// last evaluated and kept (exact: the same input gives the same decision).
//
// CPU implementation (oneTBB instead of the paper's GPU atomics): a post-order recursion splits
// large subtrees between their two children with tbb::parallel_invoke; subtrees of at most
// kSerialNodes nodes are processed serially one height at a time (nodes of equal height have
// disjoint subtrees, so any order among them is bottom-up), which lets the DPs of four treelets
// run side by side in the four SSE lanes (per subset: the same partitions, lane-wise min). A
// treelet only touches nodes of its root's subtree, the children's subtrees are final when it
// runs, and every decision (leaf choice, DP minimum, gain test) depends on the treelet alone, in a
// fixed order, so the tree does not depend on the thread count or on the batching. Afterwards the
// nodes are laid out again in the depth-first order of bvh.h (pair, first child's descendants,
// second child's), which refit and the traversals rely on. Prims are not moved: the treelet leaves
// keep their Morton-ordered triangle ranges, and the left child of every rewired node holds the
// leftmost treelet leaf, which keeps the node order close to the Morton curve.
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

#include "build_internal.h"

namespace interfere::detail {
namespace {

constexpr int kMaxLeaves = 7;  // treelet leaves (the paper's choice: 7 leaves, 6 inner nodes)
constexpr unsigned kSubsets = 1u << kMaxLeaves;

constexpr std::size_t count_partitions() {
  std::size_t count = 0;
  for (unsigned s = 0; s < kSubsets; ++s) {
    const int k = std::popcount(s);
    if (k >= 2) count += (std::size_t{1} << (k - 1)) - 1;
  }
  return count;
}
constexpr std::size_t kPartitions = count_partitions();  // 966 for 7 leaves

// For every subset S (a bit mask over the treelet leaves) with at least two elements: the parts P
// of its partitions {P, S\P}, each unordered partition once (P holds S's lowest leaf). Sorted by S,
// so the entries of the masks below 2^k serve treelets of k leaves.
struct PartitionTable {
  std::array<std::uint16_t, kSubsets + 1> begin{};
  std::array<std::uint8_t, kPartitions> part{};
  // The same as byte offsets of rows c[P] and c[S\P] of a float[kSubsets][4] cost table: the
  // lane-wise DP's inner loop then needs no index arithmetic.
  std::array<std::array<std::uint16_t, 2>, kPartitions> offset{};
};

constexpr PartitionTable make_partition_table() {
  PartitionTable t;
  std::size_t i = 0;
  for (unsigned s = 0; s < kSubsets; ++s) {
    t.begin[s] = static_cast<std::uint16_t>(i);
    if (std::popcount(s) < 2) continue;
    const unsigned low = s & (0u - s), rest = s ^ low;
    // Every q strictly inside `rest`, in increasing order ((q - rest) & rest steps to the next).
    for (unsigned q = 0; q != rest; q = (q - rest) & rest) {
      const unsigned p = low | q;
      t.part[i] = static_cast<std::uint8_t>(p);
      t.offset[i] = {static_cast<std::uint16_t>(16 * p), static_cast<std::uint16_t>(16 * (s ^ p))};
      ++i;
    }
  }
  t.begin[kSubsets] = static_cast<std::uint16_t>(i);
  return t;
}
constexpr PartitionTable kTable = make_partition_table();
static_assert(kTable.begin[kSubsets] == kPartitions);

constexpr float kInf = std::numeric_limits<float>::infinity();

// Half the surface area and the box union, written once for the scalar and the lane-wise DP so
// that both compute bit-identical costs: (dx*dy + dz*dx) + dy*dz, and min(a, b) = a < b ? a : b
// (the semantics of SSE minps/maxps, NaNs included).
template <class F, class Sub, class Mul, class Add>
F half_area_of(const F lo[3], const F hi[3], Sub sub, Mul mul, Add add) {
  const F dx = sub(hi[0], lo[0]), dy = sub(hi[1], lo[1]), dz = sub(hi[2], lo[2]);
  return add(add(mul(dx, dy), mul(dz, dx)), mul(dy, dz));
}

inline float half_area(const AabbF& b) {
  return half_area_of<float>(
      b.lo, b.hi, [](float x, float y) { return x - y; }, [](float x, float y) { return x * y; },
      [](float x, float y) { return x + y; });
}

inline void prefetch(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

#if !defined(__SSE2__)
// As SSE minps/maxps.
inline float min_f(float a, float b) {
  return a < b ? a : b;
}
inline float max_f(float a, float b) {
  return a > b ? a : b;
}
#endif

// A node while restructuring: the BvhNode (box; leaves: their prims range) with explicit children
// (those of a rewired node are no longer adjacent), the subtree's size and the pass state.
struct Link {
  BvhNode node;          // inner nodes: node.first = first child, node.count = 0
  std::uint32_t kid1;    // inner nodes: second child
  std::uint32_t leaves;  // BVH leaves in the subtree (k leaves: 2k - 1 nodes)
  std::uint8_t dirty;    // the treelet rooted here must be evaluated in the next pass
  std::uint8_t near;     // this pass: depth below it of the highest rewired node (kFar: none
                         // near, and always for BVH leaves)
  bool is_leaf() const { return node.is_leaf(); }
};

constexpr std::size_t kSerialNodes = 4096;  // subtrees of at most this many nodes run serially

// Treelets read nodes at most kMaxLeaves - 1 levels below their root (inner nodes at most
// kMaxLeaves - 2), and a rewiring changes the links of its root and of nodes below it, never the
// root's box: a treelet whose root is not dirty and that has no node rewired in this pass at most
// kMaxLeaves - 2 levels below it has the input it had when it was last evaluated and kept.
constexpr std::uint8_t kFar = kMaxLeaves - 1;

struct Treelet {
  std::uint32_t root;
  int k;                                // leaves (3..7)
  std::uint8_t below;                   // Link::near if it stays
  float cost;                           // current sum of the inner nodes' areas
  std::uint32_t leaf[kMaxLeaves];       // left to right
  std::uint32_t inner[kMaxLeaves - 1];  // inner[0] = root
};

class Restructurer {
 public:
  explicit Restructurer(Link* links) : links_(links) {}

  // The first pass, which also fills the links from the builder's tree `nodes` (there, the
  // descendants of inner node x are the contiguous range [x.first, end), as in refit.cpp), each
  // serial subtree just before its pass (still in cache), every treelet marked for evaluation.
  void first_pass(const BvhNode* nodes, std::uint32_t x, std::size_t end) const {
    const BvhNode& n = nodes[x];
    if (n.is_leaf()) {
      init_node(nodes, x);
      return;
    }
    if (end - n.first + 1 <= kSerialNodes) {  // the subtree: x and [x.first, end)
      for (std::size_t i = end; i-- > n.first;) init_node(nodes, i);
      init_node(nodes, x);
      serial_pass(x);
      return;
    }
    const std::uint32_t c0 = n.first, c1 = c0 + 1;
    const std::size_t end0 = nodes[c1].is_leaf() ? end : nodes[c1].first;
    tbb::parallel_invoke([&] { first_pass(nodes, c0, end0); }, [&] { first_pass(nodes, c1, end); });
    init_node(nodes, x);
    top_treelet(x);
  }

  // A later pass over the subtree of x.
  void pass(std::uint32_t x) const {
    const Link& l = links_[x];
    if (l.is_leaf()) return;
    if (2 * std::size_t{l.leaves} - 1 <= kSerialNodes) {
      serial_pass(x);
      return;
    }
    tbb::parallel_invoke([&] { pass(l.node.first); }, [&] { pass(l.kid1); });
    top_treelet(x);
  }

  // Writes node x to out[slot] and its descendants from out[next] on, in bvh.h's layout.
  void place(std::uint32_t x, std::size_t slot, std::size_t next, BvhNode* out) const {
    const Link& l = links_[x];
    BvhNode& o = out[slot];
    o = l.node;
    if (l.is_leaf()) return;
    o.first = static_cast<std::uint32_t>(next);
    const std::uint32_t c0 = l.node.first, c1 = l.kid1;
    prefetch(&links_[c1]);
    const std::size_t next1 = next + 2 + (2 * std::size_t{links_[c0].leaves} - 2);
    if (2 * std::size_t{l.leaves} > kSerialNodes) {
      tbb::parallel_invoke([&] { place(c0, next, next + 2, out); },
                           [&] { place(c1, next + 1, next1, out); });
    } else {
      place(c0, next, next + 2, out);
      place(c1, next + 1, next1, out);
    }
  }

 private:
  void top_treelet(std::uint32_t x) const {
    Treelet t;
    if (form(x, t)) {
      const Treelet* one = &t;
      solve(&one, 1);
    }
  }

  void init_node(const BvhNode* nodes, std::size_t i) const {
    Link& l = links_[i];
    l.node = nodes[i];
    l.dirty = 1;
    l.near = kFar;
    if (l.is_leaf()) {
      l.leaves = 1;
    } else {
      l.kid1 = l.node.first + 1;
      l.leaves = links_[l.node.first].leaves + links_[l.kid1].leaves;
    }
  }

  // Serial pass over the subtree of x, one height (longest path to a leaf) at a time, treelets of
  // equal height solved four at a time.
  struct Item {
    std::uint32_t node, height;
  };

  void serial_pass(std::uint32_t x) const {
    std::vector<Item> items;  // inner nodes
    items.reserve(links_[x].leaves);
    std::uint32_t max_height = collect(x, items);
    std::vector<std::uint32_t> start(max_height + 2, 0);  // counting sort by height
    for (const Item& it : items) ++start[it.height + 1];
    for (std::uint32_t h = 1; h <= max_height + 1; ++h) start[h] += start[h - 1];
    std::vector<std::uint32_t> order(items.size());
    for (const Item& it : items) order[start[it.height]++] = it.node;
    std::vector<Treelet> batch;
    std::vector<const Treelet*> by_k;
    std::size_t lo = 0;
    for (std::uint32_t h = 1; h <= max_height; ++h) {
      const std::size_t hi = start[h];  // nodes of height h: order[lo, hi)
      batch.clear();
      batch.resize(hi - lo);
      std::size_t formed = 0;
      for (std::size_t i = lo; i < hi; ++i) formed += form(order[i], batch[formed]) ? 1 : 0;
      // Batches of similar size (the DP runs to the largest treelet of a batch).
      by_k.clear();
      for (int k = kMaxLeaves; k >= 3; --k) {
        for (std::size_t i = 0; i < formed; ++i) {
          if (batch[i].k == k) by_k.push_back(&batch[i]);
        }
      }
      for (std::size_t i = 0; i < by_k.size(); i += 4) {
        solve(by_k.data() + i, static_cast<int>(std::min<std::size_t>(4, by_k.size() - i)));
      }
      lo = hi;
    }
  }

  // Appends the inner nodes of x's subtree with their heights; returns x's height (leaf: 0).
  std::uint32_t collect(std::uint32_t x, std::vector<Item>& items) const {
    const Link& l = links_[x];
    if (l.is_leaf()) return 0;
    prefetch(&links_[l.kid1]);  // the walk is latency-bound in later passes
    const std::uint32_t h = 1 + std::max(collect(l.node.first, items), collect(l.kid1, items));
    items.push_back({x, h});
    return h;
  }

  // Decides whether the treelet at `root` needs evaluation and, if so, forms it (expand the
  // inner treelet leaf of largest area until 7 leaves). Returns true when a DP must run; otherwise
  // the root's pass state is final.
  bool form(std::uint32_t root, Treelet& t) const {
    Link& r = links_[root];
    const int near = std::min(links_[r.node.first].near, links_[r.kid1].near);  // leaves: kFar
    const auto below = static_cast<std::uint8_t>(std::min(near + 1, int{kFar}));
    r.near = below;
    if (below > kMaxLeaves - 2 && !r.dirty) return false;
    r.dirty = 0;
    float area[kMaxLeaves];  // of the treelet leaves; -1 for BVH leaves (not expandable)
    int k = 0;
    auto put = [&](int j, std::uint32_t x) {
      t.leaf[j] = x;
      area[j] = links_[x].is_leaf() ? -1.0f : half_area(links_[x].node.box);
    };
    put(k++, r.node.first);
    put(k++, r.kid1);
    t.inner[0] = root;
    t.cost = half_area(r.node.box);
    int ni = 1;
    while (k < kMaxLeaves) {
      int best = 0;
      for (int j = 1; j < k; ++j) best = area[j] > area[best] ? j : best;
      if (!(area[best] >= 0)) break;  // only BVH leaves (or NaN boxes) left
      const std::uint32_t x = t.leaf[best];
      t.inner[ni++] = x;
      t.cost += area[best];
      for (int j = k; j > best + 1; --j) t.leaf[j] = t.leaf[j - 1], area[j] = area[j - 1];
      put(best, links_[x].node.first);
      put(best + 1, links_[x].kid1);
      ++k;
    }
    if (k < 3) return false;  // two leaves: one topology
    t.root = root, t.k = k, t.below = below;
    return true;
  }

  // The DP for n (1..4) treelets side by side in SIMD lanes (lanes past n repeat the
  // first), then the rewiring of those it improves. c = 0 for one leaf: the treelet leaves' own
  // costs are the same in every topology.
  void solve(const Treelet* const* ts, int n) const {
    const Treelet* lane[4];
    for (int j = 0; j < 4; ++j) lane[j] = ts[j < n ? j : 0];
    int kmax = 0;
    for (int j = 0; j < n; ++j) kmax = std::max(kmax, lane[j]->k);
    alignas(16) float c[kSubsets][4];
    const unsigned full = (1u << kmax) - 1;
#if defined(__SSE2__)
    struct Boxes {
      __m128 lo[3], hi[3];
    };
    Boxes box[kSubsets];  // uninitialised scratch
    for (int i = 0; i < kmax; ++i) {
      // Lane j's box as (lo0 lo1 lo2 hi0) and (hi0 hi1 hi2 -) (the 4 bytes after the box are
      // BvhNode::first), transposed to one register per coordinate. Leaves past a lane's k repeat
      // its first (their subsets are never read).
      static_assert(offsetof(BvhNode, box) == 0 && offsetof(BvhNode, first) == sizeof(AabbF));
      __m128 a[4], b[4];
      for (int j = 0; j < 4; ++j) {
        const AabbF& bj = links_[lane[j]->leaf[i < lane[j]->k ? i : 0]].node.box;
        a[j] = _mm_loadu_ps(bj.lo);
        b[j] = _mm_loadu_ps(bj.hi);
      }
      _MM_TRANSPOSE4_PS(a[0], a[1], a[2], a[3]);
      _MM_TRANSPOSE4_PS(b[0], b[1], b[2], b[3]);
      Boxes& leaf = box[1u << i];
      leaf.lo[0] = a[0], leaf.lo[1] = a[1], leaf.lo[2] = a[2];
      leaf.hi[0] = b[0], leaf.hi[1] = b[1], leaf.hi[2] = b[2];
      _mm_store_ps(c[1u << i], _mm_setzero_ps());
    }
    for (unsigned s = 3; s <= full; ++s) {
      if ((s & (s - 1)) == 0) continue;
      const Boxes& a = box[s & (s - 1)];
      const Boxes& b = box[s & (0u - s)];
      Boxes& m = box[s];
      for (int d = 0; d < 3; ++d) {
        m.lo[d] = _mm_min_ps(a.lo[d], b.lo[d]);
        m.hi[d] = _mm_max_ps(a.hi[d], b.hi[d]);
      }
      const __m128 area = half_area_of<__m128>(
          m.lo, m.hi, [](__m128 x, __m128 y) { return _mm_sub_ps(x, y); },
          [](__m128 x, __m128 y) { return _mm_mul_ps(x, y); },
          [](__m128 x, __m128 y) { return _mm_add_ps(x, y); });
      // Lane-wise min (minps(v, b) = v < b ? v : b) with two chains.
      const auto* p = kTable.offset.data() + kTable.begin[s];
      const auto* const end = kTable.offset.data() + kTable.begin[s + 1];
      const char* const cb = reinterpret_cast<const char*>(c);
      auto row = [cb](std::uint16_t offset) {
        return _mm_load_ps(reinterpret_cast<const float*>(cb + offset));
      };
      __m128 b0 = _mm_set1_ps(kInf), b1 = b0;
      for (; end - p >= 2; p += 2) {
        b0 = _mm_min_ps(_mm_add_ps(row(p[0][0]), row(p[0][1])), b0);
        b1 = _mm_min_ps(_mm_add_ps(row(p[1][0]), row(p[1][1])), b1);
      }
      if (p < end) b0 = _mm_min_ps(_mm_add_ps(row(p[0][0]), row(p[0][1])), b0);
      _mm_store_ps(c[s], _mm_add_ps(area, _mm_min_ps(b1, b0)));
    }
#else
    struct Boxes {
      float lo[3][4], hi[3][4];
    };
    Boxes box[kSubsets];
    for (int i = 0; i < kmax; ++i) {
      for (int j = 0; j < 4; ++j) {
        const AabbF& b = links_[lane[j]->leaf[i < lane[j]->k ? i : 0]].node.box;
        for (int a = 0; a < 3; ++a)
          box[1u << i].lo[a][j] = b.lo[a], box[1u << i].hi[a][j] = b.hi[a];
        c[1u << i][j] = 0;
      }
    }
    for (unsigned s = 3; s <= full; ++s) {
      if ((s & (s - 1)) == 0) continue;
      const Boxes& a = box[s & (s - 1)];
      const Boxes& b = box[s & (0u - s)];
      Boxes& m = box[s];
      for (int j = 0; j < 4; ++j) {
        float lo[3], hi[3];
        for (int d = 0; d < 3; ++d) {
          lo[d] = m.lo[d][j] = min_f(a.lo[d][j], b.lo[d][j]);
          hi[d] = m.hi[d][j] = max_f(a.hi[d][j], b.hi[d][j]);
        }
        const float area = half_area_of<float>(
            lo, hi, [](float x, float y) { return x - y; }, [](float x, float y) { return x * y; },
            [](float x, float y) { return x + y; });
        float best = kInf;
        for (unsigned i = kTable.begin[s]; i < kTable.begin[s + 1]; ++i) {
          const unsigned q = kTable.part[i];
          best = min_f(c[q][j] + c[s ^ q][j], best);
        }
        c[s][j] = area + best;
      }
    }
#endif
    for (int j = 0; j < n; ++j) {
      const Treelet& t = *lane[j];
      const unsigned set = (1u << t.k) - 1;
      Link& r = links_[t.root];
      // A clear gain only (see the file comment); NaN boxes never pass.
      if (!(c[set][j] < t.cost - t.cost * 0x1p-16f)) {
        r.near = t.below;
        continue;
      }
      int next_inner = 1;
      rewire(set, t.root, t, next_inner, &c[0][j]);
      r.near = 0;
    }
  }

  // Gives node `slot` the DP's optimal topology over the treelet leaves in `s` (c: stride 4).
  void rewire(unsigned s, std::uint32_t slot, const Treelet& t, int& next_inner,
              const float* c) const {
    unsigned best_p = kTable.part[kTable.begin[s]];
    float best = kInf;
    for (unsigned i = kTable.begin[s]; i < kTable.begin[s + 1]; ++i) {
      const unsigned p = kTable.part[i];
      const float v = c[4 * p] + c[4 * (s ^ p)];
      if (v < best) best = v, best_p = p;
    }
    std::uint32_t kid[2];
    const unsigned part[2] = {best_p, s ^ best_p};
    for (int h = 0; h < 2; ++h) {
      if ((part[h] & (part[h] - 1)) == 0) {  // one leaf (part[h] != 0)
        kid[h] = t.leaf[std::min(std::countr_zero(part[h]), kMaxLeaves - 1)];
      } else {
        kid[h] = t.inner[next_inner++];
        rewire(part[h], kid[h], t, next_inner, c);
      }
    }
    // The treelet's inner slots now hold other subtrees: evaluate them again in the next pass.
    Link& l = links_[slot];
    l.node.first = kid[0], l.kid1 = kid[1];
    l.leaves = links_[kid[0]].leaves + links_[kid[1]].leaves;
    l.dirty = 1;
    AabbF b = links_[kid[0]].node.box;  // as the builders: first child's box, grown by the second's
    b.expand(links_[kid[1]].node.box);
    l.node.box = b;
  }

  Link* links_;
};

}  // namespace

void optimize_treelets(Bvh& bvh, std::uint32_t passes) {
  const std::size_t n = bvh.nodes.size();
  if (passes == 0 || n < 5) return;  // fewer than three leaves: nothing to restructure
  Buffer<Link> links(n);
  const Restructurer r(links.data());
  r.first_pass(bvh.nodes.data(), 0, n);
  for (std::uint32_t p = 1; p < passes; ++p) r.pass(0);
  r.place(0, 0, 1, bvh.nodes.data());
}

}  // namespace interfere::detail
