// Roller end against a rib (flange) face (issue #27; Jia & Zheng 2019, §2.1 Fig. 1: the ribs of the
// inner ring guide the rollers' ends). raceway.h documents the quantity:
//     s = min over K of l(p),  l(p) = (p - center).normal,  K = roller ∩ {ri <= rho(p) <= ro}
// with rho the distance to the ring axis. K is compact but not convex (rho >= ri), so the minimum of
// the linear l over K is found among the places where a minimum can be:
//   (a) on an end circle of the roller: l restricted to the whole circle has its minimum at
//       c - r n_perp/|n_perp| (n_perp = normal's part in the circle's plane; closed form, the rim
//       case of the support function centre.n + r sqrt(1 - (n.axis)^2)); it counts when that point
//       lies in the shell ri <= rho <= ro;
//   (b) on the curves where the roller's boundary meets the cylinders rho = ri and rho = ro.
// Why nothing else: on the lateral surface l is linear along each generator, so a minimum over K is
// at a generator's end in K: on an end circle or where the generator leaves the shell (b); on an end
// disk l is linear, so its minimum over disk ∩ shell is on the disk's circle or on the shell's
// boundary (b); inside the roller, a minimum over K lies on the shell's boundary rho = c, where l is
// linear along the lines parallel to the ring axis, so it is at such a line's exit from the roller
// (b). A minimum on an end circle that is not (a) is at an arc end, i.e. on (b). For (b), each line
// parallel to the ring axis at radius c and azimuth psi meets the convex roller in a segment (exact
// line-frustum clipping, a quadratic); l is linear along it, so the segment's lower end is the
// candidate, and psi is searched in 1-D: 41 samples over the roller's angular window, seeded also
// with the azimuth of the roller's point nearest to (c = ro) / farthest from (c = ri) the axis (where
// a thin crossing arc lies), then golden-section refinement of the two best sampled local minima
// and of the seed. (c) Before (b): the usual case in closed form with a KKT certificate
// (outer_shell_closed_form below); (d) the inner case (the lowest rim point inside ri) in closed
// form with a certificate (inner_shell_closed_form); (b) runs only where neither applies.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "golden.h"
#include "interfere/bearing/raceway.h"
#include "raceway_detail.h"

namespace interfere::bearing {
namespace {

using detail::golden_min;
using detail::perpendicular_unit;
using detail::Rim;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The row of a rib point found at height l over the face: the roller point p and its foot on the face.
PairDistance rib_row(double l, const Vec3& p, const Vec3& n) {
  PairDistance out;
  out.distance = l;
  out.point_a = p;
  out.point_b = p - n * l;
  out.path = AnalyticPath::rib;
  return out;
}

/// The segment [z0, z1] of the line q + z u inside the solid frustum c; false when they miss.
bool clip_line(const Cylinder& c, const Vec3& q, const Vec3& u, double& z0, double& z1) {
  const Vec3& d = c.axis;
  const double h = c.height, r0 = c.radius, s = (c.top() - c.radius) / h;
  const Vec3 v = q - c.base;
  const double a0 = dot(v, d), ud = dot(u, d);
  double lo = -kInf, hi = kInf;
  if (ud != 0) {
    lo = (0 - a0) / ud, hi = (h - a0) / ud;
    if (lo > hi) std::swap(lo, hi);
  } else if (!(a0 >= 0 && a0 <= h)) {
    return false;
  }
  const Vec3 w0 = v - d * a0, w1 = u - d * ud;
  const double R0 = r0 + s * a0, sr = s * ud;
  const double A = dot(w1, w1) - sr * sr, B = dot(w0, w1) - sr * R0, C = dot(w0, w0) - R0 * R0;
  // Q(z) = A z^2 + 2 B z + C <= 0 inside the lateral surface (the radius is >= 0 within the slab);
  // inside the slab the feasible set is an interval (intersection of convex sets)
  std::array<double, 4> br{};
  int nb = 0;
  if (std::isfinite(lo)) br[nb++] = lo, br[nb++] = hi;
  const double disc = B * B - A * C;
  if (disc >= 0 && (A != 0 || B != 0)) {
    if (A != 0) {
      const double sq = std::sqrt(disc);
      const double qq = -(B + (B >= 0 ? sq : -sq));
      if (qq != 0) br[nb++] = qq / A, br[nb++] = C / qq;
      else br[nb++] = 0;
    } else {
      br[nb++] = -C / (2 * B);
    }
  }
  if (!std::isfinite(lo)) {  // unbounded slab (ud = 0): A = |w1|^2 > 0, the roots bound it
    if (!(disc >= 0) || A <= 0) return false;
    lo = -kInf, hi = kInf;
  }
  std::sort(br.begin(), br.begin() + nb);
  double f0 = kInf, f1 = -kInf;
  const auto Q = [&](double z) { return (A * z + 2 * B) * z + C; };
  for (int i = 0; i < nb; ++i) {
    const double x = br[i];
    if (!(x >= lo && x <= hi)) continue;
    // the sub-interval to the right is feasible when its midpoint is
    if (i + 1 < nb) {
      const double y = std::min(br[i + 1], hi);
      if (y > x && Q(0.5 * (x + y)) <= 0) f0 = std::min(f0, x), f1 = std::max(f1, y);
    }
  }
  // a degenerate (single-point) interval: a tangent line
  if (!(f0 <= f1)) {
    for (int i = 0; i < nb; ++i) {
      const double x = br[i];
      if (x >= lo && x <= hi && Q(x) <= 0) {
        f0 = f1 = x;
        break;
      }
    }
  }
  if (!(f0 <= f1)) return false;
  z0 = std::max(f0, lo), z1 = std::min(f1, hi);
  return z0 <= z1;
}

struct Candidate {
  double l = kInf;
  Vec3 p;
};

/// (b) for the cylinder rho = c: min over the azimuth of l at the roller's boundary on the line.
Candidate shell_curve(const Cylinder& roller, const Rib& rib, double c, const Vec3& a1, const Vec3& a2,
                      double psi_lo, double psi_hi, double seed) {
  const Vec3& u = rib.axis;
  const double un = dot(u, rib.normal);
  const auto eval = [&](double psi, Vec3* at) {
    const Vec3 q = rib.center + a1 * (c * std::cos(psi)) + a2 * (c * std::sin(psi));
    double z0, z1;
    if (!clip_line(roller, q, u, z0, z1)) return kInf;
    const double z = un > 0 ? z0 : z1;
    const Vec3 p = q + u * z;
    if (at) *at = p;
    return dot(p - rib.center, rib.normal);
  };
  constexpr int kN = 40;
  const double step = (psi_hi - psi_lo) / kN;
  std::array<double, kN + 1> v{};
  for (int i = 0; i <= kN; ++i) v[i] = eval(psi_lo + i * step, nullptr);
  std::array<int, kN + 1> mins{};
  int nm = 0;
  for (int i = 0; i <= kN; ++i) {
    if (!(v[i] < kInf)) continue;
    const double l = i > 0 ? v[i - 1] : kInf, r = i < kN ? v[i + 1] : kInf;
    if (v[i] <= l && v[i] <= r) mins[nm++] = i;
  }
  std::sort(mins.begin(), mins.begin() + nm, [&](int x, int y) { return v[x] < v[y]; });
  std::array<double, 3> starts{};
  int ns = 0;
  for (int k = 0; k < std::min(nm, 2); ++k) starts[ns++] = psi_lo + mins[k] * step;
  starts[ns++] = seed;
  Candidate best;
  for (int k = 0; k < ns; ++k) {
    const double s0 = starts[k];
    const auto [psi, val] = golden_min([&](double x) { return eval(x, nullptr); }, s0 - step, s0 + step, 64);
    Vec3 p;
    if (val < best.l) {
      const double lp = eval(psi, &p);
      if (lp < kInf) best.l = lp, best.p = p;
    }
  }
  return best;
}

/// (c) the closed form of the usual case (issue #27, speed): for a face with normal = +-axis, the
/// minimum of l over the larger convex set H = {d'.(x - e) >= 0} ∩ {rho <= ro} (H ⊇ roller ∩
/// {rho <= ro} ⊇ K; e the centre of the end facing the rib, d' the unit axis from it into the
/// roller, n.d' > 0). On the plane d'.(x - e) = 0 the cylinder rho = ro is an ellipse,
/// x(psi) = center + ro (cos psi a1 + sin psi a2) + z(psi) u with
///   z(psi) = (d'.(e - center) - ro (cos psi d'.a1 + sin psi d'.a2)) / d'.u,
/// and l = (n.u) z is smallest at (cos psi, sin psi) = (d'.a1, d'.a2) / h, h = |d' across u| > 0
/// (n.u and d'.u have the same sign). That point x* satisfies the KKT conditions of min l over H:
/// n = mu d' - lambda rho_hat with lambda = (n.d') h / |rho_hat across d'|^2 > 0 and mu = n.d' +
/// lambda h > 0 (n is across rho_hat), and H is convex, so l(x*) is the minimum over H. When x* lies
/// in the end disk it is a point of the roller with rho = ro, i.e. of K, so it is K's minimum: exact
/// by a certificate, no search (the usual pose: the roller tilted outward, its lowest rim point
/// beyond ro). Otherwise (x* outside the disk: the minimum is where the rim crosses rho = ro; or the
/// lowest rim point inside ri, the non-convex side) nothing is returned and (b) searches.
bool outer_shell_closed_form(const Cylinder& roller, const Rib& rib, Candidate& out) {
  const Vec3& n = rib.normal;
  const Vec3& u = rib.axis;
  const bool same = n.x == u.x && n.y == u.y && n.z == u.z;
  if (!same && !(n.x == -u.x && n.y == -u.y && n.z == -u.z)) return false;
  const double nd = dot(n, roller.axis);
  if (!(std::fabs(nd) >= 0.5)) return false;
  const bool from_base = nd > 0;
  const Vec3 dp = from_base ? roller.axis : roller.axis * -1.0;
  const Vec3 e = from_base ? roller.base : roller.top_center();
  const double r = from_base ? roller.radius : roller.top();
  const Vec3 a1 = perpendicular_unit(u), a2 = cross(u, a1);
  const double x1 = dot(dp, a1), x2 = dot(dp, a2), h = std::hypot(x1, x2);
  if (!(h > 1e-12)) return false;  // the end parallel to the face: l constant on the ellipse
  const double du = dot(dp, u), ro = rib.outer_radius;
  const Vec3 radial = a1 * (x1 / h) + a2 * (x2 / h);
  const double z = (dot(dp, e - rib.center) - ro * h) / du;
  const Vec3 p = rib.center + radial * ro + u * z;
  const Vec3 w = p - e;
  const double off = dot(w, dp);
  // in the disk with a margin far above the rounding of p (else (b) decides)
  if (!(dot(w, w) - off * off < r * r * (1 - 0x1p-20))) return false;
  out.l = same ? z : -z;  // l(p) = n.(p - center) = (n.u) z, without p's rounding
  out.p = p;
  return true;
}

/// (d) the inner case in closed form (issue #27, speed): the roller's end e facing the rib (d' into
/// the roller, n.d' > 0, n = +-u) has its lowest rim point g inside ri (rho(g) < ri), where (c) does
/// not apply. With z0(x) the lowest l over the roller's points above the point x of the face plane
/// (projected along n; Omega the roller's projection), min over K of l = min of z0 over Omega with
/// ri <= rho <= ro; z0 is convex (the lower boundary of a convex solid) with its minimum at g's foot,
/// inside ri, so for any p of Omega in the annulus the segment from p to g's foot crosses rho = ri at
/// a point no higher than p: the minimum is on the circle C = {rho = ri} (never on the ro curve).
/// Candidates: the two points R1, R2 where the rim of e crosses C (Newton on |R(phi)|^2 - ri^2 from
/// the crossings of the projected rim's circle with C), points of K; z* = the lower of l(R1), l(R2).
/// Certificate that z0 >= z* - eps on C within the roller's angular window: every roller point is
/// q + s d' with q in the end disk and 0 <= s <= L, so z0(x) = P(x) + s_min(x)/(n.d') (P the end
/// disk's plane, s_min >= 0); at R_k the disk's projection lies in nu_k.(x - R_k) <= 0, nu_k = w -
/// d'(w.n)/(n.d') (w the rim's outward unit at R_k), so s_min(x) >= nu_k.(x - R_k)/(nu_k.d') when
/// nu_k.d' > 0, and x is in Omega only if nu_k.(x - R_k) <= L nu_k.d' (only if nu_k.(x - R_k) <= 0
/// when nu_k.d' <= 0). Each of these lower bounds (P itself; P + nu_k.(x - R_k)/((n.d')(nu_k.d')))
/// and exclusions is linear in x, so on C it holds on an arc (closed form, acos); the certificate is
/// that the arcs where a bound is >= z* - eps or x is excluded cover the window. eps = 2^-44 of the
/// scale: the value l(R) is exact to that (and to rounding, the margins being far above it).
/// Untapered rollers only (the q + s d' form); false when any condition fails (then (b) searches).
bool inner_shell_closed_form(const Cylinder& roller, const Rib& rib, Candidate& out) {
  const Vec3& n = rib.normal;
  const Vec3& u = rib.axis;
  if (roller.tapered()) return false;
  const bool same = n.x == u.x && n.y == u.y && n.z == u.z;
  if (!same && !(n.x == -u.x && n.y == -u.y && n.z == -u.z)) return false;
  const double ri = rib.inner_radius;
  if (!(ri > 0)) return false;
  const double nd = dot(n, roller.axis);
  if (!(std::fabs(nd) >= 0.5)) return false;
  const Vec3 dp = nd > 0 ? roller.axis : roller.axis * -1.0;
  const Vec3 e = nd > 0 ? roller.base : roller.top_center();
  const double r = roller.radius, L = roller.height, dn = std::fabs(nd);
  const Vec3 np = n - dp * dn;  // n's part in the disk's plane; -np/|np| points to the lowest rim point
  const double snp = norm(np);
  if (!(snp > 1e-12)) return false;
  // (np is n less its part along d': cancellation when the roller is nearly parallel to n; the
  // direction is made orthogonal to d' again so that the rim points lie in the end plane to rounding)
  Vec3 f1 = np * (-1.0 / snp);
  f1 = f1 - dp * dot(f1, dp);
  f1 = f1 / norm(f1);
  const Vec3 f2 = cross(dp, f1);
  const auto horiz = [&](const Vec3& v) { return v - n * dot(v, n); };  // across the ring axis
  const Vec3 a = horiz(e - rib.center), b = horiz(f1) * r, c = horiz(f2) * r;
  const double scale = std::max({std::fabs(rib.center.x), std::fabs(rib.center.y), std::fabs(rib.center.z)}) +
                       norm(e - rib.center) + L + r + rib.outer_radius;
  const double eps = 0x1p-44 * scale;
  // the lowest rim point strictly inside ri (else (b) decides)
  if (!(dot(a + b, a + b) < ri * ri * (1 - 0x1p-30))) return false;
  const auto f = [&](double phi, double* df) {
    const double cs = std::cos(phi), sn = std::sin(phi);
    const Vec3 x = a + b * cs + c * sn;
    if (df) *df = 2 * dot(x, c * cs - b * sn);
    return dot(x, x) - ri * ri;
  };
  // starting angles: the projected rim taken as the circle (centre a, radius r) against C
  const double am = norm(a);
  if (!(am > 0)) return false;
  const double cos_t = std::clamp((am * am + r * r - ri * ri) / (2 * am * r), -1.0, 1.0);
  const double t = std::acos(cos_t);  // angle at a between -a (toward the ring axis) and a crossing
  const Vec3 toward = a * (-1.0 / am);
  const double base_phi = std::atan2(dot(toward, c), dot(toward, b));  // phi of the rim point toward the axis
  struct Crossing {
    Vec3 R, w;
    double l = kInf;
  };
  std::array<Crossing, 2> cr{};
  for (int k = 0; k < 2; ++k) {
    double phi = k == 0 ? base_phi - t : base_phi + t;
    for (int it = 0; it < 16; ++it) {  // (whether it reached C is checked below)
      double df = 0;
      const double fv = f(phi, &df);
      if (!(df != 0) || !std::isfinite(fv)) break;
      const double step = fv / df;
      phi -= step;
      if (!(std::fabs(step) > 0x1p-50 * (1 + std::fabs(phi)))) break;
    }
    if (!std::isfinite(phi)) return false;
    cr[k].w = f1 * std::cos(phi) + f2 * std::sin(phi);
    cr[k].R = e + cr[k].w * r;
    if (!(std::fabs(norm(horiz(cr[k].R - rib.center)) - ri) <= eps)) return false;  // Newton did not reach C
    cr[k].l = dot(cr[k].R - rib.center, n);
  }
  const Crossing& best = cr[1].l < cr[0].l ? cr[1] : cr[0];
  const double zs = best.l;
  // the roller's angular window seen from the ring axis (bounding sphere), as (b)
  const Vec3 a1 = perpendicular_unit(u), a2 = cross(u, a1);
  const Vec3 m = roller.center() - rib.center;
  const double mx = dot(m, a1), my = dot(m, a2), D = std::hypot(mx, my);
  const double rb = std::hypot(0.5 * L, r);
  if (!(D > rb * 1.000001)) return false;
  const double psi_m = std::atan2(my, mx), half = std::asin(std::min(1.0, rb / D)) * 1.000001 + 1e-12;
  // the arcs of C (angles relative to psi_m) where k0 + G.x >= 0, x = ri (cos, sin) in (a1, a2)
  std::array<std::pair<double, double>, 15> arcs{};
  int na = 0;
  bool whole = false;
  const auto add = [&](double k0, const Vec3& G) {
    const double gx = dot(G, a1), gy = dot(G, a2), amp = ri * std::hypot(gx, gy);
    if (k0 >= amp) {
      whole = true;
      return;
    }
    if (!(k0 > -amp)) return;  // nowhere (or not a number)
    const double h = std::acos(std::clamp(-k0 / amp, -1.0, 1.0)) * (1 - 0x1p-30);
    double cen = std::atan2(gy, gx) - psi_m;
    cen = std::remainder(cen, 2 * std::numbers::pi);
    for (const double sh : {-2 * std::numbers::pi, 0.0, 2 * std::numbers::pi}) arcs[na++] = {cen + sh - h, cen + sh + h};
  };
  const Vec3 gradP = horiz(dp) * (-1.0 / dn);  // P(x) = l(R) + gradP.(x - R) on the face plane
  add(eps - dot(gradP, horiz(best.R - rib.center)), gradP);  // P >= z* - eps
  for (const Crossing& ck : cr) {
    const double wn = dot(ck.w, n);
    const Vec3 nu = horiz(ck.w - dp * (wn / dn));
    const double nud = -wn / dn;  // nu.d'
    const double nr = dot(nu, horiz(ck.R - rib.center));
    const double margin = 0x1p-40 * scale * norm(nu);
    if (nud > 0) {
      const Vec3 G = gradP + nu * (1 / (dn * nud));  // P + s_min/(n.d') >= z* - eps
      add(ck.l - zs + eps - dot(G, horiz(ck.R - rib.center)), G);
      add(-nr - L * nud - margin, nu);  // outside Omega: nu.(x - R) > L nu.d'
    } else {
      add(-nr - margin, nu);  // outside Omega: nu.(x - R) > 0
    }
  }
  if (!whole) {
    std::sort(arcs.begin(), arcs.begin() + na);
    double reach = -half;
    for (int i = 0; i < na && reach < half; ++i)
      if (arcs[i].first <= reach) reach = std::max(reach, arcs[i].second);
    if (!(reach >= half)) return false;
  }
  out.l = zs;
  out.p = best.R;
  return true;
}

/// A lower bound of l over the roller's points with rho >= ro (so over the ro curve of (b)), for an
/// untapered roller whose end e facing the rib (d' into the roller, n.d' > 0) leans toward the ring
/// axis (m.d' <= 0, m the unit radial direction of e; the usual pose of (c)'s fallback: the lowest
/// rim point inside ri). Every roller point is x = q + s d' with q in the end disk and s >= 0, so
/// l(x) = l(q) + s n.d' >= l(q) and m.(q - center) >= m.(x - center); with |t.(x - center)| <= T
/// (t = u x m), rho(x) >= ro gives m.(x - center) >= a = sqrt(ro^2 - T^2). The bound is the minimum
/// of the linear l over the disk cut by m.(q - center) >= a: the disk's lowest point if it is
/// kept, else the lower end of the chord (closed form), less a margin far above rounding. -inf
/// where these conditions do not hold (issue #27, speed: the ro curve's search is then skipped
/// when the bound is above the ri curve's value).
double outer_curve_lower_bound(const Cylinder& roller, const Rib& rib) {
  const Vec3& n = rib.normal;
  const Vec3& u = rib.axis;
  const double nd = dot(n, roller.axis);
  if (roller.tapered() || !(std::fabs(nd) >= 0.5)) return -kInf;
  const Vec3 dp = nd > 0 ? roller.axis : roller.axis * -1.0;
  const Vec3 e = nd > 0 ? roller.base : roller.top_center();
  const double r = roller.radius, L = roller.height, ro = rib.outer_radius;
  const Vec3 v = e - rib.center;
  const Vec3 across = v - u * dot(v, u);
  const double rr = norm(across);
  if (!(rr > 0)) return -kInf;
  const Vec3 m = across / rr, t = cross(u, m);
  const double md = dot(m, dp);
  if (!(md <= 0) || !(rr - r - L * std::fabs(md) > 0)) return -kInf;  // (m.(x - center) > 0 on the roller)
  const double T = std::fabs(dot(t, v)) + r + L * std::fabs(dot(t, dp));
  if (!(T < ro)) return -kInf;
  const double a = std::sqrt(ro * ro - T * T);
  const Vec3 f1 = perpendicular_unit(dp), f2 = cross(dp, f1);
  const double gx = dot(n, f1), gy = dot(n, f2), kx = dot(m, f1), ky = dot(m, f2);
  const double g = std::hypot(gx, gy), k = std::hypot(kx, ky), le = dot(v, n);
  const double margin = 1e-9 * (1 + rr + L);
  const double lowest = le - r * g;  // the disk's lowest point
  if (!(k > 0)) return -kInf;
  const double b0 = a - dot(m, v), dist = b0 / k;  // the chord: (kx, ky).w = b0
  if (!(g > 0) || (-r * (kx * gx + ky * gy) / g) >= b0 || !(dist < r)) return lowest - margin;
  const double h = std::sqrt(std::max(0.0, r * r - dist * dist));
  const double cx = kx / k * dist, cy = ky / k * dist, px = -ky / k * h, py = kx / k * h;
  return le + std::min(gx * (cx + px) + gy * (cy + py), gx * (cx - px) + gy * (cy - py)) - margin;
}

}  // namespace

PairDistance roller_rib_distance(const Cylinder& roller, const Rib& rib) {
  const Vec3& n = rib.normal;
  const Vec3& u = rib.axis;
  const double ri = rib.inner_radius, ro = rib.outer_radius;
  const Vec3& d = roller.axis;
  const auto rho = [&](const Vec3& p) { return norm(cross(p - rib.center, u)); };
  const auto l = [&](const Vec3& p) { return dot(p - rib.center, n); };
  const Rim rims[2] = {{roller.base, roller.radius}, {roller.top_center(), roller.top()}};
  Candidate best;
  double plane_min = kInf;  // min of l over the whole roller (a lower bound when apart)
  Vec3 plane_p;
  // (a) the minimum of l on each end circle
  const Vec3 np = n - d * dot(n, d);
  const double snp = norm(np);
  for (const Rim& rim : rims) {
    if (snp > 1e-12) {
      const Vec3 p = rim.c - np * (rim.r / snp);
      const double lp = l(p), rp = rho(p);
      if (lp < plane_min) plane_min = lp, plane_p = p;
      if (rp >= ri && rp <= ro && lp < best.l) best.l = lp, best.p = p;
    } else {  // the circle is parallel to the face: l is constant on it; any point in the shell
      const Vec3 f1 = perpendicular_unit(d), f2 = cross(d, f1);
      for (int k = 0; k < 16; ++k) {
        const Vec3 p = detail::rim_point(rim, f1, f2, k * (std::numbers::pi / 8));
        const double lp = l(p), rp = rho(p);
        if (lp < plane_min) plane_min = lp, plane_p = p;
        if (rp >= ri && rp <= ro && lp < best.l) best.l = lp, best.p = p;
      }
    }
  }
  // l is linear, so its minimum over the whole roller is plane_min (on a rim, (a)); when that point
  // lies in the shell it is the minimum over K too, and no point of (b) can be lower: done.
  if (best.l == plane_min) return rib_row(best.l, best.p, n);
  // (c) the usual case in closed form (certified; see outer_shell_closed_form)
  if (Candidate c; outer_shell_closed_form(roller, rib, c)) return rib_row(c.l, c.p, n);
  // (d) the inner case in closed form (certified; see inner_shell_closed_form): the minimum over K
  // is on the ri curve, at the rim's crossing R; an (a) candidate can only tie it
  if (Candidate c; inner_shell_closed_form(roller, rib, c)) {
    if (c.l < best.l) best = c;
    return rib_row(best.l, best.p, n);
  }
  // (b) the curves on rho = ro and rho = ri, searched over the roller's angular window seen from the
  // ring axis (bounding sphere of the roller: centre m, radius rb)
  const Vec3 a1 = perpendicular_unit(u), a2 = cross(u, a1);
  const Vec3 m = roller.center() - rib.center;
  const double mx = dot(m, a1), my = dot(m, a2), D = std::hypot(mx, my);
  const double rb = std::hypot(0.5 * roller.height, roller.max_radius());
  double psi_lo = -std::numbers::pi, psi_hi = std::numbers::pi;
  const double psi_m = std::atan2(my, mx);
  if (D > rb * 1.000001) {
    const double w = std::asin(std::min(1.0, rb / D)) * 1.000001 + 1e-12;
    psi_lo = psi_m - w, psi_hi = psi_m + w;
  }
  // seeds: the azimuths of the roller's extreme points in rho (thin crossings lie around them)
  double min_rho = kInf, max_rho = 0;
  Vec3 far_p;
  for (const Rim& rim : rims) {
    const auto [r, p] = detail::max_axis_distance_on_rim(rim, d, rib.center, u);
    if (r > max_rho) max_rho = r, far_p = p;
  }
  Cylinder enclosing = roller;  // contains the roller: its min rho is a lower bound
  enclosing.radius = roller.max_radius(), enclosing.top_radius = -1;
  const RadialMin near = min_axis_distance(enclosing, rib.center, u);
  min_rho = near.rho;
  const auto azimuth = [&](const Vec3& p) { return std::atan2(dot(p - rib.center, a2), dot(p - rib.center, a1)); };
  // a curve exists only where the roller crosses the cylinder (min_rho is a lower bound)
  // the ri curve first: when the ro curve's lower bound is above what is known, its search cannot
  // change the result (the best is still the first smallest in the order (a), ro, ri)
  const bool on_ro = min_rho <= ro && max_rho >= ro, on_ri = ri > 0 && min_rho <= ri && max_rho >= ri;
  Candidate c_ri;
  if (on_ri) c_ri = shell_curve(roller, rib, ri, a1, a2, psi_lo, psi_hi, azimuth(far_p));
  if (on_ro && !(outer_curve_lower_bound(roller, rib) > std::min(best.l, c_ri.l))) {
    const Candidate c = shell_curve(roller, rib, ro, a1, a2, psi_lo, psi_hi, azimuth(near.point));
    if (c.l < best.l) best = c;
  }
  if (c_ri.l < best.l) best = c_ri;
  if (best.l < kInf) return rib_row(best.l, best.p, n);
  PairDistance out;
  // no point over the annulus: a positive lower bound of the distance (radial gap to the shell, or
  // the plane gap of the whole roller)
  const double radial = std::max(min_rho - ro, ri - max_rho);
  out.distance = std::max({radial, plane_min, 0.0});
  if (out.distance == plane_min) {
    out.point_a = plane_p, out.point_b = plane_p - n * plane_min;
  } else if (radial == min_rho - ro) {
    out.point_a = near.point;
    out.point_b = near.point;  // moved radially onto rho = ro below
    const Vec3 v = near.point - rib.center;
    const Vec3 rad = v - u * dot(v, u);
    const double rr = norm(rad);
    if (rr > 0) out.point_b = rib.center + u * dot(v, u) + rad * (ro / rr);
  } else {
    out.point_a = far_p;
    const Vec3 v = far_p - rib.center;
    const Vec3 rad = v - u * dot(v, u);
    const double rr = norm(rad);
    out.point_b = rr > 0 ? rib.center + u * dot(v, u) + rad * (ri / rr) : far_p;
  }
  out.path = AnalyticPath::apart;
  return out;
}

}  // namespace interfere::bearing
