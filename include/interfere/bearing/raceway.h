// Exact pair solvers for the parts of a real roller bearing (issue #27, deliverable 1): a roller
// inside the concave bore of an outer ring, a roller end against a rib (flange) face, a tapered
// roller against the cone raceway of a tapered bearing's inner ring, and a tapered roller inside
// the cup (concave cone bore) of its outer ring. The geometry is Jia & Zheng 2019, §2.1, Fig. 1
// (rings and rollers whose axes are coplanar or meet at a point); the paper itself only treats two
// convex cylinders (§3.3), so every case here goes beyond it (docs/bearing.md, "Raceways").
//
// Every solver returns PairDistance (analytic.h) with the module's sign convention: distance > 0 is
// a clearance, distance < 0 is minus the interference depth (the paper's maximum interference
// distance). point_a lies on (or in) the roller where the extremum is reached, point_b on the other
// part's boundary (the raceway surface, the rib face). Never NaN for input that passes the
// validate_* functions below (the solvers themselves do not check: they run in the per-frame loop;
// call validate_* once when an assembly is built).
//
// Roller: a `Cylinder` (cylinder.h), a cone frustum when top_radius >= 0 (radius, top() >= 0, not
// both 0, height > 0, unit axis).
#pragma once
#include "interfere/bearing/analytic.h"
#include "interfere/bearing/cylinder.h"
#include "interfere/core/error.h"

namespace interfere::bearing {

/// The raceway bore of an outer ring (cylindrical roller bearing). The ring's material is every
/// point at distance >= radius from the axis line whose axial position z = (p - base).axis lies in
/// [0, width].
struct Bore {
  Vec3 base;           ///< a point of the axis, the ring's side face z = 0
  Vec3 axis{0, 0, 1};  ///< unit axis
  double radius = 1;   ///< raceway radius, > 0
  double width = 1;    ///< > 0
};

/// The cup of a tapered roller bearing (its outer ring): a conical bore whose radius varies linearly
/// from `radius` at z = 0 to `top_radius` at z = width. Material: rho >= R(z), z in [0, width].
struct Cup {
  Vec3 base;
  Vec3 axis{0, 0, 1};
  double radius = 1;      ///< bore radius at z = 0, > 0
  double top_radius = 1;  ///< bore radius at z = width, > 0
  double width = 1;       ///< > 0
};

/// A rib (flange) face of a ring: the planar annulus of points x with (x - center).normal = 0 and
/// inner_radius <= rho_axis(x) <= outer_radius, rho_axis the distance to the ring's axis line through
/// `center`. The rib's material lies behind the face ((x - center).normal <= 0); `normal` points out
/// of it, toward the rollers. For a ring, normal = +-axis (a face perpendicular to the ring axis).
struct Rib {
  Vec3 center;           ///< on the ring axis, in the face plane
  Vec3 normal{0, 0, 1};  ///< unit, out of the rib material toward the rollers
  double inner_radius = 0;
  double outer_radius = 1;  ///< > inner_radius >= 0
  Vec3 axis{0, 0, 1};       ///< unit ring axis; |normal . axis| >= 0.5 required
};

/// Checks of the preconditions, naming the parameter ("roller.radius must be > 0", ...); `what`
/// prefixes the message (e.g. "bearing 2 roller 7").
Status validate_roller(const Cylinder& roller, const char* what = "roller");
Status validate_bore(const Bore& bore, const char* what = "bore");
Status validate_cup(const Cup& cup, const char* what = "cup");
Status validate_rib(const Rib& rib, const char* what = "rib");

/// 1. Roller (convex, possibly tapered) inside a concave cylindrical bore:
///        s = radius - max over K of rho(p)
/// rho the distance to the bore axis, K = the roller's SOLID restricted to the ring's width (the
/// slab 0 <= z <= width; a convex set, all of the roller in the bearing's normal state). The maximum
/// of the convex rho over the whole frustum is reached on an end circle: the farthest point of an
/// ellipse (the circle projected along the bore axis) from a point (the axis), the unique root of a
/// monotone function (closed form to rounding; raceway.cpp). When that point lies in the width it is
/// K's maximum too. Otherwise K's maximum is on an end circle's arc within the width or on the
/// curves where the lateral surface crosses the side faces (raceway_slab.cpp). Cases:
///   - s <= 0: the solids meet; -s is the depth of the roller's farthest point in the width beyond
///     the raceway, measured radially (exact);
///   - s > 0 with K's maximiser the whole roller's: s is the radial clearance, the Euclidean distance
///     to the ring (exact; path `bore`);
///   - s > 0 otherwise (the roller overhangs a side face): the reported value is max(radius - max
///     over the whole roller of rho, 0), a lower bound of the distance (path `apart`);
///   - K empty (the solid misses the width): the axial gap, a lower bound (path `apart`).
/// point_b: point_a moved radially onto the bore surface. (Until issue #27's fix the roller's AXIS
/// was clipped to the width: a roller lying across a side face came out as 0, "contact".)
PairDistance roller_bore_distance(const Cylinder& roller, const Bore& bore);

/// 2. Roller end against a rib face: with l(p) = (p - center).normal (the height above the face plane)
/// and K = the roller's points with inner_radius <= rho_axis(p) <= outer_radius (over the annulus),
///        s = min over K of l(p)
/// i.e. minus the depth of the roller below the face plane within the annulus (negative: the roller
/// reaches into the rib; positive: the normal gap over the annulus). Exact: the minimum of a linear
/// function over K lies on an end circle of the roller (closed form) or on the curves where the
/// roller's boundary crosses the cylinders rho = inner_radius / outer_radius (a 1-D search over the
/// azimuth, raceway_rib.cpp). Never reports "clear" when the solids overlap: any common point is in
/// K below the plane. When the roller has no point over the annulus, s is a positive lower bound of
/// the distance (radial gap to the annulus' shell, or the plane gap; path `apart`).
PairDistance roller_rib_distance(const Cylinder& roller, const Rib& rib);

/// 3. s(A, B) = min over points p of solid A of sd_B(p) (analytic.h) for a (possibly tapered) A and a
/// possibly tapered B (a cone frustum: the inner ring "cone" of a tapered bearing). An untapered B is
/// cylinder_pair_distance. Else: the lateral lower bound g(p) = signed distance to the tangent plane
/// of B's cone along p's meridian (sd_B >= g everywhere) is minimised over A through its dual (a
/// 1-D search of a support function) and the bracket V_g <= s <= sd_B(p*) certifies the value when
/// it closes (path `cone`, ~6 us; side and end-circle contact, line contact of tapered rollers);
/// else, for axes within 60 degrees, B's cross-sections (path `slice`, analytic.h, ~0.1 ms: rollers
/// side by side, the reverse s(cone ring, roller)); else the same with one of B's end faces in the
/// bound (path `cone`, ~0.5 ms: A against B's end
/// face or edge, e.g. the reverse s(cone ring, roller) of a two-sided value, also for an untapered
/// roller B when A is tapered); otherwise the standard solver (untapered B) or a nested golden-section
/// minimisation of the convex sd_B over A (path `general`, ~5 ms; clear pairs whose nearest points
/// involve B's end faces, both end faces active). Also serves tapered roller against tapered roller.
PairDistance cone_pair_distance(const Cylinder& a, const Cylinder& b);

/// 4. Tapered (or cylindrical) roller inside a cup: g(p) = (rho(p) - R(z(p))) / sqrt(1 + k^2), the
/// signed distance of p beyond the cone line in its meridian half-plane (k = dR/dz), is convex;
///        s = -max over K of g(p)
/// with K the roller's solid within the width and the cases as in roller_bore_distance (s > 0 with
/// the whole roller's maximiser in the width: the distance to the cone line, a lower bound of the
/// distance to the ring that is exact when point_b lies in the width; overhanging and clear: path
/// `apart`, max(-max over the roller of g, 0)). The maximum over an end circle: a 1-D maximisation
/// over the circle's angle (dense bracketing then golden-section refinement of every bracketed
/// maximum; raceway.cpp). point_b: the foot of point_a on the cone line. With top_radius == radius
/// this is roller_bore_distance.
PairDistance roller_cup_distance(const Cylinder& roller, const Cup& cup);

/// The signed distance from p to a solid cone frustum (or cylinder): closed form in p's meridian
/// half-plane (distance to the trapezoid |x| <= R(z), 0 <= z <= h). Exposed for tests.
double point_frustum_signed_distance(const Cylinder& c, const Vec3& p);

/// The point of c's boundary nearest p (c a frustum or cylinder).
Vec3 nearest_on_frustum_boundary(const Cylinder& c, const Vec3& p);

}  // namespace interfere::bearing
