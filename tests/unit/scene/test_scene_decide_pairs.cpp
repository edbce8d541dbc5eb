// SceneClashOptions::decide_pairs and finish_result (include/interfere/scene/engine.h; issue #31):
// a scene's candidate pairs split into parts, each part decided by its own engine run on the whole
// scene, the runs' clashes merged by finish_result, give the clashes, ids, summaries and groups of
// one run on the whole scene. Oracle: that one run (the split changes which pairs a run decides,
// never how). BroadPhase finds clash_scene's candidates (counts) on body metadata alone.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"

namespace interfere::scene {
namespace {

using Row = std::tuple<std::string, std::string, std::string, std::string, std::string, double, double, double, std::size_t>;

std::vector<Row> rows(const Scene& s, const SceneClashResult& r) {
  std::vector<Row> out;
  for (const SceneClash& c : r.clashes)
    out.push_back({c.test, s.bodies[c.a].id, s.bodies[c.b].id, c.id, c.kind, c.depth_bound, c.distance, c.box.lo.x, c.cross_pairs});
  return out;
}

TEST(SceneDecidePairs, PartsMergedEqualTheWholeRun) {
  AssemblyGenOptions g;
  g.bodies = 70;  // 10 joints: repeated pairs in one relative pose are decided once
  g.segments = 24;
  g.clashes = 4;
  g.gaps = 3;
  const Scene scene = generate_assembly(g);
  std::vector<ClashTest> tests(2);
  tests[0].name = "hard";
  tests[1].name = "gap", tests[1].mode = ClashMode::clearance, tests[1].clearance = 0.4;
  SceneClashOptions o;
  o.curves = false;
  const SceneClashResult whole = clash_scene(scene, tests, o);
  ASSERT_GT(whole.clash_count, 0u);
  ASSERT_GT(whole.clearance_count, 0u);

  // The broad phase on metadata: the same candidate count; its pairs, split three ways.
  std::vector<AabbF> boxes;
  for (const Body& b : scene.bodies) {
    Aabb local;
    for (const Vec3& p : b.mesh->positions) local.expand(p);
    boxes.push_back(broad_box(local, b.pose));
  }
  BroadPhase broad(scene.bodies, tests);
  std::size_t candidates = 0, suppressed = 0;
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const CandidatePair& c : broad.candidates(boxes, candidates, suppressed)) pairs.emplace(c.a, c.b);
  EXPECT_EQ(candidates, whole.candidate_pairs);
  EXPECT_EQ(suppressed, whole.suppressed);
  ASSERT_GT(pairs.size(), 6u);

  SceneClashResult merged;
  std::size_t runs = 0;
  for (int part = 0; part < 3; ++part) {
    SceneClashOptions po = o;
    int k = 0;
    for (const auto& [a, b] : pairs)
      if (k++ % 3 == part) po.decide_pairs.emplace_back(b, a);  // (either order)
    const SceneClashResult r = clash_scene(scene, tests, po);
    EXPECT_EQ(r.candidate_pairs, whole.candidate_pairs);  // (counted whole, decided in part)
    merged.clashes.insert(merged.clashes.end(), r.clashes.begin(), r.clashes.end());
    runs += r.core_runs;
  }
  finish_result(scene, tests, o, merged);
  EXPECT_EQ(rows(scene, merged), rows(scene, whole));
  EXPECT_EQ(merged.clash_count, whole.clash_count);
  EXPECT_EQ(merged.clearance_count, whole.clearance_count);
  EXPECT_EQ(merged.verdict, whole.verdict);
  ASSERT_EQ(merged.pairs.size(), whole.pairs.size());
  ASSERT_EQ(merged.groups.size(), whole.groups.size());
  for (std::size_t i = 0; i < merged.groups.size(); ++i) EXPECT_EQ(merged.groups[i].id, whole.groups[i].id);
  EXPECT_GE(runs, whole.core_runs);  // (a class split over runs is decided in each)

  // All pairs in one run: the whole run, core runs included.
  SceneClashOptions all = o;
  for (const auto& p : pairs) all.decide_pairs.push_back(p);
  const SceneClashResult one = clash_scene(scene, tests, all);
  EXPECT_EQ(rows(scene, one), rows(scene, whole));
  EXPECT_EQ(one.core_runs, whole.core_runs);
}

}  // namespace
}  // namespace interfere::scene
