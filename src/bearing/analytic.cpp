// Standard solver (Jia & Zheng 2019, §3.1): analytic signed distance between two finite cylinders.
// Axis-segment closest points (side contact) and the end-circle case reduced to a planar
// point-to-ellipse distance (Eberly, "Distance to Circles in 3D" and "Distance from a Point to an
// Ellipse, an Ellipsoid, or a Hyperellipsoid", Geometric Tools), with a certificate that B's side
// is what is nearest; a nested golden-section fallback for the general convex problem.
#include "interfere/bearing/analytic.h"
#include "golden.h"
#include "interfere/bearing/raceway.h"
#include "raceway_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace interfere::bearing {
namespace {

using detail::golden_min;


double get_root(double r0, double z0, double z1, double g) {
  // Root of G(s) = (n0/(s+r0))^2 + (z1/(s+1))^2 - 1 on [s0, s1] (G(s0) >= 0 >= G(s1)). G is convex
  // and decreasing there, so Newton's method started at the left end increases monotonically to
  // the root without overshooting (a handful of steps) until rounding stalls it; should it ever leave
  // the bracket, Eberly's bisection finishes the job.
  const double n0 = r0 * z0;
  double s0 = z1 - 1, s1 = g < 0 ? 0 : std::hypot(n0, z1) - 1;
  double s = s0;
  // Start nearer the root: G's tangent at s1 lies below the convex G, so its zero is at or left of
  // the root (never past it): the monotone iteration below keeps its guarantees from there. For
  // nearly circular ellipses (r0 ~ 1: nearly parallel axes, the common case in bearings) it lands
  // within rounding of the root, and one or two steps finish. (Rounding may put G there slightly
  // below 0: the step is then not taken.)
  {
    const double a = n0 / (s1 + r0), b = z1 / (s1 + 1);
    const double gs = a * a + b * b - 1, dg = -2 * (a * a / (s1 + r0) + b * b / (s1 + 1));
    const double t = s1 - gs / dg;
    if (gs < 0 && dg < 0 && t > s0 && t < s1) {
      const double at = n0 / (t + r0), bt = z1 / (t + 1);
      if (at * at + bt * bt - 1 > 0) s = t;
    }
  }
  for (int i = 0; i < 60; ++i) {
    const double a = n0 / (s + r0), b = z1 / (s + 1);
    const double gs = a * a + b * b - 1;
    if (!(gs > 0)) {
      if (gs == 0) return s;
      s1 = std::min(s1, s);
      break;
    }
    s0 = s;
    const double dg = -2 * (a * a / (s + r0) + b * b / (s + 1));
    const double next = s - gs / dg;
    if (!(next > s)) return s;  // converged: rounding stalls the monotone iteration at the root
    if (!(next < s1)) break;    // past the bracket (rounding): bisect
    s = next;
  }
  for (int i = 0; i < 2200; ++i) {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) break;
    const double ratio0 = n0 / (s + r0), ratio1 = z1 / (s + 1);
    g = ratio0 * ratio0 + ratio1 * ratio1 - 1;
    if (g > 0) s0 = s;
    else if (g < 0) s1 = s;
    else break;
  }
  return s;
}

Vec3 any_perpendicular(const Vec3& u) {
  const Vec3 t = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 p = cross(u, t);
  return p / norm(p);
}

}  // namespace

const char* analytic_path_name(AnalyticPath p) {
  switch (p) {
    case AnalyticPath::side: return "side";
    case AnalyticPath::end: return "end";
    case AnalyticPath::parallel: return "parallel";
    case AnalyticPath::tapered: return "tapered";
    case AnalyticPath::general: return "general";
    case AnalyticPath::core: return "core";
    case AnalyticPath::bore: return "bore";
    case AnalyticPath::cup: return "cup";
    case AnalyticPath::rib: return "rib";
    case AnalyticPath::cone: return "cone";
    case AnalyticPath::apart: return "apart";
    case AnalyticPath::slice: return "slice";
  }
  return "?";
}

EllipsePoint point_ellipse_distance(double e0, double e1, double y0, double y1) {
  const double s0 = y0 < 0 ? -1.0 : 1.0, s1 = y1 < 0 ? -1.0 : 1.0;
  y0 = std::fabs(y0), y1 = std::fabs(y1);
  EllipsePoint out;
  if (e1 <= 0) {  // degenerate: the segment [-e0, e0] x {0}
    out.x0 = std::min(y0, e0), out.x1 = 0;
    out.distance = std::hypot(y0 - out.x0, y1);
  } else if ((y0 / e0) * (y0 / e0) + (y1 / e1) * (y1 / e1) <= 1) {  // inside the solid ellipse
    out.x0 = y0, out.x1 = y1, out.distance = 0;
  } else if (y1 > 0) {
    if (y0 > 0) {
      const double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
      const double r0 = (e0 / e1) * (e0 / e1);
      const double sbar = get_root(r0, z0, z1, g);
      out.x0 = r0 * y0 / (sbar + r0);
      out.x1 = y1 / (sbar + 1);
      out.distance = std::hypot(out.x0 - y0, out.x1 - y1);
    } else {
      out.x0 = 0, out.x1 = e1, out.distance = std::fabs(y1 - e1);
    }
  } else {
    const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
    if (numer0 < denom0) {
      const double xde0 = numer0 / denom0;
      out.x0 = e0 * xde0;
      out.x1 = e1 * std::sqrt(std::max(0.0, 1 - xde0 * xde0));
      out.distance = std::hypot(out.x0 - y0, out.x1);
    } else {
      out.x0 = e0, out.x1 = 0, out.distance = std::fabs(y0 - e0);
    }
  }
  out.x0 *= s0, out.x1 *= s1;
  return out;
}

using detail::accurate_cross;

namespace {
/// B's slab |z - c.u| <= hh for min_axis_distance_in: `margin` far above the rounding of the point
/// and of its height.
struct Slab {
  double hh, margin;
};

/// min_axis_distance; with `beyond` (issue #27, speed) the end path first bounds its point's height
/// along u without solving the ellipse: the point is the end circle's centre plus r (cs f1 + sn g2)
/// with cs^2 + sn^2 = 1 (or <= 1 on the disk), so its height differs from the centre's by at most
/// r (|f1.u| + |g2.u|). When that puts it beyond the slab for certain (|z| - hh > 0 by more than the
/// margin), cylinder_pair_distance's certificate cannot hold (dz > 0 fails both of its cases), so the
/// point is not needed: returns false (out untouched). Otherwise the same operations as without it.
bool min_axis_distance_in(const Cylinder& a, const Vec3& c, const Vec3& u, RadialMin& out, const Slab* beyond);
}  // namespace

RadialMin min_axis_distance(const Cylinder& a, const Vec3& c, const Vec3& u) {
  RadialMin out;
  min_axis_distance_in(a, c, u, out, nullptr);
  return out;
}

namespace {
bool min_axis_distance_in(const Cylinder& a, const Vec3& c, const Vec3& u, RadialMin& out, const Slab* beyond) {
  const Vec3 d = a.axis;
  const double r = a.radius, h = a.height;
  const Vec3 v0 = a.base - c;
  const double cg = dot(d, u);
  // d x u, for nearly (anti)parallel axes as the same vector (d -+ u) x u, whose d -+ u is exact
  // (Sterbenz): cross(d, u) there is rounding noise and f1 = cr / |cr| a random direction (axes
  // 1e-16 .. 1e-11 apart, as a bearing's posed rollers are, gave distances off by up to 6 mm, both
  // ways; review, issue #27, test_review_parallel_axes.cpp)
  const Vec3 cr = accurate_cross(d, u);
  const double sl = norm(cr);
  if (!(sl > 1e-150)) {  // parallel axes: the projected shape is one circle
    out.path = AnalyticPath::parallel;
    const Vec3 perp = v0 - u * dot(v0, u);
    const double rho_axis = norm(perp);
    // every t is a minimiser: take the one whose height on B's axis is nearest B's centre (c)
    const double z0 = dot(v0, u), dz = h * cg;
    double t = dz != 0 ? -z0 / dz : 0.5;
    t = std::clamp(t, 0.0, 1.0);
    const Vec3 at = a.base + d * (t * h);
    if (rho_axis > r) {
      out.rho = rho_axis - r;
      out.point = at - perp * (r / rho_axis);
    } else {
      out.rho = 0;
      out.point = at - perp;
    }
    return true;
  }
  const Vec3 f1 = cr / sl;         // in A's end-disk plane and perpendicular to u
  const Vec3 e2 = cross(u, f1);    // completes (f1, e2) in the plane perpendicular to u
  const Vec3 g2 = cross(d, f1);    // in A's disk plane; g2 . e2 = cg
  const double xa = dot(v0, f1);
  const double y0 = dot(v0, e2), y1 = y0 + h * sl;  // projected axis: from y0 up to y1
  const double px = -xa;
  if (y0 <= 0 && 0 <= y1) {  // the straight part: axis-segment closest points (side contact)
    out.path = AnalyticPath::side;
    const double t = std::clamp(-y0 / (h * sl), 0.0, 1.0);
    const Vec3 at = a.base + d * (t * h);
    if (std::fabs(px) > r) {
      out.rho = std::fabs(px) - r;
      out.point = at + f1 * (px > 0 ? r : -r);
    } else {
      out.rho = 0;
      out.point = at + f1 * px;
    }
    return true;
  }
  const bool bottom = 0 < y0;
  const double py = bottom ? -y0 : -y1;
  const Vec3 center = bottom ? a.base : a.top_center();
  if (beyond) {
    const double zc = std::fabs(dot(center - c, u)), reach = r * (std::fabs(dot(f1, u)) + std::fabs(dot(g2, u)));
    if (zc - reach - beyond->hh > beyond->margin) return false;
  }
  out.path = AnalyticPath::end;
  const EllipsePoint ep = point_ellipse_distance(r, r * std::fabs(cg), px, py);
  out.rho = ep.distance;
  if (ep.distance == 0) {
    // B's axis crosses the end disk: the point of the disk on B's axis
    const double cs = px / r;
    const double sn = cg != 0 ? py / (r * cg) : 0.0;
    out.point = center + f1 * (r * cs) + g2 * (r * sn);
    return true;
  }
  double cs = ep.x0 / r, sn;
  if (cg != 0) {
    sn = ep.x1 / (r * cg);
  } else {  // perpendicular axes: both signs project alike; take the one nearer B's centre
    sn = std::sqrt(std::max(0.0, 1 - cs * cs));
    if (dot(center - c + g2 * sn, u) * dot(g2, u) > 0) sn = -sn;
  }
  const double len = std::hypot(cs, sn);
  cs /= len, sn /= len;
  out.point = center + f1 * (r * cs) + g2 * (r * sn);
  return true;
}
}  // namespace

Vec3 nearest_on_cylinder_boundary(const Cylinder& b, const Vec3& p) {
  const Vec3 m = b.center();
  const Vec3 v = p - m;
  const double z = dot(v, b.axis);
  Vec3 radial = v - b.axis * z;
  const double rho = norm(radial);
  const Vec3 ur = rho > 0 ? radial / rho : any_perpendicular(b.axis);
  const double hh = 0.5 * b.height, R = b.radius;
  const double dr = rho - R, dz = std::fabs(z) - hh;
  double rr = rho, zz = z;
  if (dr <= 0 && dz <= 0) {  // inside: to the nearer of side and cap
    if (dr >= dz) rr = R;
    else zz = z < 0 ? -hh : hh;
  } else {
    rr = std::min(rho, R);
    zz = std::clamp(z, -hh, hh);
  }
  return m + b.axis * zz + ur * rr;
}

PairDistance cylinder_pair_distance_general(const Cylinder& a, const Cylinder& b) {
  const double hh = 0.5 * b.height;
  const Vec3 bc = b.center();
  const auto sd = [&](const Vec3& p) {
    const Vec3 v = p - bc;
    return signed_distance_rz(norm(cross(v, b.axis)), dot(v, b.axis), b.radius, hh);
  };
  const auto [p, value] = detail::nested_min_over_frustum(a, any_perpendicular(a.axis), sd);
  PairDistance out;
  out.point_a = p;
  out.distance = value;
  out.point_b = nearest_on_cylinder_boundary(b, out.point_a);
  out.path = AnalyticPath::general;
  return out;
}

namespace {
/// min over a tapered A of the distance to the line (c, u): the disk at axis parameter t projects to
/// an ellipse of semi-axes r(t), r(t)|cos gamma| centred on the projected axis point; the distance to
/// it is convex in t (partial minimisation of a convex function over a convex set).
RadialMin min_axis_distance_tapered(const Cylinder& a, const Vec3& c, const Vec3& u) {
  const Vec3 d = a.axis;
  const double h = a.height;
  const Vec3 v0 = a.base - c;
  const double cg = dot(d, u);
  // d x u, for nearly (anti)parallel axes as the same vector (d -+ u) x u, whose d -+ u is exact
  // (Sterbenz): cross(d, u) there is rounding noise and f1 = cr / |cr| a random direction (axes
  // 1e-16 .. 1e-11 apart, as a bearing's posed rollers are, gave distances off by up to 6 mm, both
  // ways; review, issue #27, test_review_parallel_axes.cpp)
  const Vec3 cr = accurate_cross(d, u);
  const double sl = norm(cr);
  const Vec3 f1 = sl > 1e-150 ? cr / sl : any_perpendicular(d);
  const Vec3 e2 = cross(u, f1);
  const Vec3 g2 = cross(d, f1);
  const double xa = dot(v0, f1), y0 = dot(v0, e2), dy = h * dot(d, e2);
  const auto radius = [&](double t) { return a.radius + (a.top() - a.radius) * (t / h); };
  const auto at = [&](double t) {
    const double r = radius(t);
    return point_ellipse_distance(r, r * std::fabs(cg), -xa, -(y0 + dy * (t / h)));
  };
  const auto [t, rho] = golden_min([&](double tt) { return at(tt).distance; }, 0.0, h, 90);
  RadialMin out;
  out.path = AnalyticPath::tapered;
  const EllipsePoint ep = at(t);
  const double r = radius(t);
  out.rho = ep.distance;
  double cs = ep.x0 / r, sn = cg != 0 ? ep.x1 / (r * cg) : std::sqrt(std::max(0.0, 1 - cs * cs));
  if (ep.distance == 0) cs = -xa / r, sn = cg != 0 ? -(y0 + dy * (t / h)) / (r * cg) : 0.0;
  const double len = std::hypot(cs, sn);
  if (len > 0 && ep.distance > 0) cs /= len, sn /= len;
  out.point = a.base + d * t + f1 * (r * cs) + g2 * (r * sn);
  (void)rho;
  return out;
}
}  // namespace

namespace {
/// B's core (its points at the greatest depth m = min(R, h/2)): the axis segment |z| <= h/2 - R
/// when R <= h/2, else the mid-plane disk rho <= R - h/2. sd_A is convex, so its minimum over the
/// core is a golden-section search (nested over the disk); a negative minimum is a core point
/// inside A, and then s(A, B) = -m exactly (no point of B is deeper), else nullopt. A untapered.
bool core_inside(const Cylinder& a, const Cylinder& b, PairDistance& out) {
  const Vec3 bc = b.center();
  const double R = b.radius, hh = 0.5 * b.height;
  constexpr int kIter = 90;
  // Exact skip: sd_A(p) >= rho_A(p) - R_A everywhere (A lies in its infinite cylinder), so when the
  // whole core lies outside that infinite cylinder by more than any rounding of the searches below
  // (margin), no evaluation can be negative and the search would return false: skip it. The core's
  // smallest rho_A: a segment's distance to A's axis line (closed form), a disk's centre value less
  // its radius (rho_A is 1-Lipschitz).
  {
    const double margin = 1e-9 * (1 + std::max({std::fabs(bc.x), std::fabs(bc.y), std::fabs(bc.z)}) +
                                   std::max({std::fabs(a.base.x), std::fabs(a.base.y), std::fabs(a.base.z)}) +
                                   a.height + a.radius + b.height + b.radius);
    const auto perp = [&](const Vec3& v) { return v - a.axis * dot(v, a.axis); };
    double rho_lo;
    if (R <= hh) {
      const Vec3 q0 = perp(bc - b.axis * (hh - R) - a.base), dq = perp(b.axis * (2 * (hh - R)));
      const double dd = dot(dq, dq);
      const double t = dd > 0 ? std::clamp(-dot(q0, dq) / dd, 0.0, 1.0) : 0.0;
      rho_lo = norm(q0 + dq * t);
    } else {
      rho_lo = norm(perp(bc - a.base)) - (R - hh);
    }
    if (rho_lo - a.radius > margin) return false;
  }
  Vec3 p;
  double value;
  if (R <= hh) {
    const auto at = [&](double t) { return bc + b.axis * t; };
    const auto [t, v] = golden_min([&](double tt) { return point_signed_distance(a, at(tt)); }, -(hh - R), hh - R, kIter);
    p = at(t), value = v;
  } else {
    const Vec3 f1 = any_perpendicular(b.axis);
    const Vec3 f2 = cross(b.axis, f1);
    const double rc = R - hh;
    const auto at = [&](double x, double y) { return bc + f1 * x + f2 * y; };
    const auto over_y = [&](double x) {
      const double ym = std::sqrt(std::max(0.0, rc * rc - x * x));
      return golden_min([&](double y) { return point_signed_distance(a, at(x, y)); }, -ym, ym, kIter);
    };
    const auto [x, v] = golden_min([&](double xx) { return over_y(xx).second; }, -rc, rc, kIter);
    p = at(x, over_y(x).first), value = v;
  }
  if (!(value < 0)) return false;
  out.distance = -std::min(R, hh);
  out.point_a = p;
  out.point_b = nearest_on_cylinder_boundary(b, p);
  out.path = AnalyticPath::core;
  return true;
}
}  // namespace

namespace detail {
/// The `slice` path (analytic.h; also cone_pair_distance): A and B cylinders or cone frustums, axes
/// within 60 degrees. sd_B(p) = phi(rho_B(p), z_B(p)), phi the meridian-plane signed distance to B's
/// rectangle or trapezoid, nondecreasing in rho (B's section is closed under moving toward the axis,
/// its complement under moving away); so min over A's cross-section by the plane across B's axis at
/// height z of sd_B is G(z) = phi(F(z), z), F(z) the distance from B's axis point at z to that
/// section, and s(A, B) = min over z of G(z). G is convex (partial minimisation of the convex sd_B
/// over the convex A), so one golden-section search over the heights of the planes that meet A is
/// exact. The section, in the plane's coordinates x along A's projected axis m and y across it
/// (n = b x m, perpendicular to A's axis), origin at A's axis point (axis parameter tO): a point is
/// in A's (double) cone when x^2 (1 - ma^2) + y^2 <= (r(tO) + k ma x)^2 (ma = |m . a|, k = dr/dt),
/// i.e. c (x - xc)^2 + y^2 <= Q with c = 1 - ma^2 (1 + k^2) > 0 (required: 1/4 or more), xc =
/// r(tO) k ma / c, Q = r(tO)^2 + c xc^2: an ellipse; A's end planes t = 0, h_A are lines x = const
/// (t = tO + ma x). Distance to ellipse /\ strip: the ellipse's (Eberly) when its nearest point lies
/// in the strip, else the nearer of the two chords' (the nearest point of a convex set clipped by a
/// strip lies on the strip's boundary when the unclipped one is outside it).
bool slice_distance(const Cylinder& a, const Cylinder& b, PairDistance& out) {
  const double ab = dot(a.axis, b.axis);
  if (!(std::fabs(ab) >= 0.5)) return false;
  // m = a - b (a . b), accurate for nearly (anti)parallel axes (raceway_detail.h): plain, it cancels
  // to rounding noise there and m left the plane across B's axis (axes 1e-16 .. 1e-13 apart gave
  // depths off by up to 5.8 mm; review, issue #27, test_review_parallel_axes.cpp)
  Vec3 m = detail::accurate_across(a.axis, b.axis);
  const double ma = norm(m);  // = m . a after normalising: t_A grows by ma per unit x
  m = ma > 1e-300 ? m / ma : any_perpendicular(b.axis);
  const Vec3 n = cross(b.axis, m);
  const double ha = a.height, r0 = a.radius, r1 = a.top(), k = (r1 - r0) / ha;
  const double c = 1 - ma * ma * (1 + k * k);
  if (!(c >= 0.25)) return false;
  const double w0 = dot(a.base - b.base, b.axis);  // B-height of A's base centre
  const double za = w0, zb = w0 + ab * ha;         // B-heights of A's axis ends
  const double lo = std::min(za - r0 * ma, zb - r1 * ma), hi = std::max(za + r0 * ma, zb + r1 * ma);
  const Vec3 eb = any_perpendicular(b.axis);
  const auto phi = [&](double rho, double z) {
    return b.tapered() ? point_frustum_signed_distance(b, b.base + b.axis * z + eb * rho)
                       : signed_distance_rz(rho, z - 0.5 * b.height, b.radius, 0.5 * b.height);
  };
  const auto nearest = [&](double z) {
    const double to = (z - w0) / ab, ro = r0 + k * to;
    const double xc = ro * k * ma / c, q2 = ro * ro + c * xc * xc;
    const double ey = std::sqrt(q2), ex = std::sqrt(q2 / c);
    const Vec3 o = a.base + a.axis * to;  // A's axis in the plane
    const Vec3 q = b.base + b.axis * z - o;
    const double qx = dot(q, m), qy = dot(q, n);
    const EllipsePoint ep = point_ellipse_distance(ex, ey, qx - xc, qy);
    const double tx = to + (xc + ep.x0) * ma;
    if (tx >= 0 && tx <= ha) return std::pair<Vec3, double>{o + m * (xc + ep.x0) + n * ep.x1, ep.distance};
    std::pair<Vec3, double> best{o, std::numeric_limits<double>::infinity()};
    if (ma > 0)
      for (const double t : {0.0, ha}) {
        const double x0 = (t - to) / ma, y2 = q2 - c * (x0 - xc) * (x0 - xc);
        if (!(y2 >= 0)) continue;
        const double ym = std::sqrt(y2), y = std::clamp(qy, -ym, ym), d = std::hypot(qx - x0, qy - y);
        if (d < best.second) best = {o + m * x0 + n * y, d};
      }
    return best;
  };
  const auto value = [&](double z) {  // +inf where rounding leaves an end plane's section empty
    const double f = nearest(z).second;
    return std::isfinite(f) ? phi(f, z) : std::numeric_limits<double>::infinity();
  };
  const auto [z, v] = golden_min(value, lo, hi, 110);
  if (!std::isfinite(v)) return false;
  out.distance = v;
  out.point_a = nearest(z).first;
  out.point_b = b.tapered() ? nearest_on_frustum_boundary(b, out.point_a) : nearest_on_cylinder_boundary(b, out.point_a);
  out.path = AnalyticPath::slice;
  return true;
}
}  // namespace detail

PairDistance cylinder_pair_distance(const Cylinder& a, const Cylinder& b) {
  const Vec3 bc = b.center();
  const double R = b.radius, hh = 0.5 * b.height;
  RadialMin rm;
  bool certified = false;
  // (issue #27, speed) an untapered A's end-path minimiser is not computed where it lies beyond B's
  // slab for certain (min_axis_distance_in): the certificate below fails there, and nothing else
  // reads rm; nearly parallel neighbouring rollers offset along their axes take this skip
  const Slab slab{hh, 1e-9 * (1 + std::max({std::fabs(a.base.x), std::fabs(a.base.y), std::fabs(a.base.z),
                                            std::fabs(bc.x), std::fabs(bc.y), std::fabs(bc.z)}) +
                              a.height + a.radius + b.height + b.radius)};
  if (a.tapered() ? (rm = min_axis_distance_tapered(a, bc, b.axis), true) : min_axis_distance_in(a, bc, b.axis, rm, &slab)) {
    const double z = dot(rm.point - bc, b.axis);
    const double dr = rm.rho - R, dz = std::fabs(z) - hh;
    // certificate: at the minimiser of rho_B over A, sd_B = rho_B - R (B's side is nearest)
    certified = rm.rho > 0 && (dr >= 0 ? dz <= 0 : dz <= dr);
  }
  if (!certified && !b.tapered()) {
    // Apart solids: both one-sided values are their Euclidean distance, s(A, B) = s(B, A). So when
    // the reverse closed form is certified with a positive value (B's point nearest A's axis has
    // A's side nearest, outside A: the solids are apart), it is s(A, B) exactly. Nearly parallel
    // rollers offset along their axes: A's nearest rim point lies beyond B's end (not certified),
    // while B's lies within A's length (certified), and the searches below are not needed.
    const Vec3 ac = a.center();
    const RadialMin rr = min_axis_distance(b, ac, a.axis);
    const double zr = dot(rr.point - ac, a.axis);
    const double drr = rr.rho - a.radius, dzr = std::fabs(zr) - 0.5 * a.height;
    if (!a.tapered() && rr.rho > 0 && drr > 0 && dzr <= 0) {
      PairDistance out;
      out.distance = drr;
      out.point_b = rr.point;
      out.point_a = nearest_on_cylinder_boundary(a, rr.point);
      out.path = rr.path;
      return out;
    }
  }
  if (!certified) {
    PairDistance core;
    if (!a.tapered() && core_inside(a, b, core)) return core;
    if (detail::slice_distance(a, b, core)) return core;
    return cylinder_pair_distance_general(a, b);
  }
  PairDistance out;
  out.distance = rm.rho - R;
  out.point_a = rm.point;
  out.point_b = nearest_on_cylinder_boundary(b, rm.point);
  out.path = rm.path;
  return out;
}

}  // namespace interfere::bearing
