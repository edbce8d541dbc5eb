// The quadtree's calculation layer (Jia & Zheng 2019, §2.4; issue #27): "the highest nodes whose
// leaves all lie inside the ideal maximum interference range" (the paper's rule, the default),
// against a brute-force enumeration of every node of the built tree, with the leaves' angles taken
// from the mesh vertices themselves; and the former rule (nodes still spanning the window) kept as
// CalculationLayerRule::spanning_window.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/roller.h"
#include "interfere/bearing/window.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kPi = std::numbers::pi;

struct NodeLeaves {
  int level = 0;
  std::vector<double> angles;  // the leaves' (side vertices') angles, from the mesh positions
};

// Every node of the side tree with its leaves, collected by walking the tree down to its leaves.
std::vector<NodeLeaves> enumerate(const Roller& r, const RollerQuadtree& t) {
  std::vector<NodeLeaves> out;
  std::vector<std::pair<std::int32_t, int>> stack{{t.side_root, 0}};
  while (!stack.empty()) {
    const auto [id, level] = stack.back();
    stack.pop_back();
    NodeLeaves nl;
    nl.level = level;
    std::vector<std::int32_t> sub{id};
    while (!sub.empty()) {
      const QuadNode& q = t.nodes[static_cast<std::size_t>(sub.back())];
      sub.pop_back();
      if (q.child_count == 0) {
        const Vec3& p = r.mesh.positions[r.side_vertex(q.i0, q.j0)];
        nl.angles.push_back(std::atan2(p.y, p.x));
      }
      for (std::int32_t k = 0; k < q.child_count; ++k) sub.push_back(q.first_child + k);
    }
    const QuadNode& q = t.nodes[static_cast<std::size_t>(id)];
    for (std::int32_t k = 0; k < q.child_count; ++k) stack.push_back({q.first_child + k, level + 1});
    out.push_back(std::move(nl));
  }
  return out;
}

// Whether every angle lies within [c - w, c + w] for some centre c: the smallest arc holding all
// the angles (2 pi minus the largest circular gap between consecutive sorted angles) is <= 2w.
bool fits(std::vector<double> a, double w) {
  std::sort(a.begin(), a.end());
  double gap = a.front() + 2 * kPi - a.back();
  for (std::size_t k = 1; k < a.size(); ++k) gap = std::max(gap, a[k] - a[k - 1]);
  return 2 * kPi - gap <= 2 * w * (1 + 1e-12) + 1e-12;
}

// Brute force of the paper's rule: the highest level all of whose nodes fit inside the range.
int brute_paper_layer(const std::vector<NodeLeaves>& nodes, double w) {
  std::map<int, bool> all_fit;
  for (const NodeLeaves& n : nodes) {
    auto [it, fresh] = all_fit.try_emplace(n.level, true);
    it->second = it->second && fits(n.angles, w);
  }
  for (const auto& [level, ok] : all_fit)
    if (ok) return level;
  return -1;
}

}  // namespace

TEST(BearingQuadtreeLayer, PaperRuleAgainstBruteForce) {
  for (const auto& [n, m] : {std::pair{32, 31}, std::pair{48, 8}, std::pair{24, 23}, std::pair{17, 5}, std::pair{64, 63}}) {
    const Roller r = *make_roller({.radius = 10, .height = 40, .radial_segments = n, .height_segments = m});
    const RollerQuadtree t = build_quadtree(r);
    EXPECT_EQ(t.options.layer_rule, CalculationLayerRule::paper);
    const std::vector<NodeLeaves> nodes = enumerate(r, t);
    const double col = 2 * kPi / n;
    std::vector<double> widths;
    for (int k = 0; k <= 200; ++k) widths.push_back(kPi * k / 200);
    for (int c = 0; c <= n; ++c)  // exactly at, and just around, the node widths
      for (const double f : {1 - 1e-9, 1.0, 1 + 1e-9}) widths.push_back(0.5 * c * col * f);
    widths.push_back(0.5 * ideal_interference_range({.max_tilt = 1 * kPi / 180}));  // the example
    for (const double w : widths) {
      const int want = brute_paper_layer(nodes, w);
      ASSERT_GE(want, 0);
      EXPECT_EQ(t.calculation_layer(w, n), want) << n << " " << w;
      EXPECT_EQ(t.calculation_layer(w, n, CalculationLayerRule::paper), want) << n << " " << w;
    }
  }
}

TEST(BearingQuadtreeLayer, PaperLayerNodesLieInsideARangeCentredOnThem) {
  // Positional check: each node of the paper's layer, with the range centred on the middle of its
  // leaves, has every leaf inside; and some node one level higher cannot lie inside any range.
  const Roller r = *make_roller({.radius = 10, .height = 40, .radial_segments = 48, .height_segments = 47});
  const RollerQuadtree t = build_quadtree(r);
  const std::vector<NodeLeaves> nodes = enumerate(r, t);
  const double col = 2 * kPi / 48;
  const double w = 0.5 * ideal_interference_range({.max_tilt = 1 * kPi / 180});  // 18.7 degrees
  const int L = t.calculation_layer(w, 48);
  EXPECT_EQ(L, 4);  // 48 -> 24 -> 12 -> 6 (leaves span 37.5 > 37.36 degrees) -> 3 (15 degrees)
  bool higher_too_wide = false;
  for (const NodeLeaves& nl : nodes) {
    const auto [lo, hi] = std::minmax_element(nl.angles.begin(), nl.angles.end());
    if (nl.level == L - 1 && *hi - *lo > 2 * w && *hi - *lo < kPi) higher_too_wide = true;
    if (nl.level != L || *hi - *lo > kPi) continue;  // (nodes across the +-pi seam: covered by fits())
    const double c = 0.5 * (*lo + *hi);
    for (const double a : nl.angles) EXPECT_LE(std::fabs(a - c), w + 1e-12);
  }
  EXPECT_TRUE(higher_too_wide);
  // the former rule keeps one level higher here: nodes of 6 columns still span 45 >= 37.4 degrees
  EXPECT_EQ(t.calculation_layer(w, 48, CalculationLayerRule::spanning_window), 3);
  EXPECT_GE(6 * col, 2 * w);
}

TEST(BearingQuadtreeLayer, OptionSelectsTheFormerRule) {
  const Roller r = *make_roller({.radius = 10, .height = 40, .radial_segments = 32, .height_segments = 31});
  const RollerQuadtree t = build_quadtree(r, {.layer_rule = CalculationLayerRule::spanning_window});
  for (int k = 1; k <= 100; ++k) {
    const double w = kPi * k / 100;
    const std::int32_t L = t.calculation_layer(w, 32);
    EXPECT_EQ(L, t.calculation_layer(w, 32, CalculationLayerRule::spanning_window));
    // nodes of the former layer span the window (cells), the next level's do not
    EXPECT_GE(2 * kPi * std::ceil(32 / std::pow(2.0, L)) / 32, 2 * w);
    if (L < t.depth) EXPECT_LT(2 * kPi * std::ceil(32 / std::pow(2.0, L + 1)) / 32, 2 * w);
    // never deeper than the paper's
    EXPECT_LE(L, t.calculation_layer(w, 32, CalculationLayerRule::paper));
  }
}
