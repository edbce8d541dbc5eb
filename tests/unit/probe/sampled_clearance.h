// Independent clearance oracle for the probe tests (issue #23, item 14): dense samples of a body's
// surface against the triangles by reference::point_triangle_distance (unit/reference_distance.h:
// plane projection with edge-side tests, else the nearest edge), sharing nothing with the probe's
// cylinder/box-triangle distance code it checks. (np::closest_point_on_triangle, Ericson's
// Voronoi-region walk, is not used: the cylinder distance (probe/cylinder_distance.cpp) and the
// box-holder distance (box_triangle_distance -> triangle_triangle_closest) both call it.)
//
// Error bound: the distance between a solid body and a triangle outside it is attained at a
// boundary point p*; the samples lie on grids of the surface whose cells have sides at most a and
// b, so some sample s is within h of p* (h = half the cell diagonal on flat faces, the full
// diagonal on the cylinder's caps, see sample_cylinder):
//   true <= sampled <= true + h.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "interfere/mesh/tri_mesh.h"
#include "interfere/probe/box.h"
#include "interfere/probe/cylinder.h"
#include "unit/reference_distance.h"

namespace interfere::probe::oracle {

struct Sampled {
  std::vector<Vec3> points;
  double h = 0;  ///< covering radius (see above)
};

/// Samples of the solid cylinder's surface (side and both caps) with spacing <= `step`.
inline Sampled sample_cylinder(const Cylinder& c, double step) {
  Sampled s;
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const Vec3 u = d / len;
  Vec3 e1 = cross(u, std::fabs(u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
  e1 = e1 / norm(e1);
  const Vec3 e2 = cross(u, e1);
  const int rings = std::max(1, static_cast<int>(std::ceil(len / step)));
  const int around = std::max(8, static_cast<int>(std::ceil(2 * M_PI * c.radius / step)));
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * M_PI * j / around;
      s.points.push_back(c.c0 + d * (double(i) / rings) + e1 * (c.radius * std::cos(phi)) +
                         e2 * (c.radius * std::sin(phi)));
    }
  }
  const int radial = std::max(1, static_cast<int>(std::ceil(c.radius / step)));
  for (const Vec3& centre : {c.c0, c.c1}) {
    for (int k = 0; k <= radial; ++k) {
      const double rr = c.radius * k / radial;
      const int m = std::max(1, static_cast<int>(std::ceil(2 * M_PI * rr / step)));
      for (int j = 0; j < m; ++j) {
        const double phi = 2 * M_PI * j / m;
        s.points.push_back(centre + e1 * (rr * std::cos(phi)) + e2 * (rr * std::sin(phi)));
      }
    }
  }
  // Cells: side len/rings x arc 2 pi r/around (half-diagonal on the unrolled side); caps: rings
  // r/radial apart with arcs <= step, where the nearest ring's sample is within
  // sqrt((a/2)^2 + 1.5 (b/2)^2); hypot(a, b) covers both with room.
  const double a = std::max(len / rings, c.radius / radial), b = step;
  s.h = std::hypot(a, b);
  return s;
}

/// Samples of the oriented box's six faces (from its frame) with spacing <= `step`.
inline Sampled sample_box(const OrientedBox& box, double step) {
  Sampled s;
  double a = 0;
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    const int nu = std::max(1, static_cast<int>(std::ceil(2 * box.half[u] / step)));
    const int nv = std::max(1, static_cast<int>(std::ceil(2 * box.half[v] / step)));
    a = std::max({a, 2 * box.half[u] / nu, 2 * box.half[v] / nv});
    for (const double side : {-1.0, 1.0}) {
      for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nv; ++j) {
          s.points.push_back(box.centre + box.axes[k] * (side * box.half[k]) +
                             box.axes[u] * (box.half[u] * (2.0 * i / nu - 1)) +
                             box.axes[v] * (box.half[v] * (2.0 * j / nv - 1)));
        }
      }
    }
  }
  s.h = 0.5 * std::hypot(a, a);
  return s;
}

/// Smallest sample-to-triangle distance over the triangles whose boxes are within `reach` of the
/// samples' box (farther triangles cannot be nearer than `reach`).
inline double sampled_distance(const Sampled& s, const TriMesh& mesh, double reach) {
  Aabb box;
  for (const Vec3& p : s.points) box.expand(p);
  double best = INFINITY;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Aabb tb = mesh.triangle_box(t);
    double gap2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double g = std::max({0.0, tb.lo[k] - box.hi[k], box.lo[k] - tb.hi[k]});
      gap2 += g * g;
    }
    if (std::sqrt(gap2) > reach) continue;
    const auto tri = mesh.corners(t);
    for (const Vec3& p : s.points)
      best = std::min(best, reference::point_triangle_distance(p, tri));
  }
  return best;
}

}  // namespace interfere::probe::oracle
