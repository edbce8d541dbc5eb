// The probe primitive: a solid finite cylinder, and its exact intersection test and distance to a
// triangle (issue #5, item 3c). Li, Zhou & Zheng (J. Image and Graphics 13(11), 2008, §3.4) decide
// cylinder/triangle contact by three orthographic projections; that test is not complete (see
// three_projection_test below, paper_tests.h and docs/probe.md), ours is exact in every configuration.
#pragma once
#include <array>
#include <limits>

#include "interfere/core/aabb.h"
#include "interfere/core/vec.h"

namespace interfere::probe {

/// Solid closed cylinder: the points whose projection on the line c0c1 lies on the segment [c0, c1]
/// and whose distance to that line is <= radius. c0, c1 and radius are the exact doubles stored here:
/// every decision below is exact for this cylinder (docs/probe.md, "exact to rounding"). The probe's
/// tip end circle is centred at c0. Precondition of every function below: c0 != c1 (a probe of
/// positive length; the CLI and the Python bindings reject non-positive sizes).
struct Cylinder {
  Vec3 c0;
  Vec3 c1;
  double radius = 0;
};

/// The cylinder with end-circle centre `tip`, going back from it against the unit `axis` (the
/// direction the probe points) over `length`: c0 = tip, c1 = tip - length * axis (rounded once).
inline Cylinder cylinder_from_tip(const Vec3& tip, const Vec3& axis, double length, double radius) {
  return {tip, tip - axis * length, radius};
}

/// Exact: is `p` in the closed solid cylinder.
bool point_in_cylinder(const Cylinder& c, const Vec3& p);

/// Exact: do the closed solid cylinder and the closed triangle `t` share a point. Degenerate
/// triangles (segments, points) are handled. The decision is a Boolean combination of signs of
/// polynomials in the input doubles (degree <= 10), each evaluated with a certified double filter
/// and, when that cannot decide, in exact expansion arithmetic.
bool cylinder_triangle_intersect(const Cylinder& c, const std::array<Vec3, 3>& t);

/// Polynomial signs that the double filter could not decide and exact arithmetic did (diagnostics).
unsigned long long cylinder_exact_fallbacks();

struct CylinderTriangleDistance {
  double distance = 0;  ///< 0 exactly when cylinder_triangle_intersect is true
  Vec3 on_cylinder;     ///< closest point on the cylinder (construction, double)
  Vec3 on_triangle;     ///< closest point on the triangle
  bool intersecting = false;
};

/// Euclidean distance between the solid cylinder and the triangle. Intersection is decided exactly
/// first (distance 0); otherwise the distance is the minimum over candidates that are each attained
/// by a point of the triangle (the plane-support candidate of the triangle's interior and a convex
/// 1D minimisation along each edge), so it is never below the true distance by more than rounding
/// and never above it by more than 1e-9 times the edge length (docs/probe.md).
/// With `upper_bound` finite, candidates whose lower bound is >= upper_bound are skipped: the result
/// is exact as above when the distance is < upper_bound, and some value >= upper_bound otherwise
/// (a best-first search passes its current best).
CylinderTriangleDistance cylinder_triangle_distance(const Cylinder& c, const std::array<Vec3, 3>& t,
                                                    double upper_bound = std::numeric_limits<double>::infinity());

/// Distance from a point to the solid cylinder (0 inside), in double; `closest` receives the
/// closest point of the cylinder when not null.
double point_cylinder_distance(const Cylinder& c, const Vec3& p, Vec3* closest = nullptr);

/// Lower bound (exact to rounding) of the distance from the cylinder to the segment [p, q]: the
/// distance between [p, q] and the axis segment minus the radius (the cylinder lies inside that
/// capsule).
double segment_cylinder_lower_bound(const Cylinder& c, const Vec3& p, const Vec3& q);

/// Conservative axis-aligned box of the cylinder (contains it; rounded outward by a relative 1e-12).
Aabb cylinder_box(const Cylinder& c);

/// The cylinder grown by `delta` >= 0 radially and axially at both ends: it contains every point
/// within `delta` of `c` (Minkowski sum with a ball), with the rounding of its construction
/// covered by a relative margin of 1e-12.
Cylinder grown(const Cylinder& c, double delta);

/// The project's earlier reconstruction (issue #5, NOT the paper's §3.4): the triangle and the
/// cylinder are declared to intersect when their orthographic projections overlap on the three
/// planes of the probe frame (the plane normal to the axis: disk vs triangle; two planes containing
/// the axis: rectangle vs triangle). Necessary but NOT sufficient (test_cylinder_triangle.cpp,
/// FrameProjectionIsIncomplete). Double precision; kept for comparison only.
bool frame_projection_test(const Cylinder& c, const std::array<Vec3, 3>& t);

/// The paper's test as written (Li, Zhou & Zheng 2008, §3.4): overlap of the projections along the
/// cylinder axis, along the triangle edge t[edge] -> t[edge + 1] and along a diameter of the end
/// circle (paper_tests.h, paper_projections, for each projection's outcome and the choice of
/// diameter). Never misses a contact, reports false contacts (test_paper_tests.cpp). Double
/// precision; an option beside the exact test, never the default.
bool three_projection_test(const Cylinder& c, const std::array<Vec3, 3>& t, int edge = 0);

}  // namespace interfere::probe
