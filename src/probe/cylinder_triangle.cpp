// Exact solid-cylinder / triangle intersection (issue #5, item 3c). The paper (Li, Zhou & Zheng
// 2008, §3.3) projects both shapes on three planes; that is not a complete separating test. Here
// T ∩ C ≠ ∅ is decided as the disjunction of three sound and jointly complete conditions
// (docs/probe.md, "The exact cylinder-triangle test"), with C the solid cylinder of axis segment
// [c0, c1], d = c1 - c0, radius r, and Q(p) = |(p - c0) × d|^2 the squared distance to the axis
// line times |d|^2:
//  (A) the axis segment meets T (orient3d, exact);
//  (B) an edge of T meets C: an endpoint in C, or (edge parallel to d) the constant radial distance
//      is <= r over an overlapping axial range, or the edge crosses a cap plane inside the cap disk,
//      or the edge's point nearest the axis line (minimum of the convex quadratic Q along it) lies
//      on the edge, inside the slab and within r;
//  (C) a cap disk meets T in T's interior: the point of the line T ∩ cap plane nearest the cap
//      centre is inside T and within r of it.
// Completeness: if T ∩ C ≠ ∅ but (A) and (B) fail, the minimum of Q over T ∩ slab is attained on a
// cap-plane section of T (interior minima need the axis to pierce T inside the slab, which is (A);
// on T's edges (B) would hold), and there (C) holds. Every quantity is a polynomial in the input
// doubles (degree <= 10): signs come from exact_poly.h (double filter, exact expansion fallback).
#include <algorithm>
#include <atomic>
#include <cmath>

#include "exact_poly.h"
#include "interfere/core/predicates.h"
#include "interfere/np/distance.h"
#include "interfere/probe/cylinder.h"

namespace interfere::probe {
namespace {

using detail::Expansion;
using detail::Filtered;
using detail::V3;

template <class N>
V3<N> mk(const Vec3& p) {
  return {N(p.x), N(p.y), N(p.z)};
}

/// Sign of the polynomial `poly` (a generic lambda taking a number type): filtered, then exact.
std::atomic<unsigned long long> g_fallbacks{0};

template <class P>
int sign_of(const P& poly) {
  const int s = poly.template operator()<Filtered>().sign();
  if (s != 2) return s;
  g_fallbacks.fetch_add(1, std::memory_order_relaxed);
  return poly.template operator()<Expansion>().sign();
}

/// s_k(p) = (p - c_k) · d.
int slab_sign(const Cylinder& c, const Vec3& ck, const Vec3& p) {
  return sign_of([&]<class N>() {
    const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
    return detail::dot(mk<N>(p) - mk<N>(ck), d);
  });
}

/// r^2 |d|^2 - |(p - c0) × d|^2 >= 0 iff p is within r of the axis line.
int radial_sign(const Cylinder& c, const Vec3& p) {
  return sign_of([&]<class N>() {
    const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
    const V3<N> w = detail::cross(mk<N>(p) - mk<N>(c.c0), d);
    const N r(c.radius);
    return r * r * detail::dot(d, d) - detail::dot(w, w);
  });
}

bool point_inside(const Cylinder& c, const Vec3& p) {
  return slab_sign(c, c.c0, p) >= 0 && slab_sign(c, c.c1, p) <= 0 && radial_sign(c, p) >= 0;
}

/// (e × d) == 0 exactly (edge parallel to the axis, or a zero-length edge).
bool parallel_to_axis(const Cylinder& c, const Vec3& p, const Vec3& q) {
  for (int k = 0; k < 3; ++k) {
    const int s = sign_of([&]<class N>() {
      const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
      const V3<N> e = mk<N>(q) - mk<N>(p);
      const V3<N> x = detail::cross(e, d);
      return k == 0 ? x.x : (k == 1 ? x.y : x.z);
    });
    if (s != 0) return false;
  }
  return true;
}

/// Double filter for (B): the edge is farther than r from the axis segment (C lies in that
/// capsule) by a margin of 1e-9 x the coordinate scale, >= 10^6 times the rounding error of the
/// closest-point computation (np/distance.h, Ericson §5.1.9).
bool edge_clearly_missed(const Cylinder& c, const Vec3& p, const Vec3& q) {
  const double scale = std::max({norm(p - c.c0), norm(q - c.c0), norm(c.c1 - c.c0), c.radius});
  return segment_segment_closest(p, q, c.c0, c.c1).distance > c.radius + 1e-9 * scale;
}

/// (B) for the segment [p, q] (endpoints already known to be outside C).
bool edge_meets(const Cylinder& c, const Vec3& p, const Vec3& q) {
  if (edge_clearly_missed(c, p, q)) return false;
  const int p0 = slab_sign(c, c.c0, p), q0 = slab_sign(c, c.c0, q);
  const int p1 = slab_sign(c, c.c1, p), q1 = slab_sign(c, c.c1, q);
  if ((p0 < 0 && q0 < 0) || (p1 > 0 && q1 > 0)) return false;  // both beyond the same cap plane
  if (parallel_to_axis(c, p, q)) return radial_sign(c, p) >= 0;
  // Crossing a cap plane strictly: the crossing point inside the cap disk?
  for (int k = 0; k < 2; ++k) {
    const int sp = k == 0 ? p0 : p1, sq = k == 0 ? q0 : q1;
    if (sp * sq >= 0) continue;
    const Vec3& ck = k == 0 ? c.c0 : c.c1;
    const int s = sign_of([&]<class N>() {
      const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
      const V3<N> P = mk<N>(p), Q = mk<N>(q), Ck = mk<N>(ck);
      const N vp = detail::dot(P - Ck, d), vq = detail::dot(Q - Ck, d);
      const N den = vp - vq;
      const V3<N> W = detail::cross(P - mk<N>(c.c0), d);
      const V3<N> E = detail::cross(Q - P, d);
      const V3<N> G = detail::scale(den, W) + detail::scale(vp, E);
      const N r(c.radius);
      return r * r * detail::dot(d, d) * den * den - detail::dot(G, G);
    });
    if (s >= 0) return true;
  }
  // Point of the edge nearest the axis line: t* = -(W·E)/|E|^2 in [0, 1], inside the slab, within r.
  auto poly = [&](int which) {
    return sign_of([&]<class N>() {
      const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
      const V3<N> P = mk<N>(p), Q = mk<N>(q);
      const V3<N> e = Q - P;
      const V3<N> W = detail::cross(P - mk<N>(c.c0), d);
      const V3<N> E = detail::cross(e, d);
      const N EE = detail::dot(E, E), WE = detail::dot(W, E);
      switch (which) {
        case 0: return -WE;                                       // t* >= 0
        case 1: return EE + WE;                                   // t* <= 1
        case 2: {                                                 // axial >= 0
          const N s0 = detail::dot(P - mk<N>(c.c0), d);
          return s0 * EE - WE * detail::dot(e, d);
        }
        case 3: {                                                 // axial <= |d|^2
          const N s0 = detail::dot(P - mk<N>(c.c0), d);
          return detail::dot(d, d) * EE - (s0 * EE - WE * detail::dot(e, d));
        }
        default: {                                                // within r
          const N r(c.radius);
          return r * r * detail::dot(d, d) * EE - (EE * detail::dot(W, W) - WE * WE);
        }
      }
    });
  };
  for (int which = 0; which < 5; ++which) {
    if (poly(which) < 0) return false;
  }
  return true;
}

/// Sound double filter for (C): the in-plane distance from the cap centre to the line T ∩ cap
/// plane, |n·(v0 - ck)| / |n × d/|d||, clearly exceeds r. The margins (1e-12 |e1||e2| ...) are
/// ~10^3 times the rounding bounds of n (componentwise 2u|e1||e2|), of the dot and cross products.
/// Well conditioned where the exact polynomials are not (T nearly parallel to the cap).
bool cap_clearly_missed(const Cylinder& c, const Vec3& ck, const std::array<Vec3, 3>& t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 n = cross(e1, e2);
  const Vec3 d = c.c1 - c.c0;
  const double dl = norm(d);
  if (!(dl > 0)) return false;
  const double s = norm(cross(n, d / dl));
  const double ee = norm(e1) * norm(e2);
  const double a = std::fabs(dot(n, t[0] - ck));
  const double err_a = 1e-12 * ee * norm(t[0] - ck), err_s = 1e-12 * ee;
  return a - err_a > c.radius * (s + err_s) * (1 + 1e-12);
}

/// (C) for cap k: the point of T ∩ cap plane nearest the cap centre is in T and within r.
bool cap_meets_interior(const Cylinder& c, const Vec3& ck, const std::array<Vec3, 3>& t) {
  if (cap_clearly_missed(c, ck, t)) return false;
  // n × d == 0: T parallel to the cap plane (or degenerate); then (C) adds nothing to (A), (B).
  bool parallel = true;
  for (int k = 0; k < 3 && parallel; ++k) {
    parallel = sign_of([&]<class N>() {
                 const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
                 const V3<N> V0 = mk<N>(t[0]);
                 const V3<N> n = detail::cross(mk<N>(t[1]) - V0, mk<N>(t[2]) - V0);
                 const V3<N> x = detail::cross(n, d);
                 return k == 0 ? x.x : (k == 1 ? x.y : x.z);
               }) == 0;
  }
  if (parallel) return false;
  // With w = n × d: m = d × w = |d|^2 n - (n·d) d is the in-plane direction normal to the line
  // L = T ∩ cap plane, n·m = |w|^2, |m|^2 = |d|^2 |w|^2, and the nearest point of L to ck is
  // q = ck + (a / |w|^2) m with a = n·(v0 - ck). Written with cross products and sums of squares
  // (no |n|^2|d|^2 - (n·d)^2 cancellation), so the filter stays sharp when T is nearly parallel
  // to the cap, the usual situation of a probe held normal to the surface.
  auto poly = [&](int which) {
    return sign_of([&]<class N>() {
      const V3<N> d = mk<N>(c.c1) - mk<N>(c.c0);
      const V3<N> V0 = mk<N>(t[0]);
      const V3<N> n = detail::cross(mk<N>(t[1]) - V0, mk<N>(t[2]) - V0);
      const V3<N> w = detail::cross(n, d);
      const V3<N> Ck = mk<N>(ck);
      const N a = detail::dot(n, V0 - Ck);
      const N ww = detail::dot(w, w);
      if (which == 3) {  // |q - ck| <= r  <=>  a^2 |d|^2 <= r^2 |w|^2
        const N r(c.radius);
        return r * r * ww - a * a * detail::dot(d, d);
      }
      const V3<N> m = detail::cross(d, w);
      const V3<N> Vi = mk<N>(t[which]), Vj = mk<N>(t[(which + 1) % 3]);
      const V3<N> qi = detail::scale(ww, Ck - Vi) + detail::scale(a, m);  // |w|^2 (q - Vi)
      return detail::dot(detail::cross(Vj - Vi, qi), n);
    });
  };
  for (int which : {3, 0, 1, 2}) {
    if (poly(which) < 0) return false;
  }
  return true;
}

/// (A): the axis segment [c0, c1] meets T (non-coplanar case; coplanar contact is (B) or (C)).
bool axis_meets(const Cylinder& c, const std::array<Vec3, 3>& t) {
  const int o0 = orient3d(t[0], t[1], t[2], c.c0);
  const int o1 = orient3d(t[0], t[1], t[2], c.c1);
  if (o0 == o1) return false;  // both strictly on one side, or both in the plane
  if (o0 * o1 > 0) return false;
  const int a = orient3d(c.c0, c.c1, t[0], t[1]);
  const int b = orient3d(c.c0, c.c1, t[1], t[2]);
  const int e = orient3d(c.c0, c.c1, t[2], t[0]);
  return (a >= 0 && b >= 0 && e >= 0) || (a <= 0 && b <= 0 && e <= 0);
}

/// Sound double-precision rejection: the cylinder lies strictly on one side of T's plane, with a
/// margin far above the rounding of n (which, for slivers, is relative to |e1||e2|, not |n|).
bool plane_separates(const Cylinder& c, const std::array<Vec3, 3>& t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 n = cross(e1, e2);
  const Vec3 d = c.c1 - c.c0;
  const double dn = norm(d);
  if (!(dn > 0)) return false;
  const double h0 = dot(n, c.c0 - t[0]), h1 = dot(n, c.c1 - t[0]);
  const double ext = c.radius * norm(cross(n, d)) / dn;
  const double scale = norm(e1) * norm(e2) * (norm(c.c0 - t[0]) + norm(c.c1 - t[0]) + c.radius);
  const double margin = 1e-10 * scale;
  return std::min(h0, h1) - ext > margin || std::max(h0, h1) + ext < -margin;
}

}  // namespace

bool point_in_cylinder(const Cylinder& c, const Vec3& p) { return point_inside(c, p); }

unsigned long long cylinder_exact_fallbacks() { return g_fallbacks.load(std::memory_order_relaxed); }

bool cylinder_triangle_intersect(const Cylinder& c, const std::array<Vec3, 3>& t) {
  // Exact slab rejection: every vertex strictly beyond the same cap plane.
  int below = 0, above = 0;
  int s0[3], s1[3];
  for (int i = 0; i < 3; ++i) {
    s0[i] = slab_sign(c, c.c0, t[i]);
    s1[i] = slab_sign(c, c.c1, t[i]);
    below += s0[i] < 0;
    above += s1[i] > 0;
  }
  if (below == 3 || above == 3) return false;
  if (plane_separates(c, t)) return false;
  for (int i = 0; i < 3; ++i) {
    if (s0[i] >= 0 && s1[i] <= 0 && radial_sign(c, t[i]) >= 0) return true;  // vertex in C
  }
  if (axis_meets(c, t)) return true;
  for (int i = 0; i < 3; ++i) {
    if (edge_meets(c, t[i], t[(i + 1) % 3])) return true;
  }
  return cap_meets_interior(c, c.c0, t) || cap_meets_interior(c, c.c1, t);
}

Aabb cylinder_box(const Cylinder& c) {
  const Vec3 d = c.c1 - c.c0;
  const double dd = dot(d, d);
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    // Disk extent along axis k: r * sqrt(1 - (d_k/|d|)^2).
    const double s = dd > 0 ? std::sqrt(std::max(0.0, 1.0 - d[k] * d[k] / dd)) : 1.0;
    const double e = c.radius * std::min(1.0, s * (1 + 1e-12) + 1e-12);
    const double lo = std::min(c.c0[k], c.c1[k]) - e, hi = std::max(c.c0[k], c.c1[k]) + e;
    const double pad = 1e-12 * (std::fabs(lo) + std::fabs(hi) + c.radius);
    b.lo[k] = lo - pad;
    b.hi[k] = hi + pad;
  }
  return b;
}

Cylinder grown(const Cylinder& c, double delta) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const double scale = std::max({std::fabs(c.c0.x), std::fabs(c.c0.y), std::fabs(c.c0.z), std::fabs(c.c1.x),
                                 std::fabs(c.c1.y), std::fabs(c.c1.z), c.radius, len});
  const double g = delta * (1 + 1e-12) + 1e-12 * scale;
  if (!(len > 0)) return {c.c0, c.c1, c.radius + g};
  const Vec3 u = d / len;
  return {c.c0 - u * g, c.c1 + u * g, c.radius + g};
}

}  // namespace interfere::probe
