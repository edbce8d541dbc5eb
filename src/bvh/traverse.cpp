// Node-pair task list for the parallel tree-vs-tree traversal (Embree's collider: breadth-first
// split of the root pair into many independent jobs). The templates live in
// traverse.h/traverse_parallel.h.
#include "interfere/bvh/traverse.h"

#include <algorithm>

namespace interfere {

std::vector<std::pair<std::uint32_t, std::uint32_t>> split_node_pairs(
    const Bvh& a, const Bvh& b, const ParallelTraversalOptions& options) {
  using detail::NodePair;
  std::vector<NodePair> cur;
  if (a.empty() || b.empty() || !boxes_overlap(a.nodes[0].box, b.nodes[0].box, options.margin)) {
    return cur;
  }
  const std::size_t target = std::max<std::uint32_t>(1, options.target_tasks);
  const float m = options.margin;
  cur.push_back({0, 0});
  std::vector<NodePair> next;
  while (cur.size() < target) {
    next.clear();
    bool expanded = false;
    for (std::size_t i = 0; i < cur.size(); ++i) {
      const auto [ia, ib] = cur[i];
      const BvhNode& na = a.nodes[ia];
      const BvhNode& nb = b.nodes[ib];
      // Expanding replaces one pair by up to two: stop once that could exceed the target.
      if ((na.is_leaf() && nb.is_leaf()) || next.size() + (cur.size() - i) + 1 > target) {
        next.push_back(cur[i]);
        continue;
      }
      expanded = true;
      if (detail::descend_a(na, nb)) {
        for (std::uint32_t c = na.first; c < na.first + 2; ++c) {
          if (boxes_overlap(a.nodes[c].box, nb.box, m)) next.push_back({c, ib});
        }
      } else {
        for (std::uint32_t c = nb.first; c < nb.first + 2; ++c) {
          if (boxes_overlap(na.box, b.nodes[c].box, m)) next.push_back({ia, c});
        }
      }
    }
    cur.swap(next);
    if (!expanded) break;
  }
  return cur;
}

}  // namespace interfere
