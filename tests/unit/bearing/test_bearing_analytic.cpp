// Standard solver (analytic.h): analytic cases with known answers, the general (nested) path, and
// an independent reference (bearing_oracle.h: a fine tessellation of A, minimised by subdivision
// with a convexity bound and its own signed distance; bracket widened by the facet gap). Issue #4,
// deliverables 5 and 9; issue #23, item 14.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/scar.h"
#include "bearing_oracle.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

Cylinder cyl(Vec3 base, Vec3 axis, double h, double r) {
  Cylinder c;
  c.base = base, c.axis = axis / norm(axis), c.height = h, c.radius = r;
  return c;
}

void expect_rel(double got, double want, double rel = 1e-9) {
  EXPECT_NEAR(got, want, rel * std::max(1.0, std::fabs(want))) << "got " << got << " want " << want;
}

/// Independent bracket of s(A, B) = min of sd_B over A's surface (A not containing B's core):
/// A tessellated with n sides (inside A; its surface within facet_gap of the mesh), the mesh
/// minimum bracketed by subdivision to 1e-8, the lower end widened by the facet gap.
bearing_oracle::Bracket oracle(const Cylinder& a, const Cylinder& b, int n = 4096) {
  bearing_oracle::Bracket br = bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(a, n), b, 1e-8);
  EXPECT_LE(br.upper - br.lower, 1e-8);
  br.lower -= bearing_oracle::facet_gap(a, n);
  return br;
}

}  // namespace

TEST(BearingAnalytic, ParallelAxesAtKnownDistance) {
  const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 60, 30);
  for (const double gap : {2.5, 0.0, -0.125, -3.0}) {
    const Cylinder a = cyl({40 + gap, 0, 10}, {0, 0, 1}, 40, 10);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, gap);
    EXPECT_EQ(pd.path, AnalyticPath::parallel);
    EXPECT_NEAR(pd.point_a.x, 30 + gap, 1e-12);
    EXPECT_NEAR(std::hypot(pd.point_b.x, pd.point_b.y), 30, 1e-12);
  }
}

TEST(BearingAnalytic, CrossedAxes) {
  const Cylinder b = cyl({0, 0, -30}, {0, 0, 1}, 60, 30);
  for (const double gap : {1.0, -0.5}) {
    // A along y, its axis 40 + gap from B's axis, crossing B's axis direction at z = 0
    const Cylinder a = cyl({40 + gap, -20, 0}, {0, 1, 0}, 40, 10);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, gap);
    EXPECT_EQ(pd.path, AnalyticPath::side);
    EXPECT_NEAR(pd.point_a.x, 30 + gap, 1e-12);
    EXPECT_NEAR(pd.point_a.y, 0, 1e-12);
  }
}

TEST(BearingAnalytic, TiltedByAlphaInterferesByHbTanAlpha) {
  // A roller touching B along a generator, tilted by alpha about its bottom rim's contact point
  // towards B: its length L = h_b / cos(alpha) spans the height h_b and its top end presses
  // L sin(alpha) = h_b tan(alpha) into B (docs/bearing.md).
  const double R = 30, r = 10, hb = 40;
  const Cylinder b = cyl({0, 0, -100}, {0, 0, 1}, 300, R);
  for (const double deg : {0.25, 1.0, 3.0, 10.0}) {
    const double al = deg * std::numbers::pi / 180;
    const double L = hb / std::cos(al);
    const Cylinder a = cyl({R + r * std::cos(al), 0, r * std::sin(al)}, {-std::sin(al), 0, std::cos(al)}, L, r);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, -hb * std::tan(al));
    EXPECT_EQ(pd.path, AnalyticPath::end);
    EXPECT_NEAR(pd.point_a.x, R - hb * std::tan(al), 1e-9);
    EXPECT_NEAR(pd.point_a.z, hb, 1e-9);
  }
}

TEST(BearingAnalytic, EndCircleContacts) {
  const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 60, 30);
  // rim against rim (circle-circle): A parallel, beside and above B
  for (const double dz : {0.5, 3.0}) {
    const Cylinder a = cyl({45, 0, 60 + dz}, {0, 0, 1}, 40, 10);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, std::hypot(5.0, dz));
  }
  // end face against end face, coaxial (B's axis pierces A: the slice path, analytic.h)
  for (const double dz : {0.75, -0.25}) {
    const Cylinder a = cyl({0, 0, 60 + dz}, {0, 0, 1}, 40, 10);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, dz);
    EXPECT_EQ(pd.path, AnalyticPath::slice);
  }
  // end disk of a perpendicular A against B's side
  for (const double gap : {0.75, -0.25}) {
    const Cylinder a = cyl({30 + gap, 0, 30}, {1, 0, 0}, 40, 10);
    const PairDistance pd = cylinder_pair_distance(a, b);
    expect_rel(pd.distance, gap);
  }
  // end circle of a tilted A against B's side: the rim point nearest B's axis, checked against
  // a direct parametrisation of the rim (1-D golden search on the rim angle, independent code)
  const double al = 0.3;
  const Cylinder a = cyl({41, 0, 10}, {std::sin(al), 0.2, std::cos(al)}, 40, 10);
  const PairDistance pd = cylinder_pair_distance(a, b);
  EXPECT_EQ(pd.path, AnalyticPath::end);
  const Vec3 u = a.axis;
  Vec3 f1 = cross(u, Vec3{0, 1, 0});
  f1 = f1 / norm(f1);
  const Vec3 f2 = cross(u, f1);
  double best = 1e300;
  for (int i = 0; i < 200000; ++i) {
    const double phi = 2 * std::numbers::pi * i / 200000;
    const Vec3 p = a.base + (f1 * std::cos(phi) + f2 * std::sin(phi)) * a.radius;
    best = std::min(best, std::hypot(p.x, p.y) - 30);
  }
  EXPECT_LE(pd.distance, best + 1e-12);
  EXPECT_NEAR(pd.distance, best, 1e-8);
}

TEST(BearingAnalytic, PointEllipseDistance) {
  // circle: distance = |p| - r
  EXPECT_NEAR(point_ellipse_distance(2, 2, 3, 4).distance, 3, 1e-14);
  // axis points
  EXPECT_NEAR(point_ellipse_distance(3, 1, 5, 0).distance, 2, 1e-14);
  EXPECT_NEAR(point_ellipse_distance(3, 1, 0, -4).distance, 3, 1e-14);
  EXPECT_EQ(point_ellipse_distance(3, 1, 1, 0.1).distance, 0);
  // against dense sampling of the curve
  for (const auto& [y0, y1] : {std::pair{4.0, 2.5}, std::pair{-0.3, 1.7}, std::pair{3.2, -0.01}}) {
    const EllipsePoint ep = point_ellipse_distance(3, 1.5, y0, y1);
    double best = 1e300;
    for (int i = 0; i < 400000; ++i) {
      const double t = 2 * std::numbers::pi * i / 400000;
      best = std::min(best, std::hypot(3 * std::cos(t) - y0, 1.5 * std::sin(t) - y1));
    }
    EXPECT_LE(ep.distance, best + 1e-14);  // sampling only overestimates
    EXPECT_GE(ep.distance, best - 1e-8);
    EXPECT_NEAR((ep.x0 / 3) * (ep.x0 / 3) + (ep.x1 / 1.5) * (ep.x1 / 1.5), 1, 1e-12);
  }
}

TEST(BearingAnalytic, StandardMatchesGeneralAndDenseBruteForce) {
  SplitMix64 g{42};
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 60, 30);
    const double al = 0.2 * g.uniform(), az = 2 * std::numbers::pi * g.uniform();
    const Vec3 axis{std::sin(al) * std::cos(az), std::sin(al) * std::sin(az), std::cos(al)};
    const double gap = 2 * g.symmetric();
    const Cylinder a = cyl({40 + gap, 3 * g.symmetric(), 10 + 10 * g.symmetric()}, axis, 40, 10);
    const PairDistance fast = cylinder_pair_distance(a, b);
    const PairDistance slow = cylinder_pair_distance_general(a, b);
    ASSERT_TRUE(std::isfinite(fast.distance));
    SCOPED_TRACE(testing::Message() << "trial " << trial << " path " << analytic_path_name(fast.path) << " s " << fast.distance << " axis " << axis.x << "," << axis.y << " base " << a.base.x << "," << a.base.y << "," << a.base.z);
    // the general path is a convex minimisation converged to rounding
    EXPECT_NEAR(fast.distance, slow.distance, 1e-9 * std::max(1.0, std::fabs(fast.distance)))
        << "trial " << trial << " path " << analytic_path_name(fast.path);
    // the witness is on A and attains the value (the oracle's own signed distance)
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, fast.point_a).value, fast.distance, 1e-12);
    // the independent bracket (facet gap 2.9e-6 at 4096 sides)
    const bearing_oracle::Bracket br = oracle(a, b);
    EXPECT_LE(fast.distance, br.upper + 1e-12) << trial;
    EXPECT_GE(fast.distance, br.lower - 1e-12) << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 60);
}

TEST(BearingAnalytic, TaperedRollers) {
  const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 60, 30);
  Cylinder a = cyl({41, 0, 10}, {0, 0, 1}, 40, 10);
  a.top_radius = 8;  // cone frustum: its generator facing B leans away, nearest at the bottom rim
  const PairDistance pd = cylinder_pair_distance(a, b);
  EXPECT_EQ(pd.path, AnalyticPath::tapered);
  expect_rel(pd.distance, 1.0);
  EXPECT_NEAR(pd.point_a.z, 10, 1e-6);
  // random tilted frustums: the 1-D search equals the nested 3-D minimisation and dense sampling
  SplitMix64 g{17};
  for (int trial = 0; trial < 30; ++trial) {
    const double al = 0.3 * g.uniform(), az = 2 * std::numbers::pi * g.uniform();
    Cylinder t = cyl({40 + 2 * g.symmetric(), 2 * g.symmetric(), 10 + 5 * g.symmetric()},
                     {std::sin(al) * std::cos(az), std::sin(al) * std::sin(az), std::cos(al)}, 40, 10);
    t.top_radius = 6 + 6 * g.uniform();
    const PairDistance fast = cylinder_pair_distance(t, b);
    const PairDistance slow = cylinder_pair_distance_general(t, b);
    EXPECT_NEAR(fast.distance, slow.distance, 1e-9 * std::max(1.0, std::fabs(slow.distance))) << trial;
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, fast.point_a).value, fast.distance, 1e-9) << trial;
    const bearing_oracle::Bracket br = oracle(t, b);
    EXPECT_LE(fast.distance, br.upper + 1e-12) << trial;
    EXPECT_GE(fast.distance, br.lower - 1e-12) << trial;
  }
}

TEST(BearingAnalytic, DegenerateNeverNaN) {
  const Cylinder b = cyl({0, 0, 0}, {0, 0, 1}, 60, 30);
  // coaxial, identical, perpendicular through the centre
  for (const Cylinder& a : {cyl({0, 0, 0}, {0, 0, 1}, 60, 30), cyl({-50, 0, 30}, {1, 0, 0}, 100, 5),
                            cyl({0, 0, 30}, {0, 1, 0}, 10, 5)}) {
    const PairDistance pd = cylinder_pair_distance(a, b);
    EXPECT_TRUE(std::isfinite(pd.distance));
    EXPECT_TRUE(is_finite(pd.point_a) && is_finite(pd.point_b));
    EXPECT_LT(pd.distance, 0);
  }
  // identical cylinders: deepest point of A in B is B's core, depth min(R, h/2) = 30
  EXPECT_NEAR(cylinder_pair_distance(cyl({0, 0, 0}, {0, 0, 1}, 60, 30), b).distance, -30, 1e-9);
}

TEST(BearingAnalytic, CorePathWhenAContainsBsDeepestPoints) {
  // B's deepest points lie at depth min(R, h/2) (no point of B is deeper): when A contains one, s is
  // exactly minus that depth. Checked against the general (nested) path and by the independent
  // signed distance of the witness.
  const Cylinder tall = cyl({45, 0, -10}, {0, 0, 1}, 60, 30);  // R = h/2: the core is the centre
  const Cylinder rod = cyl({45, 0, -40}, {0, 0, 1}, 120, 30);  // R < h/2: an axis segment
  const Cylinder disk = cyl({45, 0, 10}, {0, 0, 1}, 20, 30);   // R > h/2: the mid disk rho <= 20
  // a roller across each (its axis 4 from B's, tilted 1 degree), and one beside the disk's core
  const Cylinder roller = cyl({41, 0, 0}, {0.017, 0.003, 1}, 40, 10);
  for (const auto& [b, depth] : {std::pair{tall, 30.0}, std::pair{rod, 30.0}, std::pair{disk, 10.0}}) {
    const PairDistance pd = cylinder_pair_distance(roller, b);
    EXPECT_EQ(pd.path, AnalyticPath::core);
    EXPECT_EQ(pd.distance, -depth);
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, pd.point_a).value, -depth, 1e-9);
    EXPECT_NEAR(cylinder_pair_distance_general(roller, b).distance, -depth, 1e-9);
  }
  // a roller 32 from the disk's axis reaches to 22, outside its core (radius 20), and is deepest
  // there at mid height: sd = max(22 - 30, 0 - 10) = -8 (not the core path)
  const Cylinder beside = cyl({77, 0, 0}, {0, 0, 1}, 40, 10);
  const PairDistance pd = cylinder_pair_distance(beside, disk);
  EXPECT_NE(pd.path, AnalyticPath::core);
  EXPECT_NEAR(pd.distance, -8.0, 1e-9);
}
