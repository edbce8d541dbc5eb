// Finite cylinders (and cone frustums) in world space and the signed distance of a point to a
// finite cylinder: the direct formula and Barbier & Galin's fast form ("Fast distance computation
// between a point and cylinders, cones, line-swept spheres and cone-spheres", J. Graphics Tools
// 9(2), 2004), which is the paper's comparison method.
//
// Sign convention (everywhere in the bearing module): positive = outside (Euclidean distance to
// the solid), negative = inside (minus the distance to the boundary).
#pragma once
#include "interfere/core/transform.h"
#include "interfere/core/vec.h"

namespace interfere::bearing {

struct Cylinder {
  Vec3 base;            ///< bottom end centre
  Vec3 axis{0, 0, 1};   ///< unit axis, bottom -> top
  double height = 1;    ///< > 0
  double radius = 1;    ///< bottom radius, > 0
  double top_radius = -1;  ///< < 0: same as radius (cylinder); else a cone frustum

  double top() const { return top_radius < 0 ? radius : top_radius; }
  bool tapered() const { return top() != radius; }
  Vec3 top_center() const { return base + axis * height; }
  Vec3 center() const { return base + axis * (0.5 * height); }
  double max_radius() const { return radius > top() ? radius : top(); }
};

/// The cylinder of a roller's body frame (axis +z from the origin) placed by `pose`.
Cylinder posed_cylinder(double radius, double top_radius, double height, const Transform& pose);

/// Signed distance from p to the solid cylinder c (c must not be tapered): closed form in the
/// cylinder's (radial, axial) half-plane; the radial part from the cross product (no cancellation).
double point_signed_distance(const Cylinder& c, const Vec3& p);

/// Barbier–Galin 2004, §2 (cylinder): x = (p-c).u, n2 = |p-c|^2, y2 = n2 - x^2, one square root in
/// the outside cases only. Same value as point_signed_distance up to the rounding of n2 - x^2.
double barbier_galin_signed_distance(const Cylinder& c, const Vec3& p);

/// p in c's local frame: (rho, z) with rho the distance to the axis line and z the signed height
/// from the centre.
struct RadialAxial {
  double rho = 0, z = 0;
};
RadialAxial radial_axial(const Cylinder& c, const Vec3& p);

/// The signed distance to a cylinder of radius R, half height hh from (rho, z): the formula above.
double signed_distance_rz(double rho, double z, double radius, double half_height);

/// The Aabb of a solid cylinder/cone frustum (exact up to rounding: segment box grown by
/// radius*sqrt(1 - axis_k^2) per axis).
struct Box3 {
  Vec3 lo, hi;
};
Box3 cylinder_box(const Cylinder& c);

}  // namespace interfere::bearing
