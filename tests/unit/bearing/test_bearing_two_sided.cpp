// The two-sided maximum interference distance of a pair (issue #27, "the depth is one-sided"; Jia &
// Zheng 2019, §3.3 Step 3: all four end circles, i.e. both parts against the other):
// S(A, B) = min(s(A, B), s(B, A)) = S(B, A). decide_part_pair(x, y) and (y, x) must give bitwise the
// same value, witnesses and verdict on random poses (intact, tapered and scarred parts), and the
// value must lie in the bracket of an independent dense reference (bearing_oracle.h: its own signed
// distance, best-first subdivision of a tessellation) of both one-sided depths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "bearing_oracle.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/scar.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Rng {
  SplitMix64 g;
  double uniform(double lo, double hi) { return lo + (hi - lo) * 0.5 * (g.symmetric() + 1); }
};

Cylinder partner_cylinder() {
  Cylinder b;
  b.base = {0, 0, -10}, b.axis = {0, 0, 1}, b.height = 60, b.radius = 30;
  return b;
}

/// A roller (r = 10, h = 40) pivoting about its bottom end centre at distance 40 + gap from the
/// partner's axis, tilted by up to 3 degrees in a random azimuth (the paper's motion).
Transform random_pose(Rng& g, double gap_lo, double gap_hi) {
  return roller_pose({40 + g.uniform(gap_lo, gap_hi), 0, g.uniform(-2, 2)}, g.uniform(0, 3) * kDeg,
                     g.uniform(0, 360) * kDeg, g.uniform(0, 360) * kDeg);
}

void expect_same(const PartPairResult& p, const PartPairResult& q) {
  EXPECT_EQ(p.distance, q.distance);  // bitwise: both orders run the same computation
  EXPECT_EQ(p.distance_lower, q.distance_lower);
  EXPECT_EQ(p.two_sided_exact, q.two_sided_exact);
  EXPECT_EQ(p.verdict, q.verdict);
  EXPECT_EQ(p.point_a.x, q.point_a.x);
  EXPECT_EQ(p.point_a.y, q.point_a.y);
  EXPECT_EQ(p.point_a.z, q.point_a.z);
  EXPECT_EQ(p.point_b.x, q.point_b.x);
  EXPECT_EQ(p.point_b.y, q.point_b.y);
  EXPECT_EQ(p.point_b.z, q.point_b.z);
  EXPECT_NE(p.swapped, q.swapped);
}

/// Bracket of the one-sided s(A, B) for an analytic A: A tessellated with n sides (inside A, its
/// surface within facet_gap of the mesh), the lower end widened by the facet gap.
bearing_oracle::Bracket one_sided(const Cylinder& a, const Cylinder& b, int n) {
  bearing_oracle::Bracket br =
      bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(a, n), b, 1e-9);
  br.lower -= bearing_oracle::facet_gap(a, n);
  return br;
}

std::vector<std::array<Vec3, 3>> posed_triangles(const Roller& r, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const auto c = r.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

}  // namespace

TEST(BearingTwoSided, IntactPairsAreSymmetricAndEqualTheDenseReference) {
  // Roller against partner (interfering and apart), then two crossed rollers. The reference is the
  // smaller of the two one-sided brackets (A's surface against B, B's surface against A), each by
  // the oracle's own signed distance over a 16384-sided tessellation.
  Rng g{{11}};
  const Cylinder b = partner_cylinder();
  int reverse_decided = 0, differ = 0;
  for (int k = 0; k < 24; ++k) {
    const Transform pose = random_pose(g, -0.3, 0.3);
    const ScenePart roller{.cylinder = posed_cylinder(10, -1, 40, pose)};
    const ScenePart other{.cylinder = b, .partner = true};
    const Cylinder& oc = other.cylinder;
    const PartPairResult p = decide_part_pair(roller, other, 0);
    const PartPairResult q = decide_part_pair(other, roller, 0);
    expect_same(p, q);
    // the simulation's helper: the same value, in either order
    EXPECT_EQ(two_sided_cylinder_distance(roller.cylinder, oc).distance, p.distance);
    EXPECT_EQ(two_sided_cylinder_distance(oc, roller.cylinder).distance, p.distance);
    EXPECT_TRUE(p.two_sided_exact);
    const bearing_oracle::Bracket ab = one_sided(roller.cylinder, oc, 16384);
    const bearing_oracle::Bracket ba = one_sided(oc, roller.cylinder, 16384);
    const double lo = std::min(ab.lower, ba.lower), hi = std::min(ab.upper, ba.upper);
    EXPECT_GE(p.distance, lo - 1e-9) << k;
    EXPECT_LE(p.distance, hi + 1e-9) << k;
    // the witnesses realise the value: |point_a - point_b| = |S|
    EXPECT_NEAR(norm(p.point_a - p.point_b), std::fabs(p.distance), 1e-9) << k;
    reverse_decided += p.reverse ? 1 : 0;
    if (std::fabs(ab.upper - ba.upper) > 1e-3 * std::fabs(hi)) ++differ;
  }
  // the check can fail: in these poses the two one-sided depths differ
  EXPECT_GT(differ, 3);
  // (In these 24 poses the roller's own depth is always the deeper one: `reverse` was set only on
  // apart poses, where both one-sided values are the same distance and a search's rounding put the
  // reverse 1e-14 lower. Since the apart reverse is computed by the closed form too (analytic.cpp),
  // that noise is gone; `reverse_decided` counts only reverses deeper by more than rounding.)
  EXPECT_EQ(reverse_decided, 0);
  {
    // A pose where the partner's depth into the roller decides: the roller reaches below the
    // partner's bottom face (z = -10) and leans so that it overlaps the partner more further down.
    // The roller's deepest point in the partner is limited by that face (about 0.33); the partner's
    // bottom rim lies about 0.34 inside the roller's side.
    Cylinder r;
    r.base = {39.4, 0, -25}, r.axis = {std::sin(kDeg), 0, std::cos(kDeg)}, r.radius = 10, r.height = 40;
    const ScenePart roller{.cylinder = r};
    const ScenePart other{.cylinder = partner_cylinder(), .partner = true};
    const PartPairResult p = decide_part_pair(roller, other, 0);
    expect_same(p, decide_part_pair(other, roller, 0));
    EXPECT_TRUE(p.reverse);
    const bearing_oracle::Bracket ab = one_sided(r, other.cylinder, 16384);
    const bearing_oracle::Bracket ba = one_sided(other.cylinder, r, 16384);
    EXPECT_LT(ba.upper, ab.lower - 1e-3);  // the oracle agrees: the reverse is deeper
    EXPECT_GE(p.distance, std::min(ab.lower, ba.lower) - 1e-9);
    EXPECT_LE(p.distance, std::min(ab.upper, ba.upper) + 1e-9);
  }
  // two intact rollers, crossed and tilted, in both orders
  for (int k = 0; k < 12; ++k) {
    const ScenePart x{.cylinder = posed_cylinder(10, -1, 40, roller_pose({0, 0, 0}, g.uniform(0, 20) * kDeg, g.uniform(0, 360) * kDeg, 0))};
    const ScenePart y{.cylinder = posed_cylinder(8, -1, 30, roller_pose({g.uniform(15, 19), g.uniform(-2, 2), g.uniform(-5, 15)},
                                                                         g.uniform(0, 90) * kDeg, g.uniform(0, 360) * kDeg, 0))};
    const PartPairResult p = decide_part_pair(x, y, 0), q = decide_part_pair(y, x, 0);
    expect_same(p, q);
    const bearing_oracle::Bracket ab = one_sided(x.cylinder, y.cylinder, 8192);
    const bearing_oracle::Bracket ba = one_sided(y.cylinder, x.cylinder, 8192);
    EXPECT_GE(p.distance, std::min(ab.lower, ba.lower) - 1e-9) << k;
    EXPECT_LE(p.distance, std::min(ab.upper, ba.upper) + 1e-9) << k;
  }
}

TEST(BearingTwoSided, ScarredAndTaperedPairsAreSymmetricAndBracketed) {
  // Scarred rollers (random scars, facing the partner or not) against the partner: the value is
  // s(A, B) on the scarred surface (bracketed independently); the partner's depth into the scarred
  // roller is bounded below by its depth into the roller's intact cylinder, and S is exact when
  // that bound is not deeper; else [distance_lower, distance] must hold the oracle's smaller
  // one-sided value's bracket.
  Rng g{{23}};
  const Cylinder b = partner_cylinder();
  int exact = 0, bracketed = 0;
  for (int k = 0; k < 24; ++k) {
    Roller r = *make_roller({.radius = 10, .height = 40, .radial_segments = 32, .height_segments = 31});
    ASSERT_TRUE(apply_scar(r, {.angle_center_deg = g.uniform(0, 360), .angle_width_deg = g.uniform(30, 200), .z_min = 0,
                               .z_max = 40, .depth = g.uniform(0.02, 0.2), .seed = 100u + static_cast<unsigned>(k)})
                    .has_value());
    const RollerQuadtree tree = build_quadtree(r);
    const Transform pose = random_pose(g, -0.3, 0.05);
    const ScenePart a{.cylinder = posed_cylinder(10, -1, 40, pose), .mesh = &r, .tree = &tree, .pose = pose};
    const ScenePart p{.cylinder = b, .partner = true};
    const PartPairResult x = decide_part_pair(a, p, 0), y = decide_part_pair(p, a, 0);
    expect_same(x, y);
    EXPECT_EQ(x.solver, PartPairSolver::scarred);
    // s(A, B) over the scarred triangles, independently
    const bearing_oracle::Bracket ab = bearing_oracle::surface_min_bracket(posed_triangles(r, pose), b, 1e-10);
    // s(B, A0): the partner's surface against the roller's intact cylinder (a lower bound of s(B, A))
    const bearing_oracle::Bracket ba0 = one_sided(b, a.cylinder, 16384);
    EXPECT_GE(x.distance, ab.lower - 1e-9) << k;  // the upper end is s(A, B) exactly
    EXPECT_LE(x.distance, ab.upper + 1e-9) << k;
    EXPECT_LE(x.distance_lower, x.distance);
    if (x.two_sided_exact) {
      ++exact;
      EXPECT_EQ(x.distance_lower, x.distance);
      // apart: both one-sided values are the distance of the solids; overlapping: B is not deeper
      // in A0 than A is in B
      if (ab.upper < 0) EXPECT_GE(ba0.upper, ab.lower - 1e-9) << k;
    } else {
      ++bracketed;
      EXPECT_GE(x.distance_lower, ba0.lower - 1e-9) << k;
      EXPECT_LE(x.distance_lower, ba0.upper + 1e-9) << k;
      EXPECT_LT(x.distance_lower, x.distance);
    }
  }
  RecordProperty("exact", exact);
  RecordProperty("bracketed", bracketed);
  EXPECT_GT(exact, 0);
  EXPECT_GT(bracketed, 0);  // the bound is not always enough: reported as a bracket, not hidden
  // tapered rollers against the partner and against each other: symmetric too
  for (int k = 0; k < 20; ++k) {
    const Transform pose = random_pose(g, -0.3, 0.3);
    const ScenePart t{.cylinder = posed_cylinder(10, g.uniform(7, 9.5), 40, pose)};
    const ScenePart p{.cylinder = b, .partner = true};
    expect_same(decide_part_pair(t, p, 0), decide_part_pair(p, t, 0));
    const ScenePart u{.cylinder = posed_cylinder(9, 7, 35, roller_pose({g.uniform(15, 20), 0, 0}, g.uniform(0, 10) * kDeg, 0, 0))};
    const ScenePart v{.cylinder = posed_cylinder(10, 8, 40, roller_pose({0, 0, 0}, g.uniform(0, 10) * kDeg, 0, 0))};
    expect_same(decide_part_pair(u, v, 0), decide_part_pair(v, u, 0));
  }
}
