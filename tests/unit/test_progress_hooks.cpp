// The libraries' progress hooks behind the CLI's progress bar (issue #30, item 5): each is called
// once per unit of work, from any thread, and reaches the whole count; the results do not depend
// on whether a hook is set. Checked by counting the calls (atomics) and comparing with a run
// without the hook: bearing::simulate (frames, calling thread), bearing::run_assembly (frames, as
// they finish), probe::sweep (points, clearances, segments) and scene::clash_scene (the pair jobs
// of a static scene).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <vector>

#include "interfere/bearing/assembly.h"
#include "interfere/bearing/simulation.h"
#include "interfere/probe/generate.h"
#include "interfere/probe/sweep.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"
#include "unit/bearing/assembly_fixture.h"

namespace interfere {
namespace {

// Every (done, count) call: done values seen, counts seen.
struct Calls {
  std::mutex m;
  std::vector<std::size_t> done, count;
  std::function<void(std::size_t, std::size_t)> hook() {
    return [this](std::size_t d, std::size_t c) {
      const std::lock_guard lock(m);
      done.push_back(d), count.push_back(c);
    };
  }
  // Each value 1..n exactly once (in any order), every count n.
  void expect_each_once(std::size_t n) const {
    std::vector<std::size_t> d = done;
    std::sort(d.begin(), d.end());
    ASSERT_EQ(d.size(), n);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(d[i], i + 1);
    for (std::size_t c : count) EXPECT_EQ(c, n);
  }
};

TEST(ProgressHooks, BearingSimulationCallsOncePerFrameInOrder) {
  bearing::SceneParams p;
  p.pairs = 6, p.frames = 7, p.gap = -0.1;
  p.roller = {.radius = 10, .height = 40, .radial_segments = 16, .height_segments = 15};
  Calls c;
  const Expected<bearing::SimulationResult> with = bearing::simulate(p, true, c.hook());
  const Expected<bearing::SimulationResult> without = bearing::simulate(p, true);
  ASSERT_TRUE(with && without);
  c.expect_each_once(7);
  EXPECT_TRUE(std::is_sorted(c.done.begin(), c.done.end()));  // (the calling thread, frame by frame)
  EXPECT_EQ(with->min_distance, without->min_distance);
  EXPECT_EQ(with->interfering_rows, without->interfering_rows);
}

TEST(ProgressHooks, BearingAssemblyReachesEveryFrame) {
  Expected<bearing::AssemblySpec> s =
      bearing::parse_assembly(bearing::test::assembly_json(bearing::test::kLively, bearing::test::both_bearings()), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<bearing::Assembly> as = bearing::build_assembly(*s);
  ASSERT_TRUE(as) << as.error().message();
  const bearing::AssemblyMotion m = bearing::generate_motion(*as, 5, 2);
  std::atomic<std::size_t> calls{0}, largest{0};
  const bearing::AssemblyResult with = bearing::run_assembly(*as, m, [&](std::size_t d, std::size_t n) {
    EXPECT_EQ(n, 5u);
    EXPECT_LE(d, n);
    ++calls;
    std::size_t seen = largest.load();
    while (d > seen && !largest.compare_exchange_weak(seen, d)) {
    }
  });
  const bearing::AssemblyResult without = bearing::run_assembly(*as, m);
  EXPECT_GE(calls.load(), 1u);
  EXPECT_LE(calls.load(), 5u);  // (once per whole frame reached)
  EXPECT_EQ(largest.load(), 5u);
  ASSERT_EQ(with.rows.size(), without.rows.size());
  for (std::size_t i = 0; i < with.rows.size(); ++i) EXPECT_EQ(with.rows[i].result.distance, without.rows[i].result.distance);
}

TEST(ProgressHooks, SweepCountsPointsClearancesAndSegments) {
  using namespace probe;
  const ProbeShape shape{.radius = 5, .length = 40};
  const TriMesh mesh = make_panel(PanelKind::saddle, 12, 8);
  const ProbePath path = make_panel_path(PanelKind::saddle, {.lines = 2, .points_per_line = 9, .standoff = 8, .collide_every = 5});
  const Robot robot = pivot_machine(150);
  const Workpiece w = prepare_workpiece(mesh, shape, {.hierarchy = Hierarchy::bvh});
  const std::size_t n = path.size();
  for (const bool clearance : {true, false}) {
    Calls c;
    const SweepResult with = sweep(w, path, &robot, {.probe = shape, .clearance = clearance, .progress = c.hook()});
    const SweepResult without = sweep(w, path, &robot, {.probe = shape, .clearance = clearance});
    c.expect_each_once(n + (clearance ? n : 0) + (n - 1));
    EXPECT_EQ(with.colliding_points, without.colliding_points);
    EXPECT_EQ(with.colliding_segments, without.colliding_segments);
  }
}

TEST(ProgressHooks, StaticSceneCountsItsPairJobs) {
  scene::AssemblyGenOptions g;
  g.bodies = 30;
  g.segments = 24;
  g.clashes = 3;
  g.gaps = 2;
  const scene::Scene s = scene::generate_assembly(g);
  std::vector<scene::ClashTest> tests(1);
  tests[0].name = "hard";
  scene::SceneClashOptions o;
  o.curves = false;
  Calls c;
  o.pair_progress = c.hook();
  const scene::SceneClashResult with = scene::clash_scene(s, tests, o);
  o.pair_progress = nullptr;
  const scene::SceneClashResult without = scene::clash_scene(s, tests, o);
  ASSERT_FALSE(c.count.empty());
  c.expect_each_once(c.count.front());
  EXPECT_LE(c.count.front(), with.candidate_pairs);  // (pairs in one relative pose are one job)
  EXPECT_EQ(with.clash_count, without.clash_count);
  ASSERT_EQ(with.clashes.size(), without.clashes.size());
  for (std::size_t i = 0; i < with.clashes.size(); ++i) EXPECT_EQ(with.clashes[i].id, without.clashes[i].id);
}

}  // namespace
}  // namespace interfere
