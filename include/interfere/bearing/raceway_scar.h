// Scars on raceways (issue #27, deliverable 2: "scars on any part (rollers and raceways)"): the inner
// ring's convex raceway cylinder, the outer ring's concave raceway bore, and a tapered bearing's cone
// (convex) and cup (concave). Jia & Zheng 2019, §2.2 model a scar as a radial disturbance of a
// part's surface points over a window, joined to the intact surface by a median filter; the paper
// puts scars on rollers only, this puts the same scars on the rings.
//
// Representation. A raceway is a surface of revolution about its ring's axis (the ring's body frame
// +z): radius `radius` at the axial position z0, `top_radius` at z0 + width (a cylinder, or a cone
// for the cone and cup). Its scarred surface is meshed exactly as a roller's side is (roller.h): a
// regular (angle x axial position) vertex grid over the WHOLE circumference and width, with
// `radial_segments` columns and `height_segments` + 1 rings, carried by a `Roller` whose body frame
// is the ring's frame shifted by z0 along the axis (its "height" is the raceway's width). The scar
// generators and importers of scar.h and scar_import.h are applied to that grid unchanged: the
// diamond-square map with the median-filtered border band (apply_scar), a CSV grid over angle x
// axial position or a 16-bit PNG (resample_height_map), a point cloud or registered STL
// (scar_from_points). Reusing the roller's grid also reuses its quadtree (quadtree.h) and its exact
// branch-and-bound solver (scarred.h) for the pair solver (raceway_scar_solver.h).
//
// Sign. A raceway scar's height is measured along the raceway's normal TOWARD THE ROLLERS: positive
// = raised (material added above the nominal surface), negative = a pit (inward, into the ring:
// the usual case, §2.2). For the convex raceways (inner, cone) toward the rollers is away from the
// axis, as for a roller (scar_import.h's heights); for the concave ones (outer bore, cup) it is
// toward the axis, so their heights are negated onto the grid's radial heights. A point cloud is
// geometry (points of the worn surface in the ring's frame): its radial deviations are taken as
// measured, whatever the side.
//
// Window. Angles are degrees about the ring's +z from its +x (the ring's body frame), axial
// positions are measured from the raceway's start z0 (0 .. width), as a roller's z from its bottom
// end. A generated scar's window (ScarParams: angle_center_deg, angle_width_deg, z_min, z_max, depth,
// roughness, border, seed, raised) must lie on the raceway: 0 <= z_min < z_max <= width, depth in
// (0, 0.5 x the smallest radius); errors name the parameter with the caller's prefix
// ("bearings[0].scars[1].z_max must be ..."). An imported CSV map whose rows lie outside 0 .. width
// is an error naming the file and line.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/roller.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scar_import.h"
#include "interfere/core/error.h"
#include "interfere/core/transform.h"

namespace interfere::bearing {

enum class RacewaySurface : std::uint8_t {
  inner,  ///< cylindrical bearing: the inner ring's raceway cylinder (convex; material rho <= R)
  outer,  ///< cylindrical bearing: the outer ring's raceway bore (concave; material rho >= R)
  cone,   ///< tapered bearing: the cone's raceway (convex frustum)
  cup,    ///< tapered bearing: the cup's raceway (concave cone)
};
const char* raceway_surface_name(RacewaySurface s);
inline bool raceway_concave(RacewaySurface s) { return s == RacewaySurface::outer || s == RacewaySurface::cup; }

/// A raceway in its ring's body frame (axis +z).
struct RacewayGeometry {
  RacewaySurface surface = RacewaySurface::inner;
  double z0 = 0;          ///< axial position (ring frame) of the raceway's start: the scar's z = 0
  double width = 1;       ///< axial extent (> 0)
  double radius = 1;      ///< at z0 (> 0)
  double top_radius = 1;  ///< at z0 + width (> 0; equal to radius for inner and outer)
  double radius_at(double z) const { return radius + (top_radius - radius) * (z / width); }
};

/// The raceway grid (the scar's resolution; the intact part of the raceway is meshed at the same
/// resolution: the scarred solver measures the whole faceted raceway, docs/bearing.md).
struct RacewayGrid {
  int radial_segments = 512;  ///< columns around the whole circumference (>= 8)
  int height_segments = 63;   ///< quads across the width (>= 1)
};

struct RacewayScar {
  RacewayGeometry geometry;
  RacewayGrid grid;
  /// The raceway surface as a roller grid (roller.h), scar applied; body frame = ring frame shifted
  /// by z0 (`to_ring`). Its displacement is roller.h's (radial, > 0 toward the axis).
  Roller surface;
  /// Its quadtree (quadtree.h). Concave raceways: the two end-cap trees are replaced by an empty
  /// node (the caps of a bore are not ring material), so the solvers see the side triangles only.
  RollerQuadtree tree;
  Transform to_ring;       ///< surface body frame -> ring body frame (translation z0 along +z)
  /// The smallest window (covered_window, scar_import.h) holding every scar vertex: angle centre
  /// and width in degrees, z_min .. z_max from z0. `depth` the largest |height|.
  ScarParams window;
  /// The largest height toward the rollers (>= 0): the scarred raceway lies within the intact one
  /// moved toward the rollers by this much (radially).
  double raise = 0;
  int scar_vertices = 0;
  std::string source;  ///< "generated (seed S)" or the imported file
};

/// Checks the geometry and the grid, naming the parameter ("raceway.width must be > 0, got 0").
Status validate(const RacewayGeometry& g, const RacewayGrid& grid, const std::string& prefix = "raceway");

/// The roller grid parameters that carry the raceway (radius, top radius, width as height).
RollerParams raceway_roller_params(const RacewayGeometry& g, const RacewayGrid& grid);

/// A generated scar (scar.h's diamond-square map and median filter): `s.raised` = toward the rollers.
/// Errors name the parameter under `prefix` (the window off the raceway, depth, roughness, ...).
Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid, const ScarParams& s,
                                        const std::string& prefix = "scar");

/// An imported height map (CSV grid over angle x axial position, or a PNG: read by scar_import.h),
/// heights toward the rollers. Errors: a map row outside the raceway's width (naming the file and the
/// CSV line, or the PNG), a map that covers no vertex, non-finite heights (the readers), and
/// resample_height_map's.
Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid, const HeightMap& map,
                                        int border = 0);

/// A point cloud (or a registered STL's vertices) of the worn raceway in the ring's body frame:
/// scar_from_points on the grid (after the shift by -z0).
Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid,
                                        const std::vector<Vec3>& points_ring_frame,
                                        const PointScarOptions& options = {}, const std::string& source = "points",
                                        int border = 0);

/// Whether the ring-frame angle `phi` (radians) lies in the scar's angular window widened by `margin`.
bool raceway_scar_angle_contains(const RacewayScar& s, double phi, double margin);

}  // namespace interfere::bearing
