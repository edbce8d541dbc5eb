// The box-shaped probe holder (issue #5, item 2: "a holder cylinder/box behind the probe"): a solid
// oriented box, its exact intersection test and distance to a triangle (docs/probe.md, "Box holder").
//
// The solid decided exactly is the convex hull of the box's 8 corner doubles. The corners are
// computed once from the frame (rounded); their 6 faces are then, in general, not exactly planar
// quadrilaterals, so each face is split along the diagonal that keeps the surface convex (one exact
// orient3d per face). The 12 triangles then bound the convex hull, and
//   T meets the box  <=>  T meets one of the 12 boundary triangles (np/tri_tri.h, exact)
//                         or a vertex of T lies inside (exact orient3d against the 12 face planes):
// T is connected, so if it misses the boundary it lies wholly inside or wholly outside.
#pragma once
#include <array>
#include <cstdint>
#include <limits>

#include "interfere/core/aabb.h"
#include "interfere/core/vec.h"
#include "interfere/probe/cylinder.h"

namespace interfere::probe {

/// Solid oriented box: centre, orthonormal axes and half extents (the construction), and the exact
/// solid: the convex hull of `corners`. Corner i = centre + sum_k (bit k of i ? +1 : -1) half[k]
/// axes[k]. `faces` are the 12 boundary triangles (corner indices), counter-clockwise seen from
/// outside. Build it with make_box (or holder_box); precondition of every function below: half
/// extents > 0 and not below ~1e-9 of the coordinates (so rounding cannot fold the corners).
struct OrientedBox {
  Vec3 centre;
  std::array<Vec3, 3> axes{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  std::array<double, 3> half{};
  std::array<Vec3, 8> corners{};
  std::array<std::array<std::uint8_t, 3>, 12> faces{};
  std::array<Vec3, 3> face(int f) const { return {corners[faces[f][0]], corners[faces[f][1]], corners[faces[f][2]]}; }
};

/// Box from its frame: `axes` orthonormal to rounding (right- or left-handed), `half` > 0. Computes
/// the corners (rounded once per coordinate) and the convex split of each face.
OrientedBox make_box(const Vec3& centre, const std::array<Vec3, 3>& axes, const std::array<double, 3>& half);

/// The holder box behind the probe: its front face centred at `back_centre` (the probe's back
/// end-circle centre c1 = tip - length * axis), extending `length` further along -axis; `width`
/// along the unit reference direction `ref` (perpendicular to the unit `axis`) and `depth` along
/// axis x ref. axes = {ref, axis x ref, axis} (right-handed), so axes[2] points to the tip.
OrientedBox holder_box(const Vec3& back_centre, const Vec3& axis, const Vec3& ref, double width, double depth,
                       double length);

/// Exact: is `p` in the closed solid box (the convex hull of the corners).
bool point_in_box(const OrientedBox& b, const Vec3& p);

/// Exact: do the closed solid box and the closed triangle `t` share a point. Degenerate triangles
/// (segments, points) are handled. Decisions are orient3d signs and tri_tri_exact_intersects, both
/// exact on the input doubles (the corners and the triangle's vertices).
bool box_triangle_intersect(const OrientedBox& b, const std::array<Vec3, 3>& t);

struct BoxTriangleDistance {
  double distance = 0;  ///< 0 exactly when box_triangle_intersect is true
  Vec3 on_box;          ///< closest point on the box (construction, double)
  Vec3 on_triangle;     ///< closest point on the triangle
  bool intersecting = false;
};

/// Euclidean distance between the solid box and the triangle. Intersection is decided exactly first
/// (distance 0; witnesses: t[0] for both when it is inside, else the closest pair of a boundary
/// triangle and t, ~0 apart). Otherwise the box is convex and T lies outside it, so the distance is
/// attained on the boundary: the minimum over the 12 boundary triangles of the triangle-triangle
/// distance (np/distance.h, Ericson's 6 vertex-triangle + 9 edge-edge candidates), with its witness
/// points. With `upper_bound` finite, a lower bound (the separation along the box axes) >=
/// upper_bound returns that lower bound without witnesses (a best-first search passes its best).
BoxTriangleDistance box_triangle_distance(const OrientedBox& b, const std::array<Vec3, 3>& t,
                                          double upper_bound = std::numeric_limits<double>::infinity());

/// Conservative axis-aligned box of the corners (rounded outward by a relative 1e-12).
Aabb box_aabb(const OrientedBox& b);

/// A cylinder around axes[2] containing the box (radius = half-diagonal of the cross-section, with
/// a relative margin of 1e-12 covering the rounding of the corners): for the BVH cull and the
/// distance field, which are written for cylinders.
Cylinder bounding_cylinder(const OrientedBox& b);

/// The box with every half extent grown by `delta` >= 0 (plus a relative 1e-12 for rounding): it
/// contains every point within `delta` of `b`.
OrientedBox grown(const OrientedBox& b, double delta);

}  // namespace interfere::probe
