// Scarred solver (Jia & Zheng 2019, §3.2): temporally coherent branch and bound down the roller's
// quadtree, exact on the scarred triangle surface; the exact surface reference; and the vertex
// methods the paper compares (brute force, Barbier–Galin 2004 point-to-cylinder distance, the
// paper's quadtree method over the window of Eq. (1)).
#include "interfere/bearing/scarred.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#include "interfere/bearing/raceway.h"
#include "interfere/core/predicates.h"
#include "golden.h"

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using detail::golden_min;


/// The signed distance to a solid frustum in its meridian half-plane (rho >= 0, z from its centre):
/// radius Rm + k z on -hh <= z <= hh. The section is the trapezoid |x| <= Rm + k z (convex,
/// symmetric): inside, minus the distance to the nearest edge line (the lateral one, or an end);
/// outside, the distance to the nearest of the three edge segments of the half x >= 0 (bottom, top,
/// lateral). Nondecreasing in rho for a fixed z (a convex section symmetric about x = 0).
double frustum_sd_rz(double rho, double z, double Rm, double k, double nk, double hh) {
  const double r0 = Rm - k * hh, r1 = Rm + k * hh;
  const double lat = (rho - (Rm + k * z)) / nk;  // signed distance to the lateral line
  if (std::fabs(z) <= hh && lat <= 0) return std::max(std::fabs(z) - hh, lat);
  const double db = std::hypot(std::max(rho - r0, 0.0), z + hh);
  const double dt = std::hypot(std::max(rho - r1, 0.0), z - hh);
  // the lateral segment (r0, -hh) .. (r1, hh): direction (2 k hh, 2 hh) ~ (k, 1)
  const double w = std::clamp(((rho - r0) * k + (z + hh)) / (2 * hh * (1 + k * k)), 0.0, 1.0);
  const double dl = std::hypot(rho - (r0 + w * 2 * k * hh), z - (-hh + w * 2 * hh));
  return std::min({db, dt, dl});
}

/// node_lower_bound's terms that depend only on a node's frame angle (its cos_mid, sin_mid) and on
/// B's frame: the box's radial and tangential axes in B's frame and, for the curvature bound, the
/// radial axis projected along B's axis (|g_r| = gr, its direction (urx, ury); radial: gr^2 > 1/4).
struct AngleTerms {
  std::uint64_t cos_bits = ~std::uint64_t{0}, sin_bits = ~std::uint64_t{0};  // (a NaN: no angle yet)
  double erx = 0, ery = 0, etx = 0, ety = 0, erz = 0, etz = 0, abs_erz = 0, abs_etz = 0;
  bool radial = false;
  double gr = 0, urx = 0, ury = 0;
};

/// B's local frame (centre at the origin, axis +z) and the map body(A) -> local(B). B is a cylinder
/// (radius R) or a frustum (issue #27: a tapered roller, a tapered bearing's cone): radius
/// Rm + k z on -hh <= z <= hh, nk = sqrt(1 + k^2).
struct LocalFrame {
  Vec3 c, bx, by, u;
  double R = 1, hh = 1;
  bool tapered = false;
  double Rm = 1, k = 0, nk = 1;
  double m[3][3];  // local = m * body + o
  Vec3 o;

  LocalFrame(const Transform& pose, const Cylinder& b) {
    c = b.center(), u = b.axis;
    const Vec3 t = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    bx = cross(u, t);
    bx = bx / norm(bx);
    by = cross(u, bx);
    R = b.radius, hh = 0.5 * b.height;
    tapered = b.tapered();
    if (tapered) Rm = 0.5 * (b.radius + b.top()), k = (b.top() - b.radius) / b.height, nk = std::sqrt(1 + k * k);
    const Vec3 rows[3] = {bx, by, u};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        m[i][j] = rows[i].x * pose.r[0][j] + rows[i].y * pose.r[1][j] + rows[i].z * pose.r[2][j];
    }
    const Vec3 d = pose.t - c;
    o = {dot(bx, d), dot(by, d), dot(u, d)};
  }
  Vec3 local(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + o.x,
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + o.y,
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + o.z};
  }
  Vec3 world(const Vec3& q) const { return c + bx * q.x + by * q.y + u * q.z; }
  /// sd_B in (rho, z), nondecreasing in rho.
  double sd_rz(double rho, double z) const {
    return tapered ? frustum_sd_rz(rho, z, Rm, k, nk, hh) : signed_distance_rz(rho, z, R, hh);
  }
  double sd(const Vec3& q) const { return sd_rz(std::sqrt(q.x * q.x + q.y * q.y), q.z); }
  /// node_lower_bound's terms for the angle (cos, sin), kept for the next node of the same angle
  /// (compared bit for bit).
  const AngleTerms& terms(double cos_mid, double sin_mid) const {
    const auto cb = std::bit_cast<std::uint64_t>(cos_mid), sb = std::bit_cast<std::uint64_t>(sin_mid);
    if (cb == angle_.cos_bits && sb == angle_.sin_bits) return angle_;
    AngleTerms& at = angle_;
    at.cos_bits = cb, at.sin_bits = sb;
    at.erx = m[0][0] * cos_mid + m[0][1] * sin_mid;
    at.ery = m[1][0] * cos_mid + m[1][1] * sin_mid;
    at.etx = -m[0][0] * sin_mid + m[0][1] * cos_mid;
    at.ety = -m[1][0] * sin_mid + m[1][1] * cos_mid;
    at.erz = m[2][0] * cos_mid + m[2][1] * sin_mid;
    at.etz = -m[2][0] * sin_mid + m[2][1] * cos_mid;
    at.abs_erz = std::fabs(at.erz), at.abs_etz = std::fabs(at.etz);
    const double gr2 = at.erx * at.erx + at.ery * at.ery;
    at.radial = gr2 > 0.25;
    if (at.radial) at.gr = std::sqrt(gr2), at.urx = at.erx / at.gr, at.ury = at.ery / at.gr;
    return at;
  }

 private:
  mutable AngleTerms angle_;
};

/// The minimum of a convex G on [lo, hi] near a guess, certified: Newton steps on central differences
/// (step d, adapted to the curvature), each stencil x1 - d, x1, x1 + d checked by convexity. With
/// every evaluation within eps of G: g0, g2 >= g1 + 2 eps puts the minimiser in [x1 - d, x1 + d],
/// where G >= g1 - max(g0 - g1, g2 - g1) - 3 eps (the secants bound it); at an end (x1 - d = lo,
/// g1 >= g0 + 2 eps, g2 >= g1 + 2 eps) the minimiser lies in [lo, x1] and G >= 2 g1 - g2 - 3 eps
/// there. Accepted when the value returned is within `tol` of that bound; false: not certified (the
/// caller searches).
template <class G>
bool certified_convex_min(G&& g, double lo, double hi, double z, double d, double eps, double tol, double& z_out,
                          double& v_out) {
  for (int it = 0; it < 8; ++it) {
    if (!(hi - lo > 4 * d) || !(d > 0)) return false;
    const double x1 = std::clamp(z, lo + d, hi - d);
    const double g0 = g(x1 - d), g1 = g(x1), g2 = g(x1 + d);
    if (!(std::isfinite(g0) && std::isfinite(g1) && std::isfinite(g2))) return false;
    if (g0 >= g1 + 2 * eps && g2 >= g1 + 2 * eps && std::max(g0 - g1, g2 - g1) + 3 * eps <= tol) {
      z_out = x1, v_out = g1;
      return true;
    }
    if (x1 - d <= lo && g1 >= g0 + 2 * eps && g2 >= g1 + 2 * eps && g0 - 2 * g1 + g2 + 3 * eps <= tol) {
      z_out = lo, v_out = g0;
      return true;
    }
    if (x1 + d >= hi && g1 >= g2 + 2 * eps && g0 >= g1 + 2 * eps && g2 - 2 * g1 + g0 + 3 * eps <= tol) {
      z_out = hi, v_out = g2;
      return true;
    }
    const double curv = g2 - 2 * g1 + g0;
    if (!(curv > 0)) return false;
    z = x1 - d * (g2 - g0) / (2 * curv);
    // the step d adapts to G's curvature: second differences (G'' d^2) above rounding (8 eps) and
    // below the tolerance (tol / 4); steep sections of thin triangles need a smaller d, flat ones a
    // larger one
    if (curv < 8 * eps && std::fabs(z - x1) < 2 * d) {
      d *= 4;
    } else if (curv > 0.25 * tol && std::fabs(z - x1) < 2 * d) {
      d *= 0.25;
    } else if (std::fabs(z - x1) < 0.25 * d && it > 0) {
      return false;  // converged without a certificate (a kink)
    }
  }
  return false;
}

/// Exact minimum of sd_B over a triangle given in B's local frame. `cut` (issue #27, the solver's
/// best value so far): a triangle that cannot hold a value <= cut may return early with a value
/// above cut (a lower bound of its minimum) instead of its minimum.
TriangleMin local_triangle_min(const LocalFrame& f, const Vec3& a, const Vec3& b, const Vec3& c, double cut = kInf) {
  TriangleMin out;
  // planar distance from B's axis (the origin) to the projected triangle
  const std::array<Vec3, 3> v = {a, b, c};
  const int s0 = orient2d(v[0].x, v[0].y, v[1].x, v[1].y, 0, 0);
  const int s1 = orient2d(v[1].x, v[1].y, v[2].x, v[2].y, 0, 0);
  const int s2 = orient2d(v[2].x, v[2].y, v[0].x, v[0].y, 0, 0);
  const bool pierced = (s0 >= 0 && s1 >= 0 && s2 >= 0 && (s0 | s1 | s2)) ||
                       (s0 <= 0 && s1 <= 0 && s2 <= 0 && (s0 | s1 | s2));
  double rho = kInf;
  Vec3 p;
  if (!pierced) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& e0 = v[static_cast<std::size_t>(k)];
      const Vec3& e1 = v[static_cast<std::size_t>((k + 1) % 3)];
      const double dx = e1.x - e0.x, dy = e1.y - e0.y, l2 = dx * dx + dy * dy;
      double t;
      if (l2 > 0) {
        t = std::clamp(-(e0.x * dx + e0.y * dy) / l2, 0.0, 1.0);
      } else {  // the edge is parallel to B's axis: every t is a minimiser, take |z| smallest
        const double dz = e1.z - e0.z;
        t = dz != 0 ? std::clamp(-e0.z / dz, 0.0, 1.0) : 0.0;
      }
      const Vec3 q = e0 + (e1 - e0) * t;
      const double r = std::sqrt(q.x * q.x + q.y * q.y);
      if (r < rho || (r == rho && std::fabs(q.z) < std::fabs(p.z))) rho = r, p = q;
    }
  }
  if (!pierced && rho > 0 && !f.tapered) {
    const double dr = rho - f.R, dz = std::fabs(p.z) - f.hh;
    if (dr >= 0 ? dz <= 0 : dz <= dr) {  // certificate: B's side is what is nearest
      out.value = dr, out.point = p, out.certified = true;
      return out;
    }
    // (issue #27, speed: the searches below for a triangle that cannot improve the solver's best)
    // sd_B >= max(rho - R, |z| - hh) at every point (inside B it is that max; outside it is the
    // distance to B, at least either), so over the triangle sd_B >= max(rho_min - R, |z|_min - hh).
    // Every value returned below is sd_B (sd_rz) at a point of the triangle up to rounding (a few
    // ulps of the scale), so with the margin 2^-40 of the scale, lb - margin > cut means the value
    // would be > cut too: the caller (which keeps only values <= its best) decides the same.
    // Beyond an end plane and outside B's side (zmin >= hh, rho >= R: a face overhanging B's end,
    // e.g. a roller's end cap past its neighbour's end), every point of the triangle is, and sd_B
    // there is hypot(rho - R, |z| - hh), nondecreasing in both: sd_B >= hypot(dr, zmin - hh)
    // (issue #27, speed: those triangles took the searches below).
    if (cut < kInf) {
      const double zl = std::min({a.z, b.z, c.z}), zh = std::max({a.z, b.z, c.z});
      const double zmin = zl <= 0 && zh >= 0 ? 0.0 : std::min(std::fabs(zl), std::fabs(zh));
      const double lb = dr >= 0 && zmin >= f.hh ? std::hypot(dr, zmin - f.hh) : std::max(dr, zmin - f.hh);
      const double scale = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(b.x), std::fabs(b.y),
                                     std::fabs(b.z), std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}) +
                           f.R + f.hh;
      if (lb - 0x1p-40 * scale > cut) {
        out.value = lb, out.point = p, out.certified = true;
        return out;
      }
    }
  }
  // slices (analytic.h's slice path): sd_B = phi(rho, z) with phi nondecreasing in rho, so the
  // minimum over the triangle is min over z of phi(F(z), z), F(z) the distance from B's axis to the
  // triangle's section by the plane at height z (a segment: its edges' crossings); convex in z
  // (partial minimisation of the convex sd_B over the triangle): one golden-section search.
  const double zl = std::min({a.z, b.z, c.z}), zh = std::max({a.z, b.z, c.z});
  const double span = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(b.x), std::fabs(b.y),
                                std::fabs(b.z), std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  if (zh - zl > 1e-6 * span) {
    const auto section = [&](double z, Vec3* at) {
      Vec3 pts[3];
      int np = 0;
      for (int k = 0; k < 3; ++k) {
        const Vec3& e0 = v[static_cast<std::size_t>(k)];
        const Vec3& e1 = v[static_cast<std::size_t>((k + 1) % 3)];
        if (e0.z == z) pts[np++] = e0;
        else if ((e0.z < z && e1.z > z) || (e0.z > z && e1.z < z))
          pts[np++] = e0 + (e1 - e0) * ((z - e0.z) / (e1.z - e0.z));
      }
      if (np == 0) return kInf;
      Vec3 p0 = pts[0], p1 = pts[0];  // the segment: the farthest pair
      double far = -1;
      for (int i = 0; i < np; ++i)
        for (int j = i; j < np; ++j)
          if (const double d2 = (pts[i].x - pts[j].x) * (pts[i].x - pts[j].x) + (pts[i].y - pts[j].y) * (pts[i].y - pts[j].y);
              d2 > far)
            far = d2, p0 = pts[i], p1 = pts[j];
      const double dx = p1.x - p0.x, dy = p1.y - p0.y, l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::clamp(-(p0.x * dx + p0.y * dy) / l2, 0.0, 1.0) : 0.0;
      const Vec3 q{p0.x + dx * t, p0.y + dy * t, z};
      if (at) *at = q;
      return f.sd_rz(std::sqrt(q.x * q.x + q.y * q.y), z);
    };
    // A triangle outside B's infinite cylinder whose point nearest the axis lies beyond an end
    // plane z = +-hh (a face overhanging a roller end, e.g. a cage web): the minimum is just past
    // the end, where G(u) = hypot(F - R, u) (u = |z| - hh). With F modelled linearly between the end
    // plane and that point, the minimiser is u* = -g k / (1 + k^2) (g = F(hh) - R, k = dF/du <= 0).
    // Certificate, whatever the model: G is convex, so G(z* -+ delta) >= G(z*) puts the minimiser
    // in [z* - delta, z* + delta], and there G >= G(z*) - max(G(z* -+ delta) - G(z*)) (the secant
    // slopes bound it); accepted when that gap is below rounding-level tolerance, else the search.
    // (cylinders only: a frustum B goes to the search below, which needs no closed form)
    if (!f.tapered && !pierced && rho >= f.R && std::fabs(p.z) > f.hh) {
      // w: the distance past the end plane on p's side; the triangle's sections there start at
      // w_near (0 when the end plane crosses the triangle, else its nearest vertex height)
      const double sgn = p.z > 0 ? 1.0 : -1.0, wp = std::fabs(p.z) - f.hh;
      const double w_near = std::max(0.0, (sgn > 0 ? zl : -zh) - f.hh);
      const double z_near = sgn * (f.hh + w_near);
      if (z_near >= zl && z_near <= zh && wp > w_near) {
        Vec3 qn;
        const double gn = section(z_near, &qn);
        const double fn = std::sqrt(qn.x * qn.x + qn.y * qn.y) - f.R;  // F - R at w_near
        const double k = std::min(0.0, (rho - f.R - fn) / (wp - w_near));
        // G(w)^2 = (fn + k (w - w_near))^2 + w^2: stationary at w (1 + k^2) = -k (fn - k w_near)
        const double ws = std::clamp(-k * (fn - k * w_near) / (1 + k * k), w_near, wp);
        double zc, vc;
        if (std::isfinite(gn) &&
            certified_convex_min([&](double zz) { return section(zz, nullptr); }, zl, zh, sgn * (f.hh + ws),
                                 0x1p-24 * (zh - zl), 0x1p-48 * (zh - zl + f.R + f.hh),
                                 0x1p-40 * (zh - zl + f.R + f.hh), zc, vc)) {
          out.value = vc, out.certified = false;
          section(zc, &out.point);
          return out;
        }
      }
    }
    // The same for a triangle reaching into B (a face pressed into a roller near its end: the
    // original certificate fails when |z| - hh > rho - R at the point nearest the axis): inside,
    // sd_B = max(rho - R, |z| - hh), so the minimum over the sections is where F - R = |z| - hh, a
    // root of h(u) = F - R - (u - hh) (u = |z| on that side) between u_a = hh - (R - rho) (h >= 0:
    // F >= rho) and u_b = |p.z| (h < 0), found by regula falsi (Illinois), then the same convexity
    // certificate (a kink: the gap is about delta times the slope, delta at 2^-46 of the scale).
    if (!f.tapered && !pierced && rho > 0 && rho < f.R) {
      const double sgn = p.z > 0 ? 1.0 : -1.0, scale = zh - zl + f.R + f.hh;
      const auto h = [&](double u) {
        Vec3 q;
        const double gv = section(sgn * u, &q);
        return std::isfinite(gv) ? std::sqrt(q.x * q.x + q.y * q.y) - f.R - (u - f.hh) : std::nan("");
      };
      double ua = f.hh - (f.R - rho), ub = std::fabs(p.z);
      const double ulo = sgn > 0 ? zl : -zh;
      double ha = ua > ulo ? h(ua) : std::nan(""), hb = ub > ua ? h(ub) : std::nan("");
      if (ha >= 0 && hb < 0) {
        const double root_tol = 0x1p-50 * scale;
        int side = 0;
        for (int it = 0; it < 60 && ub - ua > root_tol; ++it) {
          const double uc = (ua * hb - ub * ha) / (hb - ha);
          if (!(uc > ua && uc < ub)) break;
          const double hc = h(uc);
          if (!(hc == hc)) break;
          if (hc >= 0) {
            ua = uc, ha = hc;
            if (side == -1) hb *= 0.5;
            side = -1;
          } else {
            ub = uc, hb = hc;
            if (side == 1) ha *= 0.5;
            side = 1;
          }
        }
        const double zs = sgn * (ha <= -hb ? ua : ub), delta = 0x1p-46 * scale, tol = 0x1p-43 * scale;
        Vec3 q0;
        const double g0 = section(zs, &q0);
        const double gl = zs - delta > zl ? section(zs - delta, nullptr) : g0;
        const double gr = zs + delta < zh ? section(zs + delta, nullptr) : g0;
        if (std::isfinite(g0) && gl >= g0 && gr >= g0 && std::max(gl - g0, gr - g0) <= tol) {
          out.value = g0, out.point = q0, out.certified = false;
          return out;
        }
      }
    }
    // A frustum B: the convex G(z) = phi(F(z), z) minimised by certified_convex_min (Newton steps on
    // central differences with the convexity certificate above: accepted within 2^-40 of the scale),
    // started at the height of the point nearest B's axis (or the centroid's); not certified: the
    // golden-section search below
    if (f.tapered) {
      const double scale = zh - zl + f.Rm + std::fabs(f.k) * f.hh + f.hh;
      const double start = !pierced && rho < kInf ? p.z : (a.z + b.z + c.z) / 3;
      double zc, vc;
      if (certified_convex_min([&](double zz) { return section(zz, nullptr); }, zl, zh, std::clamp(start, zl, zh),
                               0x1p-24 * (zh - zl), 0x1p-48 * scale, 0x1p-40 * scale, zc, vc)) {
        out.value = vc, out.certified = false;
        section(zc, &out.point);
        return out;
      }
    }
    const auto [z, value] = golden_min([&](double zz) { return section(zz, nullptr); }, zl, zh, 100);
    if (std::isfinite(value)) {
      out.value = value;
      section(z, &out.point);
      out.certified = false;  // (not the closed form: counted as a fallback, as before)
      return out;
    }
  }
  // general: nested golden-section over the barycentric coordinates (sd_B is convex)
  constexpr int kIter = 64;
  const Vec3 ab = b - a, ac = c - a;
  const auto inner = [&](double s) {
    return golden_min([&](double t) { return f.sd(a + ab * s + ac * t); }, 0.0, 1.0 - s, kIter);
  };
  const auto [s, value] = golden_min([&](double ss) { return inner(ss).second; }, 0.0, 1.0, kIter);
  const double t = inner(s).first;
  out.value = value;
  out.point = a + ab * s + ac * t;
  out.certified = false;
  return out;
}

struct Evaluator {
  const Roller& roller;
  LocalFrame frame;
  MeshPairResult best;

  void triangle(std::uint32_t id) {
    const Tri& t = roller.mesh.triangles[id];
    const TriangleMin tm = local_triangle_min(frame, frame.local(roller.mesh.positions[t[0]]),
                                              frame.local(roller.mesh.positions[t[1]]),
                                              frame.local(roller.mesh.positions[t[2]]));
    ++best.evaluated;
    best.fallbacks += tm.certified ? 0 : 1;
    if (tm.value < best.distance || (tm.value == best.distance && id < best.triangle)) {
      best.distance = tm.value;
      best.triangle = id;
      best.point_a = tm.point;  // local for now
    }
  }
  MeshPairResult finish(const Cylinder& b) {
    MeshPairResult out = best;
    out.point_a = frame.world(best.point_a);
    out.point_b = b.tapered() ? nearest_on_frustum_boundary(b, out.point_a) : nearest_on_cylinder_boundary(b, out.point_a);
    return out;
  }
};

/// The same over the entries of a FacetStrips tree (quadtree.h; issue #27): an entry is a mesh
/// triangle or one of the two triangles of a planar strip of intact cells. Ties keep the lowest
/// entry index (deterministic: the entries' order is fixed when the tree is built).
struct StripEvaluator {
  const Roller& roller;
  const FacetStrips& fs;
  LocalFrame frame;
  MeshPairResult best;
  std::uint32_t best_entry = 0xffffffffu;
  const StripLeaf* best_leaf = nullptr;  ///< the record holding best_entry

  /// Entry r.entry + k with its corners in B's frame.
  double entry(const StripLeaf& r, std::uint32_t k, const Vec3& a, const Vec3& b, const Vec3& c) {
    const std::uint32_t e = r.entry + k;
    const TriangleMin tm = local_triangle_min(frame, a, b, c, best.distance);
    ++best.evaluated;
    best.fallbacks += tm.certified ? 0 : 1;
    if (tm.value < best.distance || (tm.value == best.distance && e < best_entry)) {
      best.distance = tm.value;
      best_entry = e, best_leaf = &r;
      best.point_a = tm.point;  // local for now
    }
    return tm.value;
  }
  /// A leaf's entries from its record (quadtree.h, StripLeaf): the copies of its corners, each
  /// mapped to B's frame once (the same doubles as the mesh's, so the same bits as mapping each
  /// entry's three vertices).
  /// Returns the smallest value of its entries (an entry that returned early, above the best
  /// value then: that larger value).
  double leaf(const StripLeaf& r) {
    Vec3 q[4];
    for (int k = 0; k < r.vertices; ++k) q[k] = frame.local(r.v[k]);
    double low = kInf;
    for (std::uint32_t k = 0; k < r.count; ++k)
      low = std::min(low, entry(r, k, q[r.corner[k][0]], q[r.corner[k][1]], q[r.corner[k][2]]));
    return low;
  }
  /// An end cap is skipped when it cannot hold a value below the best by more than 2^-44 of the
  /// local scale (issue #27: the cap's fan triangles next to a contact at the rim tie with the side's
  /// value, so their box bounds never prune them). sd_B is convex, so with g its gradient (a
  /// subgradient: the active piece inside B) at the best point y, sd_B(x) >= sd_B(y) + g.(x - y)
  /// for every x; the cap is the fan over its centre and rim vertices, inside their convex hull, so
  /// over the cap sd_B >= sd_B(y) + min over those vertices of g.(v - y). When y is the rim point
  /// where the cap's minimum is (its minimum over the rim, which the side's triangles hold), that is
  /// sd_B(y) to rounding. Cylinders only (a frustum B: false, the cap tree is searched).
  bool cap_cannot_improve(bool top) const {
    if (frame.tapered || best_entry == 0xffffffffu) return false;
    const Vec3& y = best.point_a;  // local
    const double rho = std::sqrt(y.x * y.x + y.y * y.y);
    const double dr = rho - frame.R, dz = std::fabs(y.z) - frame.hh, sz = y.z < 0 ? -1.0 : 1.0;
    Vec3 g;
    if (dr > 0 && dz > 0) {
      const double len = std::hypot(dr, dz);
      g = {dr / len * y.x / rho, dr / len * y.y / rho, dz / len * sz};
    } else if (dr >= dz) {
      if (!(rho > 0)) return false;
      g = {y.x / rho, y.y / rho, 0};
    } else {
      g = {0, 0, sz};
    }
    const int n = roller.n();
    const auto& pos = roller.mesh.positions;
    const auto value = [&](std::size_t v) { return dot(g, frame.local(pos[v]) - y); };
    double low = value(static_cast<std::size_t>(n) * (roller.m() + 1) + (top ? 1 : 0));  // the centre
    const std::size_t rim0 = static_cast<std::size_t>(top ? roller.m() : 0) * static_cast<std::size_t>(n);
    // (issue #27, speed) the rim's minimum from the 3 vertices nearest its minimising angle when
    // that is certain, else from every rim vertex; the same values, so the same minimum, bit for
    // bit. value(v) = c.v + g.(o - y) exactly, c = M^T g (body frame). On the regular polygon
    // (FacetStrips::rims) c.v = r |c_xy| cos(a - psi) + c_z z, smallest at a = psi; the vertex i*
    // nearest psi is within 0.5 step (0.6 with rounding) of it, every vertex not within one index
    // of i* is 1.5 steps (1.4) or more away, so its exact value is above i*'s by r |c_xy| gap
    // less 2 |c| dev (the rim's distance from the polygon). Each computed value is within err of
    // its exact value (err, 2^-40 of the magnitudes, is far above the rounding of the few
    // products and sums): with that difference above 2 err, every other vertex's computed value
    // is above i*'s, and the minimum over all is the minimum over i* - 1 .. i* + 1.
    const FacetStrips::Rim& rim = fs.rims[top ? 1 : 0];
    const double cx = frame.m[0][0] * g.x + frame.m[1][0] * g.y + frame.m[2][0] * g.z;
    const double cy = frame.m[0][1] * g.x + frame.m[1][1] * g.y + frame.m[2][1] * g.z;
    const double cz = frame.m[0][2] * g.x + frame.m[1][2] * g.y + frame.m[2][2] * g.z;
    const double err = 0x1p-40 * (rim.radius + std::fabs(rim.z) + std::fabs(frame.o.x) + std::fabs(frame.o.y) +
                                  std::fabs(frame.o.z) + std::fabs(y.x) + std::fabs(y.y) + std::fabs(y.z));
    // (|c_xy| and |c| <= about 1: no overflow; the test decides only which vertices are read)
    const double cxy = std::sqrt(cx * cx + cy * cy);
    if (rim.radius * cxy * fs.rim_gap - 2 * std::sqrt(cxy * cxy + cz * cz) * rim.dev > 2 * err) {
      const double u = std::atan2(-cy, -cx) / (2 * std::numbers::pi) * n;  // psi in steps, in [-n/2, n/2]
      const int c = ((static_cast<int>(std::floor(u + 0.5)) % n) + n) % n;
      for (const int i : {c == 0 ? n - 1 : c - 1, c, c + 1 == n ? 0 : c + 1})
        low = std::min(low, value(rim0 + static_cast<std::size_t>(i)));
    } else {
      for (int i = 0; i < n; ++i) low = std::min(low, value(rim0 + static_cast<std::size_t>(i)));
    }
    const double scale = std::fabs(y.x) + std::fabs(y.y) + std::fabs(y.z) + frame.R + frame.hh;
    return frame.sd(y) + low >= best.distance - 0x1p-44 * scale;
  }
  /// (issue #27, speed) When the best point lies on a vertex line of its side leaf (a strip or a
  /// cell of column i: on the generator of column i or i + 1), the first triangle of the cell of
  /// the column beyond that line in the point's row, else kNone. An intact facetted roller's
  /// nearest point to a part beside it is on a vertex line (the polygon's vertex nearest the
  /// direction to the part), which the two columns sharing it reach with the same value: evaluated
  /// first, that cell's leaf is not pruned but not searched for either (descend_strips). Only the
  /// work depends on it. The leaf record's corners: v[0], v[3] on column i's line, v[1], v[2] on
  /// column i + 1's (quadtree.cpp, add_leaf_record: (a0, b0, b1), (a0, b1, a1)).
  std::uint32_t partner() const {
    if (best_entry == 0xffffffffu || best_leaf->vertices != 4) return 0xffffffffu;
    const std::uint32_t t = best_leaf->mesh_triangle[0];
    const int n = roller.n(), m = roller.m();
    int i;
    if (t == FacetStrips::kStrip) {
      i = best_leaf->strip[0];
    } else if (t < 2 * static_cast<std::uint32_t>(n) * static_cast<std::uint32_t>(m)) {
      i = static_cast<int>((t / 2) % static_cast<std::uint32_t>(n));
    } else {
      return 0xffffffffu;  // a cap
    }
    const Vec3 q = best.point_a - frame.o;  // body = m^T (local - o)
    const Vec3 p{frame.m[0][0] * q.x + frame.m[1][0] * q.y + frame.m[2][0] * q.z,
                 frame.m[0][1] * q.x + frame.m[1][1] * q.y + frame.m[2][1] * q.z,
                 frame.m[0][2] * q.x + frame.m[1][2] * q.y + frame.m[2][2] * q.z};
    const auto off_line = [&](const Vec3& a, const Vec3& b) {  // squared distance from the segment a b
      const Vec3 d = b - a, w = p - a;
      const double l2 = dot(d, d), s = l2 > 0 ? std::clamp(dot(w, d) / l2, 0.0, 1.0) : 0.0;
      const Vec3 e = w - d * s;
      return dot(e, e);
    };
    const Vec3* v = best_leaf->v;
    const double tol = 1e-18 * (dot(v[0], v[0]) + dot(v[2], v[2]));  // (1e-9 of the scale, squared)
    int c;
    if (off_line(v[0], v[3]) <= tol) {
      c = i == 0 ? n - 1 : i - 1;
    } else if (off_line(v[1], v[2]) <= tol) {
      c = i + 1 == n ? 0 : i + 1;
    } else {
      return 0xffffffffu;
    }
    const double guess = p.z / roller.params.height * m;
    const int j = std::isfinite(guess) ? std::clamp(static_cast<int>(guess), 0, m - 1) : 0;
    return roller.side_triangle(c, j);
  }
  /// The mesh triangle under the witness (a strip entry: the cell of its run that holds the
  /// witness, then the cell's triangle by the side of its diagonal v(i, j) .. v(i+1, j+1)).
  std::uint32_t mesh_triangle() const {
    if (best_entry == 0xffffffffu) return 0xffffffffu;
    const std::uint32_t t = best_leaf->mesh_triangle[best_entry - best_leaf->entry];
    if (t != FacetStrips::kStrip) return t;
    const int i = best_leaf->strip[0], j0 = best_leaf->strip[1], j1 = best_leaf->strip[2];
    const Vec3 q = best.point_a - frame.o;  // body = m^T (local - o)
    const Vec3 p{frame.m[0][0] * q.x + frame.m[1][0] * q.y + frame.m[2][0] * q.z,
                 frame.m[0][1] * q.x + frame.m[1][1] * q.y + frame.m[2][1] * q.z,
                 frame.m[0][2] * q.x + frame.m[1][2] * q.y + frame.m[2][2] * q.z};
    const auto& pos = roller.mesh.positions;
    // the cell: the last row j in [j0, j1) with j == j0 or z(j) <= p.z (the rows' heights increase
    // along a strip); from the row its height suggests (issue #27: a walk from j0 fetched a cache
    // line per row), moved down and up to that same row
    const double guess = p.z / roller.params.height * roller.m();
    int j = std::isfinite(guess) ? std::clamp(static_cast<int>(guess), j0, j1 - 1) : j0;
    while (j > j0 && !(pos[roller.side_vertex(i, j)].z <= p.z)) --j;
    while (j + 1 < j1 && pos[roller.side_vertex(i, j + 1)].z <= p.z) ++j;
    const Vec3& a = pos[roller.side_vertex(i, j)];
    const Vec3& b = pos[roller.side_vertex(i + 1, j)];
    const double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
    const double tt = l2 > 0 ? ((p.x - a.x) * ex + (p.y - a.y) * ey) / l2 : 0.0;
    const double dz = pos[roller.side_vertex(i, j + 1)].z - a.z;
    const double ss = dz > 0 ? (p.z - a.z) / dz : 0.0;
    return roller.side_triangle(i, j) + (tt >= ss ? 0u : 1u);
  }
  MeshPairResult finish(const Cylinder& b) {
    MeshPairResult out = best;
    out.triangle = mesh_triangle();
    out.point_a = frame.world(best.point_a);
    out.point_b = b.tapered() ? nearest_on_frustum_boundary(b, out.point_a) : nearest_on_cylinder_boundary(b, out.point_a);
    return out;
  }
};

std::atomic<bool> g_facet_strips{true};

/// Lower bound of sd_B over a node's oriented box (see quadtree.h; a QuadNode or a BoundNode).
/// `cut` (issue #27, Table 3 with the scars in range): the bound is the max of three terms (linear
/// lateral, curvature, axial); when the two cheap ones (no square root of the curvature term)
/// already reach `cut`, their max is returned (a smaller lower bound, still >= cut): a caller that
/// prunes at lb >= cut decides the same, and every value below `cut` is the full bound, unchanged.
template <class Node>
double node_lower_bound(const LocalFrame& f, const Node& n, double cut = kInf) {
  if (n.half_r < 0) return kInf;  // no triangles
  const Vec3 c = f.local(n.box_center);
  const double rho = std::sqrt(c.x * c.x + c.y * c.y);
  if (!(rho > 0)) return -kInf;
  const double nx = c.x / rho, ny = c.y / rho;
  // the box's axes in B's frame, from the node's angle: the last angle's (a column's nodes share
  // theirs; issue #27, speed: the same operations on the same values, so the same bits)
  const AngleTerms& at = f.terms(n.cos_mid, n.sin_mid);
  const double erx = at.erx, ery = at.ery, etx = at.etx, ety = at.ety;
  const double ezx = f.m[0][2], ezy = f.m[1][2];
  // sd_B >= |z| - hh too (the slab of B's end planes): boxes beyond B's ends (a raceway's grid
  // past a roller's end, issue #27) are pruned by it where the lateral bound cannot
  const double erz = at.erz, etz = at.etz;
  // The box's distance from B's axis in the box's own directions (issue #27). Project along B's
  // axis: the box becomes c + sum s_i h_i g_i (|s_i| <= 1, g_r, g_t, g_z the projected axes); with
  // u_r = g_r / |g_r| and u_t = u_r turned by 90 degrees, every point x of it has
  //   |x.u_r| >= |c.u_r| - h_r |g_r| - h_t |g_t.u_r| - h_z |g_z.u_r| =: a,
  //   |x.u_t| >= |c.u_t| - h_t |g_t.u_t| - h_z |g_z.u_t|             =: b   (g_r has no u_t part),
  // so rho(x) >= sqrt(a^2 + b^2) (a, b clamped at 0). The linear bound below loses the curvature
  // across the box's width: a cell one column beside the contact generator of two nearly parallel
  // parts keeps about half its gap ((t^2 / 2) (1/r + 1/R) at tangential offset t) and was not
  // pruned, so the search scanned the cells beside the contact line (3-8x the triangles on the
  // benchmark, docs/bearing.md); a tilt across the contact line costs nothing here where b is 0.
  // Used when the box's radial axis is not nearly along B's axis (|g_r| > 1/2: within 60 degrees
  // of parallel; else -inf), less a rounding margin; the larger of it and the linear bound is taken.
  const auto box_rho = [&] {
    if (!at.radial) return -kInf;
    const double gr = at.gr, urx = at.urx, ury = at.ury;
    const double cr = c.x * urx + c.y * ury, ct = c.y * urx - c.x * ury;
    const double a = std::max(0.0, std::fabs(cr) - n.half_r * gr - n.half_t * std::fabs(etx * urx + ety * ury) -
                                       n.half_z * std::fabs(ezx * urx + ezy * ury));
    const double b = std::max(0.0, std::fabs(ct) - n.half_t * std::fabs(ety * urx - etx * ury) -
                                       n.half_z * std::fabs(ezy * urx - ezx * ury));
    const double margin = 16 * std::numeric_limits<double>::epsilon() *
                          (rho + f.R + f.Rm + n.half_r + n.half_t + n.half_z + std::fabs(f.o.x) + std::fabs(f.o.y) +
                           std::fabs(f.o.z));
    return std::sqrt(a * a + b * b) - margin;
  };
  const double axial = std::fabs(c.z) - n.half_r * at.abs_erz - n.half_t * at.abs_etz - n.half_z * std::fabs(f.m[2][2]) - f.hh;
  double lateral;
  if (!f.tapered) {
    lateral = rho - n.half_r * std::fabs(nx * erx + ny * ery) - n.half_t * std::fabs(nx * etx + ny * ety) -
              n.half_z * std::fabs(nx * ezx + ny * ezy) - f.R;
    if (const double cheap = std::max(lateral, axial); cheap >= cut) return cheap;
    lateral = std::max(lateral, box_rho() - f.R);  // (the curvature bound, above)
  } else {
    // a frustum B: sd_B >= (rho - Rm - k z) / nk (the plane tangent to B's cone along a meridian
    // supports the convex B; raceway_cone.cpp), and rho >= n.(x, y) for the unit n of the box
    // centre's meridian, so sd_B >= w.q / nk - Rm / nk with w = (nx, ny, -k): linear, smallest over
    // the box at the centre minus the half extents times |w . e|
    lateral = (rho - f.k * c.z - n.half_r * std::fabs(nx * erx + ny * ery - f.k * erz) -
               n.half_t * std::fabs(nx * etx + ny * ety - f.k * etz) -
               n.half_z * std::fabs(nx * ezx + ny * ezy - f.k * f.m[2][2]) - f.Rm) /
              f.nk;
    // the same support with rho bounded by the curvature bound (above) and k z by its largest
    // value over the box: sd_B >= (rho - Rm - k z) / nk holds at every point
    const double kz = f.k * c.z + std::fabs(f.k) * (n.half_r * std::fabs(erz) + n.half_t * std::fabs(etz) +
                                                    n.half_z * std::fabs(f.m[2][2]));
    if (const double cheap = std::max(lateral, axial); cheap >= cut) return cheap;
    lateral = std::max(lateral, (box_rho() - f.Rm - kz) / f.nk);
  }
  return std::max(lateral, axial);
}

double wrap_pi(double a) {
  const double two_pi = 2 * std::numbers::pi;
  a = std::fmod(a, two_pi);
  if (a < 0) a += two_pi;
  return a;
}

}  // namespace

TriangleMin triangle_min_signed_distance(const Cylinder& b, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  const LocalFrame f(Transform::identity(), b);
  TriangleMin tm = local_triangle_min(f, f.local(t0), f.local(t1), f.local(t2));
  tm.point = f.world(tm.point);
  return tm;
}

MeshPairResult surface_reference(const Roller& roller, const Transform& pose, const Cylinder& b) {
  Evaluator ev{roller, LocalFrame(pose, b), {}};
  ev.best.distance = kInf;
  for (std::uint32_t t = 0; t < roller.mesh.triangles.size(); ++t) ev.triangle(t);
  return ev.finish(b);
}

MeshPairResult ScarredSolver::solve(const Transform& pose, const Cylinder& b) { return run(pose, b, nullptr); }

MeshPairResult ScarredSolver::solve(const Transform& pose, const Cylinder& b, const Vec3& hint) {
  return run(pose, b, &hint);
}

namespace {

/// Depth-first branch and bound from the roots, the smaller child bound first; triangles already
/// evaluated (the previous frame's, the hinted cell's) are skipped.
template <class Node>
void descend(Evaluator& ev, const std::vector<Node>& nodes, std::array<std::int32_t, 3> roots, std::uint32_t previous,
             std::uint32_t hinted, std::uint32_t none) {
  struct Item {
    std::int32_t node;
    double lb;
  };
  // depth-first: at most 3 pending siblings per level plus the roots (a few dozen entries)
  Item stack[1024];
  int top = 0;
  for (const std::int32_t root : roots) stack[top++] = {root, node_lower_bound(ev.frame, nodes[static_cast<std::size_t>(root)])};
  while (top > 0) {
    const Item it = stack[--top];
    if (it.lb >= ev.best.distance) continue;
    const Node& n = nodes[static_cast<std::size_t>(it.node)];
    ++ev.best.nodes_visited;
    if (n.child_count == 0) {
      for (std::uint32_t k = 0; k < n.tri_count; ++k) {
        const std::uint32_t id = n.tri_first + k;
        if (id != previous && (hinted == none || (id != hinted && id != hinted + 1))) ev.triangle(id);
      }
      continue;
    }
    Item kids[4];
    int count = 0;
    for (std::int32_t k = 0; k < n.child_count && k < 4; ++k) {
      const std::int32_t id = n.first_child + k;
      const Node& kid = nodes[static_cast<std::size_t>(id)];
      // the kid's own children are what the descent loads next (depth first, the smaller bound
      // first): their cache lines are fetched while the kid's bound is computed (issue #27, Table
      // 3: the node loads were the largest single cost of a scarred row; no effect on any value)
      if (kid.child_count > 0) {
        const char* next = reinterpret_cast<const char*>(&nodes[static_cast<std::size_t>(kid.first_child)]);
        for (std::size_t b = 0; b < 2 * sizeof(Node); b += 64) __builtin_prefetch(next + b);
      }
      const double lb = node_lower_bound(ev.frame, kid, ev.best.distance);
      if (lb < ev.best.distance) kids[count++] = {id, lb};
    }
    for (int a = 1; a < count; ++a)  // descending lower bound: the smallest is popped first
      for (int c = a; c > 0 && kids[c - 1].lb < kids[c].lb; --c) std::swap(kids[c - 1], kids[c]);
    for (int k = 0; k < count && top < 1024; ++k) stack[top++] = kids[k];
  }
}

/// A leaf evaluated before the descent (its record, its entries, its smallest value).
struct Evaluated {
  std::int32_t record = -1;
  std::uint32_t entry = 0, count = 0;
  double value = kInf;
};

/// The same descent over a FacetStrips tree; the leaves already evaluated (`done`, from
/// StripEvaluator::leaf) are not again. `roots`: the bounds of the top, bottom and side roots
/// (node_lower_bound without a cut; the caller computes them while it waits for the first leaf's
/// record; -inf: not needed, see below).
void descend_strips(StripEvaluator& ev, const FacetStrips& fs, const std::array<Evaluated, 3>& done,
                    const std::array<double, 3>& roots) {
  const BoundTree& t = fs.tree;
  const std::vector<BoundNode>& nodes = t.nodes;
  struct Item {
    std::int32_t node;
    double lb;
  };
  Item stack[1024];
  int top = 0;
  // the side first (popped first), then the caps, each skipped when the side's best point shows it
  // cannot hold a lower value (cap_cannot_improve)
  stack[top++] = {t.top_root, roots[0]};
  stack[top++] = {t.bottom_root, roots[1]};
  stack[top++] = {t.side_root, roots[2]};
  // (issue #27) a node holding the best entry so far, or an entry evaluated first whose value ties
  // with it (an intact roller's minimum is on a vertex line, shared by two columns' strips: the
  // hinted one and its neighbour evaluated first, run()), is not pruned: its bound is at most that
  // entry's value, the best value (it bounds that entry's triangle from below). So its bound only
  // orders it against its sibling and is computed only when the sibling is not pruned (then the
  // order is the one by bounds, as before).
  // (the entries of `done` whose leaf value is at most the best value: refreshed when it changes)
  double tie_value = std::numeric_limits<double>::quiet_NaN();
  std::uint32_t ties[3] = {};
  int nties = 0;
  const auto holds = [&](const BoundNode& kid) {
    if (ev.best_entry - kid.tri_first < kid.tri_count) return true;
    for (int q = 0; q < nties; ++q)
      if (ties[q] - kid.tri_first < kid.tri_count) return true;
    return false;
  };
  while (top > 0) {
    const Item it = stack[--top];
    if (it.lb >= ev.best.distance) continue;
    if ((it.node == t.bottom_root || it.node == t.top_root) && ev.cap_cannot_improve(it.node == t.top_root)) continue;
    const BoundNode& n = nodes[static_cast<std::size_t>(it.node)];
    ++ev.best.nodes_visited;
    if (n.child_count == 0) {
      if (n.first_child != done[0].record && n.first_child != done[1].record && n.first_child != done[2].record)
        ev.leaf(fs.leaves[static_cast<std::size_t>(n.first_child)]);
      continue;
    }
    const int nk = std::min<std::int32_t>(n.child_count, 2);
    double lbs[2] = {kInf, kInf};
    bool keep[2] = {false, false}, holder[2] = {false, false};
    if (!(ev.best.distance == tie_value)) {
      tie_value = ev.best.distance, nties = 0;
      for (const Evaluated& e : done)
        if (e.record >= 0 && e.value <= tie_value) ties[nties++] = e.entry;
    }
    for (int k = 0; k < nk; ++k) {
      const BoundNode& kid = nodes[static_cast<std::size_t>(n.first_child + k)];
      if (kid.child_count > 0) {
        const char* next = reinterpret_cast<const char*>(&nodes[static_cast<std::size_t>(kid.first_child)]);
        for (std::size_t b = 0; b < 2 * sizeof(BoundNode); b += 64) __builtin_prefetch(next + b);
      } else {  // a leaf: its record (2 cache lines)
        const char* rec = reinterpret_cast<const char*>(&fs.leaves[static_cast<std::size_t>(kid.first_child)]);
        __builtin_prefetch(rec), __builtin_prefetch(rec + 64);
      }
      holder[k] = holds(kid);
    }
    // (a holder leaf was evaluated already: not again)
    for (int k = 0; k < nk; ++k) {
      if (holder[k]) continue;
      lbs[k] = node_lower_bound(ev.frame, nodes[static_cast<std::size_t>(n.first_child + k)], ev.best.distance);
      keep[k] = lbs[k] < ev.best.distance;
    }
    const auto inner = [&](int k) { return nodes[static_cast<std::size_t>(n.first_child + k)].child_count > 0; };
    for (int k = 0; k < nk; ++k) {
      if (!holder[k] || !inner(k)) continue;
      const bool sibling = nk == 2 && (keep[1 - k] || (holder[1 - k] && inner(1 - k)));
      lbs[k] = sibling ? node_lower_bound(ev.frame, nodes[static_cast<std::size_t>(n.first_child + k)], ev.best.distance)
                       : -kInf;
      keep[k] = lbs[k] < ev.best.distance;
    }
    Item kids[2];
    int count = 0;
    for (int k = 0; k < nk; ++k)
      if (keep[k]) kids[count++] = {n.first_child + k, lbs[k]};
    if (count == 2 && kids[0].lb < kids[1].lb) std::swap(kids[0], kids[1]);  // the smaller popped first
    for (int k = 0; k < count && top < 1024; ++k) stack[top++] = kids[k];
  }
}

}  // namespace

void set_facet_strips_for_testing(bool enabled) { g_facet_strips.store(enabled, std::memory_order_relaxed); }

namespace {
/// The side cell under a hint (body-frame angle and height): its first triangle, or kNone.
std::uint32_t hinted_cell(const Roller& roller, const Transform& pose, const Vec3& hint) {
  const Vec3 w = hint - pose.t;
  const double x = pose.r[0][0] * w.x + pose.r[1][0] * w.y + pose.r[2][0] * w.z;
  const double y = pose.r[0][1] * w.x + pose.r[1][1] * w.y + pose.r[2][1] * w.z;
  const double z = pose.r[0][2] * w.x + pose.r[1][2] * w.y + pose.r[2][2] * w.z;
  const int n = roller.n(), m = roller.m();
  const double u = wrap_pi(std::atan2(y, x)) / (2 * std::numbers::pi) * n;
  const double v = z / roller.params.height * m;
  if (!(std::isfinite(u) && std::isfinite(v))) return 0xffffffffu;
  const int i = std::clamp(static_cast<int>(u), 0, n - 1), j = std::clamp(static_cast<int>(v), 0, m - 1);
  return roller.side_triangle(i, j);
}
}  // namespace

MeshPairResult ScarredSolver::run(const Transform& pose, const Cylinder& b, const Vec3* hint) {
  // the tree of coplanar facet strips (quadtree.h, FacetStrips; issue #27): a planar run of intact
  // cells is one rectangle (two triangles), so a contact line along a generator, where the cells'
  // bounds tie, costs two triangle minima instead of one per cell. The value is the minimum over
  // the same point set (the runs are exactly the union of their cells); the first bounds come from
  // the leaves holding the previous frame's triangle and the hinted cell.
  if (!tree_->strips.empty() && g_facet_strips.load(std::memory_order_relaxed)) {
    const FacetStrips& fs = tree_->strips;
    // (issue #27: a scarred roller's tree is cold in a frame) the hinted cell's record index and
    // the roots are fetched while B's frame is set up
    const std::uint32_t h = hint ? hinted_cell(*roller_, pose, *hint) : kNone;
    const bool hinted = h != kNone && h < fs.leaf_record_of_triangle.size();
    if (hinted) __builtin_prefetch(&fs.leaf_record_of_triangle[h]);
    for (const std::int32_t root : {fs.tree.side_root, fs.tree.bottom_root, fs.tree.top_root}) {
      const char* at = reinterpret_cast<const char*>(&fs.tree.nodes[static_cast<std::size_t>(root)]);
      for (std::size_t k = 0; k < 3 * sizeof(BoundNode); k += 64) __builtin_prefetch(at + k);  // (and its children)
    }
    StripEvaluator ev{*roller_, fs, LocalFrame(pose, b), {}};
    ev.best.distance = kInf;
    ev.best.triangle = kNone;
    std::int32_t skip0 = -1, skip1 = -1;  // (records of the leaves evaluated first)
    if (previous_ != kNone && previous_ < fs.leaf_record_of_triangle.size()) skip0 = fs.leaf_record_of_triangle[previous_];
    if (hinted) skip1 = fs.leaf_record_of_triangle[h];
    if (skip1 == skip0) skip1 = -1;
    // the records of the hinted cell's neighbours in its row (the partner below is usually one)
    if (hinted) {
      const int n = roller_->n(), i = static_cast<int>((h / 2) % static_cast<std::uint32_t>(n));
      const std::uint32_t row = h - 2 * static_cast<std::uint32_t>(i);
      for (const int c : {i == 0 ? n - 1 : i - 1, i + 1 == n ? 0 : i + 1})
        if (const std::int32_t r = fs.leaf_record_of_triangle[row + 2 * static_cast<std::uint32_t>(c)]; r >= 0)
          __builtin_prefetch(&fs.leaves[static_cast<std::size_t>(r)]), __builtin_prefetch(reinterpret_cast<const char*>(&fs.leaves[static_cast<std::size_t>(r)]) + 64);
    }
    for (const std::int32_t r : {skip0, skip1})
      if (r >= 0) {
        const char* at = reinterpret_cast<const char*>(&fs.leaves[static_cast<std::size_t>(r)]);
        __builtin_prefetch(at), __builtin_prefetch(at + 64);
      }
    // the node pairs on the way down to the first leaf (the descent visits them first: the leaf
    // holds the best value so far), fetched together (FacetStrips::leaf_paths)
    if (const std::int32_t r = skip1 >= 0 ? skip1 : skip0; r >= 0 && static_cast<std::size_t>(r) < fs.leaf_paths.size())
      for (const std::uint16_t first : fs.leaf_paths[static_cast<std::size_t>(r)]) {
        if (first == 0xffff) break;
        const char* at = reinterpret_cast<const char*>(&fs.tree.nodes[first]);
        for (std::size_t k = 0; k < 2 * sizeof(BoundNode); k += 64) __builtin_prefetch(at + k);
      }
    const BoundNode& side = fs.tree.nodes[static_cast<std::size_t>(fs.tree.side_root)];
    std::array<double, 3> roots = {node_lower_bound(ev.frame, fs.tree.nodes[static_cast<std::size_t>(fs.tree.top_root)]),
                                   node_lower_bound(ev.frame, fs.tree.nodes[static_cast<std::size_t>(fs.tree.bottom_root)]),
                                   -kInf};
    std::array<Evaluated, 3> done;
    std::size_t k = 0;
    for (const std::int32_t r : {skip0, skip1})
      if (r >= 0) {
        const StripLeaf& rec = fs.leaves[static_cast<std::size_t>(r)];
        done[k++] = {r, rec.entry, rec.count, ev.leaf(rec)};
      }
    // the partner: the cell across the vertex line the best point lies on (StripEvaluator::partner)
    if (const std::uint32_t t = ev.partner(); t != kNone)
      if (const std::int32_t r = fs.leaf_record_of_triangle[t]; r >= 0 && r != skip0 && r != skip1) {
        const StripLeaf& rec = fs.leaves[static_cast<std::size_t>(r)];
        done[k++] = {r, rec.entry, rec.count, ev.leaf(rec)};
      }
    // the side root holding the best entry is not pruned (descend_strips): its bound is not needed
    if (!(ev.best_entry - side.tri_first < side.tri_count)) roots[2] = node_lower_bound(ev.frame, side);
    descend_strips(ev, fs, done, roots);
    MeshPairResult out = ev.finish(b);
    previous_ = out.triangle;
    return out;
  }
  Evaluator ev{*roller_, LocalFrame(pose, b), {}};
  ev.best.distance = kInf;
  ev.best.triangle = 0xffffffffu;
  if (previous_ != kNone) ev.triangle(previous_);  // temporal coherence: a tight first bound
  std::uint32_t hinted = kNone;
  if (hint) {  // the side cell under the hint (body-frame angle and height)
    const Vec3 w = *hint - pose.t;
    const double x = pose.r[0][0] * w.x + pose.r[1][0] * w.y + pose.r[2][0] * w.z;
    const double y = pose.r[0][1] * w.x + pose.r[1][1] * w.y + pose.r[2][1] * w.z;
    const double z = pose.r[0][2] * w.x + pose.r[1][2] * w.y + pose.r[2][2] * w.z;
    const int n = roller_->n(), m = roller_->m();
    const double u = wrap_pi(std::atan2(y, x)) / (2 * std::numbers::pi) * n;
    const double v = z / roller_->params.height * m;
    if (std::isfinite(u) && std::isfinite(v)) {
      const int i = std::clamp(static_cast<int>(u), 0, n - 1), j = std::clamp(static_cast<int>(v), 0, m - 1);
      hinted = roller_->side_triangle(i, j);
      if (hinted != previous_) ev.triangle(hinted);
      if (hinted + 1 != previous_) ev.triangle(hinted + 1);
    }
  }
  // the bound tree (quadtree.h: column-first, so a contact strip along a generator is reached
  // at one column's width near the top); a tree assembled by hand without one: the quadtree
  if (!tree_->bounds.empty()) {
    const BoundTree& t = tree_->bounds;
    descend(ev, t.nodes, {t.side_root, t.bottom_root, t.top_root}, previous_, hinted, kNone);
  } else {
    descend(ev, tree_->nodes, {tree_->side_root, tree_->bottom_root, tree_->top_root}, previous_, hinted, kNone);
  }
  previous_ = ev.best.triangle;
  return ev.finish(b);
}

namespace {
template <class Sd>
MeshPairResult vertex_min(const Roller& roller, const Transform& pose, const Cylinder& b, Sd&& sd) {
  MeshPairResult out;
  out.distance = kInf;
  for (std::uint32_t v = 0; v < roller.mesh.positions.size(); ++v) {
    const Vec3 p = pose.apply(roller.mesh.positions[v]);
    const double d = sd(b, p);
    ++out.evaluated;
    if (d < out.distance) out.distance = d, out.triangle = v, out.point_a = p;
  }
  out.point_b = nearest_on_cylinder_boundary(b, out.point_a);
  return out;
}
}  // namespace

MeshPairResult vertex_brute_force(const Roller& roller, const Transform& pose, const Cylinder& b) {
  return vertex_min(roller, pose, b, [](const Cylinder& c, const Vec3& p) { return point_signed_distance(c, p); });
}

MeshPairResult vertex_barbier_galin(const Roller& roller, const Transform& pose, const Cylinder& b) {
  return vertex_min(roller, pose, b,
                    [](const Cylinder& c, const Vec3& p) { return barbier_galin_signed_distance(c, p); });
}

double contact_direction_angle(const Transform& pose, const Cylinder& b, double /*height*/) {
  const Vec3 a0 = pose.t;  // the pivot: the nominal centre line starts there
  const Vec3 bc = b.center();
  const Vec3 foot = bc + b.axis * dot(a0 - bc, b.axis);
  const Vec3 w = foot - a0;
  // body coordinates (R^T w); the axial component is dropped (projection on the disk plane)
  const double x = pose.r[0][0] * w.x + pose.r[1][0] * w.y + pose.r[2][0] * w.z;
  const double y = pose.r[0][1] * w.x + pose.r[1][1] * w.y + pose.r[2][1] * w.z;
  return wrap_pi(std::atan2(y, x));
}

MeshPairResult vertex_quadtree_method(const Roller& roller, const RollerQuadtree& tree, const Transform& pose,
                                      const Cylinder& b, double window) {
  MeshPairResult out;
  out.distance = kInf;
  const auto eval = [&](const Vec3& body, std::uint32_t id) {
    const Vec3 p = pose.apply(body);
    const double d = barbier_galin_signed_distance(b, p);
    ++out.evaluated;
    if (d < out.distance) out.distance = d, out.triangle = id, out.point_a = p;
    return d;
  };
  const int n = roller.n();
  const double phi = contact_direction_angle(pose, b, roller.params.height);
  const double col = 2 * std::numbers::pi / n;
  const double lo = phi - window, hi = phi + window;  // in radians, may wrap
  const auto intersects = [&](const QuadNode& q) {
    const double a0 = q.i0 * col, a1 = q.i1 * col;  // node spans [a0, a1) (cells up to the next column)
    for (int k = -1; k <= 1; ++k) {
      const double s = k * 2 * std::numbers::pi;
      if (a0 + s <= hi + col && lo - col <= a1 + s) return true;
    }
    return false;
  };
  const std::int32_t layer = tree.calculation_layer(window, n);
  // collect the calculation layer's nodes in the window
  std::vector<std::int32_t> frontier{tree.side_root}, next;
  for (std::int32_t level = 0; level < layer; ++level) {
    next.clear();
    for (const std::int32_t id : frontier) {
      const QuadNode& q = tree.nodes[static_cast<std::size_t>(id)];
      if (q.child_count == 0) { next.push_back(id); continue; }
      for (std::int32_t k = 0; k < q.child_count; ++k)
        if (intersects(tree.nodes[static_cast<std::size_t>(q.first_child + k)])) next.push_back(q.first_child + k);
    }
    frontier.swap(next);
  }
  std::vector<std::int32_t> stack;
  for (const std::int32_t id : frontier) {
    const QuadNode& q = tree.nodes[static_cast<std::size_t>(id)];
    if (q.scar) {  // scarred nodes: every vertex
      stack.push_back(id);
      while (!stack.empty()) {
        const QuadNode& s = tree.nodes[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        if (s.child_count == 0) {
          eval(roller.mesh.positions[roller.side_vertex(s.i0, s.j0)], roller.side_vertex(s.i0, s.j0));
          continue;
        }
        for (std::int32_t k = 0; k < s.child_count; ++k) stack.push_back(s.first_child + k);
      }
      continue;
    }
    // intact nodes: greedy descent along the smallest virtual vertex
    std::int32_t cur = id;
    while (tree.nodes[static_cast<std::size_t>(cur)].child_count > 0) {
      const QuadNode& s = tree.nodes[static_cast<std::size_t>(cur)];
      double best = kInf;
      std::int32_t pick = s.first_child;
      for (std::int32_t k = 0; k < s.child_count; ++k) {
        const QuadNode& c = tree.nodes[static_cast<std::size_t>(s.first_child + k)];
        const double d = c.child_count == 0
                             ? eval(roller.mesh.positions[roller.side_vertex(c.i0, c.j0)], roller.side_vertex(c.i0, c.j0))
                             : barbier_galin_signed_distance(b, pose.apply(c.virtual_vertex));
        if (d < best) best = d, pick = s.first_child + k;
      }
      cur = pick;
    }
    const QuadNode& leaf = tree.nodes[static_cast<std::size_t>(cur)];
    eval(roller.mesh.positions[roller.side_vertex(leaf.i0, leaf.j0)], roller.side_vertex(leaf.i0, leaf.j0));
  }
  out.point_b = nearest_on_cylinder_boundary(b, out.point_a);
  return out;
}

}  // namespace interfere::bearing
