// The pair solver of a roller (intact or scarred) against a scarred raceway (raceway_scar.h; issue
// #27, deliverable 2 and the target "one maximum-interference computation of a scarred roller
// against a scarred raceway at 64^2 vertices, scar in range").
//
// The quantity extends the scarred solver's (scarred.h; Jia & Zheng 2019, §3.2: the scarred
// surface against the analytic partner) to a pair in which either part, or both, carry a scar:
//
//   raceway term  T_r = min over the scarred raceway's faceted surface (every triangle of its grid,
//                       the scar and the intact rest; a convex raceway's end faces too, a concave
//                       one's not) of sd_A^, the signed distance to the roller's enclosing intact
//                       solid A^ (its cylinder or frustum; a raised roller scar grows it radially by
//                       the scar's raise, Roller::raise; a tapered roller's frustum is taken exactly
//                       by scarred.h since issue #27's tapered scars);
//   roller term   T_a = (scarred rollers only) the scarred roller's surface against the raceway's
//                       enclosing intact ring material B^ (the raceway moved toward the rollers by
//                       the raceway scar's raise): convex raceway: min over the roller's triangles
//                       of sd_B^ (B^ the raceway cylinder or the cone's frustum, scarred.h's exact
//                       solver); concave: minus
//                       the largest meridian distance beyond B^'s surface over the roller's mesh
//                       clipped to the ring's width (its vertices in the width and its edges'
//                       crossings of the side faces: rho - R(z) is convex, its maximum over a
//                       clipped triangle lies at a vertex of the clipped polygon);
//   S = min(T_r, T_a)   (> 0 clearance, < 0 minus the interference depth).
//
// S is one number for the pair: it is defined without an order of the parts, and
// raceway_scar_pair(roller, ring) and raceway_scar_pair(ring, roller) run the same computation
// (bitwise equal). Each term is exact to rounding (scarred.h's per-triangle minimum and branch and
// bound; the vertex maximum) against independent dense references (tests/unit/bearing/
// test_raceway_scar.cpp). What it is not: when both parts carry scars, each scar is measured against
// the other part's enclosing intact solid, so a roller pit over a raceway bump is not seen as a gap
// (the value is then the deeper, conservative one). For an intact roller and an unscarred stretch of
// raceway T_r is the ring's deepest point in the roller on the faceted raceway (within the facets'
// sagitta of the analytic ring solvers' two-sided value, ring_two_sided.h).
#pragma once
#include <cstdint>
#include <limits>

#include "interfere/bearing/cylinder.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/raceway_scar.h"
#include "interfere/bearing/roller.h"

namespace interfere::bearing {

/// The roller of the pair.
struct RacewayPairRoller {
  Cylinder cylinder;                     ///< world frame: its intact solid (a frustum when tapered)
  const Roller* mesh = nullptr;          ///< a scarred roller's surface (body frame), else null
  const RollerQuadtree* tree = nullptr;  ///< its quadtree (with mesh)
  Transform pose;                        ///< body -> world (with mesh)
};

/// The ring whose raceway carries the scar.
struct RacewayPairRing {
  const RacewayScar* scar = nullptr;
  Transform pose;  ///< ring body frame -> world
};

/// Which part's scar surface the minimum lies on.
enum class ScarCarrier : std::uint8_t { none, roller, raceway };
const char* scar_carrier_name(ScarCarrier c);

struct RacewayScarPairResult {
  double distance = 0;          ///< S: > 0 clearance, < 0 minus the interference depth
  Vec3 point_roller;            ///< world: on (or in) the roller, the witness of S
  Vec3 point_raceway;           ///< world: on (or in) the raceway
  ScarCarrier carrier = ScarCarrier::none;  ///< a scar vertex on the minimising triangle (or vertex)
  /// The value depends on a scar: carrier != none, or the winning term's solid (A^ or B^) was
  /// grown by the other part's raised scar.
  bool scar = false;
  /// false: a bound. Since scarred.h takes frustums (issue #27), tapered rollers and cones are exact
  /// too: always true today (kept for callers that check it).
  bool exact = true;
  double raceway_term = std::numeric_limits<double>::infinity();  ///< T_r
  double roller_term = std::numeric_limits<double>::infinity();   ///< T_a (+inf: intact roller)
  std::uint32_t evaluated = 0;  ///< triangles evaluated exactly (both terms)
  std::uint32_t nodes_visited = 0;  ///< quadtree nodes visited (both terms)
  std::uint32_t fallbacks = 0;      ///< triangles whose minimum needed scarred.h's search (both terms)
};

/// S of the pair (above). Preconditions: ring.scar set; the roller's cylinder valid (raceway.h).
RacewayScarPairResult raceway_scar_pair(const RacewayPairRoller& roller, const RacewayPairRing& ring);
/// The same pair given the other way round: the same computation, the same result.
RacewayScarPairResult raceway_scar_pair(const RacewayPairRing& ring, const RacewayPairRoller& roller);

/// The roller's enclosing intact solid A^ of the raceway term (above), world frame.
Cylinder raceway_term_roller_solid(const RacewayPairRoller& roller, bool* exact = nullptr);

/// The surface grid's pose (body -> world): the ring's pose after the shift by z0.
Transform raceway_surface_pose(const RacewayPairRing& ring);

/// Whether the roller lies in range of the raceway's scar: the angular span (ring frame, about the
/// ring's axis) of the roller's bounding sphere overlaps the scar's angular window widened by
/// `margin` radians. The assembly's rows use the pair solver for rollers in range and the intact
/// ring's analytic solvers otherwise (as the simulation does with a roller's scar and Eq. (1)).
bool raceway_scar_in_range(const RacewayPairRoller& roller, const RacewayPairRing& ring, double margin = 0);

}  // namespace interfere::bearing
