// Golden-section search shared by the bearing solvers (analytic.cpp: the general nested path and
// tapered rollers; scarred.cpp: per-triangle minima along edges). Kiefer 1953.
#pragma once
#include <utility>

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
  for (int k = 0; k < iterations; ++k) {
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

}  // namespace interfere::bearing::detail
