// The scene engine runs the exact core once per body pair and derives every test's clashes from
// that one result (engine.cpp, engine_pair.cpp: at the largest clearance any test of the pair
// needs). Oracle: each test run alone, in a scene engine run of its own, must give the same
// clashes as the tests run together.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"

namespace interfere::scene {
namespace {

using Row = std::tuple<std::string, std::string, std::string, double, double, double, double, double, std::size_t,
                       std::size_t>;

std::map<std::string, std::vector<Row>> rows_by_test(const SceneClashResult& r) {
  std::map<std::string, std::vector<Row>> out;
  for (const SceneClash& c : r.clashes)
    out[c.test].push_back({c.id, verdict_name(c.verdict), c.kind, c.depth, c.depth_bound, c.distance, c.box.lo.x,
                           c.box.hi.z, c.cross_pairs, c.touch_pairs});
  return out;
}

TEST(SceneSharedCore, TestsTogetherEqualTestsAlone) {
  AssemblyGenOptions o;
  o.bodies = 70;  // 10 joints
  o.segments = 24;
  o.clashes = 4;
  o.gaps = 3;
  AssemblyInfo info;
  const Scene scene = generate_assembly(o, &info);
  ASSERT_FALSE(info.clash_pairs.empty());
  ASSERT_FALSE(info.gap_pairs.empty());

  std::vector<ClashTest> tests(4);
  tests[0].name = "hard";
  tests[1].name = "hard_tol", tests[1].tolerance = 0.5;  // shallow crossings become contacts
  tests[2].name = "clear_small", tests[2].mode = ClashMode::clearance, tests[2].clearance = 0.1;
  tests[3].name = "clear_large", tests[3].mode = ClashMode::clearance, tests[3].clearance = 0.4;
  ClearanceOverride ov;  // nuts: a smaller clearance than the rest of the test
  ov.a = {*Selector::parse("name:nut*")};
  ov.b = {Selector{}};
  ov.clearance = 0.06;
  tests[3].clearance_overrides.push_back(ov);

  const SceneClashResult together = clash_scene(scene, tests);
  const auto got = rows_by_test(together);
  std::size_t clearances = 0;
  for (const ClashTest& t : tests) {
    const auto alone = rows_by_test(clash_scene(scene, {t}));
    const auto it = got.find(t.name);
    ASSERT_EQ(alone.count(t.name), it != got.end() ? 1u : 0u) << t.name;
    if (it == got.end()) continue;
    EXPECT_EQ(it->second, alone.at(t.name)) << t.name;
    for (const Row& r : it->second) clearances += std::get<1>(r) == "clearance";
  }
  EXPECT_GT(clearances, 0u);  // the clearance filtering was exercised
  EXPECT_GT(together.clash_count, 0u);
}

}  // namespace
}  // namespace interfere::scene
