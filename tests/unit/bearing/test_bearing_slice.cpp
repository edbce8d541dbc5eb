// The `slice` path of the standard solver (analytic.h, issue #27): untapered pairs whose
// certificate fails (nearest or deepest points at an end face of B: rollers side by side with an
// axial offset, a long raceway cylinder against a short roller in the reverse direction of a
// two-sided value) are solved by one convex search over B's cross-sections instead of the nested
// general path. Checked against the independent bracket of bearing_oracle.h (A's surface
// tessellated, sd_B bracketed by subdivision; nothing of the bearing module's distance code) and
// against the general path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/raceway.h"
#include "interfere/bearing/scarred.h"
#include "unit/bearing/bearing_oracle.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

Cylinder cyl(const Vec3& base, const Vec3& axis, double h, double r) {
  Cylinder c;
  c.base = base, c.axis = axis / norm(axis), c.height = h, c.radius = r;
  return c;
}

double seg(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

/// Independent signed distance to a solid frustum (base radius r0, top r1, height h, unit axis):
/// in the meridian plane, the distance to the trapezoid's three outer edges, negative inside.
double frustum_sd(const Vec3& base, const Vec3& axis, double r0, double r1, double h, const Vec3& p) {
  const Vec3 v = p - base;
  const double z = dot(v, axis), x = norm(v - axis * z);
  const double d = std::min({seg(x, z, 0, 0, r0, 0), seg(x, z, r0, 0, r1, h), seg(x, z, r1, h, 0, h)});
  const bool inside = z > 0 && z < h && x < r0 + (r1 - r0) * z / h;
  return inside ? -d : d;
}

}  // namespace

TEST(BearingSlice, TaperedRollersSideBySide) {
  // tapered rollers (8 -> 9.5, length 30) as neighbours in a tapered bearing: axes up to 12 degrees
  // apart, axially offset, clear or pressed together. Reference: A's boundary sampled densely (the
  // sampled minimum of sd_B (boundary and interior) is >= the exact one and within the grid's reach of it), the witness
  // checked on A and attaining the value with the test's own frustum signed distance.
  std::mt19937_64 g(2720);
  const auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  int slice = 0, clear = 0, overlap = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Cylinder b;
    b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 8, b.top_radius = 9.5;
    const double tilt = uni(0, 0.2), az = uni(0, 2 * std::numbers::pi);
    Cylinder a = b;
    a.axis = {std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
    a.base = {17.5 + uni(-0.6, 0.6), uni(-2, 2), uni(-15, 15)};
    const PairDistance pd = cone_pair_distance(a, b);
    ASSERT_TRUE(std::isfinite(pd.distance));
    SCOPED_TRACE(testing::Message() << "trial " << trial << " path " << analytic_path_name(pd.path) << " s "
                                    << pd.distance);
    slice += pd.path == AnalyticPath::slice;
    clear += pd.distance > 0, overlap += pd.distance < 0;
    const auto sd_b = [&](const Vec3& p) { return frustum_sd(b.base, b.axis, 8, 9.5, 30, p); };
    EXPECT_LE(frustum_sd(a.base, a.axis, 8, 9.5, 30, pd.point_a), 1e-9);  // the witness lies in A
    EXPECT_NEAR(sd_b(pd.point_a), pd.distance, 1e-9);                   // and attains the value
    const Vec3 f1 = std::fabs(a.axis.x) < 0.9 ? cross(a.axis, Vec3{1, 0, 0}) : cross(a.axis, Vec3{0, 1, 0});
    const Vec3 e1 = f1 / norm(f1), e2 = cross(a.axis, e1);
    double sampled = 1e300;
    constexpr int kA = 720, kT = 240;
    for (int i = 0; i < kA; ++i) {
      const double ang = 2 * std::numbers::pi * i / kA;
      const Vec3 dir = e1 * std::cos(ang) + e2 * std::sin(ang);
      for (int j = 0; j <= kT; ++j) {
        const double t = 30.0 * j / kT;
        sampled = std::min(sampled, sd_b(a.base + a.axis * t + dir * (8 + 1.5 * t / 30)));
      }
      for (int j = 0; j < 40; ++j) {
        sampled = std::min(sampled, sd_b(a.base + dir * (8.0 * j / 40)));
        sampled = std::min(sampled, sd_b(a.base + a.axis * 30.0 + dir * (9.5 * j / 40)));
      }
      // the interior too: a deep overlap's deepest point of A in B need not lie on A's boundary
      if (i % 4 == 0)
        for (int j = 0; j <= 60; ++j)
          for (int f = 1; f < 16; ++f) {
            const double t = 30.0 * j / 60;
            sampled = std::min(sampled, sd_b(a.base + a.axis * t + dir * ((8 + 1.5 * t / 30) * f / 16)));
          }
    }
    EXPECT_LE(pd.distance, sampled + 1e-9);
    // apart, the minimum lies on A's boundary (fine grid); overlapping, possibly inside A (the
    // interior grid's spacing, ~0.5 mm, bounds how far above the exact value its minimum can be)
    EXPECT_GE(pd.distance, sampled - (pd.distance > 0 ? 0.02 : 0.5));
  }
  EXPECT_GT(slice, 15);
  EXPECT_GT(clear, 5);
  EXPECT_GT(overlap, 5);
}

TEST(BearingSlice, RollersSideBySideAndRacewayIntoRoller) {
  std::mt19937_64 g(2719);
  const auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  int slice = 0, clear = 0, overlap = 0;
  for (int trial = 0; trial < 48; ++trial) {
    const double tilt = uni(0, 0.02), az = uni(0, 2 * std::numbers::pi);
    const Vec3 axis{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
    Cylinder a, b;
    if (trial % 2 == 0) {  // two rollers (radius 10, length 38) side by side, axially offset
      b = cyl({0, 0, 0}, {0, 0, 1}, 38, 10);
      a = cyl({20 + uni(-0.3, 0.3), uni(-2, 2), uni(-20, 20)}, axis, 38, 10);
    } else {  // the raceway cylinder (radius 110, width 50) into a roller pressed on it
      b = cyl({0, 0, 0}, {0, 0, 1}, 38, 10);
      a = cyl({-120 + uni(-0.3, 0.2), uni(-1, 1), uni(-12, -6)}, axis, 50, 110);
    }
    const PairDistance fast = cylinder_pair_distance(a, b);
    ASSERT_TRUE(std::isfinite(fast.distance));
    SCOPED_TRACE(testing::Message() << "trial " << trial << " path " << analytic_path_name(fast.path) << " s "
                                    << fast.distance);
    slice += fast.path == AnalyticPath::slice;
    clear += fast.distance > 0, overlap += fast.distance < 0;
    const int n = trial % 2 == 0 ? 4096 : 16384;
    bearing_oracle::Bracket br =
        bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(a, n), b, 1e-8);
    br.lower -= bearing_oracle::facet_gap(a, n);
    EXPECT_LE(fast.distance, br.upper + 1e-9);
    EXPECT_GE(fast.distance, br.lower - 1e-9);
    // the witness is on A and attains the value (the oracle's own signed distance)
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, fast.point_a).value, fast.distance, 1e-9);
    if (fast.path == AnalyticPath::slice && trial < 16)
      EXPECT_NEAR(cylinder_pair_distance_general(a, b).distance, fast.distance, 1e-9 * std::max(1.0, std::fabs(fast.distance)));
  }
  EXPECT_GT(slice, 10);
  EXPECT_GT(clear, 5);
  EXPECT_GT(overlap, 5);
}

TEST(BearingSlice, LongTrianglesBesideACylinder) {
  // cage-web-like triangles: long along the cylinder's axis, reaching past its end faces, beside or
  // into its side (where the closed-form certificate fails: scarred.h's exact triangle minimum takes
  // the slice search instead of the nested one). Against bearing_oracle's independent bracket.
  std::mt19937_64 g(2721);
  const auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 38, 10);
  int fallbacks = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double x = 10 + uni(-0.5, 0.5), y = uni(-4, 4);
    const Vec3 t0{x + uni(-0.1, 0.1), y - 3, uni(-8, 2)}, t1{x + uni(-0.1, 0.1), y + 3, uni(-8, 2)};
    const Vec3 t2{x + uni(-0.1, 0.1), y + uni(-3, 3), uni(36, 46)};
    const TriangleMin tm = triangle_min_signed_distance(b, t0, t1, t2);
    fallbacks += !tm.certified;
    const auto br = bearing_oracle::surface_min_bracket({{t0, t1, t2}}, b, 1e-10);
    EXPECT_LE(tm.value, br.upper + 1e-9) << trial;
    EXPECT_GE(tm.value, br.lower - 1e-9) << trial;
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, tm.point).value, tm.value, 1e-9) << trial;
  }
  EXPECT_GT(fallbacks, 10);
}
