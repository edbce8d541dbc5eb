// The project's earlier reconstruction of the paper's projection test (issue #5, before the paper's
// text was available; NOT the paper's §3.4, which is paper_projections in three_projection.cpp and
// projects along the axis, a triangle edge and a diameter): the probe cylinder and a triangle are
// declared to intersect when their orthographic projections overlap on the three coordinate planes
// of the probe frame: on the plane normal to the axis the cylinder projects to a
// disk, on the two planes containing the axis to a rectangle. Projections of intersecting sets
// always overlap, so the test never misses a contact; but three directions are not a complete set
// of separating axes for a cylinder and a triangle (a plane oblique to all three can separate
// them), so it reports false contacts. Kept for comparison (double precision).
#include <algorithm>
#include <cmath>

#include "interfere/probe/cylinder.h"

namespace interfere::probe {
namespace {

struct P2 {
  double x, y;
};

double cross2(const P2& a, const P2& b, const P2& c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

/// Distance from the origin to the segment [a, b] in 2D.
double origin_segment_distance(const P2& a, const P2& b) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double ee = ex * ex + ey * ey;
  double s = ee > 0 ? -(a.x * ex + a.y * ey) / ee : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return std::hypot(a.x + s * ex, a.y + s * ey);
}

bool triangle_disk(const P2 t[3], double r) {
  const P2 o{0, 0};
  const double a = cross2(t[0], t[1], o), b = cross2(t[1], t[2], o), c = cross2(t[2], t[0], o);
  if ((a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0)) return true;
  for (int i = 0; i < 3; ++i) {
    if (origin_segment_distance(t[i], t[(i + 1) % 3]) <= r) return true;
  }
  return false;
}

/// Triangle vs axis-aligned rectangle [xlo, xhi] x [ylo, yhi]: 2D separating axes.
bool triangle_rectangle(const P2 t[3], double xlo, double xhi, double ylo, double yhi) {
  const double minx = std::min({t[0].x, t[1].x, t[2].x}), maxx = std::max({t[0].x, t[1].x, t[2].x});
  const double miny = std::min({t[0].y, t[1].y, t[2].y}), maxy = std::max({t[0].y, t[1].y, t[2].y});
  if (maxx < xlo || minx > xhi || maxy < ylo || miny > yhi) return false;
  const P2 corners[4] = {{xlo, ylo}, {xhi, ylo}, {xhi, yhi}, {xlo, yhi}};
  for (int i = 0; i < 3; ++i) {
    const P2& a = t[i];
    const P2& b = t[(i + 1) % 3];
    const double nx = -(b.y - a.y), ny = b.x - a.x;  // edge normal
    const double tri_other = nx * (t[(i + 2) % 3].x - a.x) + ny * (t[(i + 2) % 3].y - a.y);
    double lo = 1e300, hi = -1e300;
    for (const P2& q : corners) {
      const double v = nx * (q.x - a.x) + ny * (q.y - a.y);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (tri_other > 0 && hi < 0) return false;
    if (tri_other < 0 && lo > 0) return false;
  }
  return true;
}

}  // namespace

bool frame_projection_test(const Cylinder& c, const std::array<Vec3, 3>& t) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const Vec3 u = d / len;
  const Vec3 helper = std::fabs(u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 e1 = cross(u, helper);
  e1 = e1 / norm(e1);
  const Vec3 e2 = cross(u, e1);
  P2 xy[3], xz[3], yz[3];
  for (int i = 0; i < 3; ++i) {
    const Vec3 w = t[i] - c.c0;
    const double x = dot(w, e1), y = dot(w, e2), z = dot(w, u);
    xy[i] = {x, y}, xz[i] = {x, z}, yz[i] = {y, z};
  }
  return triangle_disk(xy, c.radius) && triangle_rectangle(xz, -c.radius, c.radius, 0, len) &&
         triangle_rectangle(yz, -c.radius, c.radius, 0, len);
}

}  // namespace interfere::probe
