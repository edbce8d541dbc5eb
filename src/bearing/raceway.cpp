// Raceway pairs of a roller bearing (issue #27; Jia & Zheng 2019, §2.1 Fig. 1 geometry): the roller
// inside a concave cylindrical bore (outer ring of a cylindrical roller bearing) and inside a conical
// cup (outer ring of a tapered roller bearing); parameter checks; the point-to-frustum signed
// distance. The rib is raceway_rib.cpp, the cone-cone pair raceway_cone.cpp. docs/bearing.md,
// "Raceways (issue #27)".
#include "interfere/bearing/raceway.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "golden.h"
#include "raceway_detail.h"

namespace interfere::bearing {
namespace {

using detail::golden_min;
using detail::perpendicular_unit;
using detail::Rim;
using detail::max_axis_distance_on_rim;
using detail::max_over_angle;
using detail::max_convex_over_slab;

Error bad(const char* what, const std::string& reason) { return Error{"", -1, -1, std::string(what) + "." + reason}; }

bool finite3(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool unit(const Vec3& v) { return finite3(v) && std::fabs(norm(v) - 1) <= 1e-9; }

/// When the roller's solid misses the slab 0 <= z <= width of a ring (z along u from base): the
/// axial gap between them, a lower bound of the distance (path apart), with its witnesses.
PairDistance slab_gap(const detail::AxialExtent& e, const Vec3& base, const Vec3& u, double width) {
  const bool above = e.zmin > width;  // the roller lies beyond z = width: its lowest point matters
  const Vec3 p = above ? e.low : e.high;
  const double z = dot(p - base, u);
  PairDistance out;
  out.distance = std::max(above ? z - width : -z, 0.0);
  out.point_a = p;
  out.point_b = p - u * (above ? z - width : z);
  out.path = AnalyticPath::apart;
  return out;
}

bool in_slab(const Vec3& p, const Vec3& base, const Vec3& u, double width) {
  const double z = dot(p - base, u);
  return z >= 0 && z <= width;
}

/// Farthest point of the ellipse x0^2/e0^2 + x1^2/e1^2 = 1 (e0 >= e1 >= 0) from (y0, y1): returns the
/// distance and the point. Lagrange: x - y = lambda (x0/e0^2, x1/e1^2); the farthest point has
/// lambda > e0^2 and lies in the quadrant opposite y: with X_i = |x_i| = |y_i| e_i^2/(lambda - e_i^2)
/// the constraint is G(mu) = (|y0| e0/mu)^2 + (|y1| e1/(mu + e0^2 - e1^2))^2 - 1 = 0 for
/// mu = lambda - e0^2 > 0. G decreases strictly from +inf (|y0| > 0) to -1, so the root is unique:
/// bisected to rounding on [0, hypot(y0 e0, y1 e1)] (G <= 0 there). With y0 = 0 the maximiser is the
/// minor vertex opposite y when |y1| e1 >= e0^2 - e1^2, else lambda = e0^2 (two symmetric points).
/// Evaluated in mu (no cancellation near the pole); the distance is hypot(|y0| + X0, |y1| + X1).
struct Far {
  double distance = 0, x0 = 0, x1 = 0;
};
constexpr double kInf = std::numeric_limits<double>::infinity();
Far farthest_on_ellipse(double e0, double e1, double y0, double y1) {
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
    const double top = std::hypot(n0, n1);
    double mu = top;
    // (issue #27, speed) G as evaluated is non-increasing in mu (each rounded operation is monotone),
    // so the bisection below ends at min(top, the least double t with G(t) <= 0), whatever its path.
    // t is found directly: Newton from n0 (G(n0) >= 0; G is convex and decreasing, so the iterates
    // rise to the root), then a walk by ulps to where G changes sign. The bisection remains for the
    // cases where the walk does not settle within 64 steps; both give the same bits. Start: the root
    // is at least max(n0, top - gap) (G(mu) >= (n0^2 + n1^2)/(mu + gap)^2 - 1), taken 2^-40 lower so
    // that it lies left of the root in spite of rounding.
    bool found = false;
    {
      double x = std::max(n0, (top - gap) * (1 - 0x1p-40));
      for (int i = 0; i < 40; ++i) {
        const double q0 = n0 / x, q1 = n1 / (x + gap);
        const double g = q0 * q0 + q1 * q1 - 1;
        const double dg = -2 * (q0 * q0 / x + q1 * q1 / (x + gap));
        if (!(g > 0) || !(dg < 0)) break;
        const double next = x - g / dg;
        if (!(next > x) || !std::isfinite(next)) break;
        x = next;
      }
      double t = x;
      int steps = 0;
      if (std::isfinite(t) && t > 0) {
        while (G(t) > 0 && steps < 64) t = std::nextafter(t, kInf), ++steps;
        while (steps < 64) {
          const double below = std::nextafter(t, 0.0);
          if (!(below > 0) || G(below) > 0) break;
          t = below, ++steps;
        }
        if (steps < 64 && G(t) <= 0 && !(std::nextafter(t, 0.0) > 0 && G(std::nextafter(t, 0.0)) <= 0)) {
          mu = std::min(top, t), found = true;
        }
      }
    }
    if (!found) {
      double lo = 0, hi = top;
      for (int i = 0; i < 1100; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (G(mid) > 0) lo = mid;
        else hi = mid;
      }
      mu = hi;
    }
    // G(mu) <= 0: X0 <= e0 (the point is on or just inside the ellipse)
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
  Far out;
  out.distance = std::hypot(a0 + X0, a1 + X1);
  out.x0 = -s0 * X0, out.x1 = -s1 * X1;
  return out;
}

/// max over one end circle of rho (distance to the line base + z u): the circle projected along u is
/// an ellipse, semi-axes r along f1 = d x u / |d x u| and r |cos gamma| along e2 = u x f1 (gamma the
/// angle between the axes); the line projects to a point. Returns (rho, the circle's point).
}  // namespace

namespace detail {
std::pair<double, Vec3> max_axis_distance_on_rim(const Rim& rim, const Vec3& d, const Vec3& base, const Vec3& u) {
  // accurate for nearly (anti)parallel axes (plain d x u there: f1 left the rim's plane, the reach
  // came out low by up to 7.5 %; review, issue #27)
  const Vec3 cr = accurate_cross(d, u);
  const double sl = norm(cr);
  const Vec3 f1 = sl > 0 ? cr / sl : perpendicular_unit(d);
  const Vec3 e2 = cross(u, f1), g2 = cross(d, f1);
  const double cg = dot(g2, e2);  // +-cos gamma
  const Vec3 q = rim.c - base;
  // |cg| <= 1 (rounding gave 1 + 2^-52 for parallel axes: e1 > e0, gap = e0^2 - e1^2 < 0, and a
  // centre on the line came out up to 11 % farther than the rim reaches; review, issue #27)
  const Far far = farthest_on_ellipse(rim.r, rim.r * std::min(1.0, std::fabs(cg)), -dot(q, f1), -dot(q, e2));
  double cs = rim.r > 0 ? far.x0 / rim.r : 1.0, sn;
  if (cg != 0 && rim.r > 0) sn = far.x1 / (rim.r * cg);
  else sn = std::sqrt(std::max(0.0, 1 - cs * cs));  // both signs project alike
  const double len = std::hypot(cs, sn);
  if (len > 0) cs /= len, sn /= len;
  return {far.distance, rim.c + f1 * (rim.r * cs) + g2 * (rim.r * sn)};
}
}  // namespace detail

namespace {

/// p moved within its meridian half-plane (of the axis base + z u) onto the point (R, z) of it.
Vec3 radial_to(const Vec3& p, const Vec3& base, const Vec3& u, double R) {
  const Vec3 v = p - base;
  const double z = dot(v, u);
  const Vec3 radial = v - u * z;
  const double rho = norm(radial);
  const Vec3 ur = rho > 0 ? radial / rho : perpendicular_unit(u);
  return base + u * z + ur * R;
}

}  // namespace

Status validate_roller(const Cylinder& c, const char* what) {
  if (!finite3(c.base)) return bad(what, "base must be finite");
  if (!unit(c.axis)) return bad(what, "axis must be a unit vector");
  if (!(c.height > 0) || !std::isfinite(c.height)) return bad(what, "height must be > 0 and finite");
  if (!(c.radius >= 0) || !std::isfinite(c.radius)) return bad(what, "radius must be >= 0 and finite");
  if (!std::isfinite(c.top_radius)) return bad(what, "top_radius must be finite");
  if (!(c.radius > 0 || c.top() > 0)) return bad(what, "radius and top_radius must not both be 0");
  return {};
}

Status validate_bore(const Bore& b, const char* what) {
  if (!finite3(b.base)) return bad(what, "base must be finite");
  if (!unit(b.axis)) return bad(what, "axis must be a unit vector");
  if (!(b.radius > 0) || !std::isfinite(b.radius)) return bad(what, "radius must be > 0 and finite");
  if (!(b.width > 0) || !std::isfinite(b.width)) return bad(what, "width must be > 0 and finite");
  return {};
}

Status validate_cup(const Cup& c, const char* what) {
  if (!finite3(c.base)) return bad(what, "base must be finite");
  if (!unit(c.axis)) return bad(what, "axis must be a unit vector");
  if (!(c.radius > 0) || !std::isfinite(c.radius)) return bad(what, "radius must be > 0 and finite");
  if (!(c.top_radius > 0) || !std::isfinite(c.top_radius)) return bad(what, "top_radius must be > 0 and finite");
  if (!(c.width > 0) || !std::isfinite(c.width)) return bad(what, "width must be > 0 and finite");
  return {};
}

Status validate_rib(const Rib& r, const char* what) {
  if (!finite3(r.center)) return bad(what, "center must be finite");
  if (!unit(r.normal)) return bad(what, "normal must be a unit vector");
  if (!unit(r.axis)) return bad(what, "axis must be a unit vector");
  if (!(std::fabs(dot(r.normal, r.axis)) >= 0.5)) return bad(what, "normal must be within 60 degrees of axis");
  if (!(r.inner_radius >= 0) || !std::isfinite(r.inner_radius)) return bad(what, "inner_radius must be >= 0 and finite");
  if (!(r.outer_radius > r.inner_radius) || !std::isfinite(r.outer_radius))
    return bad(what, "outer_radius must be > inner_radius and finite");
  return {};
}

double point_frustum_signed_distance(const Cylinder& c, const Vec3& p) {
  // meridian half-plane of p: x = rho >= 0, z from the base; the section is the trapezoid
  // |x| <= R(z) = R0 + (R1 - R0) z / h, 0 <= z <= h (convex; for x >= 0 only the bottom, top and
  // right lateral edges can be nearest).
  const Vec3 v = p - c.base;
  const double z = dot(v, c.axis), x = norm(cross(v, c.axis));
  const double h = c.height, R0 = c.radius, R1 = c.top();
  const double L = std::hypot(R1 - R0, h);
  const double lat = ((x - R0) * h - z * (R1 - R0)) / L;  // signed distance to the lateral line
  if (z >= 0 && z <= h && lat <= 0) return -std::min({z, h - z, -lat});
  // outside: the distance to the nearest of the three edge segments
  const double db = std::hypot(std::max(x - R0, 0.0), z);
  const double dt = std::hypot(std::max(x - R1, 0.0), z - h);
  const double w = std::clamp(((x - R0) * (R1 - R0) + z * h) / (L * L), 0.0, 1.0);
  const double dl = std::hypot(x - (R0 + w * (R1 - R0)), z - w * h);
  return std::min({db, dt, dl});
}

Vec3 nearest_on_frustum_boundary(const Cylinder& c, const Vec3& p) {
  const Vec3 v = p - c.base;
  const double z = dot(v, c.axis);
  const Vec3 radial = v - c.axis * z;
  const double x = norm(radial);
  const Vec3 ur = x > 0 ? radial / x : perpendicular_unit(c.axis);
  const double h = c.height, R0 = c.radius, R1 = c.top();
  const double L = std::hypot(R1 - R0, h);
  const double lat = ((x - R0) * h - z * (R1 - R0)) / L;
  double bx, bz;
  const double w = std::clamp(((x - R0) * (R1 - R0) + z * h) / (L * L), 0.0, 1.0);
  const double lx = R0 + w * (R1 - R0), lz = w * h;
  if (z >= 0 && z <= h && lat <= 0) {
    const double m = std::min({z, h - z, -lat});
    if (m == -lat) bx = x - lat * h / L, bz = z + lat * (R1 - R0) / L;  // foot on the lateral line
    else if (m == z) bx = x, bz = 0;
    else bx = x, bz = h;
  } else {
    const double db = std::hypot(std::max(x - R0, 0.0), z);
    const double dt = std::hypot(std::max(x - R1, 0.0), z - h);
    const double dl = std::hypot(x - lx, z - lz);
    if (dl <= db && dl <= dt) bx = lx, bz = lz;
    else if (db <= dt) bx = std::min(x, R0), bz = 0;
    else bx = std::min(x, R1), bz = h;
  }
  return c.base + c.axis * bz + ur * bx;
}

// Both raceway pairs (docs/bearing.md, "Raceways"): g convex (bore: rho - R; cup: the signed
// distance beyond the cone line), the ring's material inside {g >= 0} /\ slab. With G = max of g over
// the whole roller (an end circle) and G_K its maximum over K = roller /\ slab:
//   - the maximiser of G lies in the slab: G_K = G, s = -G (exact);
//   - else G_K by max_convex_over_slab: G_K >= 0 means the solids meet, s = -G_K (the depth, exact);
//     G_K < 0: they are apart, and every point p of the roller is at least -g(p) from the material
//     (it lies in {g >= 0}), so max(-G, 0) is a lower bound of the distance: reported with path
//     `apart` (never a wrong clash or contact; the assembly leaves a non-clear verdict undecided).
PairDistance roller_bore_distance(const Cylinder& roller, const Bore& bore) {
  const detail::AxialExtent ext = detail::axial_extent(roller, bore.base, bore.axis);
  if (ext.zmax < 0 || ext.zmin > bore.width) return slab_gap(ext, bore.base, bore.axis, bore.width);
  // max of the convex rho over the frustum: at an extreme point, i.e. on an end circle
  // (issue #27, speed) a circle's maximum is at most its centre's rho plus its radius (rho is
  // 1-Lipschitz): the circle whose centre is farther is solved first, and the other only when that
  // bound (with a margin far above the rounding of both) does not put it below the first's maximum.
  // A skipped circle could not have been taken (the larger is taken, the base circle's on ties), so
  // the maximum and its point are the same as solving both
  const Rim rim_lo{roller.base, roller.radius}, rim_hi{roller.top_center(), roller.top()};
  const double reach_lo = norm(cross(rim_lo.c - bore.base, bore.axis)) + rim_lo.r;
  const double reach_hi = norm(cross(rim_hi.c - bore.base, bore.axis)) + rim_hi.r;
  const double margin = 1e-9 * (1 + std::max({std::fabs(roller.base.x), std::fabs(roller.base.y), std::fabs(roller.base.z),
                                              std::fabs(bore.base.x), std::fabs(bore.base.y), std::fabs(bore.base.z)}) +
                                roller.height + roller.max_radius() + bore.radius);
  std::pair<double, Vec3> lo, hi;
  if (reach_hi >= reach_lo) {
    hi = max_axis_distance_on_rim(rim_hi, roller.axis, bore.base, bore.axis);
    // (lo skipped: lo < hi, the top circle's is taken)
    lo = reach_lo + margin < hi.first ? std::pair<double, Vec3>{-kInf, {}}
                                      : max_axis_distance_on_rim(rim_lo, roller.axis, bore.base, bore.axis);
  } else {
    lo = max_axis_distance_on_rim(rim_lo, roller.axis, bore.base, bore.axis);
    // (hi skipped: hi < lo, the base circle's is taken)
    hi = reach_hi + margin < lo.first ? std::pair<double, Vec3>{-kInf, {}}
                                      : max_axis_distance_on_rim(rim_hi, roller.axis, bore.base, bore.axis);
  }
  double rho = hi.first > lo.first ? hi.first : lo.first;
  Vec3 pa = hi.first > lo.first ? hi.second : lo.second;
  PairDistance out;
  out.path = AnalyticPath::bore;
  if (!in_slab(pa, bore.base, bore.axis, bore.width)) {
    const auto rho_of = [&](const Vec3& p) { return norm(cross(p - bore.base, bore.axis)); };
    const detail::SlabMax k = max_convex_over_slab(roller, bore.base, bore.axis, 0, bore.width, rho_of);
    if (k.value < bore.radius) {
      out.distance = std::max(bore.radius - rho, 0.0);
      out.path = AnalyticPath::apart;
    } else {
      rho = k.value, pa = k.point;
    }
  }
  if (out.path == AnalyticPath::bore) out.distance = bore.radius - rho;
  out.point_a = pa;
  out.point_b = radial_to(pa, bore.base, bore.axis, bore.radius);
  return out;
}

PairDistance roller_cup_distance(const Cylinder& roller, const Cup& cup) {
  const detail::AxialExtent ext = detail::axial_extent(roller, cup.base, cup.axis);
  if (ext.zmax < 0 || ext.zmin > cup.width) return slab_gap(ext, cup.base, cup.axis, cup.width);
  const Vec3& u = cup.axis;
  const double k = (cup.top_radius - cup.radius) / cup.width;
  const double cb = 1 / std::sqrt(1 + k * k);
  // g(p) = (rho - R0 - k z) cb: convex (rho convex, z linear), so its maximum over the roller is
  // on an end circle; on a circle h(phi) = rho(phi) - k z(phi) is smooth where rho > 0.
  const Vec3 f1 = perpendicular_unit(roller.axis), f2 = cross(roller.axis, f1);
  const auto h_at = [&](const Vec3& p) {
    const Vec3 v = p - cup.base;
    return norm(cross(v, u)) - k * dot(v, u);
  };
  const auto h_of = [&](const Rim& rim) {
    return [&, rim](double phi) { return h_at(detail::rim_point(rim, f1, f2, phi)); };
  };
  const Rim rlo{roller.base, roller.radius}, rhi{roller.top_center(), roller.top()};
  const auto lo = max_over_angle(h_of(rlo));
  const auto hi = max_over_angle(h_of(rhi));
  const bool top = hi.second > lo.second;
  Vec3 pa = detail::rim_point(top ? rhi : rlo, f1, f2, top ? hi.first : lo.first);
  PairDistance out;
  out.path = AnalyticPath::cup;
  if (!in_slab(pa, cup.base, u, cup.width)) {
    const detail::SlabMax m = max_convex_over_slab(roller, cup.base, u, 0, cup.width, h_at);
    if (m.value < cup.radius) {  // g < 0 over K: apart; the lower bound max(-G, 0)
      out.distance = std::max(-(h_at(pa) - cup.radius) * cb, 0.0);
      out.path = AnalyticPath::apart;
    } else {
      pa = m.point;
    }
  }
  const Vec3 v = pa - cup.base;
  const double z = dot(v, u), rho = norm(cross(v, u));
  const double g = (rho - cup.radius - k * z) * cb;  // signed distance beyond the cone line
  if (out.path == AnalyticPath::cup) out.distance = -g;
  out.point_a = pa;
  // the foot on the cone line (R0 + k z', z') of the meridian half-plane: move by -g along the
  // line's outward normal (1, -k) cb
  const Vec3 radial = v - u * z;
  const Vec3 ur = rho > 0 ? radial / rho : perpendicular_unit(u);
  out.point_b = cup.base + u * (z + g * k * cb) + ur * (rho - g * cb);
  return out;
}

}  // namespace interfere::bearing
