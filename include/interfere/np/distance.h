// Closest points between primitives, in double (constructions; not decisions).
#pragma once
#include <array>

#include "interfere/core/vec.h"

namespace interfere {

struct ClosestPoints {
  double distance = 0;  ///< Euclidean distance between p and q
  Vec3 p;               ///< on the first primitive
  Vec3 q;               ///< on the second primitive
};

/// Closest point on triangle t to point p (Ericson, Real-Time Collision Detection, §5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const std::array<Vec3, 3>& t);

/// Closest points of segments [p0,p1], [q0,q1] (Ericson §5.1.9), robust for parallel/degenerate.
ClosestPoints segment_segment_closest(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                      const Vec3& q1);

/// Closest points between two triangles: minimum over the 6 vertex–triangle and 9 edge–edge
/// candidates. Distance 0 when they intersect (callers decide intersection exactly beforehand).
ClosestPoints triangle_triangle_closest(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

}  // namespace interfere
