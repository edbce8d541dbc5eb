// Repeated configurations in the scene engine (engine_frame.cpp; issue #24, item 9): body pairs
// with the same two meshes in the same relative pose are decided once, in the first body's local
// frame, and every member gets the answer mapped to its own bodies and pose. Checked against:
//   - the generated assembly's construction (scene/generate.h knows which pairs overlap, touch or
//     stand apart by the gap; no clash query involved);
//   - each member pair checked alone (a two-body scene: nothing to share), clash for clash and field
//     for field, with source id tables that differ between instances of one mesh;
//   - the two-part query on the pair's world models (query/clash.h on make_model(transformed(...)),
//     no engine code): the same regions, and each crossing clash's world box holds the world
//     query's intersection curves;
//   - containment reasons naming each member's own bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"
#include "interfere/scene/scene.h"

namespace interfere::scene {
namespace {

using IdPair = std::pair<std::string, std::string>;

IdPair ordered(const std::string& x, const std::string& y) { return x < y ? IdPair{x, y} : IdPair{y, x}; }

std::set<IdPair> pairs_with(const Scene& s, const SceneClashResult& r, const std::string& test, Verdict v) {
  std::set<IdPair> out;
  for (const PairSummary& p : r.pairs)
    if (p.test == test && p.verdict == v) out.insert(ordered(s.bodies[p.a].id, s.bodies[p.b].id));
  return out;
}

std::set<IdPair> as_set(const std::vector<IdPair>& v) {
  std::set<IdPair> out;
  for (const auto& [x, y] : v) out.insert(ordered(x, y));
  return out;
}

Scene small_assembly(AssemblyInfo* info) {
  AssemblyGenOptions o;
  o.bodies = 7 * 40;
  o.segments = 24;
  o.clashes = 12;
  o.gaps = 6;
  o.seed = 7;
  return generate_assembly(o, info);
}

std::vector<ClashTest> hard_and_clearance() {
  ClashTest hard;
  hard.name = "hard";
  ClashTest clear;
  clear.name = "clearance";
  clear.mode = ClashMode::clearance;
  clear.clearance = 0.1;
  return {hard, clear};
}

TEST(SceneRepeats, GeneratedAssemblyMatchesItsConstructionWithOneCoreRunPerConfiguration) {
  AssemblyInfo info;
  const Scene s = small_assembly(&info);
  const SceneClashResult r = clash_scene(s, hard_and_clearance());
  EXPECT_EQ(pairs_with(s, r, "hard", Verdict::clash), as_set(info.clash_pairs));
  EXPECT_EQ(pairs_with(s, r, "hard", Verdict::contact), as_set(info.contact_pairs));
  EXPECT_EQ(pairs_with(s, r, "clearance", Verdict::clearance), as_set(info.gap_pairs));
  EXPECT_EQ(pairs_with(s, r, "hard", Verdict::undecided).size(), 0u);
  // The joints repeat: far fewer core runs than candidate pairs (each pair once for both tests).
  EXPECT_GT(r.core_runs, 0u);
  EXPECT_LT(r.core_runs * 4, r.candidate_pairs) << r.core_runs << " core runs for " << r.candidate_pairs << " candidates";
}

// Each instance's source ids differ (as FE bodies' element ids or B-Rep faces would).
void give_own_source_ids(Scene& s) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    auto ids = std::make_shared<std::vector<std::int64_t>>(s.bodies[i].mesh->num_triangles());
    for (std::size_t t = 0; t < ids->size(); ++t) (*ids)[t] = static_cast<std::int64_t>(1000000 * (i + 1) + 3 * t);
    s.bodies[i].source_ids = ids;
  }
}

void expect_same_clash(const SceneClash& x, const SceneClash& y, const std::string& where) {
  EXPECT_EQ(x.id, y.id) << where;
  EXPECT_EQ(x.verdict, y.verdict) << where;
  EXPECT_EQ(x.kind, y.kind) << where;
  EXPECT_EQ(x.point, y.point) << where;
  EXPECT_EQ(x.box.lo, y.box.lo) << where;
  EXPECT_EQ(x.box.hi, y.box.hi) << where;
  EXPECT_EQ(x.depth, y.depth) << where;
  EXPECT_EQ(x.depth_bound, y.depth_bound) << where;
  EXPECT_EQ(x.distance, y.distance) << where;
  EXPECT_EQ(x.curve_length, y.curve_length) << where;
  EXPECT_EQ(x.cross_pairs, y.cross_pairs) << where;
  EXPECT_EQ(x.touch_pairs, y.touch_pairs) << where;
  EXPECT_EQ(x.triangles_a, y.triangles_a) << where;
  EXPECT_EQ(x.triangles_b, y.triangles_b) << where;
  EXPECT_EQ(x.source_ids_a, y.source_ids_a) << where;
  EXPECT_EQ(x.source_ids_b, y.source_ids_b) << where;
  EXPECT_EQ(x.reasons, y.reasons) << where;
  ASSERT_EQ(x.curves.size(), y.curves.size()) << where;
  for (std::size_t c = 0; c < x.curves.size(); ++c) EXPECT_EQ(x.curves[c].points, y.curves[c].points) << where;
}

TEST(SceneRepeats, EveryMemberEqualsItsPairCheckedAlone) {
  AssemblyInfo info;
  Scene s = small_assembly(&info);
  give_own_source_ids(s);
  const std::vector<ClashTest> tests = hard_and_clearance();
  const SceneClashResult all = clash_scene(s, tests);
  ASSERT_LT(all.core_runs * 4, all.candidate_pairs);
  std::map<std::tuple<std::string, std::uint32_t, std::uint32_t>, std::vector<const SceneClash*>> by_pair;
  for (const SceneClash& c : all.clashes) by_pair[{c.test, c.a, c.b}].push_back(&c);
  std::size_t checked = 0, n = 0;
  for (const auto& [key, list] : by_pair) {
    const auto& [test, a, b] = key;
    // Every clashing and clearance pair, every fifth contact pair.
    if (list.front()->verdict == Verdict::contact && n++ % 5 != 0) continue;
    Scene two;
    two.units = s.units;
    two.bodies = {s.bodies[a], s.bodies[b]};
    std::vector<ClashTest> one;
    for (const ClashTest& t : tests)
      if (t.name == test) one.push_back(t);
    const SceneClashResult alone = clash_scene(two, one);
    ASSERT_EQ(alone.clashes.size(), list.size()) << s.bodies[a].id << " " << s.bodies[b].id;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const SceneClash& x = *list[i];
      const SceneClash& y = alone.clashes[i];
      EXPECT_EQ(s.bodies[x.a].id, two.bodies[y.a].id);
      EXPECT_EQ(s.bodies[x.b].id, two.bodies[y.b].id);
      expect_same_clash(x, y, test + " " + s.bodies[a].id + " x " + s.bodies[b].id);
    }
    ++checked;
  }
  EXPECT_GT(checked, 40u);
}

TEST(SceneRepeats, CrossingBoxesHoldTheWorldQuerysCurves) {
  AssemblyInfo info;
  const Scene s = small_assembly(&info);
  ClashTest hard;
  hard.name = "hard";
  const SceneClashResult r = clash_scene(s, {hard});
  std::size_t crossings = 0;
  for (const PairSummary& p : r.pairs) {
    if (p.verdict != Verdict::clash) continue;
    const Model ma = make_model(transformed(*s.bodies[p.a].mesh, s.bodies[p.a].pose));
    const Model mb = make_model(transformed(*s.bodies[p.b].mesh, s.bodies[p.b].pose));
    ClashRequest q;
    q.parallel = false;
    const ClashResult w = clash(ma, mb, q);
    ASSERT_EQ(w.regions.size(), p.clashes.size()) << s.bodies[p.a].id << " x " << s.bodies[p.b].id;
    Aabb curves_world, boxes;
    for (const ClashRegion& g : w.regions)
      for (const Polyline& l : g.curves)
        for (const Vec3& q : l.points) curves_world.expand(q);
    for (const std::uint32_t i : p.clashes) boxes.expand(r.clashes[i].box);
    if (curves_world.empty()) continue;
    ++crossings;
    const double tol = 1e-9 * (1 + norm(curves_world.extent()) + norm(curves_world.hi));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(boxes.lo[k], curves_world.lo[k], tol) << s.bodies[p.a].id << " x " << s.bodies[p.b].id;
      EXPECT_NEAR(boxes.hi[k], curves_world.hi[k], tol) << s.bodies[p.a].id << " x " << s.bodies[p.b].id;
    }
  }
  EXPECT_GT(crossings, 10u);
}

TEST(SceneRepeats, ContainmentReasonsNameEachMembersBodies) {
  const auto cube = std::make_shared<const TriMesh>(make_box({-2, -2, -2}, {2, 2, 2}, 1));
  const auto core = std::make_shared<const TriMesh>(make_box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 1));
  Scene s;
  for (int k = 0; k < 3; ++k) {
    Transform t;
    t.t = {10.0 * k, 0, 0};
    Body outer;
    outer.id = "outer" + std::to_string(k);
    outer.name = outer.id, outer.path = "/" + outer.id;
    outer.mesh = cube, outer.pose = t;
    Body inner = outer;
    inner.id = "inner" + std::to_string(k);
    inner.name = inner.id, inner.path = "/" + inner.id;
    inner.mesh = core;
    s.bodies.push_back(outer), s.bodies.push_back(inner);
  }
  ClashTest hard;
  hard.name = "hard";
  const SceneClashResult r = clash_scene(s, {hard});
  EXPECT_EQ(r.core_runs, 1u);  // three members of one configuration
  ASSERT_EQ(r.clashes.size(), 3u);
  for (const SceneClash& c : r.clashes) {
    EXPECT_EQ(c.kind, "inside");
    const std::string k = s.bodies[c.a].id.substr(5);
    EXPECT_EQ(s.bodies[c.b].id.substr(5), k);
    EXPECT_EQ(c.reasons.front(), "body 'inner" + k + "' (or a component of it) lies inside body 'outer" + k + "'");
    const double x = 10.0 * std::stoi(k);
    EXPECT_DOUBLE_EQ(c.box.lo.x, x - 0.5);
    EXPECT_DOUBLE_EQ(c.box.hi.x, x + 0.5);
  }
}

}  // namespace
}  // namespace interfere::scene
