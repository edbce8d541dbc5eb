// Independent oracles for the bearing tests (issue #23, item 14): nothing here calls the bearing
// module's distance code (cylinder.h signed distances, analytic.h, scarred.h).
//
//  * oracle_sd: the signed distance to a solid finite cylinder by a different method from
//    cylinder.h's closed form: outside, the distance to the clamped closest point; inside, the
//    largest of the three face functions. It also returns a subgradient of sd (convex, B convex).
//  * surface_min_bracket: the minimum of sd over a set of triangles (the roller's surface) by
//    best-first subdivision (longest-edge bisection): each cell's value at its centroid c is an
//    upper bound of the minimum; convexity gives the lower bound sd(c) + min over the cell's
//    corners of g . (v - c) (g a subgradient at c; a linear function is smallest at a corner), and
//    the same bound for each of sd's convex minorants rho - R, -z, z - h (B lies in each of their
//    sublevel sets, so sd >= each), which is tight along the ridges inside B where sd is their
//    maximum (and not differentiable). The largest of these lower bounds is the cell's. It returns
//    the bracket [lower, upper] that holds the exact minimum, refined until it is `tol` wide or the
//    budget of evaluations is spent.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

#include "interfere/bearing/cylinder.h"

namespace bearing_oracle {

using interfere::Vec3;
using interfere::bearing::Cylinder;

struct SdGrad {
  double value = 0;
  Vec3 grad;
};

inline SdGrad oracle_sd(const Cylinder& c, const Vec3& p) {
  const Vec3 w = p - c.base;
  const double z = dot(w, c.axis);
  const Vec3 q = w - c.axis * z;
  const double rho = norm(q);
  const Vec3 radial = rho > 0 ? q / rho : Vec3{0, 0, 0};
  const double R = c.radius, h = c.height;
  if (rho <= R && z >= 0 && z <= h) {  // inside or on the boundary: max of the face functions
    SdGrad s{rho - R, radial};
    if (-z > s.value) s = {-z, c.axis * -1.0};
    if (z - h > s.value) s = {z - h, c.axis};
    return s;
  }
  const Vec3 nearest = c.base + c.axis * std::clamp(z, 0.0, h) + radial * std::min(rho, R);
  const Vec3 d = p - nearest;
  const double l = norm(d);
  return {l, d / l};
}

struct Bracket {
  double lower = 0, upper = 0;
  std::size_t evaluations = 0;
};

/// The bracket of the minimum of sd_B over the triangles (above), for any oracle `sd` of a solid B
/// that is a cylinder or a cone frustum about b's axis (b.top() at the top): the convex minorants
/// are (rho - R(z)) / sqrt(1 + k^2) (k the radius' slope; rho - R for a cylinder), -z and z - h.
template <class Sd>
Bracket min_bracket(const std::vector<std::array<Vec3, 3>>& triangles, const Cylinder& b, double tol,
                    std::size_t budget, const Sd& sd) {
  struct Cell {
    std::array<Vec3, 3> v;
    double lower;
    bool operator<(const Cell& o) const { return lower > o.lower; }  // min-heap on lower
  };
  const double k = (b.top() - b.radius) / b.height, nk = std::sqrt(1 + k * k);
  Bracket out;
  out.upper = 1e300;
  std::priority_queue<Cell> open;
  const auto push = [&](const std::array<Vec3, 3>& v) {
    const Vec3 c = (v[0] + v[1] + v[2]) / 3.0;
    const SdGrad s = sd(b, c);
    ++out.evaluations;
    out.upper = std::min(out.upper, s.value);
    const auto bound = [&](double value, const Vec3& g) {
      double lin = 0;
      for (const Vec3& x : v) lin = std::min(lin, dot(g, x - c));
      return value + lin;
    };
    const Vec3 w = c - b.base;
    const double z = dot(w, b.axis);
    const Vec3 q = w - b.axis * z;
    const double rho = norm(q);
    const Vec3 radial = rho > 0 ? q / rho : Vec3{0, 0, 0};
    const double lateral = (rho - b.radius - k * z) / nk;
    open.push({v, std::max({bound(s.value, s.grad), bound(lateral, (radial - b.axis * k) / nk),
                            bound(-z, b.axis * -1.0), bound(z - b.height, b.axis)})});
  };
  for (const auto& t : triangles) {
    for (const Vec3& x : t) out.upper = std::min(out.upper, sd(b, x).value);
    push(t);
  }
  while (!open.empty()) {
    const Cell cell = open.top();
    if (cell.lower >= out.upper - tol || out.evaluations >= budget) break;
    open.pop();
    // longest-edge bisection (the cells of thin triangles become well shaped)
    const auto& v = cell.v;
    int e0 = 0;
    for (int e = 1; e < 3; ++e)
      if (norm(v[(e + 1) % 3] - v[e]) > norm(v[(e0 + 1) % 3] - v[e0])) e0 = e;
    const Vec3& p0 = v[e0];
    const Vec3& p1 = v[(e0 + 1) % 3];
    const Vec3& p2 = v[(e0 + 2) % 3];
    const Vec3 m = (p0 + p1) * 0.5;
    out.upper = std::min(out.upper, sd(b, m).value);
    push({p0, m, p2});
    push({m, p1, p2});
  }
  out.lower = open.empty() ? out.upper : std::min(open.top().lower, out.upper);
  return out;
}

inline Bracket surface_min_bracket(const std::vector<std::array<Vec3, 3>>& triangles,
                                   const Cylinder& b, double tol, std::size_t budget = 4'000'000) {
  return min_bracket(triangles, b, tol, budget, oracle_sd);
}

/// A closed tessellation of the (possibly tapered) cylinder a with n sides, corners on its
/// surface: it lies in the solid, and every point of a's boundary is within
/// facet_gap(a, n) = max radius * (1 - cos(pi / n)) of it. Hence, for min over the surface of a
/// 1-Lipschitz function f, min_mesh f - facet_gap <= min_surface f <= min_mesh f.
inline std::vector<std::array<Vec3, 3>> cylinder_triangles(const Cylinder& a, int n) {
  const Vec3 u = a.axis;
  const Vec3 t = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 f1 = cross(u, t);
  f1 = f1 / norm(f1);
  const Vec3 f2 = cross(u, f1);
  const Vec3 top = a.base + u * a.height;
  std::vector<Vec3> lo(static_cast<std::size_t>(n)), hi(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * std::numbers::pi * i / n;
    const Vec3 d = f1 * std::cos(phi) + f2 * std::sin(phi);
    lo[static_cast<std::size_t>(i)] = a.base + d * a.radius;
    hi[static_cast<std::size_t>(i)] = top + d * a.top();
  }
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t i = 0; i < lo.size(); ++i) {
    const std::size_t k = (i + 1) % lo.size();
    out.push_back({lo[i], lo[k], hi[k]});
    out.push_back({lo[i], hi[k], hi[i]});
    out.push_back({a.base, lo[k], lo[i]});
    out.push_back({top, hi[i], hi[k]});
  }
  return out;
}
inline double facet_gap(const Cylinder& a, int n) {
  return a.max_radius() * (1 - std::cos(std::numbers::pi / n));
}

}  // namespace bearing_oracle
