// Derived geometry of one bearing of an assembly (assembly.h): the roller placement, the raceways
// and the cage webs, in the bearing frame (axis +z, mid-plane z = 0). Tapered bearings follow the
// paper's §2.1 ("axes coplanar or meeting at a point"): the roller axes, the cone and the cup all
// meet at one apex on the bearing axis, so that a roller touches both raceways along a line.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "assembly_internal.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

/// The point where three planes n_i . x = d_i meet (Cramer's rule; the planes of a web are never
/// parallel for a valid bearing).
Vec3 meet(const Vec3& n1, double d1, const Vec3& n2, double d2, const Vec3& n3, double d3) {
  const Vec3 c23 = cross(n2, n3), c31 = cross(n3, n1), c12 = cross(n1, n2);
  const double det = dot(n1, c23);
  return (c23 * d1 + c31 * d2 + c12 * d3) / det;
}

/// A rotation taking +z to the unit vector `axis` (the smallest rotation; a half turn about x for -z).
Transform frame_of(const Vec3& position, const Vec3& axis) {
  Transform t;
  const Vec3 z{0, 0, 1};
  const double c = dot(z, axis);
  const Vec3 v = cross(z, axis);
  if (c < -1 + 1e-12) {
    t.r = {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
  } else {
    // Rodrigues: R = I + [v]x + [v]x^2 / (1 + c)
    const double k = 1.0 / (1.0 + c);
    t.r = {{{1 - k * (v.y * v.y + v.z * v.z), -v.z + k * v.x * v.y, v.y + k * v.x * v.z},
            {v.z + k * v.x * v.y, 1 - k * (v.x * v.x + v.z * v.z), -v.x + k * v.y * v.z},
            {-v.y + k * v.x * v.z, v.x + k * v.y * v.z, 1 - k * (v.x * v.x + v.y * v.y)}}};
  }
  t.t = position;
  return t;
}

}  // namespace

Expected<BearingGeometry> bearing_geometry(const BearingSpec& b) {
  BearingGeometry g;
  g.frame = frame_of(b.position, b.axis);
  const RollerSetSpec& r = b.rollers;
  double r_max = r.radius;
  if (b.type == BearingType::cylindrical) {
    g.pitch_radius = r.pitch_radius;
    g.roller_z = 0;
    g.roller_lean = 0;
    g.raceway.base = {0, 0, -0.5 * b.inner_width};
    g.raceway.axis = {0, 0, 1};
    g.raceway.height = b.inner_width;
    g.raceway.radius = b.inner_raceway;
    g.free_axial_play = 0.5 * (b.inner_width - 2 * b.rib_width - r.length);
  } else {
    r_max = r.top_radius;
    const double beta = std::atan((r.top_radius - r.radius) / r.length);  // roller half-angle
    const double alpha = b.contact_angle_deg * kPi / 180;                   // cup half-angle
    g.roller_lean = alpha - beta;
    g.cup_half_angle = alpha;
    g.cone_half_angle = alpha - 2 * beta;
    const double d1 = r.radius / std::tan(beta);  // apex -> small end centre, along the roller axis
    const double dm = d1 + 0.5 * r.length;
    g.apex_z = -dm * std::cos(g.roller_lean);
    g.pitch_radius = dm * std::sin(g.roller_lean);
    g.roller_z = 0;
    // axial extent of the roller at rest: end disks of radius r about the end centres
    const double zs = g.apex_z + d1 * std::cos(g.roller_lean) - r.radius * std::sin(g.roller_lean);
    const double zb = g.apex_z + (d1 + r.length) * std::cos(g.roller_lean) + r.top_radius * std::sin(g.roller_lean);
    g.ring_lo = zs - 0.1 * r.length;
    g.ring_hi = zb + 0.1 * r.length;
    const auto cone_r = [&](double z) {
      return (z - g.apex_z) * std::tan(g.cone_half_angle) - b.cone_clearance / std::cos(g.cone_half_angle);
    };
    g.raceway.base = {0, 0, g.ring_lo};
    g.raceway.axis = {0, 0, 1};
    g.raceway.height = g.ring_hi - g.ring_lo;
    g.raceway.radius = cone_r(g.ring_lo);
    g.raceway.top_radius = cone_r(g.ring_hi);
  }
  // cage webs: web k between roller k (at phi_k = 2 pi k / Z) and roller k + 1
  const int z = r.count;
  const double c = b.cage.pocket_clearance, t = b.cage.web_thickness;
  const double w = b.cage.width > 0 ? b.cage.width : r.length;
  const double lean = g.roller_lean;
  for (int k = 0; k < z; ++k) {
    const double phi0 = 2 * kPi * k / z, phi1 = 2 * kPi * (k + 1) / z, psi = 2 * kPi * (k + 0.5) / z;
    const Vec3 t0{-std::sin(phi0), std::cos(phi0), 0}, t1{-std::sin(phi1), std::cos(phi1), 0};
    const Vec3 m{std::cos(psi), std::sin(psi), 0};
    const Vec3 radial = m * std::cos(lean) - Vec3{0, 0, 1} * std::sin(lean);  // normal to the pitch line
    const Vec3 along = m * std::sin(lean) + Vec3{0, 0, 1} * std::cos(lean);   // along the pitch line
    const Vec3 p = m * g.pitch_radius + Vec3{0, 0, g.roller_z};
    CageWeb web;
    // faces: 0 pocket k (normal -t0), 1 pocket k+1 (normal t1), 2 inner, 3 outer, 4 low, 5 high
    web.normals = {-t0, t1, -radial, radial, -along, along};
    web.offsets = {-(r_max + c), -(r_max + c), -(dot(radial, p) - 0.5 * t), dot(radial, p) + 0.5 * t,
                   -(dot(along, p) - 0.5 * w), dot(along, p) + 0.5 * w};
    for (int i = 0; i < 8; ++i) {
      const int f0 = i & 1, f1 = 2 + ((i >> 1) & 1), f2 = 4 + ((i >> 2) & 1);
      web.corners[i] = meet(web.normals[f0], web.offsets[f0], web.normals[f1], web.offsets[f1], web.normals[f2],
                            web.offsets[f2]);
    }
    g.webs.push_back(web);
  }
  return g;
}

Transform roller_local_pose(const BearingSpec& b, const BearingGeometry& g, double phi, double tilt,
                            double axial_shift, double spin) {
  using detail::compose;
  using detail::rotation_y;
  using detail::rotation_z;
  Transform shift;
  shift.t = {0, 0, -0.5 * b.rollers.length};
  Transform pose = compose(rotation_z(phi), compose(rotation_y(g.roller_lean + tilt), compose(rotation_z(spin), shift)));
  pose.t = pose.t + Vec3{g.pitch_radius * std::cos(phi), g.pitch_radius * std::sin(phi), g.roller_z + axial_shift};
  return pose;
}

}  // namespace interfere::bearing
