// Möller, "A Fast Triangle-Triangle Intersection Test", JGT 2(2):25–30, 1997, in double (NOT
// robust). Kept as the paper's baseline strategy. Steps as published:
//  1. plane of B; signed distances of A's corners; reject if all strictly on one side (and vice
//  versa);
//  2. the intersection line L = plane(A) ∩ plane(B), direction D = N1 x N2; corners are projected
//  on
//     L by keeping only the coordinate where |D| is largest (the paper's simplification);
//  3. each triangle's interval on L from the corner alone on its side, by interpolating the
//     projections with the signed distances (t = p0 + (p1-p0) d0/(d0-d1));
//  4. the intervals overlap iff the triangles intersect;
//  coplanar case (all distances zero): project on the axis plane maximizing the normal's area, test
//  every edge pair (Franklin Antonio's segment test, Graphics Gems III) and one corner of each
//  triangle inside the other.
// The paper's optional absolute epsilon snapping of distances (EPSILON = 1e-6) is not applied: an
// absolute threshold depends on the model's unit; distances are compared with zero.
#include <algorithm>
#include <cmath>
#include <utility>

#include "interfere/np/tri_tri.h"

namespace interfere {
namespace {

using Tri = std::array<Vec3, 3>;

/// Antonio's 2D segment test: edge (v0,v1) against edge (u0,u1) on axes (i0,i1).
bool edge_edge_2d(const Vec3& v0, const Vec3& v1, const Vec3& u0, const Vec3& u1, int i0, int i1) {
  const double ax = v1[i0] - v0[i0], ay = v1[i1] - v0[i1];
  const double bx = u0[i0] - u1[i0], by = u0[i1] - u1[i1];
  const double cx = v0[i0] - u0[i0], cy = v0[i1] - u0[i1];
  const double f = ay * bx - ax * by;
  const double d = by * cx - bx * cy;
  if ((f > 0 && d >= 0 && d <= f) || (f < 0 && d <= 0 && d >= f)) {
    const double e = ax * cy - ay * cx;
    if (f > 0) return e >= 0 && e <= f;
    return e <= 0 && e >= f;
  }
  return false;
}

bool point_in_tri_2d(const Vec3& p, const Tri& t, int i0, int i1) {
  double d[3];
  for (int k = 0; k < 3; ++k) {
    const Vec3& u0 = t[k];
    const Vec3& u1 = t[(k + 1) % 3];
    const double a = u1[i1] - u0[i1];
    const double b = -(u1[i0] - u0[i0]);
    const double c = -a * u0[i0] - b * u0[i1];
    d[k] = a * p[i0] + b * p[i1] + c;
  }
  return d[0] * d[1] > 0 && d[0] * d[2] > 0;
}

bool coplanar_tri_tri(const Vec3& n, const Tri& a, const Tri& b) {
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  // Keep the two axes other than the normal's dominant one (the paper's tie-breaking).
  int i0 = 0, i1 = 1;  // drop z
  if (ax > ay && ax > az) {
    i0 = 1, i1 = 2;  // drop x
  } else if (ax <= ay && az <= ay) {
    i0 = 0, i1 = 2;  // drop y
  }
  for (int e = 0; e < 3; ++e)
    for (int f = 0; f < 3; ++f)
      if (edge_edge_2d(a[e], a[(e + 1) % 3], b[f], b[(f + 1) % 3], i0, i1)) return true;
  return point_in_tri_2d(a[0], b, i0, i1) || point_in_tri_2d(b[0], a, i0, i1);
}

/// Interval of one triangle on L (projections p, distances d). False when coplanar.
bool compute_interval(const double p[3], const double d[3], double out[2]) {
  auto isect = [&](int i0, int i1, int i2) {  // corner i0 alone
    out[0] = p[i0] + (p[i1] - p[i0]) * d[i0] / (d[i0] - d[i1]);
    out[1] = p[i0] + (p[i2] - p[i0]) * d[i0] / (d[i0] - d[i2]);
  };
  const double d0d1 = d[0] * d[1], d0d2 = d[0] * d[2];
  if (d0d1 > 0)
    isect(2, 0, 1);
  else if (d0d2 > 0)
    isect(1, 0, 2);
  else if (d[1] * d[2] > 0 || d[0] != 0)
    isect(0, 1, 2);
  else if (d[1] != 0)
    isect(1, 0, 2);
  else if (d[2] != 0)
    isect(2, 0, 1);
  else
    return false;
  if (out[0] > out[1]) std::swap(out[0], out[1]);
  return true;
}

}  // namespace

bool tri_tri_moller(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  // Plane of B, distances of A's corners.
  const Vec3 n2 = cross(b[1] - b[0], b[2] - b[0]);
  const double d2 = -dot(n2, b[0]);
  const double du[3] = {dot(n2, a[0]) + d2, dot(n2, a[1]) + d2, dot(n2, a[2]) + d2};
  if (du[0] * du[1] > 0 && du[0] * du[2] > 0) return false;
  // Plane of A, distances of B's corners.
  const Vec3 n1 = cross(a[1] - a[0], a[2] - a[0]);
  const double d1 = -dot(n1, a[0]);
  const double dv[3] = {dot(n1, b[0]) + d1, dot(n1, b[1]) + d1, dot(n1, b[2]) + d1};
  if (dv[0] * dv[1] > 0 && dv[0] * dv[2] > 0) return false;
  // Project on the dominant axis of the line direction.
  const Vec3 dir = cross(n1, n2);
  const double mx = std::fabs(dir.x), my = std::fabs(dir.y), mz = std::fabs(dir.z);
  const int index = mx >= my && mx >= mz ? 0 : (my >= mz ? 1 : 2);
  const double pa[3] = {a[0][index], a[1][index], a[2][index]};
  const double pb[3] = {b[0][index], b[1][index], b[2][index]};
  double ia[2], ib[2];
  if (!compute_interval(pa, du, ia)) return coplanar_tri_tri(n1, a, b);
  if (!compute_interval(pb, dv, ib)) return coplanar_tri_tri(n1, a, b);
  return !(ia[1] < ib[0] || ib[1] < ia[0]);
}

}  // namespace interfere
