// Broad phases over part boxes (Jia & Zheng 2019, §3.3): all pairs; sweep-and-prune on x with
// insertion sort of the previous frame's order (Baraff, "Dynamic simulation of non-penetrating
// rigid bodies", 1992; Cohen, Lin, Manocha & Ponamgi, I-COLLIDE, 1995); a loose octree (Ulrich,
// "Loose octrees", Game Programming Gems, 2000); the project's BVH (bvh/bvh.h) over the boxes,
// refitted each frame.
#include "interfere/bearing/broad_phase.h"

#include <algorithm>
#include <cmath>

#include "interfere/bvh/bvh.h"
#include "interfere/bvh/traverse.h"

namespace interfere::bearing {
namespace {

bool overlap(const Box3& a, const Box3& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

void finish(std::vector<IndexPair>& pairs) { std::sort(pairs.begin(), pairs.end()); }

class BruteForce final : public BroadPhase {
 public:
  std::vector<IndexPair> update(const std::vector<Box3>& boxes) override {
    std::vector<IndexPair> out;
    const auto n = static_cast<std::uint32_t>(boxes.size());
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::uint32_t j = i + 1; j < n; ++j)
        if (overlap(boxes[i], boxes[j])) out.emplace_back(i, j);
    return out;
  }
};

class SweepAndPrune final : public BroadPhase {
 public:
  std::vector<IndexPair> update(const std::vector<Box3>& boxes) override {
    const auto n = static_cast<std::uint32_t>(boxes.size());
    if (order_.size() != n) {
      order_.resize(n);
      for (std::uint32_t i = 0; i < n; ++i) order_[i] = i;
    }
    // insertion sort by lo.x: O(n + swaps) on the previous frame's (nearly sorted) order
    for (std::size_t k = 1; k < order_.size(); ++k) {
      const std::uint32_t v = order_[k];
      const double key = boxes[v].lo.x;
      std::size_t m = k;
      while (m > 0 && (boxes[order_[m - 1]].lo.x > key || (boxes[order_[m - 1]].lo.x == key && order_[m - 1] > v))) {
        order_[m] = order_[m - 1];
        --m;
      }
      order_[m] = v;
    }
    std::vector<IndexPair> out;
    for (std::size_t k = 0; k < order_.size(); ++k) {
      const Box3& a = boxes[order_[k]];
      for (std::size_t m = k + 1; m < order_.size() && boxes[order_[m]].lo.x <= a.hi.x; ++m) {
        if (overlap(a, boxes[order_[m]])) {
          const std::uint32_t i = order_[k], j = order_[m];
          out.emplace_back(std::min(i, j), std::max(i, j));
        }
      }
    }
    finish(out);
    return out;
  }

 private:
  std::vector<std::uint32_t> order_;
};

class LooseOctree final : public BroadPhase {
 public:
  std::vector<IndexPair> update(const std::vector<Box3>& boxes) override {
    nodes_.clear();
    std::vector<IndexPair> out;
    if (boxes.empty()) return out;
    Box3 world = boxes[0];
    for (const Box3& b : boxes) world.lo = min(world.lo, b.lo), world.hi = max(world.hi, b.hi);
    const Vec3 size = world.hi - world.lo;
    const double edge = std::max({size.x, size.y, size.z, 1e-300});
    nodes_.push_back(make_node(world.lo + Vec3{edge, edge, edge} * 0.5, 0.5 * edge));
    for (std::uint32_t i = 0; i < boxes.size(); ++i) insert(boxes[i], i);
    for (std::uint32_t i = 0; i < boxes.size(); ++i) query(0, boxes, i, out);
    finish(out);
    return out;
  }

 private:
  struct Node {
    Vec3 center;
    double half = 0;  // of the tight cell; the loose bounds are twice as large
    std::array<std::int32_t, 8> child{-1, -1, -1, -1, -1, -1, -1, -1};
    std::vector<std::uint32_t> items;
  };
  std::vector<Node> nodes_;
  static constexpr int kMaxDepth = 10;

  static Node make_node(const Vec3& center, double half) {
    Node n;
    n.center = center, n.half = half;
    return n;
  }

  void insert(const Box3& b, std::uint32_t id) {
    const Vec3 c = (b.lo + b.hi) * 0.5;
    const Vec3 e = (b.hi - b.lo) * 0.5;
    const double ext = std::max({e.x, e.y, e.z});
    std::size_t cur = 0;
    for (int depth = 0; depth < kMaxDepth; ++depth) {
      const double child_half = 0.5 * nodes_[cur].half;
      if (ext > child_half) break;  // the loose child (2 * child_half) must contain the box around its centre
      const Vec3 nc = nodes_[cur].center;
      const int k = (c.x >= nc.x) | ((c.y >= nc.y) << 1) | ((c.z >= nc.z) << 2);
      if (nodes_[cur].child[static_cast<std::size_t>(k)] < 0) {
        const Vec3 off{(k & 1) ? child_half : -child_half, (k & 2) ? child_half : -child_half,
                       (k & 4) ? child_half : -child_half};
        nodes_[cur].child[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(nodes_.size());
        nodes_.push_back(make_node(nc + off, child_half));
      }
      cur = static_cast<std::size_t>(nodes_[cur].child[static_cast<std::size_t>(k)]);
    }
    nodes_[cur].items.push_back(id);
  }

  void query(std::size_t node, const std::vector<Box3>& boxes, std::uint32_t i, std::vector<IndexPair>& out) const {
    const Node& n = nodes_[node];
    const double l = 2 * n.half;  // loose half extent
    const Box3 loose{n.center - Vec3{l, l, l}, n.center + Vec3{l, l, l}};
    if (!overlap(loose, boxes[i])) return;
    for (const std::uint32_t j : n.items)
      if (j > i && overlap(boxes[i], boxes[j])) out.emplace_back(i, j);
    for (const std::int32_t c : n.child)
      if (c >= 0) query(static_cast<std::size_t>(c), boxes, i, out);
  }
};

class BvhBroadPhase final : public BroadPhase {
 public:
  std::vector<IndexPair> update(const std::vector<Box3>& boxes) override {
    // one degenerate triangle per part spanning its box: the BVH's triangle boxes are the part boxes
    mesh_.positions.resize(boxes.size() * 2);
    mesh_.triangles.resize(boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      mesh_.positions[2 * i] = boxes[i].lo, mesh_.positions[2 * i + 1] = boxes[i].hi;
      mesh_.triangles[i] = {2 * i, 2 * i + 1, 2 * i};
    }
    if (bvh_.empty() || bvh_.prims.size() != boxes.size()) {
      bvh_ = build_bvh(mesh_, {.builder = BvhBuilder::binned_sah, .max_leaf_size = 4});
    } else {
      refit_bvh(bvh_, mesh_);  // temporal coherence: same topology, new boxes
    }
    std::vector<IndexPair> out;
    for_each_overlap(bvh_, bvh_, 0.0f, [&](std::uint32_t i, std::uint32_t j) {
      if (i < j && overlap(boxes[i], boxes[j])) out.emplace_back(i, j);
    });
    finish(out);
    return out;
  }

 private:
  TriMesh mesh_;
  Bvh bvh_;
};

}  // namespace

const char* broad_phase_name(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::brute_force: return "brute";
    case BroadPhaseKind::sweep_and_prune: return "sap";
    case BroadPhaseKind::loose_octree: return "octree";
    case BroadPhaseKind::bvh: return "bvh";
  }
  return "?";
}

bool parse_broad_phase(const std::string& name, BroadPhaseKind& out) {
  for (const BroadPhaseKind k : {BroadPhaseKind::brute_force, BroadPhaseKind::sweep_and_prune,
                                 BroadPhaseKind::loose_octree, BroadPhaseKind::bvh}) {
    if (name == broad_phase_name(k)) {
      out = k;
      return true;
    }
  }
  return false;
}

std::unique_ptr<BroadPhase> make_broad_phase(BroadPhaseKind kind) {
  switch (kind) {
    case BroadPhaseKind::brute_force: return std::make_unique<BruteForce>();
    case BroadPhaseKind::sweep_and_prune: return std::make_unique<SweepAndPrune>();
    case BroadPhaseKind::loose_octree: return std::make_unique<LooseOctree>();
    case BroadPhaseKind::bvh: return std::make_unique<BvhBroadPhase>();
  }
  return std::make_unique<BruteForce>();
}

}  // namespace interfere::bearing
