// Two-sided values of the ring pairs (ring_two_sided.h; issue #27). The certificate and the erosion
// search are derived in the header; docs/bearing.md, "Two-sided ring pairs".
#include "interfere/bearing/ring_two_sided.h"

#include "raceway_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double scale_of(const Cylinder& roller, double ring) {
  const Vec3 m = roller.center();
  return std::max({std::fabs(m.x), std::fabs(m.y), std::fabs(m.z)}) + roller.height + roller.max_radius() + ring;
}

/// A solver's decision "meets" (<= 0 and not a lower bound of a positive distance).
bool meets(const PairDistance& d) { return d.distance <= 0 && d.path != AnalyticPath::apart; }

/// The ring point at depth t in the roller found by the reverse search: q on the ring's surface;
/// point_a the roller boundary point nearest it.
TwoSidedRing from_reverse(const Cylinder& roller, const PairDistance& at_root, double depth, TwoSidedRing out) {
  out.value.distance = -depth;
  out.value.point_b = at_root.point_a;
  out.value.point_a = nearest_on_frustum_boundary(roller, at_root.point_a);
  return out;
}

/// The eroded ring's outside surface (rho <= outer - t): the roller's part K_t within the slab
/// [lo, hi] is convex, so it meets the annulus [inner + t, outer - t] iff its largest rho (the
/// raceway solver's) reaches inner + t and its smallest rho is at most `limit` = outer - t (rho is
/// continuous on a connected set). Any roller point in the slab bounds the smallest rho from above:
/// the axis, the end centres and 64 points of each end circle are tried; nullopt when none is low
/// enough (the caller then flags the value as not exact).
std::optional<Vec3> low_point(const Cylinder& roller, const Vec3& base, const Vec3& axis, double lo, double hi,
                              double limit) {
  const auto rho_z = [&](const Vec3& p) {
    const Vec3 d = p - base;
    return std::pair{norm(cross(d, axis)), dot(d, axis)};
  };
  std::optional<Vec3> best;
  double best_rho = limit;
  const auto take = [&](const Vec3& p) {
    const auto [rho, z] = rho_z(p);
    if (z >= lo && z <= hi && rho <= best_rho) best_rho = rho, best = p;
  };
  for (int i = 0; i <= 32; ++i) take(roller.base + roller.axis * (roller.height * i / 32.0));
  const Vec3 e1 = std::fabs(roller.axis.x) < 0.9 ? cross(roller.axis, Vec3{1, 0, 0}) : cross(roller.axis, Vec3{0, 1, 0});
  const Vec3 x = e1 / norm(e1), y = cross(roller.axis, x);
  for (int k = 0; k < 64; ++k) {
    const double ang = 2 * 3.14159265358979323846 * k / 64;
    const Vec3 dir = x * std::cos(ang) + y * std::sin(ang);
    take(roller.base + dir * roller.radius);
    take(roller.top_center() + dir * roller.top());
  }
  return best;
}

/// A point on the segment [far, low] (both in the convex K_t) where rho = limit: bisection of the
/// continuous rho (rho(far) > limit >= rho(low)).
Vec3 crossing(const Vec3& far, const Vec3& low, const Vec3& base, const Vec3& axis, double limit) {
  Vec3 a = low, b = far;
  for (int i = 0; i < 80; ++i) {
    const Vec3 m = (a + b) * 0.5;
    (norm(cross(m - base, axis)) <= limit ? a : b) = m;
  }
  return a;
}

/// fwd_at's correction for the outside surface (see low_point): d is the raceway solver's value on
/// the ring eroded by t; returns it unchanged, with the witness moved inside rho <= limit, or as not
/// meeting (and `unsure` set) when no low point was found.
/// `same_function`: the raceway bound is on rho too (a bore: K_t meets inner + t <= rho <= limit by
/// the intermediate value theorem); a cup's raceway bound is on g, so a witness beyond the limit
/// leaves the value unsure.
PairDistance outside_checked(PairDistance d, const Cylinder& roller, const Vec3& base, const Vec3& axis, double lo,
                             double hi, double limit, bool same_function, bool* unsure) {
  if (!meets(d) || norm(cross(d.point_a - base, axis)) <= limit) return d;
  const std::optional<Vec3> low = same_function ? low_point(roller, base, axis, lo, hi, limit) : std::nullopt;
  if (!low) {
    *unsure = true;
    d.distance = std::numeric_limits<double>::min(), d.path = AnalyticPath::apart;
    return d;
  }
  d.point_a = crossing(d.point_a, *low, base, axis, limit);
  return d;
}

}  // namespace

bool eroded_roller(const Cylinder& roller, double t, Cylinder* out) {
  *out = roller;
  if (!(t > 0)) return true;
  const double h = roller.height - 2 * t;
  if (!(h > 0)) return false;
  const double k = (roller.top() - roller.radius) / roller.height;
  const double in = t * std::sqrt(1 + k * k);
  const double r0 = roller.radius + k * t - in, r1 = roller.top() - k * t - in;
  if (!(r0 > 0) || !(r1 > 0)) return false;
  out->base = roller.base + roller.axis * t;
  out->height = h;
  out->radius = r0;
  out->top_radius = roller.tapered() ? r1 : -1;
  return true;
}

// The reverse direction's root function: the roller eroded by t against the unchanged ring part
// (bore, cup or rib); infinitely apart once the roller has eroded away.
template <class Part>
auto eroded_roller_against(const Cylinder& roller, const Part& part, PairDistance (*distance)(const Cylinder&, const Part&)) {
  return [&roller, &part, distance](double t) -> PairDistance {
    Cylinder e;
    if (!eroded_roller(roller, t, &e)) return {kInf, {}, {}, AnalyticPath::apart};
    return distance(e, part);
  };
}

double erosion_root(const std::function<PairDistance(double)>& at, double hi, double tol) {
  double a = 0, b = hi;
  if (!(hi > 0)) return 0;
  const PairDistance db = at(b);
  if (meets(db)) return b;
  double fa = std::min(at(a).distance, 0.0), fb = std::max(db.distance, std::numeric_limits<double>::min());
  int side = 0;
  double width_two_steps_ago = 2 * (b - a), width_last = b - a;
  for (int it = 0; it < 200 && b - a > tol; ++it) {
    double x;
    // Illinois (regula falsi, halving the value of an end kept twice, superlinear); a bisection
    // whenever two steps did not halve the bracket or a value is not usable keeps it shrinking
    const bool slow = b - a > 0.5 * width_two_steps_ago;
    width_two_steps_ago = width_last, width_last = b - a;
    if (slow || !std::isfinite(fa) || !std::isfinite(fb) || !(fb > fa)) {
      x = 0.5 * (a + b);
    } else {
      const double margin = 0.01 * (b - a);
      x = std::clamp(b - fb * (b - a) / (fb - fa), a + margin, b - margin);
    }
    const PairDistance dx = at(x);
    if (meets(dx)) {
      a = x, fa = std::min(dx.distance, 0.0);
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = x, fb = std::isfinite(dx.distance) ? std::max(dx.distance, std::numeric_limits<double>::min()) : dx.distance;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return a;
}

TwoSidedRing two_sided_bore(const Cylinder& roller, const Bore& bore, double outer_radius) {
  TwoSidedRing out;
  out.value = roller_bore_distance(roller, bore);
  const PairDistance& f = out.value;
  if (!meets(f)) {  // apart: the Euclidean distance (path bore) or a lower bound of it (apart)
    out.exact = f.path != AnalyticPath::apart;
    out.forward = out.reverse = f.distance;
    return out;
  }
  const double rf = -f.distance;  // >= 0: the radial reach
  const Vec3& a = bore.axis;
  const double z = dot(f.point_a - bore.base, a);
  const double rho = norm(cross(f.point_a - bore.base, a));
  out.forward = rf;
  // (ii): the witness's depth in the ring's rectangle is its radial reach; (i) holds for a bore
  if (rf <= std::min({z, bore.width - z, outer_radius - rho})) return out;
  out.certified = false;
  const double tol = 0x1p-50 * scale_of(roller, outer_radius);
  // The outside surface rho = outer_radius cannot bound a depth t <= rf when 2 rf <= outer - radius
  // (every point of K has rho <= radius + rf); else outside_checked adds it to the eroded ring.
  const bool outside_free = 2 * rf <= outer_radius - bore.radius;
  bool unsure = false;
  // fwd: the roller meets the ring eroded by t (raceway radius + t, side faces moved in by t)
  const auto eroded_ring = [&](double t) {
    Bore e = bore;
    e.radius = bore.radius + t, e.base = bore.base + a * t, e.width = bore.width - 2 * t;
    return e;
  };
  const auto fwd_at = [&](double t) -> PairDistance {
    const Bore e = eroded_ring(t);
    if (!(e.width > 0) || !(e.radius <= outer_radius - t)) return {kInf, {}, {}, AnalyticPath::apart};
    const PairDistance d = roller_bore_distance(roller, e);
    return outside_free ? d
                        : outside_checked(d, roller, bore.base, a, t, bore.width - t, outer_radius - t, true, &unsure);
  };
  const double fwd = erosion_root(fwd_at, rf, tol);
  // rev: the eroded roller meets the ring
  const auto rev_at = eroded_roller_against(roller, bore, &roller_bore_distance);
  const double rev = erosion_root(rev_at, rf, tol);
  out.forward = fwd, out.reverse = rev;
  if (rev >= fwd) return from_reverse(roller, rev_at(rev), rev, out);
  if (unsure) out.exact = false;
  // the roller's point at depth fwd in the ring, and the ring boundary point nearest it
  const PairDistance w = fwd_at(fwd);
  const Vec3 p = w.point_a;
  const double zp = dot(p - bore.base, a), rp = norm(cross(p - bore.base, a));
  const Vec3 foot = bore.base + a * zp;
  const Vec3 radial = rp > 0 ? (p - foot) / rp : Vec3{};
  out.value.distance = -fwd;
  out.value.point_a = p;
  const double d_race = rp - bore.radius, d_lo = zp, d_hi = bore.width - zp, d_out = outer_radius - rp;
  const double m = std::min({d_race, d_lo, d_hi, d_out});
  out.value.point_b = m == d_race ? foot + radial * bore.radius
                      : m == d_lo ? p - a * zp
                      : m == d_hi ? p + a * (bore.width - zp)
                                  : foot + radial * outer_radius;
  return out;
}

TwoSidedRing two_sided_cup(const Cylinder& roller, const Cup& cup, double outer_radius) {
  TwoSidedRing out;
  out.value = roller_cup_distance(roller, cup);
  const PairDistance& f = out.value;
  const Vec3& a = cup.axis;
  // the roller's axial extent along the ring's axis (raceway_slab.cpp's, accurate for nearly
  // parallel axes; issue #27 review: this file's own copy took the sine as sqrt(1 - cos^2))
  const detail::AxialExtent extent = detail::axial_extent(roller, cup.base, a);
  const double zlo = extent.zmin, zhi = extent.zmax;
  const bool within = zlo >= 0 && zhi <= cup.width;
  if (!meets(f)) {
    // the distance to the cone line; the Euclidean distance to the ring when the whole roller lies in
    // the width (its maximum of g is K's) and the foot point_b lies on the raceway (within the width)
    const double zb = dot(f.point_b - cup.base, a);
    out.exact = f.path != AnalyticPath::apart && within && zb >= 0 && zb <= cup.width;
    out.forward = out.reverse = f.distance;
    return out;
  }
  const double rf = -f.distance;
  const double z = dot(f.point_a - cup.base, a);
  const double rho = norm(cross(f.point_a - cup.base, a));
  out.forward = rf;
  if (within && rf <= std::min({z, cup.width - z, outer_radius - rho})) return out;
  out.certified = false;
  const double scale = scale_of(roller, outer_radius);
  const double tol = 0x1p-50 * scale;
  const double k = (cup.top_radius - cup.radius) / cup.width, nk = std::sqrt(1 + k * k);
  // as for the bore: K's points have rho <= R(z) + rf sqrt(1 + k^2)
  const bool outside_free = rf * (1 + nk) <= outer_radius - std::max(cup.radius, cup.top_radius);
  bool unsure = false;
  const auto fwd_at = [&](double t) -> PairDistance {
    Cup e = cup;
    e.base = cup.base + a * t, e.width = cup.width - 2 * t;
    if (!(e.width > 0)) return {kInf, {}, {}, AnalyticPath::apart};
    e.radius = cup.radius + k * t + t * nk, e.top_radius = cup.top_radius - k * t + t * nk;
    const PairDistance d = roller_cup_distance(roller, e);
    return outside_free ? d : outside_checked(d, roller, cup.base, a, t, cup.width - t, outer_radius - t, false, &unsure);
  };
  const double fwd = erosion_root(fwd_at, rf, tol);
  const auto rev_at = eroded_roller_against(roller, cup, &roller_cup_distance);
  // (i) bounds rev by rf only for a roller within the width; else up to the roller's inradius
  const double hi = within ? rf : std::min(roller.height / 2, std::min(roller.radius, roller.top()));
  const double rev = erosion_root(rev_at, hi, tol);
  out.forward = fwd, out.reverse = rev;
  if (rev >= fwd) return from_reverse(roller, rev_at(rev), rev, out);
  if (unsure) out.exact = false;
  const PairDistance w = fwd_at(fwd);
  const Vec3 p = w.point_a;
  const double zp = dot(p - cup.base, a), rp = norm(cross(p - cup.base, a));
  const Vec3 foot = cup.base + a * zp;
  const Vec3 radial = rp > 0 ? (p - foot) / rp : Vec3{};
  const double g = (rp - (cup.radius + k * zp)) / nk;
  out.value.distance = -fwd;
  out.value.point_a = p;
  const double d_lo = zp, d_hi = cup.width - zp, d_out = outer_radius - rp;
  const double m = std::min({g, d_lo, d_hi, d_out});
  // the cone line's foot: back along its normal (radial, -k axial)/nk by g
  out.value.point_b = m == g      ? p - (radial - a * k) * (g / nk)
                      : m == d_lo ? p - a * zp
                      : m == d_hi ? p + a * (cup.width - zp)
                                  : foot + radial * outer_radius;
  return out;
}

TwoSidedRing two_sided_rib(const Cylinder& roller, const Rib& rib, double thickness) {
  TwoSidedRing out;
  out.value = roller_rib_distance(roller, rib);
  const PairDistance& f = out.value;
  if (!meets(f)) {
    // the gap over the annulus is the Euclidean distance when it is also the lowest height of the
    // whole roller (every point p is at least l(p) from the material, l <= 0 there), i.e. the lower
    // of the two rims' lowest points (closed form) is not below it
    const double low = detail::lowest_height(roller, rib.center, rib.normal);
    out.exact = f.path != AnalyticPath::apart && low >= f.distance - 0x1p-44 * scale_of(roller, rib.outer_radius);
    out.forward = out.reverse = f.distance;
    return out;
  }
  const double rf = -f.distance;
  const double rho = norm(cross(f.point_a - rib.center, rib.axis));
  out.forward = rf;
  if (rf <= rib.outer_radius - rho && 2 * rf <= thickness) return out;
  out.certified = false;
  const double tol = 0x1p-50 * scale_of(roller, rib.outer_radius);
  const bool back_free = 2 * rf <= thickness;  // else fwd ignores the back face: an upper bound
  const auto fwd_at = [&](double t) -> PairDistance {
    Rib e = rib;
    e.center = rib.center - rib.normal * t;
    e.outer_radius = rib.outer_radius - t;
    if (!(e.outer_radius > e.inner_radius)) return {kInf, {}, {}, AnalyticPath::apart};
    return roller_rib_distance(roller, e);
  };
  const double fwd = erosion_root(fwd_at, rf, tol);
  const auto rev_at = eroded_roller_against(roller, rib, &roller_rib_distance);
  const double rev = erosion_root(rev_at, rf, tol);
  out.forward = fwd, out.reverse = rev;
  if (rev >= fwd) return from_reverse(roller, rev_at(rev), rev, out);
  if (!back_free) out.exact = false;
  const PairDistance w = fwd_at(fwd);
  const Vec3 p = w.point_a;
  const double l = dot(p - rib.center, rib.normal);
  const Vec3 foot = rib.center + rib.axis * dot(p - rib.center, rib.axis);
  const double rp = norm(p - foot);
  out.value.distance = -fwd;
  out.value.point_a = p;
  out.value.point_b = (-l <= rib.outer_radius - rp || !(rp > 0)) ? p - rib.normal * l
                                                                  : foot + (p - foot) * (rib.outer_radius / rp);
  return out;
}

}  // namespace interfere::bearing
