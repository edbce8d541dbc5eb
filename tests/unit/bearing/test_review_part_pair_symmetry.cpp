// Review test of 377eb6a (issue #27): decide_part_pair with tapered parts. part_pair.h promises
// S(A, B) = S(B, A) with the value, witnesses and verdict bitwise the same for (x, y) and (y, x)
// (roles by part type, ties by a canonical order). Checked here on intact frustum/frustum and
// frustum/cylinder pairs in degenerate poses the commit's tests do not single out: exactly parallel
// and coaxial axes, end faces coplanar (touching and overlapping), equal parts, antiparallel
// axes, a part 1e6 from the origin, touching within 1e-12; and the value against frustum_oracle.h's
// frustum_solid_min both ways (independent of the solvers) to 1e-9.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "frustum_oracle.h"
#include "interfere/bearing/part_pair.h"

namespace interfere::bearing {
namespace {

Cylinder frustum(const Vec3& base, Vec3 axis, double r0, double r1, double h) {
  Cylinder c;
  c.base = base, c.axis = axis / norm(axis), c.radius = r0, c.top_radius = r1 == r0 ? -1 : r1, c.height = h;
  return c;
}

ScenePart part(const Cylinder& c) {
  ScenePart p;
  p.cylinder = c;
  return p;
}

void check(const Cylinder& a, const Cylinder& b, const std::string& what, bool reference = true, double tol = 1e-9) {
  const PartPairResult xy = decide_part_pair(part(a), part(b), 0.05);
  const PartPairResult yx = decide_part_pair(part(b), part(a), 0.05);
  ASSERT_TRUE(std::isfinite(xy.distance)) << what;
  EXPECT_EQ(xy.distance, yx.distance) << what;
  EXPECT_EQ(xy.verdict, yx.verdict) << what;
  EXPECT_EQ(xy.point_a.x, yx.point_a.x) << what;
  EXPECT_EQ(xy.point_b.z, yx.point_b.z) << what;
  const bool same = a.base == b.base && a.axis == b.axis && a.radius == b.radius && a.top() == b.top() && a.height == b.height;
  if (!same) EXPECT_NE(xy.swapped, yx.swapped) << what;  // (identical parts: either order is canonical)
  if (!reference) return;
  // S = min(s(A, B), s(B, A)) over the solids, from the oracle (independent of the solvers)
  const double ref = std::min(frustum_oracle_ns::frustum_solid_min(a, b), frustum_oracle_ns::frustum_solid_min(b, a));
  EXPECT_NEAR(xy.distance, ref, tol * std::max(1.0, std::fabs(ref))) << what;
}

// (The oracle's ellipsoid method converges slowly on line and face contacts, flat valleys of sd_B:
// 1.08e-9 above the exact 0 for the antiparallel cones touching along a line; 1e-8 here, the
// bitwise symmetry is the point of this test.)
TEST(ReviewPartPairSymmetry, DegenerateFrustumPoses) {
  const Vec3 z{0, 0, 1};
  const auto check = [](const Cylinder& a, const Cylinder& b, const std::string& what) {
    interfere::bearing::check(a, b, what, true, 1e-8);
  };
  // parallel axes side by side: apart, touching, overlapping (line contact of two cones)
  for (const double gap : {0.5, 1e-12, 0.0, -1e-12, -0.3})
    check(frustum({0, 0, 0}, z, 5, 4, 20), frustum({9 + gap, 0, 0}, z, 5, 4, 20), "parallel gap " + std::to_string(gap));
  // antiparallel (a cone against an inverted one: the lateral lines parallel)
  for (const double gap : {0.5, 0.0, -0.3})
    check(frustum({0, 0, 0}, z, 5, 4, 20), frustum({9 + gap, 0, 20}, z * -1.0, 5, 4, 20), "antiparallel " + std::to_string(gap));
  // coaxial, end faces coplanar or stacked with overlap
  for (const double dz : {20.5, 20.0, 19.7, 10.0})
    check(frustum({0, 0, 0}, z, 5, 4, 20), frustum({0, 0, dz}, z, 4, 3, 10), "coaxial dz " + std::to_string(dz));
  // a cylinder against a frustum, end faces coplanar and overlapping sideways
  check(frustum({0, 0, 0}, z, 5, 5, 20), frustum({7, 0, 0}, z, 3, 2, 20), "coplanar ends");
  // equal parts at the same place, and a copy shifted by 1e-12
  check(frustum({1, 2, 3}, {0.1, 0.2, 1}, 5, 4, 20), frustum({1, 2, 3}, {0.1, 0.2, 1}, 5, 4, 20), "identical");
  check(frustum({1, 2, 3}, {0.1, 0.2, 1}, 5, 4, 20), frustum({1 + 1e-12, 2, 3}, {0.1, 0.2, 1}, 5, 4, 20), "1e-12 copy");
  // perpendicular, an end rim on the other's lateral surface
  check(frustum({0, 0, 0}, z, 5, 4, 20), frustum({4.5, 0, 10}, {1, 0, 0}, 3, 2, 10), "perpendicular");
}

TEST(ReviewPartPairSymmetry, RandomPairsNearAndFar) {
  std::mt19937_64 g(77);
  const auto U = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  for (int i = 0; i < 40; ++i) {
    const double far = i % 4 == 3 ? 1e6 : 0;
    const Vec3 o{far + U(-1, 1), U(-1, 1), U(-1, 1)};
    const Cylinder a = frustum(o, {U(-1, 1), U(-1, 1), U(-1, 1)}, U(3, 6), i % 2 ? U(2, 7) : -1, U(10, 30));
    Cylinder fa = a;
    if (fa.top_radius < 0) fa.top_radius = -1;
    const Vec3 off{U(-12, 12), U(-12, 12), U(-12, 12)};
    const Cylinder b = frustum(a.center() + off, {U(-1, 1), U(-1, 1), U(-1, 1)}, U(3, 6), U(2, 7), U(10, 30));
    check(fa.top_radius < 0 ? frustum(a.base, a.axis, a.radius, a.radius, a.height) : a, b, "random " + std::to_string(i),
          far == 0);
  }
}

}  // namespace
}  // namespace interfere::bearing
