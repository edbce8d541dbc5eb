// The scarred solver against an intact cone frustum B (issue #27, deliverable 2: scars on tapered
// rollers; scarred.h), checked against frustum_oracle.h (independent of the bearing module's
// distance code: the frustum's signed distance as a generic convex polygon walk with a subgradient,
// and a best-first subdivision of every posed triangle of the scarred mesh, dense samples refined
// around the minimum with certified convexity lower bounds). The solver's value must lie in that
// bracket, refined to 1e-9 of the scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"
#include "frustum_oracle.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;
using namespace frustum_oracle_ns;

namespace {

Roller scarred_tapered(std::uint64_t seed, bool raised, double r0 = 8, double r1 = 10, int n = 32, int m = 31) {
  Expected<Roller> r = make_roller({.radius = r0, .top_radius = r1, .height = 30, .radial_segments = n, .height_segments = m});
  EXPECT_TRUE(r.has_value());
  ScarParams s{.angle_center_deg = 0, .angle_width_deg = 120, .z_min = 4, .z_max = 26, .depth = 0.06,
               .roughness = 0.6, .border = 2, .seed = seed, .raised = raised};
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

std::vector<std::array<Vec3, 3>> posed_triangles(const Roller& r, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const auto c = r.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

/// A deterministic generator (splitmix64) for the poses.
using Rng = interfere::bearing::test::SplitMix;

double check(const Roller& a, const RollerQuadtree& tree, const Transform& pose, const Cylinder& b, const char* what,
             int trial) {
  const MeshPairResult ref = surface_reference(a, pose, b);
  ScarredSolver solver(&a, &tree);
  const MeshPairResult fast = solver.solve(pose, b);
  const double scale = std::max(b.height, b.max_radius()) + norm(pose.t);
  EXPECT_NEAR(fast.distance, ref.distance, 1e-12 * scale) << what << " " << trial;
  const Bracket br = frustum_min_bracket(posed_triangles(a, pose), b, 1e-9 * scale);
  EXPECT_LE(br.upper - br.lower, 1e-9 * scale) << what << " " << trial;
  EXPECT_GE(fast.distance, br.lower - 1e-12 * scale) << what << " " << trial;
  EXPECT_LE(fast.distance, br.upper + 1e-12 * scale) << what << " " << trial;
  // the witnesses: point_a on A's surface at that value, point_b on B's boundary
  EXPECT_NEAR(frustum_oracle(b, fast.point_a).value, fast.distance, 1e-9 * scale) << what << " " << trial;
  EXPECT_NEAR(frustum_oracle(b, fast.point_b).value, 0, 1e-9 * scale) << what << " " << trial;
  return fast.distance;
}

}  // namespace

TEST(BearingScarredFrustum, TriangleMinimaMatchTheOracle) {
  // single triangles everywhere around a frustum: beside it, past its ends, crossing its axis, inside
  Cylinder b;
  b.base = {1, -2, 3}, b.axis = Vec3{0.2, 0.1, 1} / norm(Vec3{0.2, 0.1, 1}), b.height = 30, b.radius = 8,
  b.top_radius = 12;
  Rng rng{7};
  for (int trial = 0; trial < 150; ++trial) {
    const Vec3 c = b.base + Vec3{rng.in(-25, 25), rng.in(-25, 25), rng.in(-15, 45)};
    const double size = trial % 3 == 0 ? 0.2 : trial % 3 == 1 ? 3.0 : 15.0;
    std::array<Vec3, 3> t;
    for (Vec3& v : t) v = c + Vec3{rng.in(-size, size), rng.in(-size, size), rng.in(-size, size)};
    const TriangleMin tm = triangle_min_signed_distance(b, t[0], t[1], t[2]);
    const Bracket br = frustum_min_bracket({t}, b, 1e-10);
    ASSERT_LE(br.upper - br.lower, 1e-9) << trial;
    EXPECT_GE(tm.value, br.lower - 1e-11) << trial;
    EXPECT_LE(tm.value, br.upper + 1e-11) << trial;
    EXPECT_NEAR(frustum_oracle(b, tm.point).value, tm.value, 1e-10) << trial;
  }
}

TEST(BearingScarredFrustum, ScarredTaperedRollerAgainstATaperedNeighbour) {
  // a scarred tapered roller beside an intact tapered roller (a tapered bearing's neighbours): pressed
  // into it, touching, apart; the scar inward and raised
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 8, b.top_radius = 10;
  Rng rng{11};
  for (int trial = 0; trial < 8; ++trial) {
    const Roller a = scarred_tapered(100 + trial, trial % 2 == 1);
    const RollerQuadtree tree = build_quadtree(a);
    const double gap = trial < 3 ? -0.3 : trial < 5 ? 0.0 : 0.4;
    const double tilt = rng.in(-0.03, 0.03), spin = rng.in(0, 2 * std::numbers::pi);
    // the scar (angle 0 in A's frame) faces B: spin so that A's +x points to -x
    const Transform pose = roller_pose({20 + gap + rng.in(-0.05, 0.05), rng.in(-0.5, 0.5), rng.in(-1, 1)}, tilt,
                                       0.5 * std::numbers::pi, std::numbers::pi + 0.3 * (spin - std::numbers::pi) / 3);
    const double s = check(a, tree, pose, b, "neighbour", trial);
    if (trial < 3) EXPECT_LT(s, -0.1) << trial;  // pressed in
    if (trial >= 5) EXPECT_GT(s, 0.1) << trial;  // apart
  }
}

TEST(BearingScarredFrustum, ScarredTaperedRollerAgainstAConeRaceway) {
  // a tapered bearing's cone (a large frustum) with a scarred tapered roller on it, its axis along
  // the cone's generator (line contact of the intact roller, broken by the scar and a small tilt)
  Cylinder cone;
  cone.base = {0, 0, -15}, cone.axis = {0, 0, 1}, cone.height = 30, cone.radius = 40, cone.top_radius = 46;
  const double k = 6.0 / 30;
  Rng rng{5};
  for (int trial = 0; trial < 8; ++trial) {
    const Roller a = scarred_tapered(300 + trial, trial % 2 == 0);
    const RollerQuadtree tree = build_quadtree(a);
    // the roller's bottom at z = -15 on the cone generator's outside; lean = the cone's half angle
    // plus the roller's own (its generator toward the cone parallel to the cone's)
    const double lean = std::atan(k) + std::atan((10.0 - 8.0) / 30) * -1 + rng.in(-0.01, 0.01);
    const double press = trial < 4 ? rng.in(0.02, 0.2) : rng.in(-0.3, 0.0);
    const double phi = rng.in(-0.2, 0.2);
    const Vec3 radial{std::cos(phi), std::sin(phi), 0};
    const Vec3 bottom = radial * (40 + 8 / std::cos(lean) - press) + Vec3{0, 0, -15 + rng.in(-0.2, 0.2)};
    // tilt toward +radial (azimuth phi): the roller leans outward with the cone
    const Transform pose = roller_pose(bottom, lean, phi, std::numbers::pi + rng.in(-0.4, 0.4));
    const double s = check(a, tree, pose, cone, "cone", trial);
    if (trial < 4) EXPECT_LT(s, 0) << trial;  // pressed into the cone
  }
}

TEST(BearingScarredFrustum, DeepAndCrossingPosesAndACylindricalA) {
  // a scarred roller pushed deep into the frustum (inside sd), crossing its end, and a scarred
  // cylindrical roller against a frustum
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 9, b.top_radius = 6;
  Rng rng{3};
  for (int trial = 0; trial < 6; ++trial) {
    const bool cylindrical = trial >= 3;
    Roller a = cylindrical ? scarred_tapered(500 + trial, false, 8, 8) : scarred_tapered(500 + trial, trial == 1);
    const RollerQuadtree tree = build_quadtree(a);
    const Vec3 at{rng.in(5, 14), rng.in(-3, 3), rng.in(-20, 20)};
    const Transform pose = roller_pose(at, rng.in(0, 0.6), rng.in(0, 6.28), rng.in(0, 6.28));
    const double s = check(a, tree, pose, b, cylindrical ? "cylindrical" : "deep", trial);
    EXPECT_LT(s, 0) << trial;  // (every pose overlaps)
  }
}
