// Point-to-cylinder signed distance: the direct closed form and Barbier & Galin, "Fast distance
// computation between a point and cylinders, cones, line-swept spheres and cone-spheres", J.
// Graphics Tools 9(2), 2004 (the paper's comparison method); tight boxes of posed cylinders.
#include "interfere/bearing/cylinder.h"

#include <algorithm>
#include <cmath>

namespace interfere::bearing {

Cylinder posed_cylinder(double radius, double top_radius, double height, const Transform& pose) {
  Cylinder c;
  c.base = pose.t;
  c.axis = {pose.r[0][2], pose.r[1][2], pose.r[2][2]};
  c.axis = c.axis / norm(c.axis);
  c.height = height;
  c.radius = radius;
  c.top_radius = top_radius;
  return c;
}

RadialAxial radial_axial(const Cylinder& c, const Vec3& p) {
  const Vec3 v = p - c.center();
  return {norm(cross(v, c.axis)), dot(v, c.axis)};
}

double signed_distance_rz(double rho, double z, double radius, double half_height) {
  const double dr = rho - radius, dz = std::fabs(z) - half_height;
  if (dr <= 0 && dz <= 0) return std::max(dr, dz);
  const double a = std::max(dr, 0.0), b = std::max(dz, 0.0);
  return std::sqrt(a * a + b * b);
}

double point_signed_distance(const Cylinder& c, const Vec3& p) {
  const RadialAxial ra = radial_axial(c, p);
  return signed_distance_rz(ra.rho, ra.z, c.radius, 0.5 * c.height);
}

double barbier_galin_signed_distance(const Cylinder& c, const Vec3& p) {
  const Vec3 n = p - c.center();
  const double x = dot(n, c.axis);
  const double n2 = dot(n, n);
  const double y2 = std::max(n2 - x * x, 0.0);
  const double ax = std::fabs(x), hh = 0.5 * c.height, r2 = c.radius * c.radius;
  if (ax < hh) {
    if (y2 < r2) return -std::min(c.radius - std::sqrt(y2), hh - ax);  // inside
    return std::sqrt(y2) - c.radius;                                   // beside the side
  }
  if (y2 < r2) return ax - hh;  // above/below a cap
  const double dy = std::sqrt(y2) - c.radius, dx = ax - hh;
  return std::sqrt(dy * dy + dx * dx);  // beyond a rim
}

Box3 cylinder_box(const Cylinder& c) {
  const Vec3 b = c.base, t = c.top_center();
  Box3 out;
  for (std::size_t k = 0; k < 3; ++k) {
    const double e = std::sqrt(std::max(0.0, 1.0 - c.axis[k] * c.axis[k]));
    const double eb = c.radius * e, et = c.top() * e;
    out.lo[k] = std::min(b[k] - eb, t[k] - et);
    out.hi[k] = std::max(b[k] + eb, t[k] + et);
  }
  return out;
}

}  // namespace interfere::bearing
