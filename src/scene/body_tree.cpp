// The broad phase's tree over body boxes (issue #24, item 3: "a BVH of the bodies' world boxes,
// refitted per frame"). Bodies number 10^2..10^5, so a serial median-split build (microseconds per
// thousand bodies) is enough; frames refit it rather than rebuild (ARCHITECTURE.md: motion never
// rebuilds what a refit can update).
#include <algorithm>
#include <numeric>

#include "engine_internal.h"

namespace interfere::scene::detail {
namespace {

struct Builder {
  const std::vector<AabbF>& boxes;
  std::vector<std::uint32_t>& idx;
  Bvh& tree;

  AabbF bounds(std::size_t b, std::size_t e) const {
    AabbF box;
    for (std::size_t i = b; i < e; ++i) box.expand(boxes[idx[i]]);
    return box;
  }
  // Fills node `n` with the boxes idx[b, e): a leaf of one box, or a child pair appended at the end.
  void node(std::uint32_t n, std::size_t b, std::size_t e) {
    tree.nodes[n].box = bounds(b, e);
    if (e - b == 1) {
      tree.nodes[n].first = static_cast<std::uint32_t>(b);
      tree.nodes[n].count = 1;
      return;
    }
    AabbF c;
    for (std::size_t i = b; i < e; ++i) {
      const AabbF& x = boxes[idx[i]];
      for (int k = 0; k < 3; ++k) {
        const float m = 0.5f * x.lo[k] + 0.5f * x.hi[k];
        c.lo[k] = std::min(c.lo[k], m), c.hi[k] = std::max(c.hi[k], m);
      }
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (c.hi[k] - c.lo[k] > c.hi[axis] - c.lo[axis]) axis = k;
    const std::size_t m = b + (e - b) / 2;
    std::nth_element(idx.begin() + b, idx.begin() + m, idx.begin() + e, [&](std::uint32_t x, std::uint32_t y) {
      const float cx = boxes[x].lo[axis] + boxes[x].hi[axis], cy = boxes[y].lo[axis] + boxes[y].hi[axis];
      return cx < cy || (cx == cy && x < y);
    });
    const auto first = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    tree.nodes[n].first = first;
    tree.nodes[n].count = 0;
    node(first, b, m);
    node(first + 1, m, e);
  }
};

}  // namespace

Bvh build_box_tree(const std::vector<AabbF>& boxes) {
  Bvh tree;
  if (boxes.empty()) return tree;
  std::vector<std::uint32_t> idx(boxes.size());
  std::iota(idx.begin(), idx.end(), 0u);
  tree.nodes.reserve(2 * boxes.size());
  tree.nodes.emplace_back();
  Builder{boxes, idx, tree}.node(0, 0, boxes.size());
  tree.prims = idx;
  tree.prim_boxes.resize(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) tree.prim_boxes[i] = boxes[idx[i]];
  return tree;
}

void refit_box_tree(Bvh& tree, const std::vector<AabbF>& boxes) {
  for (std::size_t i = 0; i < tree.prims.size(); ++i) tree.prim_boxes[i] = boxes[tree.prims[i]];
  // Children follow their parent (depth-first pairs appended after it): a reverse sweep sees
  // children first.
  for (std::size_t n = tree.nodes.size(); n-- > 0;) {
    BvhNode& x = tree.nodes[n];
    if (x.is_leaf()) {
      x.box = tree.prim_boxes[x.first];
    } else {
      x.box = tree.nodes[x.first].box;
      x.box.expand(tree.nodes[x.first + 1].box);
    }
  }
}

}  // namespace interfere::scene::detail
