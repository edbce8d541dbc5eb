// BVH traversals: tree vs tree (serial, and parallel split into node-pair tasks after Embree's
// collider), tree vs box, tree vs segment, and a best-first branch-and-bound over node pairs for distance queries.
// Results never depend on the thread count: the task list is built breadth-first independently of
// it, and per-task outputs are concatenated in task order.
//
// Callbacks are template parameters (inlined in the inner loops); std::function still works.
//
// Overlap test. Box a (from tree A, grown by `margin` on every side) and box b overlap when, on
// every axis k, a.lo[k] - margin <= b.hi[k] and b.lo[k] <= a.hi[k] + margin, the sums evaluated in
// float. Rounding is monotonic, so this never rejects a pair whose exactly grown boxes overlap; it
// may accept pairs that miss by less than one float ulp. boxes_overlap() is that test: brute-force
// references (tests) use it to get exactly the same pair sets.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include "interfere/bvh/bvh.h"

namespace interfere {

/// The traversals' box test: `a` grown by `margin` (>= 0) overlaps `b` (see the file comment).
inline bool boxes_overlap(const AabbF& a, const AabbF& b, float margin) {
  return a.lo[0] - margin <= b.hi[0] && b.lo[0] <= a.hi[0] + margin &&  //
         a.lo[1] - margin <= b.hi[1] && b.lo[1] <= a.hi[1] + margin &&  //
         a.lo[2] - margin <= b.hi[2] && b.lo[2] <= a.hi[2] + margin;
}

/// Squared Euclidean distance between two float boxes (0 when they overlap), computed in double and
/// rounded down by a relative 2^-50, so it is a lower bound of the exact squared distance between
/// any two points of the boxes: safe for pruning.
inline double box_distance_squared(const AabbF& a, const AabbF& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double g =
        std::max(static_cast<double>(b.lo[k]) - a.hi[k], static_cast<double>(a.lo[k]) - b.hi[k]);
    if (g > 0) d2 += g * g;
  }
  return d2 * (1.0 - 0x1p-50);
}

namespace detail {

/// LIFO stack with inline storage that spills to the heap (trees from the insertion builder can be
/// deeper than any fixed bound).
template <class T, std::size_t N = 128>
class SmallStack {
 public:
  SmallStack() = default;
  SmallStack(const SmallStack&) = delete;
  SmallStack& operator=(const SmallStack&) = delete;
  bool empty() const { return size_ == 0; }
  void push(const T& v) {
    if (size_ == cap_) grow();
    data_[size_++] = v;
  }
  T pop() { return data_[--size_]; }

 private:
  void grow() {
    std::vector<T> bigger(cap_ * 2);
    std::copy(data_, data_ + size_, bigger.begin());
    heap_.swap(bigger);
    data_ = heap_.data();
    cap_ = heap_.size();
  }
  T inline_[N];
  std::vector<T> heap_;
  T* data_ = inline_;
  std::size_t size_ = 0, cap_ = N;
};

inline float half_area(const AabbF& b) {
  const float dx = b.hi[0] - b.lo[0], dy = b.hi[1] - b.lo[1], dz = b.hi[2] - b.lo[2];
  return dx * dy + dy * dz + dz * dx;
}

/// Descent rule for a node pair that is not leaf-leaf: descend A when B is a leaf, or when A is an
/// inner node at least as large (surface area) as B.
inline bool descend_a(const BvhNode& na, const BvhNode& nb) {
  return !na.is_leaf() && (nb.is_leaf() || half_area(na.box) >= half_area(nb.box));
}

using NodePair = std::pair<std::uint32_t, std::uint32_t>;

/// Depth-first tree-vs-tree traversal from the node pair (ra, rb), whose boxes must overlap. Calls
/// f(ia, ib) for every overlapping triangle pair below it, in a deterministic order.
template <class F>
void overlap_from(const Bvh& a, const Bvh& b, float margin, std::uint32_t ra, std::uint32_t rb,
                  F& f) {
  const BvhNode* an = a.nodes.data();
  const BvhNode* bn = b.nodes.data();
  struct Pair {  // trivial, so the stack's inline storage is not initialised on every call
    std::uint32_t a, b;
  };
  SmallStack<Pair> stack;
  stack.push({ra, rb});
  while (!stack.empty()) {
    const auto [ia, ib] = stack.pop();
    const BvhNode& na = an[ia];
    const BvhNode& nb = bn[ib];
    if (na.is_leaf() && nb.is_leaf()) {
      for (std::uint32_t i = na.first; i < na.first + na.count; ++i) {
        const AabbF& pa = a.prim_boxes[i];
        if (!boxes_overlap(pa, nb.box, margin)) continue;
        for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j) {
          if (boxes_overlap(pa, b.prim_boxes[j], margin)) f(a.prims[i], b.prims[j]);
        }
      }
    } else if (descend_a(na, nb)) {
      const std::uint32_t c = na.first;
      if (boxes_overlap(an[c + 1].box, nb.box, margin)) stack.push({c + 1, ib});
      if (boxes_overlap(an[c].box, nb.box, margin)) stack.push({c, ib});
    } else {
      const std::uint32_t c = nb.first;
      if (boxes_overlap(na.box, bn[c + 1].box, margin)) stack.push({ia, c + 1});
      if (boxes_overlap(na.box, bn[c].box, margin)) stack.push({ia, c});
    }
  }
}

}  // namespace detail

/// Calls f(ia, ib) for every pair of primitives (triangle indices of A and B) whose boxes overlap
/// after each box of `a` is grown by `margin` (>= 0) on every side (boxes_overlap). Serial,
/// depth-first, deterministic order; every pair is reported once.
template <class F>
void for_each_overlap(const Bvh& a, const Bvh& b, float margin, F&& f) {
  if (a.empty() || b.empty() || !boxes_overlap(a.nodes[0].box, b.nodes[0].box, margin)) return;
  detail::overlap_from(a, b, margin, 0, 0, f);
}

/// Parallel version's callback type: `f(ia, ib, out)` appends zero or more results to `out`, a
/// vector owned by the calling thread for a run of consecutive tasks (it may already hold earlier
/// results: only append). Any callable with that signature works (collide_parallel is a template on
/// it).
template <class T>
using PairCallback = std::function<void(std::uint32_t, std::uint32_t, std::vector<T>&)>;

struct ParallelTraversalOptions {
  float margin = 0;
  std::uint32_t target_tasks = 4096;  ///< breadth-first expansion stops near this many node pairs
};

/// Node-pair task list: breadth-first expansion of the root pair, level by level, replacing each
/// non-leaf-leaf pair by its overlapping child pairs (descent rule of detail::descend_a) in place,
/// so that the list stays in traversal order. Stops when the next expansion would exceed
/// `target_tasks` pairs (the list is then at most target_tasks long) or only leaf-leaf pairs
/// remain. Every listed pair overlaps; the subtrees of the listed pairs cover every overlapping
/// primitive pair exactly once. Independent of the thread count. Empty when a tree is empty or the
/// roots do not overlap.
std::vector<std::pair<std::uint32_t, std::uint32_t>> split_node_pairs(
    const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options);

/// Runs the node-pair tasks of split_node_pairs in parallel (oneTBB; thread count from the active
/// tbb::global_control or task_arena); each task traverses its pair depth-first like
/// for_each_overlap and calls f(ia, ib, out) with a task-local `out`. Returns the task outputs
/// concatenated in task order: identical for any thread count. `f` is called concurrently from
/// several threads. Defined in traverse_parallel.h.
template <class T, class F>
std::vector<T> collide_parallel(const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options,
                                F&& f);

/// Calls f(i) for every primitive (triangle index) whose box overlaps `box` (boxes_overlap with
/// margin 0, `box` in the role of A). Serial, deterministic order.
template <class F>
void for_each_in_box(const Bvh& bvh, const AabbF& box, F&& f) {
  if (bvh.empty()) return;
  const BvhNode* nodes = bvh.nodes.data();
  if (!boxes_overlap(box, nodes[0].box, 0.0f)) return;
  detail::SmallStack<std::uint32_t> stack;
  stack.push(0);
  while (!stack.empty()) {
    const BvhNode& n = nodes[stack.pop()];
    if (n.is_leaf()) {
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j) {
        if (boxes_overlap(box, bvh.prim_boxes[j], 0.0f)) f(bvh.prims[j]);
      }
    } else {
      if (boxes_overlap(box, nodes[n.first + 1].box, 0.0f)) stack.push(n.first + 1);
      if (boxes_overlap(box, nodes[n.first].box, 0.0f)) stack.push(n.first);
    }
  }
}

/// Conservative segment/box overlap: the segment p -> p + d against `box` grown by `pad` on every
/// side (slab test in double): it may keep a box the segment misses by rounding, never drop one it
/// meets; an exact test of the primitives decides.
inline bool segment_may_hit(const Vec3& p, const Vec3& d, const AabbF& box, double pad) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double lo = static_cast<double>(box.lo[k]) - pad, hi = static_cast<double>(box.hi[k]) + pad;
    if (d[k] == 0) {
      if (p[k] < lo || p[k] > hi) return false;
      continue;
    }
    double a = (lo - p[k]) / d[k], b = (hi - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

/// Calls f(i) for every primitive (triangle index) whose box the segment p -> p + d may meet
/// (segment_may_hit with `pad`), until f returns false. Serial, deterministic order.
template <class F>
void for_each_on_segment(const Bvh& bvh, const Vec3& p, const Vec3& d, double pad, F&& f) {
  if (bvh.empty()) return;
  const BvhNode* nodes = bvh.nodes.data();
  detail::SmallStack<std::uint32_t> stack;
  stack.push(0);
  while (!stack.empty()) {
    const BvhNode& n = nodes[stack.pop()];
    if (!segment_may_hit(p, d, n.box, pad)) continue;
    if (n.is_leaf()) {
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j)
        if (segment_may_hit(p, d, bvh.prim_boxes[j], pad) && !f(bvh.prims[j])) return;
    } else {
      stack.push(n.first + 1);
      stack.push(n.first);
    }
  }
}

/// Best-first branch-and-bound over node pairs, for distance queries (minimum distance, pairs
/// within a clearance). Node pairs are visited in increasing box_distance_squared (ties: by node
/// indices), from a priority queue; a pair whose box squared distance exceeds the current bound is
/// pruned, and the traversal ends when the nearest queued pair exceeds it.
///
/// For every primitive pair (ia, ib) reached with box_distance_squared(box_a, box_b) = d2 <=
/// bound2, calls `double r = f(ia, ib, d2)`; then bound2 = min(bound2, r), or, if r < 0, the
/// traversal stops at once. For a minimum distance, f returns the exact squared distance of the two
/// triangles; to list all pairs within a clearance c, f returns c*c (never shrinking the bound).
///
/// Guarantee: every primitive pair whose box squared distance is <= the final bound2 has been
/// passed to f (unless f stopped the traversal); since a triangle lies inside its box, every pair
/// at squared distance <= the final bound2 has been visited. Returns the final bound2. Serial,
/// deterministic order.
template <class F>
double for_each_pair_within(const Bvh& a, const Bvh& b, double bound2, F&& f) {
  if (a.empty() || b.empty()) return bound2;
  struct Item {
    double d2;
    std::uint32_t ia, ib;
    bool operator>(const Item& o) const {
      return d2 != o.d2 ? d2 > o.d2 : (ia != o.ia ? ia > o.ia : ib > o.ib);
    }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  const BvhNode* an = a.nodes.data();
  const BvhNode* bn = b.nodes.data();
  const double root_d2 = box_distance_squared(an[0].box, bn[0].box);
  if (root_d2 <= bound2) queue.push({root_d2, 0, 0});
  while (!queue.empty()) {
    const Item top = queue.top();
    queue.pop();
    if (top.d2 > bound2) break;
    const BvhNode& na = an[top.ia];
    const BvhNode& nb = bn[top.ib];
    if (na.is_leaf() && nb.is_leaf()) {
      for (std::uint32_t i = na.first; i < na.first + na.count; ++i) {
        const AabbF& pa = a.prim_boxes[i];
        if (box_distance_squared(pa, nb.box) > bound2) continue;
        for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j) {
          const double d2 = box_distance_squared(pa, b.prim_boxes[j]);
          if (d2 > bound2) continue;
          const double r = f(a.prims[i], b.prims[j], d2);
          if (r < 0) return bound2;
          bound2 = std::min(bound2, r);
        }
      }
    } else if (detail::descend_a(na, nb)) {
      for (std::uint32_t c = na.first; c < na.first + 2; ++c) {
        const double d2 = box_distance_squared(an[c].box, nb.box);
        if (d2 <= bound2) queue.push({d2, c, top.ib});
      }
    } else {
      for (std::uint32_t c = nb.first; c < nb.first + 2; ++c) {
        const double d2 = box_distance_squared(na.box, bn[c].box);
        if (d2 <= bound2) queue.push({d2, top.ia, c});
      }
    }
  }
  return bound2;
}

}  // namespace interfere

#include "interfere/bvh/traverse_parallel.h"
