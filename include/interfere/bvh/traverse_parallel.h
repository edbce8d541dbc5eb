// collide_parallel: the parallel tree-vs-tree traversal (declared and documented in traverse.h).
// After Embree's BVH collider: the root pair is expanded breadth-first into node-pair tasks
// (split_node_pairs, thread-independent), the tasks run in a tbb::parallel_for, each depth-first
// with its own stack and output vector, and the outputs are concatenated in task order.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <iterator>
#include <vector>

#include "interfere/bvh/traverse.h"

namespace interfere {

template <class T, class F>
std::vector<T> collide_parallel(const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options,
                                F&& f) {
  const auto tasks = split_node_pairs(a, b, options);
  // One output vector per chunk of consecutive tasks, stored at the chunk's first task:
  // concatenating the slots in index order gives the task order whatever the chunking (i.e. the
  // thread count).
  std::vector<std::vector<T>> outs(tasks.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tasks.size(), 1), [&](const auto& r) {
    std::vector<T>& out = outs[r.begin()];
    auto emit = [&](std::uint32_t ia, std::uint32_t ib) { f(ia, ib, out); };
    for (std::size_t t = r.begin(); t < r.end(); ++t) {
      detail::overlap_from(a, b, options.margin, tasks[t].first, tasks[t].second, emit);
    }
  });
  std::size_t total = 0;
  for (const auto& o : outs) total += o.size();
  std::vector<T> result;
  result.reserve(total);
  for (auto& o : outs) {
    result.insert(result.end(), std::make_move_iterator(o.begin()),
                  std::make_move_iterator(o.end()));
  }
  return result;
}

}  // namespace interfere
