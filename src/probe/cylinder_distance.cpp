// Cylinder-triangle distance (issue #5, item 3c). Intersection is decided exactly first
// (cylinder_triangle.cpp). Otherwise dist(T, C) = min over p in T of f(p) = dist(p, C), a convex
// function: its minimum over the triangle is attained either in T's interior, where the gradient
// (p - q)/|p - q| is normal to T, so the plane of T separates and touches C at a support point q
// (the plane-support candidate), or on an edge, where f restricted to the edge is convex in the
// edge parameter (golden-section search, 64 steps: the parameter is pinned to 0.618^64 ~ 4e-14 of
// the edge, and f is 1-Lipschitz, so the value is within 4e-14 edge lengths of the edge minimum).
// Every candidate is attained by an actual point of T, hence the minimum is never below the true
// distance (beyond rounding) and one candidate is the true distance.
#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/np/distance.h"
#include "interfere/probe/cylinder.h"

namespace interfere::probe {

double point_cylinder_distance(const Cylinder& c, const Vec3& p, Vec3* closest) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const Vec3 w = p - c.c0;
  if (!(len > 0)) {  // a flat disk of zero thickness has no axis: treat it as the point c0 grown
    const double dist = std::max(0.0, norm(w) - c.radius);
    if (closest) *closest = norm(w) > c.radius ? c.c0 + w * (c.radius / norm(w)) : p;
    return dist;
  }
  const Vec3 u = d / len;
  const double z = dot(w, u);
  const Vec3 radial = w - u * z;
  const double rho = norm(radial);
  const double dz = z < 0 ? -z : (z > len ? z - len : 0.0);
  const double dr = rho > c.radius ? rho - c.radius : 0.0;
  if (closest) {
    const double zc = std::clamp(z, 0.0, len);
    const Vec3 rc = rho > c.radius ? radial * (c.radius / rho) : radial;
    *closest = c.c0 + u * zc + rc;
  }
  return std::sqrt(dz * dz + dr * dr);
}

double segment_cylinder_lower_bound(const Cylinder& c, const Vec3& p, const Vec3& q) {
  return segment_segment_closest(p, q, c.c0, c.c1).distance - c.radius;
}

namespace {

/// Axial lower bound: distance from the points' hull to the slab between the cap planes (0 when
/// the points are not all beyond the same cap plane). Any point of the hull is at least that far
/// from the cylinder, which lies inside the slab.
template <std::size_t N>
double slab_lower_bound(const Cylinder& c, const std::array<Vec3, N>& pts) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  if (!(len > 0)) return 0;
  const Vec3 u = d / len;
  double below = std::numeric_limits<double>::infinity(), above = below;
  for (const Vec3& p : pts) {
    const double z = dot(p - c.c0, u);
    below = std::min(below, -z);
    above = std::min(above, z - len);
  }
  // Relative slack for the rounding of u and the dot products.
  const double bound = std::max({below, above, 0.0});
  return bound > 0 ? bound * (1 - 1e-12) - 1e-12 * len : 0.0;
}

/// Minimum of dist(p + t (q - p), C) over t in [0, 1] (convex): golden-section search. f is
/// |q - p|-Lipschitz in t and its minimum stays inside the bracket [a, b], whose points are within
/// (1 - phi)(b - a) of a sample x1 or x2, so the minimum is >= min(f1, f2) - |q - p| (1 - phi)(b - a):
/// once that bound reaches `limit` (the caller's best) the edge cannot win and the search stops
/// early, returning a value >= limit.
double edge_distance(const Cylinder& c, const Vec3& p, const Vec3& q, Vec3& best_point,
                     double limit = std::numeric_limits<double>::infinity()) {
  const Vec3 e = q - p;
  const double lip = norm(e);
  auto f = [&](double t) { return point_cylinder_distance(c, p + e * t); };
  constexpr double kPhi = 0.6180339887498949;
  double a = 0, b = 1;
  const double fa = f(0.0), fb = f(1.0);
  double x1 = b - kPhi * (b - a), x2 = a + kPhi * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 64; ++i) {
    const double smallest = std::min(f1, f2);
    if (smallest - lip * (1 - kPhi) * (b - a) >= limit) return smallest;
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kPhi * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kPhi * (b - a), f2 = f(x2);
    }
  }
  double best_t = f1 <= f2 ? x1 : x2, best = std::min(f1, f2);
  if (fa < best) best = fa, best_t = 0;
  if (fb < best) best = fb, best_t = 1;
  best_point = p + e * best_t;
  return best;
}

}  // namespace

CylinderTriangleDistance cylinder_triangle_distance(const Cylinder& c, const std::array<Vec3, 3>& t,
                                                    double upper_bound) {
  CylinderTriangleDistance r;
  if (std::isfinite(upper_bound) && slab_lower_bound(c, t) >= upper_bound) {
    r.distance = upper_bound;  // cannot beat the caller's best
    return r;
  }
  if (cylinder_triangle_intersect(c, t)) {
    r.intersecting = true;
    r.distance = 0;
    // A witness: the triangle point nearest the cylinder in double (distance ~0).
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      Vec3 pt;
      const double v = edge_distance(c, t[i], t[(i + 1) % 3], pt);
      if (v < best) best = v, r.on_triangle = pt;
    }
    const Vec3 axis_mid = (c.c0 + c.c1) * 0.5;
    const Vec3 cp = closest_point_on_triangle(axis_mid, t);
    if (point_cylinder_distance(c, cp) <= best) r.on_triangle = cp;
    point_cylinder_distance(c, r.on_triangle, &r.on_cylinder);
    return r;
  }
  double best = std::numeric_limits<double>::infinity();
  // Plane-support candidate (interior minimum).
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nn = norm(n);
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  if (nn > 0 && len > 0) {
    const Vec3 nh = n / nn, u = d / len;
    const double h0 = dot(nh, c.c0 - t[0]), h1 = dot(nh, c.c1 - t[0]);
    const Vec3 wv = nh - u * dot(nh, u);
    const double wn = norm(wv);
    const Vec3 wh = wn > 0 ? wv / wn : Vec3{};
    const double ext = c.radius * wn;
    for (int side : {1, -1}) {
      const double gap = side > 0 ? std::min(h0, h1) - ext : -(std::max(h0, h1) + ext);
      if (!(gap > 0)) continue;
      const bool first = side > 0 ? h0 <= h1 : h0 >= h1;
      const Vec3 q = (first ? c.c0 : c.c1) - wh * (side * c.radius);
      const Vec3 p = q - nh * dot(nh, q - t[0]);
      // Inside T (barycentric signs in double: an outside verdict only drops a candidate that the
      // edge search then finds, an inside verdict on the boundary is harmless).
      bool inside = true;
      for (int i = 0; i < 3 && inside; ++i) inside = dot(cross(t[(i + 1) % 3] - t[i], p - t[i]), n) >= 0;
      if (inside && gap < best) best = gap, r.on_triangle = p, r.on_cylinder = q;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const Vec3& p = t[i];
    const Vec3& q = t[(i + 1) % 3];
    const double limit = std::min(best, upper_bound);
    if (slab_lower_bound(c, std::array<Vec3, 2>{p, q}) >= limit) continue;
    if (segment_cylinder_lower_bound(c, p, q) >= limit) continue;
    Vec3 pt;
    const double v = edge_distance(c, p, q, pt, limit);
    if (v < best && v < limit) {
      best = v;
      r.on_triangle = pt;
      point_cylinder_distance(c, pt, &r.on_cylinder);
    }
  }
  if (!std::isfinite(best)) {  // every candidate pruned by upper_bound
    r.distance = upper_bound;
    return r;
  }
  // Never report 0 for a pair the exact test separates.
  r.distance = best > 0 ? best : std::numeric_limits<double>::denorm_min();
  return r;
}

}  // namespace interfere::probe
