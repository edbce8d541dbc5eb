// cad::assembly_clash: every instance pair of an assembly, on hand-built models (no STEP needed):
// known meetings (crossing, touching, contained, within a clearance) and, on random layouts, the
// pairs found against a brute-force clash of every pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "interfere/cad/assembly_clash.h"
#include "interfere/mesh/generate.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "interfere/query/model.h"

namespace interfere::cad {
namespace {

Transform moved(double x, double y, double z) {
  Transform t;
  t.t = {x, y, z};
  return t;
}

CadModel boxes(const std::vector<std::pair<std::uint32_t, Transform>>& instances) {
  CadModel m;
  m.parts.resize(2);
  m.parts[0].name = "block";
  m.parts[0].mesh = make_box({0, 0, 0}, {1, 1, 1}, 4);
  m.parts[1].name = "cube";
  m.parts[1].mesh = make_box({0, 0, 0}, {0.2, 0.2, 0.2}, 3);
  for (const auto& [part, t] : instances)
    m.instances.push_back({.name = "i" + std::to_string(m.instances.size()), .part = part, .placement = t});
  return m;
}

TEST(AssemblyClash, CrossingTouchingContainedAndNearPairs) {
  const CadModel m = boxes({{0, Transform{}},          // 0
                            {0, moved(0.5, 0, 0)},     // 1: overlaps 0 (coplanar faces: touching only)
                            {0, moved(0, 0, 1)},       // 2: on top of 0 and 1 (face contact)
                            {1, moved(0.4, 0.4, 0.4)},  // 3: inside 0, crossing 1's face x = 0.5
                            {0, moved(5, 0, 0)},       // 4
                            {0, moved(6.05, 0, 0)}});  // 5: 0.05 from 4
  std::map<std::pair<std::uint32_t, std::uint32_t>, InstancePairResult> got;
  auto r = assembly_clash(m, {.clearance = 0.1});
  for (const auto& p : r.pairs) got[{p.a, p.b}] = p;
  ASSERT_EQ(got.size(), 6u);
  EXPECT_EQ(got.at({0, 1}).meeting, InstanceMeeting::clash);
  EXPECT_EQ(got.at({0, 1}).cross_pairs, 0u);
  EXPECT_TRUE(got.at({0, 1}).touching_overlap);
  EXPECT_EQ(got.at({0, 2}).meeting, InstanceMeeting::contact);
  EXPECT_EQ(got.at({0, 2}).cross_pairs, 0u);
  EXPECT_FALSE(got.at({0, 2}).touching_overlap);
  EXPECT_GT(got.at({0, 2}).touch_pairs, 0u);
  EXPECT_EQ(got.at({1, 2}).meeting, InstanceMeeting::contact);
  EXPECT_EQ(got.at({0, 3}).meeting, InstanceMeeting::clash);  // by containment alone
  EXPECT_EQ(got.at({0, 3}).cross_pairs + got.at({0, 3}).touch_pairs, 0u);
  EXPECT_EQ(got.at({0, 3}).containment, Containment::b_inside_a);
  EXPECT_EQ(got.at({1, 3}).meeting, InstanceMeeting::clash);
  EXPECT_GT(got.at({1, 3}).cross_pairs, 0u);
  EXPECT_EQ(got.at({4, 5}).meeting, InstanceMeeting::clearance);
  EXPECT_NEAR(got.at({4, 5}).min_clearance, 0.05, 1e-12);
  EXPECT_EQ(r.clashes, 3u);
  EXPECT_EQ(r.contacts, 2u);
  EXPECT_EQ(r.within_clearance, 1u);
  EXPECT_TRUE(r.warnings.empty());
  // Without a clearance the near pair is not reported, and is no candidate.
  auto plain = assembly_clash(m);
  EXPECT_EQ(plain.pairs.size(), 5u);
  EXPECT_EQ(plain.within_clearance, 0u);
  EXPECT_LT(plain.candidate_pairs, r.candidate_pairs);
  for (const auto& p : r.pairs) EXPECT_TRUE(p.curves.empty() && p.region_triangles_a.empty());  // not asked for
}

TEST(AssemblyClash, GeometryOfTheClashingPairs) {
  // With geometry: a crossing pair's curves lie on both surfaces and its region triangles are
  // those of the clash's regions; a contained instance is all region; contacts keep nothing.
  const CadModel m = boxes({{0, Transform{}},            // 0
                            {0, moved(0, 0, 1)},         // 1: on top of 0 (contact)
                            {1, moved(0.4, 0.4, 0.4)},   // 2: inside 0
                            {1, moved(0.9, 0.4, 0.4)}});  // 3: crossing 0's face x = 1
  std::map<std::pair<std::uint32_t, std::uint32_t>, InstancePairResult> got;
  for (const auto& p : assembly_clash(m, {.geometry = true}).pairs) got[{p.a, p.b}] = p;
  const InstancePairResult& contact = got.at({0, 1});
  EXPECT_EQ(contact.meeting, InstanceMeeting::contact);
  EXPECT_TRUE(contact.curves.empty() && contact.region_triangles_a.empty() && contact.region_triangles_b.empty());
  const InstancePairResult& inside = got.at({0, 2});
  EXPECT_EQ(inside.containment, Containment::b_inside_a);
  EXPECT_TRUE(inside.region_triangles_a.empty());
  EXPECT_EQ(inside.region_triangles_b.size(), m.parts[1].mesh.num_triangles());
  const InstancePairResult& crossing = got.at({0, 3});
  ASSERT_EQ(crossing.meeting, InstanceMeeting::clash);
  // The same triangles as the engine's clash of the two placed meshes.
  const Model a = make_model(transformed(m.parts[0].mesh, m.instances[0].placement));
  const Model b = make_model(transformed(m.parts[1].mesh, m.instances[3].placement));
  const ClashResult direct = clash(a, b);
  std::vector<std::uint32_t> ta, tb;
  for (const TrianglePair& q : direct.pairs) ta.push_back(q.a), tb.push_back(q.b);
  for (auto* v : {&ta, &tb}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  EXPECT_EQ(crossing.region_triangles_a, ta);
  EXPECT_EQ(crossing.region_triangles_b, tb);
  ASSERT_FALSE(crossing.curves.empty());
  double length = 0;
  for (const Polyline& c : crossing.curves) {
    for (const Vec3& p : c.points) EXPECT_NEAR(p.x, 1.0, 1e-12);  // on block 0's face x = 1
    length += c.length;
  }
  EXPECT_NEAR(length, 0.8, 1e-9);  // the cube's 0.2 x 0.2 section: four sides
  EXPECT_NEAR(length, crossing.curve_length, 1e-9);
}

// The deepest of dense samples of either surface inside the other solid (exact ray parity, the
// distance to the other surface): a lower bound of the true depth, from points depth_into does not
// look at (every triangle's interior on a 24 x 24 barycentric grid).
double dense_depth(const Model& x, const Model& y) {
  double deepest = 0;
  for (std::size_t t = 0; t < x.mesh.num_triangles(); ++t) {
    const auto c = x.mesh.corners(t);
    for (int i = 0; i <= 24; ++i)
      for (int j = 0; i + j <= 24; ++j) {
        const Vec3 p = c[0] + (c[1] - c[0]) * (i / 24.0) + (c[2] - c[0]) * (j / 24.0);
        if (point_in_solid(y, p) == 1) deepest = std::max(deepest, surface_distance(y, p));
      }
  }
  return deepest;
}

TEST(AssemblyClash, DepthBoundHoldsTheDenseSamplesAndIsTight) {
  // A cube through block 0's face x = 1 (0.1 deep), and a thin plate through the middle of block 0
  // whose two big triangles per face keep their edges away from the block's centre: the samples of
  // depth_into (vertices, edge stretches) miss its deepest points there (0.45 deep at (0.5, 0.5,
  // 0.55)), the bound must not.
  CadModel m = boxes({{0, Transform{}}, {1, moved(0.9, 0.4, 0.4)}});
  m.parts.push_back({.name = "plate", .mesh = make_box({-3, -0.2, 0.45}, {4, 2.2, 0.55}, 1)});
  m.instances.push_back({.name = "plate", .part = 2, .placement = Transform{}});
  std::map<std::pair<std::uint32_t, std::uint32_t>, InstancePairResult> got;
  for (const auto& p : assembly_clash(m).pairs) got[{p.a, p.b}] = p;
  for (const auto& [pair, p] : got) {
    if (p.cross_pairs == 0) continue;
    ASSERT_EQ(p.meeting, InstanceMeeting::clash);
    const Model a = make_model(transformed(m.parts[m.instances[pair.first].part].mesh, m.instances[pair.first].placement));
    const Model b = make_model(transformed(m.parts[m.instances[pair.second].part].mesh, m.instances[pair.second].placement));
    const double dense = std::max(dense_depth(a, b), dense_depth(b, a));
    EXPECT_LE(p.depth, p.depth_bound) << pair.first << " " << pair.second;
    EXPECT_LE(dense, p.depth_bound * (1 + 1e-12)) << pair.first << " " << pair.second;
    EXPECT_LE(p.depth_bound, 1.25 * std::max(dense, p.depth)) << pair.first << " " << pair.second;
  }
  EXPECT_NEAR(got.at({0, 1}).depth, 0.1, 1e-12);  // the cube: 0.1 into the block, the block 0.1 into it
  EXPECT_LT(got.at({0, 2}).depth, 0.2);           // the samples miss the plate's middle ...
  EXPECT_GE(got.at({0, 2}).depth_bound, 0.45);    // ... the bound holds it (the exact depth)
  // Without splits, no bound.
  for (const auto& p : assembly_clash(m, {.depth_bound_splits = 0}).pairs) EXPECT_EQ(p.depth_bound, 0);
}

TEST(AssemblyClash, DepthSamplesTheStretchesOfLongEdgesInsideTheOtherSolid) {
  // A rod of long triangles (every vertex outside) through a block: its long edges at y, z = 0.4
  // or 0.6 pass 0.4 from the block's faces at their middle; the block's vertices are outside.
  CadModel m = boxes({{0, Transform{}}});
  m.parts.push_back({.name = "rod", .mesh = make_box({-2, 0.4, 0.4}, {3, 0.6, 0.6}, 1)});
  m.instances.push_back({.name = "rod", .part = 2, .placement = Transform{}});
  const auto r = assembly_clash(m);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].meeting, InstanceMeeting::clash);
  EXPECT_GT(r.pairs[0].cross_pairs, 0u);
  EXPECT_NEAR(r.pairs[0].depth, 0.4, 1e-12);
  EXPECT_EQ(r.pairs[0].tessellation_error, 0.0);  // (parts not from STEP)
  // Only a vertex inside: a cube corner pushed 0.05 into the block's face.
  CadModel c = boxes({{0, Transform{}}, {1, moved(0.5, 0.5, 0.95)}});
  const auto rc = assembly_clash(c);
  ASSERT_EQ(rc.pairs.size(), 1u);
  EXPECT_NEAR(rc.pairs[0].depth, 0.05, 1e-12);
}

TEST(AssemblyClash, RandomLayoutsMatchABruteForceClashOfEveryPair) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(0, 3);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<std::pair<std::uint32_t, Transform>> inst;
    for (int k = 0; k < 14; ++k) inst.push_back({std::uint32_t(k % 2), moved(at(rng), at(rng), at(rng))});
    const CadModel m = boxes(inst);
    const double clearance = trial % 2 ? 0.15 : 0;
    const auto r = assembly_clash(m, {.clearance = clearance});
    std::vector<Model> w;
    for (const Instance& i : m.instances) {
      TriMesh t = transformed(m.parts[i.part].mesh, i.placement);
      weld_exact(t);
      w.push_back(make_model(std::move(t)));
    }
    std::size_t k = 0;
    for (std::uint32_t a = 0; a < w.size(); ++a)
      for (std::uint32_t b = a + 1; b < w.size(); ++b) {
        const ClashResult c = clash(w[a], w[b], {.clearance = clearance});
        const bool meets = c.interference() || !c.clearance.empty();
        if (!meets) continue;
        ASSERT_LT(k, r.pairs.size()) << "trial " << trial;
        EXPECT_EQ(r.pairs[k].a, a);
        EXPECT_EQ(r.pairs[k].b, b);
        EXPECT_EQ(r.pairs[k].cross_pairs, c.cross_pairs);
        EXPECT_EQ(r.pairs[k].touch_pairs, c.touch_pairs);
        EXPECT_EQ(r.pairs[k].clearance_pairs, c.clearance.size());
        EXPECT_EQ(r.pairs[k].touching_overlap, c.touching_overlap);
        ++k;
      }
    EXPECT_EQ(k, r.pairs.size()) << "trial " << trial;

    // The clash above is the engine assembly_clash itself runs on each pair: it checks the
    // instance pairs, not the meetings. Those come from the boxes' intervals (issue #23, item 14):
    // per axis the overlap min(hi) - max(lo) of the placed boxes (bounds fl(size + t), as the
    // transform rounds them); all positive: the interiors overlap (clash); all >= 0: contact;
    // otherwise the gap vector's length decides clearance or clear.
    std::map<std::pair<std::uint32_t, std::uint32_t>, InstanceMeeting> expected;
    std::map<std::pair<std::uint32_t, std::uint32_t>, double> gap;
    for (std::uint32_t a = 0; a < inst.size(); ++a)
      for (std::uint32_t b = a + 1; b < inst.size(); ++b) {
        double overlap[3], gap2 = 0;
        bool interior = true, closed = true;
        for (int axis = 0; axis < 3; ++axis) {
          const double sa = inst[a].first == 0 ? 1.0 : 0.2, sb = inst[b].first == 0 ? 1.0 : 0.2;
          const double lo_a = inst[a].second.t[axis], lo_b = inst[b].second.t[axis];
          overlap[axis] = std::min(sa + lo_a, sb + lo_b) - std::max(lo_a, lo_b);
          interior &= overlap[axis] > 0;
          closed &= overlap[axis] >= 0;
          if (overlap[axis] < 0) gap2 += overlap[axis] * overlap[axis];
        }
        if (interior) expected[{a, b}] = InstanceMeeting::clash;
        else if (closed) expected[{a, b}] = InstanceMeeting::contact;
        else if (std::sqrt(gap2) < clearance) expected[{a, b}] = InstanceMeeting::clearance, gap[{a, b}] = std::sqrt(gap2);
      }
    EXPECT_GT(expected.size(), 3u) << "trial " << trial;
    std::map<std::pair<std::uint32_t, std::uint32_t>, InstanceMeeting> got;
    for (const InstancePairResult& p : r.pairs) {
      got[{p.a, p.b}] = p.meeting;
      if (p.meeting == InstanceMeeting::clearance && gap.count({p.a, p.b}))
        EXPECT_NEAR(p.min_clearance, (gap[{p.a, p.b}]), 1e-12) << p.a << " " << p.b;
    }
    EXPECT_EQ(got, expected) << "trial " << trial;
  }
}

// Issue #23, item 13: an open instance where inside/outside decides is undecided, never a contact
// or clear; the assembly's verdict is the worst pair's.
TEST(AssemblyClash, OpenInstancesAreUndecided) {
  CadModel m = boxes({{0, Transform{}},            // 0: the block
                      {2, moved(-1, -1, -1)},      // 1: an open shell around the block (no crossing)
                      {0, moved(10, 0, 0)},        // 2
                      {0, moved(11, 0, 0)}});      // 3: a face contact with 2
  m.parts.resize(3);
  m.parts[2].name = "open_shell";
  m.parts[2].mesh = make_box({0, 0, 0}, {3, 3, 3}, 2);
  m.parts[2].mesh.triangles.pop_back();
  const AssemblyClashResult r = assembly_clash(m);
  std::map<std::pair<std::uint32_t, std::uint32_t>, InstancePairResult> got;
  for (const auto& p : r.pairs) got[{p.a, p.b}] = p;
  ASSERT_TRUE(got.count({0, 1}));
  EXPECT_EQ(got.at({0, 1}).meeting, InstanceMeeting::undecided);
  EXPECT_FALSE(got.at({0, 1}).verdict_reasons.empty());
  ASSERT_TRUE(got.count({2, 3}));
  EXPECT_EQ(got.at({2, 3}).meeting, InstanceMeeting::contact);
  EXPECT_EQ(r.undecided, 1u);
  EXPECT_EQ(r.contacts, 1u);
  EXPECT_EQ(r.verdict, Verdict::undecided);
  // A crossing anywhere makes the assembly a clash.
  m.instances.push_back({.name = "i4", .part = 0, .placement = moved(10.5, 0.5, 0.5)});
  EXPECT_EQ(assembly_clash(m).verdict, Verdict::clash);
}

}  // namespace
}  // namespace interfere::cad
