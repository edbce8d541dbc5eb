// BVH traversals: tree vs tree (serial, and parallel split into node-pair tasks after Embree's
// collider), and tree vs box. Results never depend on the thread count: the task list is built
// breadth-first independently of it, and per-task outputs are concatenated in task order.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "interfere/bvh/bvh.h"

namespace interfere {

/// Calls f(ia, ib) for every pair of primitives (triangle indices) whose boxes overlap after each
/// box of `a` is grown by `margin` (>= 0) on every side. Serial, depth-first, deterministic order.
void for_each_overlap(const Bvh& a, const Bvh& b, float margin,
                      const std::function<void(std::uint32_t, std::uint32_t)>& f);

/// Parallel version. `f(ia, ib, out)` appends zero or more results to the task-local `out`. The
/// returned vector is the concatenation of task outputs in a thread-independent order.
template <class T>
using PairCallback = std::function<void(std::uint32_t, std::uint32_t, std::vector<T>&)>;

struct ParallelTraversalOptions {
  float margin = 0;
  std::uint32_t target_tasks = 4096;  ///< breadth-first expansion stops near this many node pairs
};

/// Node-pair task list (breadth-first expansion of the root pair), exposed for tests/benchmarks.
std::vector<std::pair<std::uint32_t, std::uint32_t>> split_node_pairs(
    const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options);

/// Runs the node-pair tasks in parallel (oneTBB; thread count from the active tbb::global_control
/// or task_arena). Implemented in traverse_parallel.h as a template.
template <class T>
std::vector<T> collide_parallel(const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options,
                                const PairCallback<T>& f);

/// Calls f(i) for every primitive whose box overlaps `box`.
void for_each_in_box(const Bvh& bvh, const AabbF& box, const std::function<void(std::uint32_t)>& f);

}  // namespace interfere

#include "interfere/bvh/traverse_parallel.h"
