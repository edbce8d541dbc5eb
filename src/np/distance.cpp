// Closest points between points, segments and triangles, in double (constructions, not decisions).
//  - closest_point_on_triangle: Ericson, Real-Time Collision Detection (2005), §5.1.5: Voronoi
//    regions of the corners and edges via barycentric dot products, else the face projection.
//    Slivers, needles and degenerate triangles (where those region tests are rounding noise: 4·area²
//    below 1e-8 of the longest edge to the fourth) take the nearest of the edge projections and the
//    interior plane projection instead (found by fuzzing: needles with two nearly equal corners).
//  - segment_segment_closest: Ericson §5.1.9: minimise |P(s) - Q(t)|^2 on [0,1]^2 by solving for s,
//    clamping, recomputing t and re-clamping s. Degenerate segments (points) and parallel segments
//    (a*e - b^2 <= 0, where the minimiser is not unique) are handled by the published branches.
//  - triangle_triangle_closest: for non-intersecting triangles the minimum is attained at a corner
//    of one triangle against the other, or between two edges (Ericson §5.1, "closest points of two
//    triangles"): 6 + 9 candidates.
#include "interfere/np/distance.h"

#include <algorithm>
#include <cmath>

namespace interfere {

ClosestPoints segment_segment_closest(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                      const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) {
    s = t = 0;
  } else if (a <= 0) {
    s = 0;
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 0) {
      t = 0;
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2);
      const double denom = a * e - b * b;  // >= 0 exactly; rounding may make it <= 0 when parallel
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  ClosestPoints out;
  out.p = p0 + d1 * s;
  out.q = q0 + d2 * t;
  out.distance = distance(out.p, out.q);
  return out;
}

namespace {

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double den = dot(ab, ab);
  if (!(den > 0)) return a;
  return a + ab * std::clamp(dot(p - a, ab) / den, 0.0, 1.0);
}

/// Shape-independent variant for slivers and degenerate triangles, where the region tests of
/// §5.1.5 lose their accuracy (they difference products of nearly parallel edge vectors): the
/// nearest of the three edge projections and, when it falls inside, the plane projection.
Vec3 closest_point_on_sliver(const Vec3& p, const std::array<Vec3, 3>& t) {
  Vec3 best = closest_point_on_segment(p, t[0], t[1]);
  double best_d = squared_norm(p - best);
  for (int i = 1; i < 3; ++i) {
    const Vec3 c = closest_point_on_segment(p, t[i], t[(i + 1) % 3]);
    const double d = squared_norm(p - c);
    if (d < best_d) best = c, best_d = d;
  }
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nn = dot(n, n);
  if (nn > 0) {
    const Vec3 q = p - n * (dot(n, p - t[0]) / nn);
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i)
      inside = dot(n, cross(t[(i + 1) % 3] - t[i], q - t[i])) >= 0;
    if (inside && squared_norm(p - q) < best_d) best = q;
  }
  return best;
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const std::array<Vec3, 3>& t) {
  const Vec3& a = t[0];
  const Vec3& b = t[1];
  const Vec3& c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;  // vertex region A (exact criterion for any shape)
  // Slivers and needles (area small against the longest edge squared, i.e. a small angle at ANY
  // corner, or two nearly coincident corners) and degenerate triangles: see above.
  const double l2 = std::max({squared_norm(ab), squared_norm(ac), squared_norm(c - b)});
  if (squared_norm(cross(ab, ac)) <= 1e-8 * l2 * l2) return closest_point_on_sliver(p, t);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;  // vertex region B
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return a + ab * (d1 / (d1 - d3));  // edge AB
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;  // vertex region C
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return a + ac * (d2 / (d2 - d6));  // edge AC
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));  // edge BC
  const double sum = va + vb + vc;  // face region; > 0 unless rounding ate a tiny triangle
  if (!(sum > 0)) return closest_point_on_sliver(p, t);
  const Vec3 q = a + ab * (vb / sum) + ac * (vc / sum);
  return is_finite(q) ? q : closest_point_on_sliver(p, t);
}

ClosestPoints triangle_triangle_closest(const std::array<Vec3, 3>& a,
                                        const std::array<Vec3, 3>& b) {
  ClosestPoints best;
  best.distance = INFINITY;
  auto consider = [&](const Vec3& p, const Vec3& q) {
    const double d = distance(p, q);
    if (d < best.distance) best = {d, p, q};
  };
  for (int i = 0; i < 3; ++i) {
    consider(a[i], closest_point_on_triangle(a[i], b));
    consider(closest_point_on_triangle(b[i], a), b[i]);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const ClosestPoints c = segment_segment_closest(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
      if (c.distance < best.distance) best = c;
    }
  return best;
}

}  // namespace interfere
