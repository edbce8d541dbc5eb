// Tapered roller against the cone raceway of a tapered roller bearing (issue #27): s(A, B) of
// analytic.h with B a cone frustum (cylinder_pair_distance requires an untapered B).
//
// Lateral bound. Let B have base O, axis u, radii R0 (z = 0) .. R1 (z = h), k = (R1 - R0)/h. For a
// point p in the meridian half-plane of azimuth n (unit, perpendicular to u),
//     g(p) = (rho(p) - R0 - k z(p)) / sqrt(1 + k^2)
// is its signed distance to the plane tangent to B's cone along the generator of azimuth n. That
// tangent half-space is a supporting half-space of the convex (infinite) solid cone C ⊇ B, and the
// signed distance to a convex set is the largest signed distance to its supporting half-spaces, so
// sd_B(p) >= sd_C(p) >= g(p) for every p, hence s(A, B) >= min over A of g.
// Dual. rho(p) - k z(p) = max over unit n ⊥ u of w.(p - O) with w = n - k u, so by weak duality
//     min over A of (rho - k z)  >=  V = max over n of Phi(n),
//     Phi(n) = min over A of w.(p - O) = min over the end circles j of [w.(c_j - O) - r_j |w_perp|]
// (the support function of a frustum, w_perp = w's part perpendicular to A's axis). Phi is
// maximised over the angle of n (1-D: sampled, then golden-section refinement), and the primal point
// p* is the minimiser of w*.p over A: an end-circle point, or, when both end circles are active (a
// kink of Phi: line contact), the best point of the generator joining the two (golden section of
// the convex sd_B along it). Certificate: with V_g = (V - R0)/sqrt(1+k^2),
//     V_g <= min over A of g <= s(A, B) <= sd_B(p*),
// so when sd_B(p*) - V_g is within a few ulps of the pair's scale, s = sd_B(p*) to that accuracy
// (path `cone`; this is the roller's side or end circle against B's cone surface, the bearing's case,
// line contact included). Else the end faces join the bound (below: F = max(g, -z, z - h) <= sd_B,
// equal inside B; its minimum over A through the dual over the simplex of the three, one end face
// at a time; the same bracket certifies). Otherwise (both end faces, A crossing B's axis, deep
// overlap) sd_B is minimised over A by nested golden-section searches (sd_B convex, partial
// minimisation keeps convexity; path `general`), as cylinder_pair_distance_general does for a
// cylinder B.
#include <algorithm>
#include <cmath>

#include "golden.h"
#include "interfere/bearing/raceway.h"
#include "raceway_detail.h"

namespace interfere::bearing {
namespace {

using detail::golden_min;
using detail::perpendicular_unit;

PairDistance cone_general(const Cylinder& a, const Cylinder& b) {
  const auto [p, value] = detail::nested_min_over_frustum(
      a, perpendicular_unit(a.axis), [&](const Vec3& q) { return point_frustum_signed_distance(b, q); });
  PairDistance out;
  out.point_a = p;
  out.distance = value;
  out.point_b = nearest_on_frustum_boundary(b, out.point_a);
  out.path = AnalyticPath::general;
  return out;
}

}  // namespace

PairDistance cone_pair_distance(const Cylinder& a, const Cylinder& b) {
  // an untapered B: the standard solver, unless A is tapered (then its certificate often fails for a
  // large A, e.g. a cone ring against a cylindrical roller, and its nested path costs milliseconds:
  // the certified duals below work for k = 0 as well, the standard solver is the fallback)
  if (!b.tapered() && !a.tapered()) return cylinder_pair_distance(a, b);
  const Vec3& u = b.axis;
  const Vec3& d = a.axis;
  const double k = (b.top() - b.radius) / b.height;
  const double cb = 1 / std::sqrt(1 + k * k);
  const Vec3 e1 = perpendicular_unit(u), e2 = cross(u, e1);
  const detail::Rim rims[2] = {{a.base, a.radius}, {a.top_center(), a.top()}};
  // Phi(psi): the minimum of w.(p - O) over A (support function of the frustum at its end circles)
  const auto phi_at = [&](double psi) {
    const Vec3 w = e1 * std::cos(psi) + e2 * std::sin(psi) - u * k;
    const Vec3 wp = w - d * dot(w, d);
    const double swp = norm(wp);
    return std::min(dot(w, rims[0].c - b.base) - rims[0].r * swp, dot(w, rims[1].c - b.base) - rims[1].r * swp);
  };
  const auto [psi, V] = detail::max_over_angle(phi_at);
  // primal point: both end circles' minimisers of w.p at the optimal w (equal at a kink of Phi: line
  // contact, the bearing's case), and the best point of the generator joining them (sd_B convex
  // along it: golden section), which is where the minimum lies when both circles are active
  const Vec3 w = e1 * std::cos(psi) + e2 * std::sin(psi) - u * k;
  const Vec3 wp = w - d * dot(w, d);
  const double swp = norm(wp);
  const Vec3 p0 = swp > 0 ? rims[0].c - wp * (rims[0].r / swp) : rims[0].c;
  const Vec3 p1 = swp > 0 ? rims[1].c - wp * (rims[1].r / swp) : rims[1].c;
  const auto [lambda, sdp] =
      golden_min([&](double x) { return point_frustum_signed_distance(b, p0 + (p1 - p0) * x); }, 0.0, 1.0, 64);
  const Vec3 p = p0 + (p1 - p0) * lambda;
  const double vg = (V - b.radius) * cb;
  double scale = std::max({b.height, b.max_radius(), a.height, a.max_radius()});
  for (const Vec3& v : {a.base, b.base}) scale = std::max({scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (sdp - vg <= 0x1p-44 * scale) {  // ~5.7e-14 relative: the duality gap closes
    PairDistance out;
    out.distance = sdp;
    out.point_a = p;
    out.point_b = nearest_on_frustum_boundary(b, p);
    out.path = AnalyticPath::cone;
    return out;
  }
  // B's cross-sections (the slice path, analytic.h): exact for axes within 60 degrees, ~0.1 ms
  if (PairDistance sl; detail::slice_distance(a, b, sl)) return sl;
  // The end faces too: F = max(g, -z, z - h) <= sd_B everywhere (each is a supporting signed
  // distance; inside B, F = sd_B), so s >= min over A of F = max over lambda in the simplex of
  // min over A of sum lambda_i f_i (minimax), each term a support function of A. One end face at a
  // time (lambda of the other = 0): an outer golden section over lambda0 (the partial maximum of a
  // concave function) and, per lambda0, a search over the azimuth; the primal point as above.
  // Certified by the same bracket V <= s <= sd_B(p*).
  {
    PairDistance best_out;
    double best_gap = 1e300;
    for (const double side : {1.0, -1.0}) {  // +1: top face (z - h), -1: bottom face (-z)
      const auto D = [&](double l0, double psi) {
        const Vec3 w = (e1 * std::cos(psi) + e2 * std::sin(psi) - u * k) * (l0 * cb) + u * (side * (1 - l0));
        const Vec3 wp = w - d * dot(w, d);
        const double swp = norm(wp);
        const double m = std::min(dot(w, rims[0].c - b.base) - rims[0].r * swp, dot(w, rims[1].c - b.base) - rims[1].r * swp);
        return m - l0 * cb * b.radius - (side > 0 ? (1 - l0) * b.height : 0.0);
      };
      // per lambda0 a full azimuth search (a window around a warm start missed the optimum in about
      // a third of the reverse ring-roller poses)
      const auto inner = [&](double l0) {
        const auto r = detail::max_over_angle([&](double x) { return D(l0, x); });
        return std::pair<double, double>{r.first, -r.second};
      };
      const auto [l0, negv] = golden_min([&](double l) { return inner(l).second; }, 0.0, 1.0, 60);
      const double v = -negv;
      const double ps = inner(l0).first;
      const Vec3 w = (e1 * std::cos(ps) + e2 * std::sin(ps) - u * k) * (l0 * cb) + u * (side * (1 - l0));
      const Vec3 wp = w - d * dot(w, d);
      const double swp = norm(wp);
      const Vec3 q0 = swp > 0 ? rims[0].c - wp * (rims[0].r / swp) : rims[0].c;
      const Vec3 q1 = swp > 0 ? rims[1].c - wp * (rims[1].r / swp) : rims[1].c;
      const auto [lam, sdq] =
          golden_min([&](double x) { return point_frustum_signed_distance(b, q0 + (q1 - q0) * x); }, 0.0, 1.0, 64);
      if (sdq - v < best_gap) {
        best_gap = sdq - v;
        best_out.distance = sdq;
        best_out.point_a = q0 + (q1 - q0) * lam;
      }
    }
    if (best_gap <= 0x1p-44 * scale) {
      best_out.point_b = nearest_on_frustum_boundary(b, best_out.point_a);
      best_out.path = AnalyticPath::cone;
      return best_out;
    }
  }
  if (!b.tapered()) return cylinder_pair_distance(a, b);
  return cone_general(a, b);
}

}  // namespace interfere::bearing
