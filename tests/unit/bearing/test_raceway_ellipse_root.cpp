// raceway.cpp's farthest_on_ellipse (the bore's end-circle maximum, max_axis_distance_on_rim; issue
// #27, speed): the bisection from 0 was replaced by Newton and a walk by ulps to the least double
// where the evaluated G is <= 0. G as evaluated is monotone in mu, so both end at the same double;
// this test keeps the previous code under a test-only name (farthest_on_ellipse_bisection and the
// rim wrapper, copied from raceway.cpp before the change) and requires the same bits on random
// circles and lines: any ring axis, rollers nearly parallel to it, exactly parallel, nearly
// perpendicular, circles of radius 0, far from the origin, points on the axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "../../../src/bearing/raceway_detail.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

/// Evaluated in mu (no cancellation near the pole); the distance is hypot(|y0| + X0, |y1| + X1).
struct FarOld {
  double distance = 0, x0 = 0, x1 = 0;
};
FarOld farthest_on_ellipse_bisection(double e0, double e1, double y0, double y1) {
  const double s0 = y0 < 0 ? -1.0 : 1.0, s1 = y1 < 0 ? -1.0 : 1.0;
  const double a0 = std::fabs(y0), a1 = std::fabs(y1);
  const double gap = e0 * e0 - e1 * e1;  // >= 0
  double X0, X1;
  if (a0 > 0) {
    const double n0 = a0 * e0, n1 = a1 * e1;
    const auto G = [&](double mu) {
      const double q0 = n0 / mu, q1 = n1 / (mu + gap);
      return q0 * q0 + q1 * q1 - 1;
    };
    double lo = 0, hi = std::hypot(n0, n1);
    for (int i = 0; i < 1100; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      if (G(mid) > 0) lo = mid;
      else hi = mid;
    }
    const double mu = hi;  // G(hi) <= 0: X0 <= e0 (the point is on or just inside the ellipse)
    X0 = std::min(e0, a0 * e0 * e0 / mu);
    X1 = e1 > 0 ? std::min(e1, a1 * e1 * e1 / (mu + gap)) : 0.0;
    // project onto the ellipse along x1 (the bisection's last ulp): x0 is the accurate coordinate
    if (e1 > 0) X1 = std::max(X1, e1 * std::sqrt(std::max(0.0, 1 - (X0 / e0) * (X0 / e0))));
  } else if (a1 * e1 >= gap) {
    X0 = 0, X1 = e1;
  } else if (e1 == 0) {  // a segment: its end
    X0 = e0, X1 = 0;
  } else {
    X1 = a1 * e1 * e1 / gap;  // gap > 0 here (else a1 * e1 >= 0 = gap)
    X0 = e0 * std::sqrt(std::max(0.0, 1 - (X1 / e1) * (X1 / e1)));
  }
  FarOld out;
  out.distance = std::hypot(a0 + X0, a1 + X1);
  out.x0 = -s0 * X0, out.x1 = -s1 * X1;
  return out;
}

/// max over one end circle of rho (distance to the line base + z u): the circle projected along u is
/// an ellipse, semi-axes r along f1 = d x u / |d x u| and r |cos gamma| along e2 = u x f1 (gamma the
/// angle between the axes); the line projects to a point. Returns (rho, the circle's point).

std::pair<double, Vec3> rim_reference(const detail::Rim& rim, const Vec3& d, const Vec3& base, const Vec3& u) {
  const Vec3 cr = cross(d, u);
  const double sl = norm(cr);
  const Vec3 f1 = sl > 0 ? cr / sl : detail::perpendicular_unit(d);
  const Vec3 e2 = cross(u, f1), g2 = cross(d, f1);
  const double cg = dot(g2, e2);
  const Vec3 q = rim.c - base;
  const FarOld far = farthest_on_ellipse_bisection(rim.r, rim.r * std::fabs(cg), -dot(q, f1), -dot(q, e2));
  double cs = rim.r > 0 ? far.x0 / rim.r : 1.0, sn;
  if (cg != 0 && rim.r > 0) sn = far.x1 / (rim.r * cg);
  else sn = std::sqrt(std::max(0.0, 1 - cs * cs));
  const double len = std::hypot(cs, sn);
  if (len > 0) cs /= len, sn /= len;
  return {far.distance, rim.c + f1 * (rim.r * cs) + g2 * (rim.r * sn)};
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(BearingRaceway, EllipseRootSameBitsAsTheBisection) {
  std::mt19937_64 g(2727);
  std::uniform_real_distribution<double> U(-1, 1);
  int differ = 0;
  for (int i = 0; i < 200000; ++i) {
    Vec3 u{1, 0, 0}, d{U(g), U(g), U(g)};
    const int kind = i % 7;
    if (kind == 0) u = Vec3{U(g), U(g), U(g)};
    if (kind == 1) d = Vec3{1, 1e-4 * U(g), 1e-4 * U(g)};  // nearly parallel (the bearings' case)
    if (kind == 2) d = Vec3{1, 0, 0};                      // parallel
    if (kind == 3) d = Vec3{1e-7 * U(g), 1, U(g)};         // nearly perpendicular
    if (kind == 6) d = Vec3{1, 1e-9 * U(g), 0};
    u = u / norm(u), d = d / norm(d);
    const double scale = std::pow(10.0, static_cast<int>(3 * U(g)));
    detail::Rim rim{Vec3{9300.0 * (i % 2) + scale * U(g), 130 * U(g), 130 * U(g)}, kind == 4 ? 0.0 : 20 * std::fabs(U(g))};
    Vec3 base{U(g), U(g), U(g)};
    if (kind == 5) base = rim.c - u * 3.0;  // the circle's centre on the line
    const auto [r_new, p_new] = detail::max_axis_distance_on_rim(rim, d, base, u);
    const auto [r_old, p_old] = rim_reference(rim, d, base, u);
    const bool same = same_bits(r_new, r_old) && same_bits(p_new.x, p_old.x) && same_bits(p_new.y, p_old.y) &&
                      same_bits(p_new.z, p_old.z);
    differ += !same;
    if (!same && differ < 5) ADD_FAILURE() << "case " << i << ": " << r_new << " vs " << r_old;
  }
  EXPECT_EQ(differ, 0);
}

}  // namespace
