// Exact geometric predicates on double input (Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", Discrete Comput. Geom. 18, 1997): a
// floating-point filter with a certified error bound, and an exact expansion-arithmetic fallback.
// The sign is always the sign of the exact determinant of the (exact) double inputs.
//
// The filters live here, inline, so that the common case costs a handful of flops at the call site;
// only the exact fallback is out of line (src/core/predicates.cpp). The bounds are Shewchuk's
// "errbound A" (§4.3 and the published orient2d/orient3d): |det - fl(det)| <= c * eps * permanent
// with eps = 2^-53, valid in round-to-nearest without extended precision. The library is built with
// -ffp-contract=off; a caller that lets the compiler fuse a*b+c into an FMA keeps a valid bound,
// because a fused operation only removes one rounding error from the sum that the bound covers.
//
// A zero permanent (every term of the determinant has an exactly zero factor, as for points on an
// axis-aligned plane) is an exact zero and needs no fallback: a rounded difference is zero only
// when the coordinates are equal, and a rounded product only when a factor is zero.
//
// Precondition: every coordinate is in the supported range of interfere/core/coordinate_range.h
// (0, or 2^-250 <= |x| <= 2^100). Then every nonzero intermediate of the filters and of the
// expansions lies between 2^-959 and 2^306 in magnitude: no overflow, no underflow, so the error
// bounds and the exactness above hold (the reasoning is in coordinate_range.h). Inputs outside it
// can give wrong signs (products overflow to inf, or round to zero); the readers reject them.
#pragma once
#include <cmath>

#include "interfere/core/vec.h"

namespace interfere {

namespace detail {
inline constexpr double kPredEps = 0x1p-53;  // half an ulp of 1: the unit roundoff
/// Shewchuk's o3derrboundA and ccwerrboundA.
inline constexpr double kOrient3dErrA = (7.0 + 56.0 * kPredEps) * kPredEps;
inline constexpr double kOrient2dErrA = (3.0 + 16.0 * kPredEps) * kPredEps;

/// Exact signs (expansion arithmetic); each call counts one fallback. Same conventions as below.
int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy);
/// The exact determinants, their expansions summed in double (relative error a few 2^-53; the
/// sign is exact). Each call counts one fallback as well.
double orient3d_exact_value(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
double orient2d_exact_value(double ax, double ay, double bx, double by, double cx, double cy);
/// A filtered value is accepted by the *_value functions when its error bound is below this
/// fraction of its magnitude.
inline constexpr double kValueRelTol = 0x1p-40;

/// det[b-a, c-a, d-a] in double and its permanent (the sum of the magnitudes of its terms) for the
/// static filter: |det| > kOrient3dErrA * permanent certifies the sign. Expanded along the last
/// row, w . (u x v): the same structure (three rounded differences per row, 2x2 minors times an
/// entry) as Shewchuk's expansion, so the same bound holds.
struct Orient3dFilter {
  double det, permanent;
};
inline Orient3dFilter orient3d_filter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
  const double uyvz = uy * vz, uzvy = uz * vy;
  const double uzvx = uz * vx, uxvz = ux * vz;
  const double uxvy = ux * vy, uyvx = uy * vx;
  const double det = wx * (uyvz - uzvy) + wy * (uzvx - uxvz) + wz * (uxvy - uyvx);
  const double permanent = (std::fabs(uyvz) + std::fabs(uzvy)) * std::fabs(wx) +
                           (std::fabs(uzvx) + std::fabs(uxvz)) * std::fabs(wy) +
                           (std::fabs(uxvy) + std::fabs(uyvx)) * std::fabs(wz);
  return {det, permanent};
}
}  // namespace detail

/// Sign (-1, 0, +1) of det[a-d, b-d, c-d] = -det[b-a, c-a, d-a] (Shewchuk's orient3d): +1 when d
/// lies on the side of the plane (a,b,c) that the normal (b-a)x(c-a) points away from, i.e.
/// orient3d(a,b,c,d) > 0 iff d is BELOW the counter-clockwise triangle abc (positive when a,b,c
/// appear clockwise seen from d). Note: CGAL::orientation(a,b,c,d) is the opposite sign.
inline int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto [det, permanent] = detail::orient3d_filter(a, b, c, d);
  // One rarely taken branch; the sign itself is computed without branching (random signs would
  // otherwise mispredict).
  if (!(std::fabs(det) > detail::kOrient3dErrA * permanent)) [[unlikely]] {
    if (permanent == 0) return 0;  // every term has an exactly zero factor (e.g. an axis plane)
    return detail::orient3d_exact(a, b, c, d);
  }
  return (det < 0) - (det > 0);
}

/// Sign of det[b-a, c-a] in 2D: +1 when a,b,c are counter-clockwise.
inline int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (ax - cx) * (by - cy);
  const double right = (ay - cy) * (bx - cx);
  const double det = left - right;
  const double sum = std::fabs(left) + std::fabs(right);
  if (!(std::fabs(det) > detail::kOrient2dErrA * sum)) [[unlikely]] {
    if (sum == 0) return 0;  // both products have an exactly zero factor
    return detail::orient2d_exact(ax, ay, bx, by, cx, cy);
  }
  return (det > 0) - (det < 0);
}

/// The value of orient3d's determinant det[a-d, b-d, c-d], for constructions (e.g. where an edge
/// crosses a plane): relative error at most 2^-40 (the filtered double value when its certified
/// bound allows, else the exact expansion rounded), and its sign is always orient3d's. Differences
/// of such values keep their accuracy where the plain double determinant is all rounding noise
/// (nearly coplanar input).
inline double orient3d_value(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto [det, permanent] = detail::orient3d_filter(a, b, c, d);
  if (detail::kOrient3dErrA * permanent <= detail::kValueRelTol * std::fabs(det)) return -det;
  return detail::orient3d_exact_value(a, b, c, d);
}

/// The value of orient2d's determinant det[b-a, c-a] with the accuracy of orient3d_value.
inline double orient2d_value(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (ax - cx) * (by - cy);
  const double right = (ay - cy) * (bx - cx);
  const double det = left - right;
  const double bound = detail::kOrient2dErrA * (std::fabs(left) + std::fabs(right));
  if (bound <= detail::kValueRelTol * std::fabs(det)) return det;
  return detail::orient2d_exact_value(ax, ay, bx, by, cx, cy);
}

/// Orientation of a,b,c projected on the coordinate plane that drops axis `drop` (0,1,2), with the
/// remaining axes in cyclic order ((y,z), (z,x), (x,y)). For any triangle this equals the sign of
/// component `drop` of its normal (b-a)x(c-a).
inline int orient2d_projected(const Vec3& a, const Vec3& b, const Vec3& c, int drop) {
  const int i = drop == 0 ? 1 : (drop == 1 ? 2 : 0);
  const int j = drop == 0 ? 2 : (drop == 1 ? 0 : 1);
  return orient2d(a[i], a[j], b[i], b[j], c[i], c[j]);
}

/// True when a, b, c are collinear (exact): all three projected orientations vanish.
inline bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  return orient2d_projected(a, b, c, 2) == 0 && orient2d_projected(a, b, c, 0) == 0 &&
         orient2d_projected(a, b, c, 1) == 0;
}

/// orient3d of many points d against one fixed plane (a,b,c): the cross product and the permanent's
/// per-axis terms are computed once (the filter is orient3d's, with the same rounding steps, so the
/// result is identical: side(d) == orient3d(a,b,c,d) for every d). Keeps references to a, b, c:
/// they must outlive the object.
class Orient3dPlane {
 public:
  Orient3dPlane(const Vec3& a, const Vec3& b, const Vec3& c) : a_(&a), b_(&b), c_(&c) {
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double uyvz = uy * vz, uzvy = uz * vy;
    const double uzvx = uz * vx, uxvz = ux * vz;
    const double uxvy = ux * vy, uyvx = uy * vx;
    n_ = {uyvz - uzvy, uzvx - uxvz, uxvy - uyvx};
    p_ = {std::fabs(uyvz) + std::fabs(uzvy), std::fabs(uzvx) + std::fabs(uxvz),
          std::fabs(uxvy) + std::fabs(uyvx)};
    // kOrient3dErrA folded in: one rounding here replaces the final one of orient3d's bound.
    k_ = p_ * detail::kOrient3dErrA;
  }

  /// orient3d(a, b, c, d).
  int side(const Vec3& d) const {
    const double wx = d.x - a_->x, wy = d.y - a_->y, wz = d.z - a_->z;
    const double det = wx * n_.x + wy * n_.y + wz * n_.z;
    const double bound = k_.x * std::fabs(wx) + k_.y * std::fabs(wy) + k_.z * std::fabs(wz);
    if (!(std::fabs(det) > bound)) [[unlikely]] {
      if (bound == 0) return 0;  // zero permanent: exact zero (see the top of this file)
      return detail::orient3d_exact(*a_, *b_, *c_, d);
    }
    return (det < 0) - (det > 0);
  }

  /// orient3d_value(a, b, c, d): the determinant's value, relative error at most 2^-40.
  double value(const Vec3& d) const {
    const double wx = d.x - a_->x, wy = d.y - a_->y, wz = d.z - a_->z;
    const double det = wx * n_.x + wy * n_.y + wz * n_.z;
    const double bound = k_.x * std::fabs(wx) + k_.y * std::fabs(wy) + k_.z * std::fabs(wz);
    if (bound <= detail::kValueRelTol * std::fabs(det)) return -det;
    return detail::orient3d_exact_value(*a_, *b_, *c_, d);
  }

  /// True when some component of the normal is certified nonzero by the orient2d filter, which
  /// proves that a, b, c are not collinear. False means "not certified" (use collinear()).
  bool certainly_nondegenerate() const {
    const double k = detail::kOrient2dErrA;
    return std::fabs(n_.x) > k * p_.x || std::fabs(n_.y) > k * p_.y || std::fabs(n_.z) > k * p_.z;
  }

  /// The normal (b-a)x(c-a) rounded to double (a hint only, e.g. to pick a projection axis).
  const Vec3& normal() const { return n_; }

 private:
  const Vec3* a_;
  const Vec3* b_;
  const Vec3* c_;
  Vec3 n_;  // (b-a)x(c-a) in double
  Vec3 p_;  // per-axis permanent terms |u_j v_k| + |u_k v_j|
  Vec3 k_;  // p_ * kOrient3dErrA
};

/// Count of exact fallbacks taken since program start, by the sign and the value functions (for
/// benchmarks/diagnostics; relaxed atomic).
unsigned long long exact_fallback_count();

}  // namespace interfere
