// The two-sided value S(A, B) = min(s(A, B), s(B, A)) of two intact cylinders (part_pair.h; issue #27:
// the maximum interference distance of a pair is one number, whichever part is first), with the
// standard solver of Jia & Zheng 2019 §3.1 (analytic.h) both ways, and the proven lower bound of the
// reverse direction that lets the rows skip it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/part_pair.h"

namespace interfere::bearing {

PairDistance two_sided_cylinder_distance(const Cylinder& a, const Cylinder& b) {
  PairDistance fwd = cylinder_pair_distance(a, b);
  const PairDistance rev = cylinder_pair_distance(b, a);
  if (rev.distance < fwd.distance) {
    fwd.distance = rev.distance, fwd.point_a = rev.point_b, fwd.point_b = rev.point_a;  // on a, on b
    fwd.path = rev.path;
  }
  return fwd;
}

// A lower bound of s(B, A) = min over the solid B of sd_A, for untapered A and B (issue #27: the
// two-sided row S = min(s(A, B), s(B, A)) needs the reverse direction only when it can be the smaller
// one; in Table 3's poses it never is beyond rounding, and computing it by the standard solver's
// slice path costs ~60x the forward value).
// Planes across A's axis at A-height z: a point y of B in such a plane has sd_A(y) >= max(rho_A(y) - r,
// -z, z - h) (A is the intersection of its infinite cylinder and its slab), and rho_A(y) >= F(z), the
// distance from A's axis point at z to the section of B's infinite cylinder by the plane (an ellipse,
// semi-axes R/|a.b| and R). Points of B outside A's slab have sd_A >= 0. So
//   s(B, A) >= min(0, min over z in [0, h] of max(F(z) - r, -z, z - h)).
// F is convex in z (partial minimisation of the distance over a convex solid, as in analytic.cpp's
// slice path), so through exact samples of F the secant of two neighbouring samples, extended beyond
// them, lies below F: a piecewise-linear minorant. Samples at the slab's ends and three about the
// minimiser of the coarse (end-to-end secant) model; the minimum of the max of lines over each
// interval is at its ends or a crossing of two lines. A margin of 1e-10 of the scene's scale covers
// the rounding (the extrapolation multiplies it by at most h / spacing = 1e3). -inf when axes are
// more than 60 degrees apart (not used).
double intact_reverse_lower_bound(const Cylinder& a, const Cylinder& b) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  const double ab = dot(a.axis, b.axis);
  if (!(std::fabs(ab) >= 0.5) || a.tapered() || b.tapered()) return kNone;
  const double h = a.height, r = a.radius, R = b.radius;
  Vec3 m = b.axis - a.axis * ab;  // B's axis projected into the planes
  const double mm = norm(m);
  if (!(mm > 1e-300)) {  // parallel axes: the section is a circle, any direction across A's axis
    m = cross(a.axis, std::fabs(a.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    m = m / norm(m);
  } else {
    m = m / mm;
  }
  const Vec3 n = cross(a.axis, m);
  const double ex = R / std::fabs(ab), ey = R;
  const auto F = [&](double z) {
    const Vec3 o = a.base + a.axis * z;                                // A's axis point
    const Vec3 c = b.base + b.axis * (dot(o - b.base, a.axis) / ab);   // B's axis in the plane
    const Vec3 q = o - c;
    return point_ellipse_distance(ex, ey, dot(q, m), dot(q, n)).distance;
  };
  // the coarse model: the end-to-end secant, and its g's minimiser among the crossings
  const double f0 = F(0), fh = F(h), k = (fh - f0) / h;
  const auto g_lin = [&](double z) { return std::max({f0 + k * z - r, -z, z - h}); };
  double zs = 0, best = g_lin(0);
  for (const double z : {(r - f0) / (1 + k), (f0 - r + h) / (1 - k), h})  // f0 + kz - r = -z, = z - h
    if (z >= 0 && z <= h && g_lin(z) < best) best = g_lin(z), zs = z;
  const double d = 1e-3 * h;
  double zz[5] = {0, std::clamp(zs - d, d, h - 3 * d), 0, 0, h};
  zz[2] = zz[1] + d, zz[3] = zz[2] + d;
  double ff[5] = {f0, F(zz[1]), F(zz[2]), F(zz[3]), fh};
  struct Line {
    double c0, c1;  // c0 + c1 z
  };
  const auto secant = [&](int i, int j) {
    const double sl = (ff[j] - ff[i]) / (zz[j] - zz[i]);
    return Line{ff[i] - sl * zz[i] - r, sl};  // F - r
  };
  double lower = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {  // interval [zz[i], zz[i+1]]
    Line lines[4];
    int nl = 0;
    lines[nl++] = {0, -1}, lines[nl++] = {-h, 1};  // -z, z - h
    if (i > 0) lines[nl++] = secant(i - 1, i);     // extended forward past zz[i]
    if (i < 3) lines[nl++] = secant(i + 1, i + 2);  // extended backward before zz[i+1]
    const auto g = [&](double z) {
      double v = -std::numeric_limits<double>::infinity();
      for (int l = 0; l < nl; ++l) v = std::max(v, lines[l].c0 + lines[l].c1 * z);
      return v;
    };
    double v = std::min(g(zz[i]), g(zz[i + 1]));
    for (int l = 0; l < nl; ++l)
      for (int t = l + 1; t < nl; ++t) {
        const double ds = lines[l].c1 - lines[t].c1;
        if (ds == 0) continue;
        const double z = (lines[t].c0 - lines[l].c0) / ds;
        if (z > zz[i] && z < zz[i + 1]) v = std::min(v, g(z));
      }
    lower = std::min(lower, v);
  }
  if (!std::isfinite(lower)) return kNone;
  const double scale = 1 + std::max({std::fabs(a.base.x), std::fabs(a.base.y), std::fabs(a.base.z),
                                     std::fabs(b.base.x), std::fabs(b.base.y), std::fabs(b.base.z)}) +
                       a.height + b.height + a.radius + b.radius;
  return std::min(0.0, lower) - 1e-10 * scale;
}

// The same lower bound of s(B, A) as intact_reverse_lower_bound (planes across A's axis: s(B, A) >=
// min(0, min over z in [0, h] of max(F(z) - r, -z, z - h))), with tangents of F instead of secants of
// its samples (issue #27, Table 3 with the scars in range: the five point-to-ellipse bisections of the
// secant bound were 80 % of an intact row). In the plane at A-height z, B's section is one fixed
// ellipse E (semi-axes R / |a.b| along m, R along n) and A's axis point is q(z) = q(0) + z dq
// relative to its centre (affine in z). For every unit u, dist(q, E) >= q.u - h_E(u) with h_E(u) =
// sqrt((ex ux)^2 + (ey uy)^2) the support function of E (a supporting line of E separates q from it;
// for q inside E the right side is <= 0 = F): so ell_u(z) = q(z).u - h_E(u), linear in z, lies below
// F on all of [0, h] for any u: no convergence or convexity argument is needed, only that u is a unit
// vector (the rounding of its normalisation scales the bound by 1 +- 1e-16, inside the margin). The
// tangent of F at z is the u of q(z)'s nearest point of E: approximated by two fixed-point steps
// from the radial direction (u <- (q - grad h_E(u)) / |.|), which makes it tight to rounding for the
// nearly circular sections of nearly parallel axes, and merely less tight otherwise. Tangents at
// z = 0 and h, then at the minimiser of the current bound (a vertex of the lines' upper envelope)
// while the bound is below `target` (at most two more). The minimum of max(lines) over [0, h] is at
// an end or a crossing of two lines. Margin: 1e-13 of the scene's scale (issue #27, speed). It covers
// the rounding of these lines and of the reverse solver's value, both a few tens of ulps of the
// scale (world coordinates subtracted, then the plane's small quantities): the secant bound's 1e-10
// is that same budget times the 1e3 its extrapolation can amplify it by, which the tangents (exact
// lower bounds, no extrapolation) do not need. With 1e-10 the 1,024-roller scene (bearings up to
// 9.3 m from the origin: a margin of ~1e-6 mm) fell through to the secant bound and the slice
// reverse on its loaded roller-inner rows, where s(B, A) - s(A, B) is 1e-8 .. 1e-6 mm.
double intact_reverse_tangent_bound(const Cylinder& a, const Cylinder& b, double target) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  const double ab = dot(a.axis, b.axis);
  if (!(std::fabs(ab) >= 0.5) || a.tapered() || b.tapered()) return kNone;
  const double h = a.height, r = a.radius, R = b.radius;
  Vec3 m = b.axis - a.axis * ab;  // B's axis projected into the planes
  const double mm = norm(m);
  if (!(mm > 1e-300)) {
    m = cross(a.axis, std::fabs(a.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    m = m / norm(m);
  } else {
    m = m / mm;
  }
  const Vec3 n = cross(a.axis, m);
  const double ex = R / std::fabs(ab), ey = R, ex2 = ex * ex, ey2 = ey * ey;
  const auto q_at = [&](double z, double& qx, double& qy) {
    const Vec3 o = a.base + a.axis * z;                               // A's axis point
    const Vec3 q = o - (b.base + b.axis * (dot(o - b.base, a.axis) / ab));  // less B's axis in the plane
    qx = dot(q, m), qy = dot(q, n);
  };
  double qx0, qy0, qxh, qyh;
  q_at(0, qx0, qy0);
  q_at(h, qxh, qyh);
  const double dqx = (qxh - qx0) / h, dqy = (qyh - qy0) / h;
  struct Line {
    double c0, c1;  // c0 + c1 z
  };
  Line lines[6];
  int nl = 0;
  lines[nl++] = {0, -1}, lines[nl++] = {-h, 1};  // -z, z - h
  const auto tangent = [&](double z) {  // ell_u(z') - r for the u of q(z)
    const double px = qx0 + dqx * z, py = qy0 + dqy * z;
    double ux = 1, uy = 0;
    const double len = std::sqrt(px * px + py * py);
    if (len > 0) ux = px / len, uy = py / len;
    for (int it = 0; it < 2; ++it) {
      const double hu = std::sqrt(ex2 * ux * ux + ey2 * uy * uy);
      const double dx = px - ex2 * ux / hu, dy = py - ey2 * uy / hu;
      const double dl = std::sqrt(dx * dx + dy * dy);
      if (!(dl > 0)) break;
      ux = dx / dl, uy = dy / dl;
    }
    const double hu = std::sqrt(ex2 * ux * ux + ey2 * uy * uy);
    lines[nl++] = {qx0 * ux + qy0 * uy - hu - r, dqx * ux + dqy * uy};
  };
  double zmin = 0;
  const auto envelope_min = [&] {
    const auto g = [&](double z) {
      double v = kNone;
      for (int l = 0; l < nl; ++l) v = std::max(v, lines[l].c0 + lines[l].c1 * z);
      return v;
    };
    double best = g(0);
    zmin = 0;
    if (const double v = g(h); v < best) best = v, zmin = h;
    for (int l = 0; l < nl; ++l)
      for (int t = l + 1; t < nl; ++t) {
        const double ds = lines[l].c1 - lines[t].c1;
        if (ds == 0) continue;
        const double z = (lines[t].c0 - lines[l].c0) / ds;
        if (z > 0 && z < h)
          if (const double v = g(z); v < best) best = v, zmin = z;
      }
    return best;
  };
  const double scale = 1 + std::max({std::fabs(a.base.x), std::fabs(a.base.y), std::fabs(a.base.z),
                                     std::fabs(b.base.x), std::fabs(b.base.y), std::fabs(b.base.z)}) +
                       a.height + b.height + a.radius + b.radius;
  const double margin = 1e-13 * scale;
  tangent(0);
  tangent(h);
  double lower = envelope_min();
  for (int k = 0; k < 2 && std::isfinite(lower) && std::min(0.0, lower) - margin < target; ++k) {
    tangent(zmin);
    lower = envelope_min();
  }
  if (!std::isfinite(lower)) return kNone;
  return std::min(0.0, lower) - margin;
}

// The skip is decided by the tangent bound first, then (where it is not enough) by the secant bound;
// both are lower bounds of s(B, A) with a margin far above the reverse solver's rounding, so a skip by
// either leaves the value unchanged: the reverse would not have been below the forward value.
PairDistance intact_row_distance(const Cylinder& a, const Cylinder& b) {
  PairDistance fwd = cylinder_pair_distance(a, b);
  if (fwd.distance > 0 || intact_reverse_tangent_bound(a, b, fwd.distance) >= fwd.distance ||
      intact_reverse_lower_bound(a, b) >= fwd.distance)
    return fwd;
  const PairDistance rev = cylinder_pair_distance(b, a);  // as two_sided_cylinder_distance
  if (rev.distance < fwd.distance) {
    fwd.distance = rev.distance, fwd.point_a = rev.point_b, fwd.point_b = rev.point_a;  // on a, on b
    fwd.path = rev.path;
  }
  return fwd;
}

}  // namespace interfere::bearing
