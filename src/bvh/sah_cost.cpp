// SAH cost of a tree (MacDonald & Booth, "Heuristics for ray tracing using space subdivision",
// 1990): the expected cost of a query, each node weighted by the probability (surface area ratio
// to the root) that a random ray reaching the root reaches it. Used to compare builders.
#include "interfere/bvh/bvh.h"

namespace interfere {

double bvh_sah_cost(const Bvh& bvh, double inner_cost, double leaf_cost) {
  if (bvh.empty()) return 0;
  auto area = [](const AabbF& b) {
    const double dx = static_cast<double>(b.hi[0]) - b.lo[0];
    const double dy = static_cast<double>(b.hi[1]) - b.lo[1];
    const double dz = static_cast<double>(b.hi[2]) - b.lo[2];
    return dx * dy + dy * dz + dz * dx;
  };
  double inner = 0, leaves = 0;
  for (const BvhNode& n : bvh.nodes) {
    if (n.is_leaf()) {
      leaves += area(n.box) * n.count;
    } else {
      inner += area(n.box);
    }
  }
  const double root = area(bvh.nodes[0].box);
  return root > 0 ? (inner_cost * inner + leaf_cost * leaves) / root : 0;
}

}  // namespace interfere
