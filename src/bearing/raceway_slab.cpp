// A roller's solid restricted to a ring's width (issue #27; raceway.h, roller_bore_distance and
// roller_cup_distance): the ring's material occupies only the slab 0 <= z <= width, so the part of
// the roller that can reach into it is K = roller /\ slab, a convex set. The maximum of a convex
// function (the distance to the ring axis; its cone-line variant for a cup) over K is reached at an
// extreme point of K (Rockafellar, Convex Analysis, Cor. 32.3.2): an end circle's point within the
// slab, or a point of the curves where the lateral surface crosses the slab's planes (the end
// disks' chords in those planes end on the circles). docs/bearing.md, "Raceways (issue #27)".
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "raceway_detail.h"

namespace interfere::bearing::detail {

AxialExtent axial_extent(const Cylinder& c, const Vec3& base, const Vec3& u) {
  const Vec3& d = c.axis;
  // u's part in the end-circle planes, accurate for nearly (anti)parallel axes (plain, it is rounding
  // noise there: a roller inside the width came out beyond a side face, path apart; review, issue
  // #27, ReviewBoreRim.RollerInBoreNearlyParallel)
  const Vec3 pu = detail::accurate_across(u, d);
  const double spu = norm(pu);
  const Vec3 dir = spu > 0 ? pu / spu : Vec3{0, 0, 0};
  AxialExtent e;
  e.zmin = std::numeric_limits<double>::infinity(), e.zmax = -e.zmin;
  const Rim rims[2] = {{c.base, c.radius}, {c.top_center(), c.top()}};
  for (const Rim& rim : rims) {
    const Vec3 lo = rim.c - dir * rim.r, hi = rim.c + dir * rim.r;
    const double zl = dot(lo - base, u), zh = dot(hi - base, u);
    if (zl < e.zmin) e.zmin = zl, e.low = lo;
    if (zh > e.zmax) e.zmax = zh, e.high = hi;
  }
  return e;
}

SlabMax max_convex_over_slab(const Cylinder& c, const Vec3& base, const Vec3& u, double zlo, double zhi,
                             const std::function<double(const Vec3&)>& f) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  constexpr int kSamples = 24;  // per interval; f along a curve has at most two maxima per turn
  const Vec3& d = c.axis;
  const double h = c.height, r0 = c.radius, r1 = c.top(), k = (r1 - r0) / h;
  const Vec3 f1 = perpendicular_unit(d), f2 = cross(d, f1);
  const double a1 = dot(f1, u), a2 = dot(f2, u), du = dot(d, u), z0 = dot(c.base - base, u);
  const double spu = std::hypot(a1, a2), phu = std::atan2(a2, a1);
  const double ts[2] = {0, h}, rs[2] = {r0, r1}, levels[2] = {zlo, zhi};
  // rounding slack of the validity tests (a circle lying in a plane, a curve ending on a circle)
  const double slack_z = 0x1p-40 * (std::fabs(z0) + std::fabs(zlo) + std::fabs(zhi) + h + std::max(r0, r1));
  const double slack_t = 0x1p-40 * h;

  // the angles where an end circle (z = zc + r spu cos(phi - phu)) crosses a plane: every curve's
  // validity is constant between two consecutive ones
  std::vector<double> cuts{0, kTwoPi};
  for (int j = 0; j < 2; ++j) {
    const double zc = z0 + du * ts[j], amp = rs[j] * spu;
    if (!(amp > 0)) continue;
    for (const double level : levels) {
      const double x = (level - zc) / amp;
      if (!(x >= -1 && x <= 1)) continue;
      const double a = std::acos(x);
      for (double phi : {phu + a, phu - a}) {
        phi = std::fmod(phi, kTwoPi);
        if (phi < 0) phi += kTwoPi;
        cuts.push_back(phi);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());

  // curves 0, 1: the end circles at t = 0, h; curves 2, 3: the lateral surface in z = zlo, z = zhi
  // (the generator at angle phi, z(t) = z0 + r0 s + t (du + k s), s = (f1 cos + f2 sin).u, linear in t)
  const auto ring = [&](double phi) { return f1 * std::cos(phi) + f2 * std::sin(phi); };
  const auto section_t = [&](double level, double phi) {
    const double s = a1 * std::cos(phi) + a2 * std::sin(phi), den = du + k * s;
    return den != 0 ? (level - z0 - r0 * s) / den : std::numeric_limits<double>::infinity();
  };
  const auto point = [&](int curve, double phi) {
    if (curve < 2) return c.base + d * ts[curve] + ring(phi) * rs[curve];
    const double t = std::clamp(section_t(levels[curve - 2], phi), 0.0, h);
    return c.base + d * t + ring(phi) * (r0 + k * t);
  };
  const auto valid = [&](int curve, double phi) {
    if (curve < 2) {
      const double z = dot(point(curve, phi) - base, u);
      return z >= zlo - slack_z && z <= zhi + slack_z;
    }
    const double t = section_t(levels[curve - 2], phi);
    return t >= -slack_t && t <= h + slack_t;
  };

  SlabMax best;
  best.value = -std::numeric_limits<double>::infinity();
  const auto take = [&](double v, const Vec3& p) {
    if (v > best.value) best.value = v, best.point = p;
  };
  std::vector<double> v(kSamples);
  for (std::size_t m = 0; m + 1 < cuts.size(); ++m) {
    const double a = cuts[m], b = cuts[m + 1];
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b), step = (b - a) / (kSamples - 1);
    for (int curve = 0; curve < 4; ++curve) {
      if (!valid(curve, mid)) continue;
      const auto g = [&](double phi) { return f(point(curve, phi)); };
      for (int i = 0; i < kSamples; ++i) {
        const double phi = i + 1 == kSamples ? b : a + step * i;
        v[i] = g(phi);
        take(v[i], point(curve, phi));
      }
      for (int i = 0; i < kSamples; ++i) {  // every sampled local maximum, the ends included
        if ((i > 0 && v[i] < v[i - 1]) || (i + 1 < kSamples && v[i] < v[i + 1])) continue;
        const double lo = a + step * std::max(i - 1, 0), hi = std::min(a + step * (i + 1), b);
        const auto [phi, neg] = golden_min([&](double x) { return -g(x); }, lo, hi, 64);
        take(-neg, point(curve, phi));
      }
    }
  }
  return best;
}

}  // namespace interfere::bearing::detail
