// An independent reference for triangle distances, for tests whose subject uses np/distance.h
// (issue #23, item 14: an oracle must not share the code it checks). Different method from
// np/distance.h (Ericson's Voronoi-region walk): the distance between two disjoint triangles is the
// smallest of the 6 vertex-triangle and 9 edge-edge distances (the minimum of a convex function over
// a pair of triangles is reached with one point at a vertex of its triangle or both on edges);
// vertex-triangle by projection onto the plane and three edge-side tests, else the nearest edge;
// edge-edge
// by the stationary point of the 2x2 normal equations when it lies inside both segments, else the
// four endpoint-to-segment distances (the boundary of the parameter square).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "interfere/core/vec.h"

namespace interfere::reference {

inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + ab * t));
}

inline double point_triangle_distance(const Vec3& p, const std::array<Vec3, 3>& t) {
  const double edges = std::min({point_segment_distance(p, t[0], t[1]), point_segment_distance(p, t[1], t[2]),
                                 point_segment_distance(p, t[2], t[0])});
  // The plane from the longest edge e and the third corner's offset orthogonal to it (its width w):
  // accurate for any triangle wider than 1e-11 of its length. A thinner one is taken as its edges
  // (an error below its width).
  int k = 0;
  double longest = -1;
  for (int i = 0; i < 3; ++i) {
    const double l2 = dot(t[(i + 1) % 3] - t[i], t[(i + 1) % 3] - t[i]);
    if (l2 > longest) longest = l2, k = i;
  }
  const Vec3 a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
  const Vec3 e = b - a, f = c - a;
  if (longest == 0) return edges;
  const Vec3 w = f - e * (dot(f, e) / longest);
  if (norm(w) <= 1e-11 * std::sqrt(longest)) return edges;
  const Vec3 n = cross(e, w) / norm(cross(e, w));
  const double h = dot(p - a, n);
  const Vec3 x = p - n * h;  // p projected onto the plane
  const bool inside =
      dot(cross(b - a, x - a), n) >= 0 && dot(cross(c - b, x - b), n) >= 0 && dot(cross(a - c, x - c), n) >= 0;
  return inside ? std::min(std::fabs(h), edges) : edges;
}

inline double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  double best = std::min({point_segment_distance(p0, q0, q1), point_segment_distance(p1, q0, q1),
                          point_segment_distance(q0, p0, p1), point_segment_distance(q1, p0, p1)});
  const Vec3 u = p1 - p0, v = q1 - q0, w = p0 - q0;
  const double a = dot(u, u), b = dot(u, v), c = dot(v, v), d = dot(u, w), e = dot(v, w);
  const double den = a * c - b * b;
  if (den > 1e-14 * a * c) {  // not (nearly) parallel: the interior stationary point
    const double s = (b * e - c * d) / den, t = (a * e - b * d) / den;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = std::min(best, norm((p0 + u * s) - (q0 + v * t)));
  }
  return best;
}

/// Distance between two triangles that do not intersect.
inline double triangle_triangle_distance(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  double best = INFINITY;
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, point_triangle_distance(a[i], b));
    best = std::min(best, point_triangle_distance(b[i], a));
    for (int j = 0; j < 3; ++j)
      best = std::min(best, segment_segment_distance(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
  }
  return best;
}

}  // namespace interfere::reference
