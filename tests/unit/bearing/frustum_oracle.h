// An independent oracle for the scarred solver against a frustum (issue #27; scarred.h): nothing
// here calls the bearing module's distance code. frustum_oracle: the signed distance to a cone
// frustum as a generic convex polygon walk in the meridian plane (the symmetric trapezoid, four
// edges: outside the distance to the nearest edge point, inside minus the distance to the nearest
// edge line) with a subgradient. frustum_min_bracket: the minimum of it over a set of triangles by
// best-first subdivision (longest-edge bisection; centroid values are upper bounds, the lower bound
// of a cell is the convexity bound at its centroid, also for the convex minorants (rho - R(z)) /
// sqrt(1 + k^2), -z and z - h), refined until `tol` wide or the budget is spent.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

#include "bearing_oracle.h"
#include "interfere/bearing/cylinder.h"

namespace frustum_oracle_ns {

using interfere::Vec3;
using interfere::bearing::Cylinder;

using bearing_oracle::SdGrad;
using bearing_oracle::Bracket;

/// sd to the frustum c (radius c.radius at the base, c.top() at the top) by a generic convex
/// polygon walk in p's meridian plane.
inline SdGrad frustum_oracle(const Cylinder& c, const Vec3& p) {
  const Vec3 w = p - c.base;
  const double z = dot(w, c.axis);
  const Vec3 q = w - c.axis * z;
  const double x = norm(q);
  const Vec3 radial = x > 0 ? q / x : Vec3{1, 0, 0};
  // counter-clockwise polygon in (x, z)
  const std::array<std::array<double, 2>, 4> v = {{{-c.radius, 0}, {c.radius, 0}, {c.top(), c.height}, {-c.top(), c.height}}};
  bool inside = true;
  double best_out = 1e300, best_in = 1e300;
  double gx = 0, gz = 0, ix = 0, iz = 0;
  for (int e = 0; e < 4; ++e) {
    const auto& a = v[static_cast<std::size_t>(e)];
    const auto& b = v[static_cast<std::size_t>((e + 1) % 4)];
    const double ex = b[0] - a[0], ez = b[1] - a[1], l = std::hypot(ex, ez);
    const double nx = ez / l, nz = -ex / l;  // outward normal of a counter-clockwise polygon
    const double line = (x - a[0]) * nx + (z - a[1]) * nz;
    if (line > 0) inside = false;
    if (-line < best_in) best_in = -line, ix = nx, iz = nz;
    const double t = std::clamp(((x - a[0]) * ex + (z - a[1]) * ez) / (l * l), 0.0, 1.0);
    const double dx = x - (a[0] + t * ex), dz = z - (a[1] + t * ez), d = std::hypot(dx, dz);
    if (d < best_out) best_out = d, gx = d > 0 ? dx / d : nx, gz = d > 0 ? dz / d : nz;
  }
  if (inside) return {-best_in, radial * ix + c.axis * iz};
  return {best_out, radial * gx + c.axis * gz};
}

inline Bracket frustum_min_bracket(const std::vector<std::array<Vec3, 3>>& triangles, const Cylinder& b, double tol,
                                  std::size_t budget = 6'000'000) {
  return bearing_oracle::min_bracket(triangles, b, tol, budget, frustum_oracle);
}

/// s(A, B) = min over the SOLID a of sd_B (analytic.h), for frustums a and b: a convex program
/// (sd_B convex, a convex), solved by the central-cut ellipsoid method in 3D (Shor, Nemirovski and
/// Yudin): from a ball holding a, each step cuts the ellipsoid through its centre x with a
/// subgradient of sd_A when x lies outside a (feasibility cut), else with one of sd_B (objective
/// cut, recording sd_B(x)); the volume shrinks by a fixed factor per step, so the best recorded
/// value converges to the minimum (sd_B is 1-Lipschitz). Stops when the ellipsoid's largest axis is
/// below 1e-13 of a's size. Only frustum_oracle's values and subgradients are used.
inline double frustum_solid_min(const Cylinder& a, const Cylinder& b) {
  const double half = 0.5 * a.height, rmax = std::max(a.radius, a.top());
  const double r0 = std::sqrt(half * half + rmax * rmax) * 1.01;
  Vec3 x = a.base + a.axis * half;
  double P[3][3] = {{r0 * r0, 0, 0}, {0, r0 * r0, 0}, {0, 0, r0 * r0}};
  double best = 1e300;
  const double stop = 1e-26 * r0 * r0;
  for (int it = 0; it < 20000; ++it) {
    const SdGrad in_a = frustum_oracle(a, x);
    const SdGrad g = in_a.value <= 0 ? frustum_oracle(b, x) : in_a;
    if (in_a.value <= 0) best = std::min(best, g.value);
    const double gv[3] = {g.grad.x, g.grad.y, g.grad.z};
    double Pg[3];
    for (int r = 0; r < 3; ++r) Pg[r] = P[r][0] * gv[0] + P[r][1] * gv[1] + P[r][2] * gv[2];
    const double gPg = gv[0] * Pg[0] + gv[1] * Pg[1] + gv[2] * Pg[2];
    if (!(gPg > stop)) break;  // the ellipsoid is a point along g: converged
    const double sq = std::sqrt(gPg);
    for (double& v : Pg) v /= sq;
    x = x - Vec3{Pg[0], Pg[1], Pg[2]} * 0.25;  // 1 / (n + 1)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) P[r][c] = 1.125 * (P[r][c] - 0.5 * Pg[r] * Pg[c]);  // n^2 / (n^2 - 1), 2 / (n + 1)
    for (int r = 0; r < 3; ++r)
      for (int c = r + 1; c < 3; ++c) P[r][c] = P[c][r] = 0.5 * (P[r][c] + P[c][r]);
    if (P[0][0] + P[1][1] + P[2][2] < stop) break;
  }
  return best;
}

}  // namespace frustum_oracle_ns
