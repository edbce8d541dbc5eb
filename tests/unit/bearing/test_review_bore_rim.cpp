// Adversarial review (issue #27) of bbb236b: raceway.cpp's farthest_on_ellipse root by Newton + a
// walk by ulps (the bore's end-circle maximum, detail::max_axis_distance_on_rim). The existing test
// compares the new root with the previous bisection only; this one checks the answer itself against
// an independent oracle: the circle sampled densely in its own frame (a basis built here by
// Gram-Schmidt, not the solver's f1 / e2), the distance to the line from its definition, the best
// samples refined by golden-section search. Two sides:
//  - the oracle's value is reached at a point of the circle, so the reported maximum must not be
//    below it (an underestimated reach of the roller's rim would be a wrong "clear" of the bore);
//  - the reported point must lie on the circle and its distance to the line must equal the reported
//    value (the value is realised, so it is not above the true maximum).
// Inputs aimed at the root finder: nearly circular ellipses (roller axis within 1e-12 .. 1e-3 of the
// ring axis, and exactly parallel), extreme aspect (axes perpendicular to 1e-12), the circle's
// centre on or within 1e-300 .. 1e-9 of the line (the root at the bracket's low end), centres far
// out on the ellipse's minor axis (the root near the bracket's top), huge coordinates (1e8), tiny
// and large radii. Also: no NaN, and each call returns (no hang in the ulp walk).
// Found (and fixed in raceway.cpp, not in the root finder, which held): (1) axes 1e-12 .. 1e-6
// apart: f1 = (d x u) / |d x u| was rounding noise, the rim point left its circle and the reach came
// out low by up to 7.5 % (a roller's rim poking past the bore judged inside); (2) parallel axes and
// a centre on the line: |cg| rounded to 1 + 2^-52, e1 > e0, the ellipse's gap < 0 broke the root's
// monotonicity and the reach came out up to 11 % high.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "../../../src/bearing/raceway_detail.h"
#include "interfere/bearing/raceway.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

using SplitMix = interfere::bearing::test::SplitMix;

double line_distance(const Vec3& p, const Vec3& base, const Vec3& u) {
  const Vec3 w = p - base;
  return norm(w - u * dot(w, u));
}

struct Oracle {
  double value;
  Vec3 point;
};

Oracle oracle(const detail::Rim& rim, const Vec3& d, const Vec3& base, const Vec3& u) {
  // a basis of the circle's plane: Gram-Schmidt from the coordinate axis least aligned with d
  const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  const Vec3 e = ax <= ay && ax <= az ? Vec3{1, 0, 0} : ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  Vec3 a = e - d * dot(e, d);
  a = a / norm(a);
  const Vec3 b = cross(d, a);
  const auto at = [&](double t) { return rim.c + a * (rim.r * std::cos(t)) + b * (rim.r * std::sin(t)); };
  const auto h = [&](double t) { return line_distance(at(t), base, u); };
  constexpr int N = 4096;
  const double step = 2 * std::numbers::pi / N;
  Oracle best{-1, rim.c};
  std::vector<std::pair<double, int>> top;
  for (int i = 0; i < N; ++i) top.push_back({h(i * step), i});
  std::partial_sort(top.begin(), top.begin() + 4, top.end(), [](auto& x, auto& y) { return x.first > y.first; });
  for (int k = 0; k < 4; ++k) {
    double lo = (top[k].second - 1) * step, hi = (top[k].second + 1) * step;
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double c = hi - g * (hi - lo), dd = lo + g * (hi - lo), fc = h(c), fd = h(dd);
    for (int it = 0; it < 120; ++it) {
      if (fc >= fd) hi = dd, dd = c, fd = fc, c = hi - g * (hi - lo), fc = h(c);
      else lo = c, c = dd, fc = fd, dd = lo + g * (hi - lo), fd = h(dd);
    }
    for (const double t : {c, dd, top[k].second * step})
      if (const double v = h(t); v > best.value) best = {v, at(t)};
  }
  return best;
}

Vec3 unit(Vec3 v) { return v / norm(v); }

}  // namespace

TEST(ReviewBoreRim, FarthestRimPointAgainstDenseSampling) {
  SplitMix rng{0xb0e27};
  double worst_below = 0, worst_witness = 0, worst_rel = 0;
  int cases = 0;
  for (int i = 0; i < 6000; ++i) {
    const Vec3 u = i % 3 == 0 ? unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)}) : Vec3{0, 0, 1};
    // a unit vector perpendicular to u
    const Vec3 p = unit(cross(u, std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 p2 = cross(u, p);
    const int kind = i % 8;
    const double tiny = std::pow(10.0, -rng.in(3, 12));
    Vec3 d;
    switch (kind) {
      case 0: d = unit(u + p * (tiny * rng.in(-1, 1)) + p2 * (tiny * rng.in(-1, 1))); break;  // nearly circular
      case 1: d = u; break;                                                                    // a circle
      case 2: d = unit(p + u * (tiny * rng.in(-1, 1))); break;                                 // a segment, nearly
      case 3: d = p; break;                                                                    // a segment
      default: d = unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)}); break;
    }
    const double r = std::pow(10.0, rng.in(-3, 3));
    const double far = kind == 7 ? 1e8 : std::pow(10.0, rng.in(-1, 4));
    const Vec3 base = Vec3{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)} * far;
    Vec3 c = base + u * (far * rng.in(-1, 1));
    const int where = (i / 8) % 4;
    if (where == 0) c = c + p * (r * std::pow(10.0, -rng.in(0, 300)));  // centre (nearly) on the line
    else if (where == 1) c = c + (p * rng.in(-1, 1) + p2 * rng.in(-1, 1)) * (r * rng.in(0, 3));
    else if (where == 2) c = c + cross(u, d) * (r * rng.in(0.5, 30));  // along the minor axis
    // where == 3: exactly on the line
    const detail::Rim rim{c, r};
    const auto [got, point] = detail::max_axis_distance_on_rim(rim, d, base, u);
    ASSERT_TRUE(std::isfinite(got)) << "case " << i;
    ASSERT_TRUE(std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z)) << "case " << i;
    const Oracle o = oracle(rim, d, base, u);
    // rounding of the inputs: the coordinates' magnitude; the oracle's golden search: 1e-12 of r
    const double scale = norm(c - base) + r + 1e-16 * (norm(c) + norm(base)) * 8;
    const double tol = 1e-12 * scale + 1e-14 * (norm(c) + norm(base));
    worst_below = std::max(worst_below, o.value - got);
    worst_rel = std::max(worst_rel, std::fabs(o.value - got) / scale);
    if (got < o.value - tol && std::getenv("REVIEW_BORE_DEBUG"))
      std::printf("dbg case %d |dxu| %.3g r %.3g |c-base| %.3g rel %.3g c %a %a %a r %a d %a %a %a base %a %a %a u %a %a %a\n", i,
                  norm(cross(d, u)), r, norm(c - base), (o.value - got) / o.value, c.x, c.y, c.z, r, d.x, d.y, d.z,
                  base.x, base.y, base.z, u.x, u.y, u.z);
    EXPECT_GE(got, o.value - tol) << "case " << i << " kind " << kind << " where " << where << ": the oracle reaches "
                                  << o.value << ", reported " << got;
    // the witness: on the circle, at the reported distance
    const Vec3 w = point - c;
    const double on_plane = std::fabs(dot(w, d)), on_circle = std::fabs(norm(w) - r);
    const double wd = std::fabs(line_distance(point, base, u) - got);
    worst_witness = std::max({worst_witness, on_plane / scale, on_circle / scale, wd / scale});
    EXPECT_LE(on_plane, tol) << "case " << i;
    EXPECT_LE(on_circle, tol) << "case " << i;
    if (wd > tol && std::getenv("REVIEW_BORE_DEBUG"))
      std::printf("dbgw case %d kind %d where %d r %.17g got %.17g oracle %.17g point %.17g |dxu| %.3g |c-base| %.3g\n", i,
                  kind, where, r, got, o.value, line_distance(point, base, u), norm(cross(d, u)), norm(c - base));
    EXPECT_LE(wd, tol) << "case " << i << ": the point's distance " << line_distance(point, base, u) << " vs " << got;
    ++cases;
  }
  std::printf("[review] bore rim: %d cases, worst oracle - reported %.3g (relative %.3g), worst witness %.3g\n",
              cases, worst_below, worst_rel, worst_witness);
}

// End to end: roller_bore_distance for a roller inside the width, its axis 0 .. 1e-6 from the
// bore's (a bearing's rollers: parallel to the rings up to the rounding of their poses), in a
// general orientation. s = R - max over the roller of rho, the maximum on an end circle: both
// circles by the oracle above. Before the fix in max_axis_distance_on_rim the rim maximum was off
// for such axes (ReviewBoreRim.FarthestRimPointAgainstDenseSampling).
TEST(ReviewBoreRim, RollerInBoreNearlyParallel) {
  SplitMix rng{0xb07e};
  const double angles[] = {0, 1e-17, 1e-16, 1e-15, 1e-14, 1e-13, 1e-12, 1e-10, 1e-8, 1e-6};
  double worst = 0;
  int too_high = 0;
  for (int i = 0; i < 3000; ++i) {
    const double eps = angles[i % 10];
    const Vec3 u = unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)});
    const Vec3 p = unit(cross(u, std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 p2 = cross(u, p);
    bearing::Bore bore;
    bore.base = Vec3{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)} * std::pow(10.0, rng.in(0, 3));
    bore.axis = u, bore.radius = rng.in(60, 200), bore.width = rng.in(30, 60);
    const double rr = rng.in(4, 15), h = rng.in(8, 0.8 * bore.width);
    const double tw = rng.in(0, 2 * std::numbers::pi), ph = rng.in(0, 2 * std::numbers::pi);
    Cylinder roller;
    roller.axis = unit(u + (p * std::cos(tw) + p2 * std::sin(tw)) * eps);
    roller.radius = rr, roller.height = h;
    const double pitch = bore.radius - rr + rng.in(-0.05, 0.05);  // pressed or clear by up to 0.05
    const double z0 = rng.in(1, bore.width - h - 1);
    roller.base = bore.base + u * z0 + (p * std::cos(ph) + p2 * std::sin(ph)) * pitch;
    const PairDistance got = roller_bore_distance(roller, bore);
    const double reach = std::max(oracle({roller.base, rr}, roller.axis, bore.base, u).value,
                                  oracle({roller.top_center(), rr}, roller.axis, bore.base, u).value);
    const double ref = bore.radius - reach;
    const double tol = 1e-11 * bore.radius + 1e-14 * norm(bore.base);
    worst = std::max(worst, std::fabs(got.distance - ref));
    too_high += got.distance > ref + tol;
    EXPECT_NEAR(got.distance, ref, tol) << "case " << i << " angle " << eps << " path " << analytic_path_name(got.path)
                                        << " |d x u| " << norm(cross(roller.axis, u)) << " d.u - 1 " << dot(roller.axis, u) - 1
                                        << std::hexfloat << " roller base " << roller.base.x << " " << roller.base.y << " "
                                        << roller.base.z << " axis " << roller.axis.x << " " << roller.axis.y << " "
                                        << roller.axis.z << " r " << rr << " h " << h << " bore base " << bore.base.x << " "
                                        << bore.base.y << " " << bore.base.z << " axis " << u.x << " " << u.y << " " << u.z
                                        << " R " << bore.radius << " width " << bore.width << std::defaultfloat;
  }
  EXPECT_EQ(too_high, 0);
  std::printf("[review] roller in bore, nearly parallel: worst |s - ref| %.3g, %d above the reference\n", worst,
              too_high);
}

// The case that found raceway_slab.cpp's axial_extent bug: the roller's axis 1 ulp per component
// from the bore's (cross product exactly 0), the roller at z 1.23 .. 12.74 inside a width of 37.3,
// 0.0298 clear of the raceway; it came out path apart, 1.23 (its "axial gap"), since u - d (d . u)
// was rounding noise and the rims' axial extent was taken along it.
TEST(ReviewBoreRim, AxisOneUlpFromTheBores) {
  Cylinder roller;
  roller.base = {0x1.58f8d9d16e59bp+5, 0x1.c6175edffc15bp+5, -0x1.0b7b70cd51d1cp+5};
  roller.axis = {-0x1.23223ba9f9effp-1, 0x1.6b5b0d084613ep-1, 0x1.a9f28e228c371p-2};
  roller.radius = 0x1.c30eb18436a97p+3, roller.height = 0x1.7051d5c890288p+3;
  bearing::Bore bore;
  bore.base = {0x1.0a206f27f2c3cp+2, 0x1.5c957d12223fcp+2, -0x1.0c83913957dc7p+1};
  bore.axis = {-0x1.23223ba9f9efep-1, 0x1.6b5b0d084613dp-1, 0x1.a9f28e228c37p-2};
  bore.radius = 0x1.570cc37a894acp+6, bore.width = 0x1.2a8d301d14285p+5;
  const PairDistance got = roller_bore_distance(roller, bore);
  const double reach = std::max(oracle({roller.base, roller.radius}, roller.axis, bore.base, bore.axis).value,
                                oracle({roller.top_center(), roller.radius}, roller.axis, bore.base, bore.axis).value);
  EXPECT_EQ(got.path, AnalyticPath::bore);
  EXPECT_NEAR(got.distance, bore.radius - reach, 1e-11);
  EXPECT_NEAR(got.distance, 0.029780330329458593, 1e-11);
}
