// Two-sided values of the bearing's ring pairs (issue #27: "s(A, B) = s(B, A) — the maximum
// interference distance of a pair is one number, whichever part is first"; Jia & Zheng 2019, §3.3
// Step 3 checks the end circles of both parts). docs/bearing.md, "Two-sided ring pairs".
//
// For a roller A (a convex cylinder or frustum) and a ring feature B (a bounded solid: the outer
// ring's annulus behind its bore or cup, the rib block behind its face, a convex cage web),
//     depth_B(p) = distance from p in B to B's boundary (its free surfaces),
//     fwd = max over A of depth_B (the roller's deepest point in the ring part),
//     rev = max over B of depth_A (the ring part's deepest point in the roller),
//     S   = -max(fwd, rev) when the interiors meet; the Euclidean distance when they are apart,
// the same number whichever part is first.
//
// raceway.h's one-sided solvers measure the roller's reach beyond the raceway surface only (radial,
// along the cone line's normal, below the rib face): r_f >= fwd. Two facts make S cheap in the
// usual case:
//   (i) rev <= r_f: a ring point q at depth t in the roller has the ball B(q, t) in the roller, so
//       q + t n (n: the raceway's outward normal in q's meridian plane, radial for a bore, along
//       the cone line's normal for a cup, -face normal for a rib) is a roller point whose reach is
//       r(q) + t >= t, and it lies in the solver's set K (same z for a bore, same rho for a rib; a
//       cup needs the whole roller within the ring's width);
//  (ii) fwd = r_f when at the solver's witness p* the reach r_f is not more than p*'s distance to
//       B's other free surfaces (side faces, outside, the rib's top and back): the depth of p* in
//       B, a convex meridian polygon, is the smallest of its distances to the edges' lines.
// Then S = -r_f exactly (certificate). Otherwise (a roller overhanging a side face, pressing the
// rib's top edge, ...) fwd and rev are found as the largest erosion t for which the roller meets the
// eroded ring part B_t, and the eroded roller A_t (its inner parallel body: radius - t sqrt(1+k^2),
// ends moved in by t) meets B: raceway.h's own exact decisions at each t, the switching t
// bracketed by a safeguarded Illinois iteration to 2^-50 of the pair's scale (6-9 solver calls in the example's motion).
//
// Cage webs (assembly_pairs.cpp): the web's deepest point in the roller, rev, is the surface minimum
// of the roller's signed distance over the web. fwd, the roller's deepest point in the convex
// hexahedron, maximises the concave min over the faces of the face-plane distances over the roller:
// a golden-section search over the roller's axial parameter of an exact per-disk maximum.
#pragma once
#include <array>
#include <functional>

#include "interfere/bearing/raceway.h"

namespace interfere::bearing {

struct TwoSidedRing {
  PairDistance value;        ///< S; point_a on the roller, point_b on the ring part
  bool exact = true;         ///< false: a bound (the forward solver's `apart`, or a ring too thin)
  bool certified = true;     ///< the cheap certificate (i), (ii) held (no erosion search)
  double forward = 0;        ///< fwd (>= 0) when overlapping, else the clearance
  double reverse = 0;        ///< rev when computed (overlapping and not certified), else <= forward
};

/// Roller in an outer ring B = {radius <= rho <= outer_radius, 0 <= z <= width} (Bore).
TwoSidedRing two_sided_bore(const Cylinder& roller, const Bore& bore, double outer_radius);

/// Roller in a cup B = {R(z) <= rho <= outer_radius, 0 <= z <= width} (Cup).
TwoSidedRing two_sided_cup(const Cylinder& roller, const Cup& cup, double outer_radius);

/// Roller end against a rib block B = {inner_radius <= rho <= outer_radius, -thickness <= l <= 0}
/// (l the height above the face; rho = inner_radius is where the rib joins the ring body, whose
/// raceway is another pair, so it is not a free surface of B).
TwoSidedRing two_sided_rib(const Cylinder& roller, const Rib& rib, double thickness);

/// The largest t in [0, hi] at which `at(t)` (a raceway.h solver on eroded parts) still meets
/// (distance <= 0, not the `apart` bound); the meeting is nonincreasing in t and true at 0. A
/// safeguarded Illinois iteration on the continuous distance, stopped when the bracket is below
/// `tol`. Returns the last t that met (hi when it meets at hi).
double erosion_root(const std::function<PairDistance(double)>& at, double hi, double tol);

/// The inner parallel body of a roller at depth t (empty, nullopt-like height <= 0, when t is too
/// large): radius - t sqrt(1 + k^2) at both (moved) ends, k = d radius / d z, ends moved in by t.
bool eroded_roller(const Cylinder& roller, double t, Cylinder* out);

}  // namespace interfere::bearing
