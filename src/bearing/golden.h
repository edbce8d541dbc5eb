// Golden-section search shared by the bearing solvers (analytic.cpp: the general nested path and
// tapered rollers; scarred.cpp: per-triangle minima along edges). Kiefer 1953.
#pragma once
#include <algorithm>
#include <cmath>
#include <utility>

#include "interfere/bearing/cylinder.h"

namespace interfere::bearing::detail {

inline constexpr double kGolden = 0.61803398874989484820;

/// Golden-section minimisation of a convex f on [lo, hi]; returns (argmin, min) over every point
/// evaluated (the end points included).
template <class F>
std::pair<double, double> golden_min(F&& f, double lo, double hi, int iterations) {
  double best_x = lo, best = f(lo);
  if (!(hi > lo)) return {best_x, best};
  if (const double fh = f(hi); fh < best) best = fh, best_x = hi;
  double a = lo, b = hi;
  double c = b - kGolden * (b - a), d = a + kGolden * (b - a);
  double fc = f(c), fd = f(d);
  // Once the bracket is within rounding of its ends' magnitude or of the initial interval (2^-52,
  // about 75 steps from the start), further steps only re-sample rounding noise: stop there (the
  // searches asking for 90-110 steps reach it early; those asking for 64 do not).
  const double floor = 0x1p-52 * std::max({std::fabs(lo), std::fabs(hi), hi - lo});
  for (int k = 0; k < iterations; ++k) {
    if (!(b - a > floor)) break;
    if (fc < best) best = fc, best_x = c;
    if (fd < best) best = fd, best_x = d;
    if (fc <= fd) {
      b = d, d = c, fd = fc;
      c = b - kGolden * (b - a);
      fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + kGolden * (b - a);
      fd = f(d);
    }
    if (!(b - a > 0)) break;
  }
  if (fc < best) best = fc, best_x = c;
  if (fd < best) best = fd, best_x = d;
  return {best_x, best};
}

/// The minimum of a convex function sd over the solid cylinder / cone frustum a, by nested
/// golden-section searches (axis parameter t, then x and y across the disk of radius r(t) in the
/// frame (f1, a.axis x f1)); partial minimisation keeps convexity. Returns (minimiser, minimum).
/// The general path of cylinder_pair_distance (analytic.cpp) and of cone_pair_distance
/// (raceway_cone.cpp), with their own sd.
template <class SD>
std::pair<Vec3, double> nested_min_over_frustum(const Cylinder& a, const Vec3& f1, SD&& sd, int iterations = 64) {
  const Vec3 f2 = cross(a.axis, f1);
  const auto point = [&](double t, double x, double y) { return a.base + a.axis * t + f1 * x + f2 * y; };
  const auto radius = [&](double t) { return a.radius + (a.top() - a.radius) * (t / a.height); };
  const auto over_y = [&](double t, double x, double r) {
    const double ym = std::sqrt(std::max(0.0, r * r - x * x));
    return golden_min([&](double y) { return sd(point(t, x, y)); }, -ym, ym, iterations);
  };
  const auto over_x = [&](double t) {
    const double r = radius(t);
    return golden_min([&](double x) { return over_y(t, x, r).second; }, -r, r, iterations);
  };
  const auto [t, value] = golden_min([&](double tt) { return over_x(tt).second; }, 0.0, a.height, iterations);
  const double r = radius(t);
  const double x = over_x(t).first;
  const double y = over_y(t, x, r).first;
  return {point(t, x, y), value};
}

}  // namespace interfere::bearing::detail
