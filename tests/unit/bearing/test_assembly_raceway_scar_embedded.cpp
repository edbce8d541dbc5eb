// A roller sunk into a scarred ring's material without crossing the raceway surface (through the
// bore or beyond the outer raceway) must not be reported clear (issue #27; found in the review of
// 2026-11-29: the raceway-scar rows measured the roller against the raceway's faceted surface
// only, and reported +0.48 "clear" for a roller 15 mm deep in the inner ring). Oracle: the same
// assembly without the scar (the intact ring solvers, a different computation): a roller deeper
// than the scar's largest height plus the facets' sagitta clashes with the scarred ring as well.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "interfere/bearing/assembly.h"
#include "unit/bearing/assembly_fixture.h"

namespace interfere::bearing {
namespace {

std::string with_scar(const char* part) {
  std::string b = test::kCylindricalBearing;
  b.insert(b.rfind('}'), std::string(", \"scars\": [{\"part\": \"") + part +
                             R"(", "angle_center_deg": 270, "angle_width_deg": 120, "depth": 0.03, "seed": 3,
                     "radial_segments": 256, "height_segments": 31}])");
  return b;
}

Assembly build(const std::string& bearing) {
  const Expected<AssemblySpec> spec = parse_assembly(test::assembly_json("\"seed\": 3,", bearing), "a.json");
  EXPECT_TRUE(spec) << spec.error().message();
  Expected<Assembly> as = build_assembly(*spec);
  EXPECT_TRUE(as) << as.error().message();
  return std::move(*as);
}

/// The roller's pose moved radially so that its mid point lies at rho = c from the ring axis.
Transform at_radius(Transform t, double c, double half_length) {
  const Vec3 mid = t.apply({0, 0, half_length});
  const double s = c / std::hypot(mid.x, mid.y);
  t.t = t.t + (Vec3{mid.x * s, mid.y * s, mid.z} - mid);
  return t;
}

void check_embedded(const char* part, AssemblyPairKind kind, const std::vector<double>& radii) {
  const Assembly scarred = build(with_scar(part));
  const Assembly intact = build(test::kCylindricalBearing);
  ASSERT_EQ(scarred.pairs.size(), intact.pairs.size());
  const AssemblyMotion m = generate_motion(scarred, 1, scarred.spec.seed);
  int deep = 0, scar_rows = 0;
  for (std::size_t i = 0; i < scarred.pairs.size(); ++i) {
    const AssemblyPair& pair = scarred.pairs[i];
    if (pair.kind != kind) continue;
    for (const double c : radii) {
      std::vector<Transform> poses = m.poses[0];
      poses[pair.a] = at_radius(poses[pair.a], c, 10);
      const AssemblyPairResult r = solve_pair(scarred, pair, poses, scarred.spec.clearance);
      const AssemblyPairResult r0 = solve_pair(intact, intact.pairs[i], poses, intact.spec.clearance);
      scar_rows += r.scar;
      SCOPED_TRACE(std::string(part) + " " + scarred.parts[pair.a].id + " rho " + std::to_string(c) +
                   ": intact " + std::to_string(r0.distance) + ", scarred " + std::to_string(r.distance));
      if (r0.distance < -0.1) {  // deeper than the scar (0.03) and the sagitta (0.0023) together
        ++deep;
        EXPECT_EQ(r.verdict, Verdict::clash);
        EXPECT_LT(r.distance, 0);
      }
      if (r0.verdict != Verdict::clear) EXPECT_NE(r.verdict, Verdict::clear);
    }
  }
  EXPECT_GT(deep, 0);
  EXPECT_GT(scar_rows, 0);  // some rows were in range of the scar
}

TEST(BearingAssemblyRacewayScarEmbedded, RollerSunkIntoTheInnerRingIsNeverClear) {
  check_embedded("inner", AssemblyPairKind::roller_inner, {39.0, 25.0, 19.5, 15.0});
}

TEST(BearingAssemblyRacewayScarEmbedded, RollerSunkIntoTheOuterRingIsNeverClear) {
  check_embedded("outer", AssemblyPairKind::roller_outer, {41.0, 55.0, 60.6, 63.0});
}

}  // namespace
}  // namespace interfere::bearing
