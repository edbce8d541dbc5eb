// Parametric bearing parts (Jia & Zheng, "Dynamic interference of cylindrical roller bearings with
// scars", J. System Simulation 31(3), 2019, §2.1 "bearing.parameters"): cylinders and, beyond the
// paper, tapered rollers (truncated cones), meshed with outward triangles on a regular
// (angle x height) grid so that the vertex quadtree (quadtree.h) can address vertices by (i, j).
//
// Body frame: the axis is +z, the bottom end centre is the origin, the top end centre (0,0,height).
// Side vertex (i, j), i in [0, radial_segments), j in [0, height_segments]: angle 2*pi*i/n, height
// height*j/m, radius r(z) = radius + (top_radius - radius)*z/height minus the scar displacement
// (signed: > 0 inward, the paper's usual scar; < 0 raised, outward, issue #27).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::bearing {

struct RollerParams {
  double radius = 10.0;         ///< bottom radius (> 0)
  double top_radius = -1.0;     ///< top radius (> 0); < 0 means "same as radius" (a cylinder)
  double height = 40.0;         ///< length along the axis (> 0)
  int radial_segments = 64;     ///< side vertices per ring (>= 3)
  int height_segments = 63;     ///< quads along the height (>= 1); rings = height_segments + 1

  double top() const { return top_radius < 0 ? radius : top_radius; }
  bool tapered() const { return top() != radius; }
  double radius_at(double z) const { return radius + (top() - radius) * (z / height); }
};

/// Every parameter checked; the error names it ("roller.radius must be > 0, got -1").
Status validate(const RollerParams& p, const std::string& prefix = "roller");

/// A meshed roller. Triangle layout (fixed, used by the solvers):
///   side cell (i, j) (quad between rings j, j+1 and columns i, i+1): triangles 2*(j*n+i) and +1;
///   bottom fan: 2*n*m + i; top fan: 2*n*m + n + i.
/// Vertex layout: side (i, j) = j*n + i; bottom centre n*(m+1); top centre n*(m+1)+1.
struct Roller {
  RollerParams params;
  TriMesh mesh;                        ///< body frame, outward (counter-clockwise seen from outside)
  /// Inward radial scar displacement per side vertex: > 0 inward (a pit), < 0 outward (a raised
  /// scar, issue #27). A raised scar reaches outside the intact solid: see `raise`.
  std::vector<double> displacement;
  std::vector<std::uint8_t> scar;      ///< 1 for side vertices of a scar (scar.h), else 0
  bool has_scar = false;
  /// The largest outward displacement, max(0, -min displacement), set by update_positions(): the
  /// scarred solid lies in the intact solid grown radially by `raise` (0: inside the intact solid).
  double raise = 0;

  int n() const { return params.radial_segments; }
  int m() const { return params.height_segments; }
  std::uint32_t side_vertex(int i, int j) const {
    return static_cast<std::uint32_t>(j * n() + ((i % n()) + n()) % n());
  }
  std::uint32_t side_triangle(int i, int j) const { return static_cast<std::uint32_t>(2 * (j * n() + i)); }
  std::uint32_t bottom_triangle(int i) const { return static_cast<std::uint32_t>(2 * n() * m() + i); }
  std::uint32_t top_triangle(int i) const { return static_cast<std::uint32_t>(2 * n() * m() + n() + i); }
  double angle(int i) const;   ///< 2*pi*i/n
  double z(int j) const;       ///< height*j/m
  /// Recomputes the side positions from params and displacement (after a scar is applied), and `raise`.
  void update_positions();
};

/// Meshes a roller (no scar). Precondition: validate(p) is ok (checked; returns the error).
Expected<Roller> make_roller(const RollerParams& p);

/// Rotation about the body axis by `spin` radians, then the tilt: rotation by `tilt` radians about
/// the horizontal axis (-sin(azimuth), cos(azimuth), 0), so that the axis +z becomes
/// (sin(tilt)cos(azimuth), sin(tilt)sin(azimuth), cos(tilt)); then translation to `pivot` (where the
/// body origin, the bottom end centre, goes).
Transform roller_pose(const Vec3& pivot, double tilt, double azimuth, double spin);

}  // namespace interfere::bearing
