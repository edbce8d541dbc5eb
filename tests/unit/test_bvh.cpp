// BVH builders, refit and traversals against brute force (issue #2, items 3 and 7).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/bvh/traverse.h"
#include "interfere/mesh/generate.h"

namespace interfere {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

constexpr BvhBuilder kBuilders[] = {BvhBuilder::insertion, BvhBuilder::median_split,
                                    BvhBuilder::binned_sah, BvhBuilder::lbvh,
                                    BvhBuilder::lbvh_treelet};

TriMesh random_soup(std::size_t n, std::uint32_t seed, double size = 0.1, Vec3 offset = {}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TriMesh m;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 3; ++k) {
      m.positions.push_back(offset + c + Vec3{u(rng), u(rng), u(rng)} * size);
    }
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

TriMesh sphere(std::size_t n, Vec3 center = {}, double twist = 0) {
  return make_sphere({.target_triangles = n,
                      .radius = 1.0,
                      .center = center,
                      .bump_amplitude = 0.02,
                      .bump_frequency = 5,
                      .twist = twist});
}

// n copies of the same triangle: every centroid coincides (degenerate split input).
TriMesh coincident(std::size_t n) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (std::size_t i = 0; i < n; ++i) m.triangles.push_back({0, 1, 2});
  return m;
}

TriMesh one_triangle() {
  TriMesh m;
  m.positions = {{0.1, 0.2, 0.3}, {1, 0, 0}, {0, 1, 0.5}};
  m.triangles = {{0, 1, 2}};
  return m;
}

bool box_contains(const AabbF& outer, const AabbF& inner) {
  for (int k = 0; k < 3; ++k) {
    if (!(outer.lo[k] <= inner.lo[k] && inner.hi[k] <= outer.hi[k])) return false;
  }
  return true;
}

bool box_contains_point(const AabbF& b, const Vec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (!(static_cast<double>(b.lo[k]) <= p[k] && p[k] <= static_cast<double>(b.hi[k])))
      return false;
  }
  return true;
}

bool same_box(const AabbF& a, const AabbF& b) {
  return std::memcmp(&a, &b, sizeof(AabbF)) == 0;
}

// Full structural check; `tight` also requires every box to be exactly the union of its content.
void check_tree(const Bvh& bvh, const TriMesh& mesh, std::uint32_t max_leaf, bool tight = true) {
  const std::size_t n = mesh.num_triangles();
  if (n == 0) {
    EXPECT_TRUE(bvh.empty());
    EXPECT_TRUE(bvh.prims.empty());
    return;
  }
  ASSERT_FALSE(bvh.empty());
  ASSERT_EQ(bvh.prims.size(), n);
  ASSERT_EQ(bvh.prim_boxes.size(), n);
  const std::vector<AabbF> boxes = triangle_boxes(mesh);
  // Every node reached exactly once; every triangle in exactly one leaf; layout: the descendants of
  // a node are the contiguous range starting at its child pair (refit relies on it).
  std::vector<int> node_seen(bvh.nodes.size(), 0), prim_seen(n, 0);
  struct Range {
    std::size_t lo, hi, count;
  };
  // Iterative post-order computing the descendant index range of every node.
  std::vector<Range> desc(bvh.nodes.size(), {0, 0, 0});
  std::vector<std::pair<std::uint32_t, bool>> stack{{0, false}};
  node_seen[0] = 1;
  while (!stack.empty()) {
    auto [i, done] = stack.back();
    stack.pop_back();
    const BvhNode& nd = bvh.nodes[i];
    if (nd.is_leaf()) {
      ASSERT_LE(nd.count, max_leaf);
      ASSERT_LE(std::size_t{nd.first} + nd.count, n);
      AabbF u;
      for (std::uint32_t j = nd.first; j < nd.first + nd.count; ++j) {
        const std::uint32_t t = bvh.prims[j];
        ASSERT_LT(t, n);
        prim_seen[t]++;
        ASSERT_TRUE(same_box(bvh.prim_boxes[j], boxes[t])) << "prim box " << j;
        ASSERT_TRUE(box_contains(nd.box, bvh.prim_boxes[j]));
        for (const Vec3& p : mesh.corners(t)) ASSERT_TRUE(box_contains_point(nd.box, p));
        u.expand(bvh.prim_boxes[j]);
      }
      if (tight) {
        ASSERT_TRUE(same_box(u, nd.box)) << "leaf " << i;
      }
      continue;
    }
    ASSERT_GT(nd.first, i) << "children after their parent";
    ASSERT_LT(std::size_t{nd.first} + 1, bvh.nodes.size());
    if (!done) {
      stack.push_back({i, true});
      for (std::uint32_t c = nd.first; c < nd.first + 2; ++c) {
        ASSERT_EQ(node_seen[c], 0) << "node reached twice";
        node_seen[c] = 1;
        stack.push_back({c, false});
      }
      continue;
    }
    const BvhNode& c0 = bvh.nodes[nd.first];
    const BvhNode& c1 = bvh.nodes[nd.first + 1];
    ASSERT_TRUE(box_contains(nd.box, c0.box));
    ASSERT_TRUE(box_contains(nd.box, c1.box));
    if (tight) {
      AabbF u = c0.box;
      u.expand(c1.box);
      ASSERT_TRUE(same_box(u, nd.box)) << "inner " << i;
    }
    // Descendants: pair, then c0's descendants, then c1's, contiguous.
    std::size_t hi = nd.first + 2, count = 2;
    for (std::uint32_t c = nd.first; c < nd.first + 2; ++c) {
      const Range& r = desc[c];
      if (r.count == 0) continue;
      ASSERT_EQ(r.lo, hi) << "descendants of " << c << " not contiguous";
      hi = r.hi;
      count += r.count;
    }
    desc[i] = {nd.first, hi, count};
    ASSERT_EQ(hi - nd.first, count);
  }
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
    ASSERT_EQ(node_seen[i], 1) << "unreached " << i;
  for (std::size_t t = 0; t < n; ++t) ASSERT_EQ(prim_seen[t], 1) << "triangle " << t;
}

std::uint32_t leaf_limit(BvhBuilder b, std::uint32_t max_leaf) {
  return b == BvhBuilder::insertion ? 1 : max_leaf;
}

Pairs brute_overlaps(const TriMesh& a, const TriMesh& b, float margin) {
  const auto ba = triangle_boxes(a), bb = triangle_boxes(b);
  Pairs out;
  for (std::uint32_t i = 0; i < ba.size(); ++i) {
    for (std::uint32_t j = 0; j < bb.size(); ++j) {
      if (boxes_overlap(ba[i], bb[j], margin)) out.push_back({i, j});
    }
  }
  return out;
}

Pairs sorted(Pairs p) {
  std::sort(p.begin(), p.end());
  return p;
}

Pairs parallel_pairs(const Bvh& a, const Bvh& b, float margin, std::uint32_t target) {
  return collide_parallel<std::pair<std::uint32_t, std::uint32_t>>(
      a, b, ParallelTraversalOptions{.margin = margin, .target_tasks = target},
      [](std::uint32_t ia, std::uint32_t ib, Pairs& out) {
        out.push_back({ia, ib});
      });
}

bool same_tree(const Bvh& x, const Bvh& y) {
  return x.nodes.size() == y.nodes.size() && x.prims == y.prims &&
         x.prim_boxes.size() == y.prim_boxes.size() &&
         std::memcmp(x.nodes.data(), y.nodes.data(), x.nodes.size() * sizeof(BvhNode)) == 0 &&
         std::memcmp(x.prim_boxes.data(), y.prim_boxes.data(),
                     x.prim_boxes.size() * sizeof(AabbF)) == 0;
}

// ---------------------------------------------------------------------------------------------------

TEST(TriangleBoxes, MatchOutwardRoundingOfTheDoubleBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> e(-40, 40);
  TriMesh m;
  for (int i = 0; i < 3000; ++i) {
    m.positions.push_back({u(rng) * std::ldexp(1.0, e(rng)), u(rng) * std::ldexp(1.0, e(rng)),
                           u(rng) * std::ldexp(1.0, e(rng))});
  }
  m.positions.push_back({0, -0.0, 1e-300});  // zeros and values that round to zero
  m.positions.push_back({-1e-300, 3.0, 0.1});
  m.positions.push_back({1e300, -1e300, 0.5});  // beyond float range
  for (std::uint32_t i = 0; i + 2 < m.positions.size(); ++i)
    m.triangles.push_back({i, i + 1, i + 2});
  const auto boxes = triangle_boxes(m);
  ASSERT_EQ(boxes.size(), m.num_triangles());
  for (std::size_t t = 0; t < boxes.size(); ++t) {
    const AabbF ref = to_float_outward(m.triangle_box(t));
    ASSERT_TRUE(same_box(boxes[t], ref)) << t;
    for (const Vec3& p : m.corners(t)) ASSERT_TRUE(box_contains_point(boxes[t], p));
  }
}

class BuilderTest : public ::testing::TestWithParam<BvhBuilder> {};

TEST_P(BuilderTest, SphereTreeIsValid) {
  const TriMesh m = sphere(6000);
  for (std::uint32_t leaf : {1u, 4u, 8u}) {
    const Bvh bvh = build_bvh(m, {.builder = GetParam(), .max_leaf_size = leaf});
    check_tree(bvh, m, leaf_limit(GetParam(), leaf));
  }
}

TEST_P(BuilderTest, RandomSoupTreeIsValid) {
  const TriMesh m = random_soup(3000, 1);
  const Bvh bvh = build_bvh(m, {.builder = GetParam()});
  check_tree(bvh, m, leaf_limit(GetParam(), 4));
}

TEST_P(BuilderTest, FlatAxisAlignedTrianglesTreeIsValid) {
  const TriMesh m = make_box({-1, -2, -3}, {1, 2, 3}, 12);  // zero-volume triangle boxes
  const Bvh bvh = build_bvh(m, {.builder = GetParam()});
  check_tree(bvh, m, leaf_limit(GetParam(), 4));
}

TEST_P(BuilderTest, CoincidentCentroidsTreeIsValid) {
  for (std::size_t n : {5u, 100u, 5000u}) {
    const TriMesh m = coincident(n);
    const Bvh bvh = build_bvh(m, {.builder = GetParam()});
    check_tree(bvh, m, leaf_limit(GetParam(), 4));
  }
}

TEST_P(BuilderTest, EmptyAndOneTriangle) {
  const Bvh empty = build_bvh(TriMesh{}, {.builder = GetParam()});
  EXPECT_TRUE(empty.empty());
  EXPECT_TRUE(empty.prims.empty());
  const TriMesh one = one_triangle();
  const Bvh bvh = build_bvh(one, {.builder = GetParam()});
  check_tree(bvh, one, 1);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_TRUE(bvh.nodes[0].is_leaf());
  EXPECT_EQ(bvh.prims, std::vector<std::uint32_t>{0});
}

TEST_P(BuilderTest, SameTreeForOneAndTwoThreads) {
  // Large enough for the parallel paths (parallel binning/partition above 2^16 refs).
  const TriMesh m = GetParam() == BvhBuilder::insertion ? sphere(20000) : sphere(300000);
  Bvh one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = build_bvh(m, {.builder = GetParam()});
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = build_bvh(m, {.builder = GetParam()});
  }
  EXPECT_TRUE(same_tree(one, two));
  check_tree(two, m, leaf_limit(GetParam(), 4));
}

TEST_P(BuilderTest, RefitAfterMovingVerticesEqualsFreshBoxes) {
  const TriMesh m = sphere(GetParam() == BvhBuilder::insertion ? 8000 : 60000);
  Bvh bvh = build_bvh(m, {.builder = GetParam()});
  TriMesh moved = m;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Vec3& p : moved.positions) {
    const double a = 0.7 * p.z;  // twist about z plus noise
    p = Vec3{std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y,
             1.5 * p.z} +
        Vec3{u(rng), u(rng), u(rng)};
  }
  Bvh one = bvh, two = bvh;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    refit_bvh(one, moved);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    refit_bvh(two, moved);
  }
  EXPECT_TRUE(same_tree(one, two));
  EXPECT_EQ(two.prims, bvh.prims);
  check_tree(two, moved, leaf_limit(GetParam(), 4), /*tight=*/true);
  // Refitting back to the original vertices gives the original tree.
  refit_bvh(two, m);
  EXPECT_TRUE(same_tree(two, bvh));
}

TEST_P(BuilderTest, OverlapsEqualBruteForce) {
  struct Case {
    TriMesh a, b;
  };
  std::vector<Case> cases;
  cases.push_back({sphere(1500), sphere(1200, {1.2, 0.3, 0.1}, 0.3)});
  cases.push_back({random_soup(700, 11), random_soup(900, 12, 0.05, {0.3, 0, 0})});
  cases.push_back({make_box({0, 0, 0}, {1, 1, 1}, 8), sphere(800, {0.9, 0.9, 0.5})});
  cases.push_back({coincident(40), one_triangle()});
  for (const Case& c : cases) {
    for (BvhBuilder other : kBuilders) {
      const Bvh a = build_bvh(c.a, {.builder = GetParam()});
      const Bvh b = build_bvh(c.b, {.builder = other});
      for (float margin : {0.0f, 0.01f, 0.2f}) {
        const Pairs brute = brute_overlaps(c.a, c.b, margin);
        Pairs serial;
        for_each_overlap(a, b, margin, [&](std::uint32_t i, std::uint32_t j) {
          serial.push_back({i, j});
        });
        EXPECT_EQ(serial.size(), brute.size());
        EXPECT_EQ(sorted(serial), brute) << "margin " << margin;
        const Pairs par = parallel_pairs(a, b, margin, 64);
        EXPECT_EQ(sorted(par), brute) << "margin " << margin;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBuilders, BuilderTest, ::testing::ValuesIn(kBuilders),
                         [](const auto& info) {
                           return std::string(bvh_builder_name(info.param));
                         });

TEST(Bvh, BuilderNames) {
  EXPECT_STREQ(bvh_builder_name(BvhBuilder::insertion), "insertion");
  EXPECT_STREQ(bvh_builder_name(BvhBuilder::median_split), "median_split");
  EXPECT_STREQ(bvh_builder_name(BvhBuilder::binned_sah), "binned_sah");
  EXPECT_STREQ(bvh_builder_name(BvhBuilder::lbvh), "lbvh");
  EXPECT_STREQ(bvh_builder_name(BvhBuilder::lbvh_treelet), "lbvh_treelet");
  EXPECT_EQ(BvhBuildOptions{}.builder, BvhBuilder::lbvh);
}

int tree_depth(const Bvh& bvh) {
  int depth = 0;
  std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, d] = stack.back();
    stack.pop_back();
    depth = std::max(depth, d);
    if (!bvh.nodes[i].is_leaf()) {
      stack.push_back({bvh.nodes[i].first, d + 1});
      stack.push_back({bvh.nodes[i].first + 1, d + 1});
    }
  }
  return depth;
}

TEST(Bvh, DepthStaysLogarithmicOnDuplicatesAndStrips) {
  // Identical triangles (every box ties) and a strip in input order (each triangle next to the
  // last) are the inputs that make naive insertion or SAH degenerate.
  TriMesh strip;
  for (std::uint32_t i = 0; i < 20000; ++i) {
    strip.positions.push_back({0.001 * i, 0, 0});
    strip.positions.push_back({0.001 * i, 1, 0});
    strip.triangles.push_back({2 * i, 2 * i + 1, i > 0 ? 2 * i - 1 : 1});
  }
  for (const TriMesh* m : {&strip}) {
    for (BvhBuilder b : kBuilders) {
      const Bvh bvh = build_bvh(*m, {.builder = b});
      check_tree(bvh, *m, leaf_limit(b, 4));
      EXPECT_LE(tree_depth(bvh), 64) << bvh_builder_name(b);
    }
  }
  const TriMesh dup = coincident(20000);
  for (BvhBuilder b : kBuilders) {
    const Bvh bvh = build_bvh(dup, {.builder = b});
    EXPECT_LE(tree_depth(bvh), 64) << bvh_builder_name(b);
  }
}

TEST(Bvh, LeafSizeZeroIsTreatedAsOne) {
  const TriMesh m = sphere(500);
  for (BvhBuilder b : {BvhBuilder::median_split, BvhBuilder::binned_sah, BvhBuilder::lbvh,
                       BvhBuilder::lbvh_treelet}) {
    check_tree(build_bvh(m, {.builder = b, .max_leaf_size = 0}), m, 1);
  }
}

// ---------------------------------------------------------------------------------------------------
// Treelet restructuring (lbvh_treelet).

// A long thin mesh: a sphere stretched 40:1:0.5 (elongated triangles, flat boxes).
TriMesh needle(std::size_t n) {
  TriMesh m = sphere(n);
  for (Vec3& p : m.positions) p = Vec3{40.0 * p.x, p.y, 0.5 * p.z};
  return m;
}

double half_area(const AabbF& b) {
  const double dx = double{b.hi[0]} - b.lo[0], dy = double{b.hi[1]} - b.lo[1];
  const double dz = double{b.hi[2]} - b.lo[2];
  return dx * dy + dy * dz + dz * dx;
}

// The leaves as their 8 words (box bits, first, count), sorted: the same multiset for lbvh and
// lbvh_treelet.
std::vector<std::array<std::uint32_t, 8>> leaf_set(const Bvh& bvh) {
  std::vector<std::array<std::uint32_t, 8>> out;
  for (const BvhNode& n : bvh.nodes) {
    if (!n.is_leaf()) continue;
    std::array<std::uint32_t, 8> words;
    std::memcpy(words.data(), &n, sizeof(BvhNode));
    out.push_back(words);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Treelet, SahCostNeverAboveLbvhAndFallsWithPasses) {
  std::vector<std::pair<const char*, TriMesh>> meshes;
  meshes.emplace_back("sphere", sphere(20000));
  meshes.emplace_back("soup", random_soup(15000, 31));
  meshes.emplace_back("sparse soup", random_soup(8000, 32, 0.01));
  meshes.emplace_back("needle", needle(12000));
  for (const auto& [name, m] : meshes) {
    for (std::uint32_t leaf : {1u, 4u}) {
      const Bvh lbvh = build_bvh(m, {.builder = BvhBuilder::lbvh, .max_leaf_size = leaf});
      double last = bvh_sah_cost(lbvh);
      Bvh best;
      for (std::uint32_t passes : {1u, 2u, 3u}) {
        const Bvh t = build_bvh(
            m,
            {.builder = BvhBuilder::lbvh_treelet, .max_leaf_size = leaf, .treelet_passes = passes});
        check_tree(t, m, leaf);
        // Restructuring keeps the leaves (and the triangle order) and only rewires inner nodes.
        EXPECT_EQ(t.prims, lbvh.prims);
        EXPECT_EQ(t.nodes.size(), lbvh.nodes.size());
        EXPECT_EQ(leaf_set(t), leaf_set(lbvh)) << name;
        const double cost = bvh_sah_cost(t);
        EXPECT_LE(cost, last * (1 + 1e-12)) << name << " leaf " << leaf << " passes " << passes;
        last = cost;
        best = t;
      }
      // A clear gain, not just "not worse": the inner-node term (the leaves are the same) falls
      // by 2.4 % (overlapping soup, 4-triangle leaves) to 33 % (needle, 1-triangle leaves).
      EXPECT_LT(bvh_sah_cost(best, 1, 0), 0.99 * bvh_sah_cost(lbvh, 1, 0))
          << name << " leaf " << leaf;
    }
  }
}

TEST(Treelet, ZeroPassesIsTheLbvhTree) {
  const TriMesh m = random_soup(5000, 33);
  const Bvh lbvh = build_bvh(m, {.builder = BvhBuilder::lbvh});
  EXPECT_TRUE(
      same_tree(build_bvh(m, {.builder = BvhBuilder::lbvh_treelet, .treelet_passes = 0}), lbvh));
}

// Minimum over all binary trees with the given leaf boxes of the sum of the inner nodes' areas
// (exhaustive recursion over splits, no memo: an independent reference for the DP).
double best_tree_cost(const std::vector<AabbF>& leaves, unsigned set) {
  if ((set & (set - 1)) == 0) return 0;
  AabbF box;
  for (unsigned j = 0; j < leaves.size(); ++j) {
    if (set & (1u << j)) box.expand(leaves[j]);
  }
  double best = std::numeric_limits<double>::infinity();
  for (unsigned p = (set - 1) & set; p != 0; p = (p - 1) & set) {
    best = std::min(best, best_tree_cost(leaves, p) + best_tree_cost(leaves, set ^ p));
  }
  return half_area(box) + best;
}

TEST(Treelet, TreesOfUpToSevenLeavesBecomeSahOptimal) {
  // With at most 7 leaves the root's treelet is the whole tree: one pass must reach the optimum
  // over all topologies (up to the 2^-16 gain a rewiring needs).
  for (std::size_t n = 3; n <= 7; ++n) {
    for (std::uint32_t seed = 0; seed < 40; ++seed) {
      const TriMesh m = random_soup(n, 100 + seed, 0.3);
      const Bvh t = build_bvh(
          m, {.builder = BvhBuilder::lbvh_treelet, .max_leaf_size = 1, .treelet_passes = 1});
      check_tree(t, m, 1);
      std::vector<AabbF> leaves;
      double inner = 0;
      for (const BvhNode& nd : t.nodes) {
        if (nd.is_leaf()) {
          leaves.push_back(nd.box);
        } else {
          inner += half_area(nd.box);
        }
      }
      ASSERT_EQ(leaves.size(), n);
      const double opt = best_tree_cost(leaves, (1u << n) - 1);
      EXPECT_LE(inner, opt * (1 + 0x1p-15)) << "n " << n << " seed " << seed;
      EXPECT_GE(inner, opt * (1 - 1e-12));
    }
  }
}

TEST(Treelet, SameTreeForOneAndTwoThreadsWithThreePasses) {
  const TriMesh m = random_soup(200000, 34, 0.02);
  const BvhBuildOptions o{.builder = BvhBuilder::lbvh_treelet, .treelet_passes = 3};
  Bvh one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = build_bvh(m, o);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = build_bvh(m, o);
  }
  EXPECT_TRUE(same_tree(one, two));
  check_tree(two, m, 4);
}

TEST(Bvh, SahCostOfSmallTrees) {
  EXPECT_EQ(bvh_sah_cost(Bvh{}), 0.0);
  const TriMesh one = one_triangle();
  const Bvh leaf = build_bvh(one);
  EXPECT_DOUBLE_EQ(bvh_sah_cost(leaf), 1.0);  // one leaf of one triangle, area ratio 1
  EXPECT_DOUBLE_EQ(bvh_sah_cost(leaf, 1.0, 2.5), 2.5);
  // Two leaves of half-area 1 ([0,1]x[0,1]x{0}, [1,2]x[0,1]x{0}) under a root of half-area 2.
  TriMesh two;
  two.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
  two.triangles = {{0, 1, 2}, {3, 4, 5}};
  const Bvh t = build_bvh(two, {.max_leaf_size = 1});
  ASSERT_EQ(t.nodes.size(), 3u);
  EXPECT_DOUBLE_EQ(bvh_sah_cost(t), (2.0 + 1.0 + 1.0) / 2.0);
  EXPECT_DOUBLE_EQ(bvh_sah_cost(t, 2.0, 0.0), 2.0);
}

TEST(Bvh, RefitEmptyTreeIsANoOpAndAWrongMeshThrows) {
  Bvh empty;
  refit_bvh(empty, TriMesh{});
  EXPECT_TRUE(empty.empty());
  Bvh bvh = build_bvh(sphere(500));
  EXPECT_THROW(refit_bvh(bvh, sphere(2000)), std::invalid_argument);
  EXPECT_THROW(refit_bvh(empty, one_triangle()), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------

TEST(CollideParallel, SameOutputForAnyThreadCountAndSameSetForAnyTaskCount) {
  const SpherePair p = make_overlapping_spheres(40000);
  const Bvh a = build_bvh(p.a), b = build_bvh(p.b);
  for (float margin : {0.0f, 0.02f}) {
    Pairs serial;
    for_each_overlap(a, b, margin, [&](std::uint32_t i, std::uint32_t j) {
      serial.push_back({i, j});
    });
    ASSERT_FALSE(serial.empty());
    const Pairs reference = sorted(serial);
    EXPECT_EQ(std::adjacent_find(reference.begin(), reference.end()), reference.end())
        << "duplicates";
    for (std::uint32_t target : {0u, 1u, 7u, 64u, 4096u, 1000000u}) {
      Pairs one, two;
      {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = parallel_pairs(a, b, margin, target);
      }
      {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = parallel_pairs(a, b, margin, target);
      }
      EXPECT_EQ(one, two) << "target " << target;
      EXPECT_EQ(sorted(two), reference) << "target " << target;
    }
  }
}

TEST(CollideParallel, MatchesBruteForceWithMargin) {
  const TriMesh ma = sphere(3000), mb = sphere(2500, {1.9, 0.2, 0}, 0.2);
  const Bvh a = build_bvh(ma), b = build_bvh(mb);
  for (float margin : {0.0f, 0.05f, 0.15f}) {
    EXPECT_EQ(sorted(parallel_pairs(a, b, margin, 4096)), brute_overlaps(ma, mb, margin));
  }
}

TEST(CollideParallel, ResultsCarryTheCallbacksOutputs) {
  const TriMesh ma = sphere(2000), mb = sphere(2000, {1.5, 0, 0});
  const Bvh a = build_bvh(ma), b = build_bvh(mb);
  // Two outputs per pair, none for odd triangles of A: the concatenation keeps every output.
  const auto out =
      collide_parallel<std::uint64_t>(a, b, {}, [](std::uint32_t i, std::uint32_t j, auto& v) {
        if (i % 2) return;
        v.push_back((std::uint64_t{i} << 32) | j);
        v.push_back((std::uint64_t{i} << 32) | j);
      });
  std::size_t expected = 0;
  for (const auto& [i, j] : brute_overlaps(ma, mb, 0)) expected += (i % 2) ? 0 : 2;
  EXPECT_GT(expected, 0u);  // (an empty result would match an empty expectation)
  EXPECT_EQ(out.size(), expected);
}

TEST(CollideParallel, EmptyTreesAndDisjointRoots) {
  const TriMesh m = sphere(500);
  const Bvh a = build_bvh(m), empty;
  EXPECT_TRUE(parallel_pairs(a, empty, 0, 64).empty());
  EXPECT_TRUE(parallel_pairs(empty, a, 0, 64).empty());
  EXPECT_TRUE(split_node_pairs(empty, empty, {}).empty());
  const Bvh far = build_bvh(sphere(500, {10, 0, 0}));
  EXPECT_TRUE(parallel_pairs(a, far, 0, 64).empty());
  EXPECT_FALSE(parallel_pairs(a, far, 8.5f, 64).empty());  // the margin reaches it
  int calls = 0;
  for_each_overlap(a, empty, 1.0f, [&](std::uint32_t, std::uint32_t) { ++calls; });
  for_each_overlap(a, far, 0.0f, [&](std::uint32_t, std::uint32_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(CollideParallel, OneTriangleTrees) {
  const TriMesh one = one_triangle();
  const Bvh a = build_bvh(one), b = build_bvh(one);
  EXPECT_EQ(parallel_pairs(a, b, 0, 4096), (Pairs{{0, 0}}));
  Pairs s;
  for_each_overlap(a, b, 0, [&](std::uint32_t i, std::uint32_t j) { s.push_back({i, j}); });
  EXPECT_EQ(s, (Pairs{{0, 0}}));
}

TEST(SplitNodePairs, TasksOverlapStayBelowTargetAndCoverEverything) {
  const SpherePair p = make_overlapping_spheres(20000);
  const Bvh a = build_bvh(p.a), b = build_bvh(p.b);
  for (std::uint32_t target : {1u, 2u, 3u, 10u, 100u, 1000u, 100000u}) {
    const auto tasks = split_node_pairs(a, b, {.margin = 0.01f, .target_tasks = target});
    ASSERT_FALSE(tasks.empty());
    EXPECT_LE(tasks.size(), std::max<std::size_t>(1, target));
    std::set<std::pair<std::uint32_t, std::uint32_t>> unique(tasks.begin(), tasks.end());
    EXPECT_EQ(unique.size(), tasks.size());
    for (const auto& [ia, ib] : tasks) {
      EXPECT_TRUE(boxes_overlap(a.nodes[ia].box, b.nodes[ib].box, 0.01f));
    }
  }
  // A huge target expands down to leaf-leaf pairs only.
  const auto all = split_node_pairs(a, b, {.target_tasks = 1u << 30});
  for (const auto& [ia, ib] : all) {
    EXPECT_TRUE(a.nodes[ia].is_leaf() && b.nodes[ib].is_leaf());
  }
}

// ---------------------------------------------------------------------------------------------------

TEST(ForEachInBox, MatchesBruteForce) {
  const TriMesh m = random_soup(3000, 5);
  const auto boxes = triangle_boxes(m);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f), s(0.0f, 0.6f);
  for (BvhBuilder builder : kBuilders) {
    const Bvh bvh = build_bvh(m, {.builder = builder});
    for (int q = 0; q < 60; ++q) {
      AabbF box;
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = u(rng);
        box.hi[k] = box.lo[k] + (q % 10 == 0 ? 0.0f : s(rng));  // some zero-extent boxes
      }
      std::vector<std::uint32_t> got, want;
      for_each_in_box(bvh, box, [&](std::uint32_t t) { got.push_back(t); });
      for (std::uint32_t t = 0; t < boxes.size(); ++t) {
        if (boxes_overlap(box, boxes[t], 0.0f)) want.push_back(t);
      }
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want);
    }
    std::vector<std::uint32_t> none;
    for_each_in_box(Bvh{}, AabbF{}, [&](std::uint32_t t) { none.push_back(t); });
    AabbF far;
    for (int k = 0; k < 3; ++k) far.lo[k] = 5, far.hi[k] = 6;
    for_each_in_box(bvh, far, [&](std::uint32_t t) { none.push_back(t); });
    EXPECT_TRUE(none.empty());
  }
}

// ---------------------------------------------------------------------------------------------------

double vertex_distance2(const TriMesh& a, std::uint32_t ia, const TriMesh& b, std::uint32_t ib) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : a.corners(ia)) {
    for (const Vec3& q : b.corners(ib)) best = std::min(best, squared_norm(p - q));
  }
  return best;
}

TEST(BoxDistance, IsALowerBoundAndZeroOnOverlap) {
  AabbF a, b;
  for (int k = 0; k < 3; ++k) a.lo[k] = 0, a.hi[k] = 1, b.lo[k] = 0.5f, b.hi[k] = 2;
  EXPECT_EQ(box_distance_squared(a, b), 0.0);
  b.lo[0] = 4, b.hi[0] = 5;  // gap 3 on x
  b.lo[1] = 3, b.hi[1] = 3;  // gap 2 on y
  const double d2 = box_distance_squared(a, b);
  EXPECT_LE(d2, 13.0);
  EXPECT_GT(d2, 13.0 * (1 - 1e-14));
  EXPECT_EQ(box_distance_squared(a, b), box_distance_squared(b, a));
}

TEST(ForEachPairWithin, MinimumDistanceMatchesBruteForce) {
  struct Case {
    TriMesh a, b;
  };
  std::vector<Case> cases;
  cases.push_back({sphere(800), sphere(600, {2.3, 0.4, 0.2}, 0.2)});
  cases.push_back({random_soup(400, 21, 0.05), random_soup(300, 22, 0.05, {2.5, 0, 0})});
  cases.push_back({random_soup(300, 23), random_soup(300, 24)});  // interleaved
  cases.push_back({one_triangle(), sphere(200, {3, 0, 0})});
  for (const Case& c : cases) {
    double brute = std::numeric_limits<double>::infinity();
    for (std::uint32_t i = 0; i < c.a.num_triangles(); ++i) {
      for (std::uint32_t j = 0; j < c.b.num_triangles(); ++j)
        brute = std::min(brute, vertex_distance2(c.a, i, c.b, j));
    }
    for (BvhBuilder builder : kBuilders) {
      const Bvh a = build_bvh(c.a, {.builder = builder}), b = build_bvh(c.b, {.builder = builder});
      std::size_t visits = 0;
      const double got = for_each_pair_within(a, b, std::numeric_limits<double>::infinity(),
                                              [&](std::uint32_t i, std::uint32_t j, double box_d2) {
                                                ++visits;
                                                const double d2 = vertex_distance2(c.a, i, c.b, j);
                                                EXPECT_LE(box_d2, d2);
                                                return d2;
                                              });
      EXPECT_EQ(got, brute) << bvh_builder_name(builder);
      EXPECT_LT(visits, c.a.num_triangles() * c.b.num_triangles());
    }
  }
}

TEST(ForEachPairWithin, ListsAllPairsWithinAFixedBound) {
  const TriMesh ma = sphere(700), mb = sphere(500, {2.1, 0, 0}, 0.1);
  const Bvh a = build_bvh(ma), b = build_bvh(mb, {.builder = BvhBuilder::median_split});
  const auto ba = triangle_boxes(ma), bb = triangle_boxes(mb);
  for (double c : {0.0, 0.05, 0.2, 0.5}) {
    Pairs got, want;
    for_each_pair_within(a, b, c * c, [&](std::uint32_t i, std::uint32_t j, double) {
      got.push_back({i, j});
      return c * c;
    });
    for (std::uint32_t i = 0; i < ba.size(); ++i) {
      for (std::uint32_t j = 0; j < bb.size(); ++j) {
        if (box_distance_squared(ba[i], bb[j]) <= c * c) want.push_back({i, j});
      }
    }
    EXPECT_EQ(sorted(got), want) << c;
    if (c >= 0.2) {
      EXPECT_FALSE(want.empty());
    }
  }
}

TEST(ForEachPairWithin, NegativeReturnStopsAndEmptyTreesAreNoOps) {
  const TriMesh m = sphere(500);
  const Bvh a = build_bvh(m), b = build_bvh(m);
  int calls = 0;
  for_each_pair_within(a, b, 1.0, [&](std::uint32_t, std::uint32_t, double) {
    ++calls;
    return -1.0;
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(
      for_each_pair_within(a, Bvh{}, 2.0, [](std::uint32_t, std::uint32_t, double) { return 0.0; }),
      2.0);
}

}  // namespace
}  // namespace interfere
