// decide_part_pair's LowerEnd::decision (part_pair.h; issue #27, speed): for a scarred roller the
// reverse bound s(B, A0) is skipped when one point of B certifies it below min(s(A, B), -tol). The
// result must be the same as with LowerEnd::value bit for bit (value, witnesses, path, verdict,
// two_sided_exact, reason, work counter) except distance_lower, which is then the inradius bound
// -min(R0, h0 / 2) where `value` reports a deeper-than-tolerance s(B, A0) below s(A, B); the same
// for both orders of the parts. Poses: scarred rollers (inward and raised scars) pressed into,
// touching and clear of a partner, an inner raceway and an intact roller.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/scar.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Rng {
  SplitMix64 g;
  double uniform(double lo, double hi) { return lo + (hi - lo) * g.uniform(); }
};

void expect_same_but_lower(const PartPairResult& v, const PartPairResult& d, int k) {
  EXPECT_EQ(v.distance, d.distance) << k;
  EXPECT_EQ(v.point_a.x, d.point_a.x) << k;
  EXPECT_EQ(v.point_a.y, d.point_a.y) << k;
  EXPECT_EQ(v.point_a.z, d.point_a.z) << k;
  EXPECT_EQ(v.point_b.x, d.point_b.x) << k;
  EXPECT_EQ(v.point_b.y, d.point_b.y) << k;
  EXPECT_EQ(v.point_b.z, d.point_b.z) << k;
  EXPECT_EQ(v.swapped, d.swapped) << k;
  EXPECT_EQ(v.two_sided_exact, d.two_sided_exact) << k;
  EXPECT_EQ(v.reverse, d.reverse) << k;
  EXPECT_EQ(v.solver, d.solver) << k;
  EXPECT_EQ(v.path, d.path) << k;
  EXPECT_EQ(v.evaluated, d.evaluated) << k;
  EXPECT_EQ(v.verdict, d.verdict) << k;
  EXPECT_EQ(v.reason, d.reason) << k;
}

}  // namespace

TEST(PartPairLowerEnd, DecisionKeepsEverythingButASkippedLowerEnd) {
  Rng g{{41}};
  int skipped = 0, computed = 0, undecided = 0;
  for (int k = 0; k < 240; ++k) {
    const bool raised = k / 3 % 3 == 2;
    const double r0 = 10, h0 = 38;
    Roller r = *make_roller({.radius = r0, .height = h0, .radial_segments = 48, .height_segments = 24});
    ASSERT_TRUE(apply_scar(r, {.angle_center_deg = g.uniform(0, 360), .angle_width_deg = g.uniform(30, 350),
                               .z_min = g.uniform(0, 10), .z_max = g.uniform(28, 38), .depth = g.uniform(0.005, 0.1),
                               .seed = 300u + static_cast<unsigned>(k), .raised = raised})
                    .has_value());
    const RollerQuadtree tree = build_quadtree(r);
    // B: a partner shaft, an inner raceway (the assemblies' roller-inner rows) or an intact roller
    Cylinder b;
    double centre = 0;  // the roller's axis distance from B's axis at zero gap
    switch (k % 3) {
      case 0: b.base = {0, 0, -10}, b.axis = {0, 0, 1}, b.height = 60, b.radius = 30, centre = 40; break;
      case 1: b.base = {0, 0, -6}, b.axis = {0, 0, 1}, b.height = 50, b.radius = 110, centre = 120; break;
      default: b.base = {0, 0, g.uniform(-3, 3)}, b.axis = {0, 0, 1}, b.height = 38, b.radius = 10, centre = 20; break;
    }
    // pressed by up to 0.08, about touching, or clear by up to 0.02; tilts of up to 0.5 degree
    const double gap = k % 8 == 7 ? g.uniform(-1e-6, 1e-6) : g.uniform(-0.08, 0.02);
    const Transform pose = roller_pose({centre + gap, 0, g.uniform(-2, 2)}, g.uniform(0, 0.5) * kDeg,
                                       g.uniform(0, 360) * kDeg, g.uniform(0, 360) * kDeg);
    const ScenePart a{.cylinder = posed_cylinder(r0, -1, h0, pose), .mesh = &r, .tree = &tree, .pose = pose};
    const ScenePart p{.cylinder = b, .partner = k % 3 != 2};
    const double clearance = k % 2 ? 0.05 : 0;
    const PartPairResult v = decide_part_pair(a, p, clearance, nullptr, LowerEnd::value);
    const PartPairResult d = decide_part_pair(a, p, clearance, nullptr, LowerEnd::decision);
    const PartPairResult e = decide_part_pair(p, a, clearance, nullptr, LowerEnd::decision);
    expect_same_but_lower(v, d, k);
    EXPECT_EQ(d.distance_lower, e.distance_lower) << k;  // both orders: the same computation
    EXPECT_EQ(d.verdict, e.verdict) << k;
    EXPECT_NE(d.swapped, e.swapped) << k;
    undecided += v.verdict == Verdict::undecided;
    if (v.distance_lower == d.distance_lower) {
      ++computed;
      continue;
    }
    ++skipped;
    // skipped: value's s(B, A0) is below s(A, B) and below -tol, and the lower end is the inradius bound
    const double tol = touch_tolerance(a.cylinder, b);
    EXPECT_FALSE(v.two_sided_exact) << k;
    EXPECT_LT(v.distance_lower, std::min(v.distance, -tol)) << k;
    EXPECT_EQ(d.distance_lower, -std::min(r0 + r.raise, 0.5 * h0)) << k;
    EXPECT_LE(d.distance_lower, v.distance_lower) << k;  // (a looser bound)
  }
  RecordProperty("skipped", skipped);
  RecordProperty("computed", computed);
  EXPECT_GT(skipped, 60);
  EXPECT_GT(computed, 60);
}
