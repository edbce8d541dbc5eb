// Exact oriented-box / triangle test and distance for the box-shaped probe holder (issue #5, item 2).
// The solid is the convex hull of the 8 corner doubles, bounded by 12 triangles chosen convex
// (see box.h); contact = boundary contact (exact triangle-triangle test, Guigue & Devillers 2003
// structure in np/tri_tri.h) or containment of a vertex (exact orient3d, Shewchuk 1997). Sound
// double filters (separating-axis test on the box axes, Gottschalk, Lin & Manocha, "OBBTree", 1996)
// reject most far triangles first. Distance: Ericson, Real-Time Collision Detection §5.1.
#include <algorithm>
#include <cmath>

#include "interfere/core/predicates.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"
#include "interfere/probe/box.h"

namespace interfere::probe {
namespace {

/// Faces of a right-handed frame as quads (corner bit k = sign along axes[k]), counter-clockwise
/// seen from outside: +x, -x, +y, -y, +z, -z.
constexpr std::uint8_t kQuads[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                                       {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};

double coordinate_scale(const OrientedBox& b) {
  double s = 0;
  for (const Vec3& c : b.corners) s = std::max({s, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  return std::max({s, b.half[0], b.half[1], b.half[2]});
}

/// Separation of the triangle from the box along the box axes (double): the largest gap between the
/// projections, <= the Euclidean distance (projections on a unit vector are 1-Lipschitz).
double axis_separation(const OrientedBox& b, const std::array<Vec3, 3>& t) {
  double gap = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : t) {
      const double s = dot(v - b.centre, b.axes[k]);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    gap = std::max({gap, lo - b.half[k], -b.half[k] - hi});
  }
  return gap;
}

}  // namespace

OrientedBox make_box(const Vec3& centre, const std::array<Vec3, 3>& axes, const std::array<double, 3>& half) {
  OrientedBox b;
  b.centre = centre;
  b.axes = axes;
  b.half = half;
  const Vec3 e[3] = {axes[0] * half[0], axes[1] * half[1], axes[2] * half[2]};
  for (int i = 0; i < 8; ++i) {
    b.corners[i] = centre + ((i & 1) ? e[0] : -e[0]) + ((i & 2) ? e[1] : -e[1]) + ((i & 4) ? e[2] : -e[2]);
  }
  const bool right_handed = dot(cross(axes[0], axes[1]), axes[2]) > 0;
  for (int f = 0; f < 6; ++f) {
    std::uint8_t q[4] = {kQuads[f][0], kQuads[f][1], kQuads[f][2], kQuads[f][3]};
    if (!right_handed) std::swap(q[1], q[3]);  // a mirrored frame reverses every face's turn
    const Vec3 &a = b.corners[q[0]], &bb = b.corners[q[1]], &c = b.corners[q[2]], &d = b.corners[q[3]];
    // Rounding bends the quad slightly. With diagonal ac the surface is convex iff d is not above
    // the plane of the counter-clockwise abc (orient3d >= 0: below or on); otherwise diagonal bd
    // is (then c is below abd, orient3d(a,b,d,c) = -orient3d(a,b,c,d) > 0).
    if (orient3d(a, bb, c, d) >= 0) {
      b.faces[2 * f] = {q[0], q[1], q[2]};
      b.faces[2 * f + 1] = {q[0], q[2], q[3]};
    } else {
      b.faces[2 * f] = {q[0], q[1], q[3]};
      b.faces[2 * f + 1] = {q[1], q[2], q[3]};
    }
  }
  return b;
}

OrientedBox holder_box(const Vec3& back_centre, const Vec3& axis, const Vec3& ref, double width, double depth,
                       double length) {
  return make_box(back_centre - axis * (0.5 * length), {ref, cross(axis, ref), axis},
                  {0.5 * width, 0.5 * depth, 0.5 * length});
}

bool point_in_box(const OrientedBox& b, const Vec3& p) {
  // A convex polyhedron is the intersection of the closed half-spaces below its faces.
  for (int f = 0; f < 12; ++f) {
    const auto& i = b.faces[f];
    if (orient3d(b.corners[i[0]], b.corners[i[1]], b.corners[i[2]], p) < 0) return false;
  }
  return true;
}

bool box_triangle_intersect(const OrientedBox& b, const std::array<Vec3, 3>& t) {
  // Filter 1 (double, sound): separated along a box axis by more than a margin that covers the
  // rounding of the corners (a few ulps of the scale) and of the projections.
  const double scale =
      std::max({coordinate_scale(b), std::fabs(t[0].x), std::fabs(t[0].y), std::fabs(t[0].z), std::fabs(t[1].x),
                std::fabs(t[1].y), std::fabs(t[1].z), std::fabs(t[2].x), std::fabs(t[2].y), std::fabs(t[2].z)});
  if (axis_separation(b, t) > 1e-9 * scale) return false;
  // Filter 2 (exact): every corner strictly on one side of the triangle's plane.
  int above = 0, below = 0;
  for (const Vec3& c : b.corners) {
    const int s = orient3d(t[0], t[1], t[2], c);
    above += s<0, below += s> 0;
  }
  if (above == 8 || below == 8) return false;
  // Exact decision.
  if (point_in_box(b, t[0])) return true;
  for (int f = 0; f < 12; ++f) {
    if (tri_tri_exact_intersects(b.face(f), t)) return true;
  }
  return false;
}

BoxTriangleDistance box_triangle_distance(const OrientedBox& b, const std::array<Vec3, 3>& t, double upper_bound) {
  BoxTriangleDistance r;
  if (std::isfinite(upper_bound)) {
    const double scale = std::max({coordinate_scale(b), norm(t[0]), norm(t[1]), norm(t[2])});
    const double lower = axis_separation(b, t) - 1e-9 * scale;  // margin: rounding of corners, projections
    if (lower >= upper_bound) {
      r.distance = lower;
      return r;
    }
  }
  r.intersecting = box_triangle_intersect(b, t);
  if (r.intersecting && point_in_box(b, t[0])) {
    r.on_box = r.on_triangle = t[0];
    return r;
  }
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < 12; ++f) {
    const ClosestPoints c = triangle_triangle_closest(b.face(f), t);
    if (c.distance < best) best = c.distance, r.on_box = c.p, r.on_triangle = c.q;
  }
  r.distance = r.intersecting ? 0.0 : best;
  return r;
}

Aabb box_aabb(const OrientedBox& b) {
  Aabb a;
  for (const Vec3& c : b.corners) a.expand(c);
  const double pad = 1e-12 * coordinate_scale(b);
  a.lo = a.lo - Vec3{pad, pad, pad};
  a.hi = a.hi + Vec3{pad, pad, pad};
  return a;
}

Cylinder bounding_cylinder(const OrientedBox& b) {
  const double g = 1e-12 * coordinate_scale(b);
  const Vec3 u = b.axes[2] * (b.half[2] + g);
  return {b.centre + u, b.centre - u, std::hypot(b.half[0], b.half[1]) + g};
}

OrientedBox grown(const OrientedBox& b, double delta) {
  const double g = delta * (1 + 1e-12) + 1e-12 * coordinate_scale(b);
  return make_box(b.centre, b.axes, {b.half[0] + g, b.half[1] + g, b.half[2] + g});
}

}  // namespace interfere::probe
