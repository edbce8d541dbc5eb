// Raised scars (issue #27; scar.h `raised`, scar_import.h) reach outside the roller's intact solid,
// so the intact cylinder no longer bounds the roller. This is a cheap conservative bound of the
// part that does: spheres (body frame) covering every triangle of the roller that has a vertex
// displaced outward; sd_B (signed distance to an intact cylinder B) is 1-Lipschitz, so
// sd_B(centre) - radius bounds it from below over a sphere's triangles. Every other triangle lies
// in the intact solid (its vertices do, and the solid is convex), where sd_B >= s(intact, B).
//
// The simulation (simulation.h) uses it to decide whether the standard solver's value on the intact
// cylinder can stand for a raised-scarred roller whose scar is out of the range of Eq. (1): only
// when this bound is not below it.
#pragma once
#include <vector>

#include "interfere/bearing/cylinder.h"
#include "interfere/bearing/roller.h"

namespace interfere::bearing {

struct RaisedBound {
  struct Sphere {
    Vec3 center;  ///< body frame
    double radius = 0;
  };
  std::vector<Sphere> spheres;  ///< empty: no vertex is displaced outward
  bool empty() const { return spheres.empty(); }
};

/// Groups the triangles with an outward-displaced vertex (displacement < 0) into runs of at most
/// `triangles_per_sphere` consecutive triangle ids (neighbouring cells of one ring band) and bounds
/// each run by a sphere (centre: the middle of the run's vertex box; radius: the farthest vertex,
/// plus a relative rounding margin).
RaisedBound build_raised_bound(const Roller& roller, int triangles_per_sphere = 16);

/// A lower bound of sd_B over every triangle with an outward-displaced vertex of the roller posed
/// by `pose`; +infinity when there is none. B must be an untapered cylinder.
double raised_lower_bound(const RaisedBound& bound, const Transform& pose, const Cylinder& b);

}  // namespace interfere::bearing
