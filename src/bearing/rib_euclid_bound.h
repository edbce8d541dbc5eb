// A lower bound of the Euclidean distance of a roller and a rib block, for the rib rows that are not
// two-sided (issue #27; docs/bearing.md, "Limitations"). Such a row's value d is the roller's height
// over the rib's annulus (roller_rib_distance, raceway.h): an upper bound of the Euclidean distance E
// (the witness's foot on the annulus is a rib point at d), but a tilted roller's end face reaching
// over the rib's top edge is nearer that edge (E ~ d cos(theta)), so a verdict taken from d alone
// could say `clear` (or `clearance`) for parts within the clearance (or touching). The row keeps d;
// its verdict is the one both ends of the bracket [lower, d] give, else `undecided`.
//
// B = {r_i <= rho <= r_o, -T <= l <= 0} (rho the distance to the ring axis, l the height over the face
// plane, T the rib's width) lies in the convex solid cylinder Q = {rho <= r_o, -T <= l <= 0}. For a
// convex roller C (a cylinder or frustum, or one holding the row's solid: a scarred roller's intact
// cylinder grown by its raise holds A' = E0 u M_s u E1, scarred_rib_two_sided.h) and ANY unit w,
// p in C and q in Q give |p - q| >= w.(p - q), so
//     E(A', B) >= E(C, Q) >= gap(w) = min over C of w.x - max over Q of w.x
// (weak duality of the separating-hyperplane theorem; equality at the best w when C and Q are apart).
// Both terms are closed forms: min over C of w.x is the lower of its two rims' (a frustum is the
// convex hull of its rims), c_k.w - r_k |w - (w.d) d|; max over Q of w.x = o.w + r_o |w_perp| +
// max(0, -T w.n) (w_perp: w across the ring axis; n the face normal, o the face centre). The bound
// is the best gap over, by level:
//   0: w = n            (the roller's lowest height over the face plane, detail::lowest_height's),
//   1: w = the roller's axis, turned toward the rib's side (its end face's plane against the top
//      edge: E itself when the edge's foot on that plane lies in the end disk, the case of the review),
//   2: w = (p - q)/|p - q| for cylinder_pair_distance(C, Q)'s witnesses (analytic.h; a few
//      microseconds): any w is sound, so the search's accuracy is not relied on,
// less a rounding margin (2^-40 of the pair's scale, far above the closed forms' rounding). Not tight
// where B's inner edge (rho = r_i) is the nearest: Q holds the ring body's side of it there.
#pragma once
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/raceway.h"

namespace interfere::bearing::detail {

/// gap(w) above for the rib block of width `thickness` and a unit w (no margin): <= E(c, B).
double rib_support_gap(const Cylinder& c, const Rib& rib, double thickness, const Vec3& w);

/// A lower bound of E(c, B) (and of E for any solid inside c): the best gap(w) of the levels 0..`level`
/// above, less the rounding margin. May be <= 0.
double rib_euclid_lower(const Cylinder& c, const Rib& rib, double thickness, int level);

/// A rib row whose value is not S (not exact and two-sided): a `clear` or `clearance` verdict is
/// kept only when E's lower bound (the levels tried in turn, cheapest first) gives it too, else the
/// row is `undecided`; its other fields are unchanged. The row's roller solid lies in `roller` grown
/// radially by `raise` (a scarred roller's Roller::raise; 0 for an intact roller). `apart_bound`: a
/// value on roller_rib_distance's `apart` path is a lower bound of E for the row's whole solid (an
/// intact roller; not a scarred roller's piece): the row is left as it is.
void rib_euclid_verdict(AssemblyPairResult& row, const Cylinder& roller, double raise, const Rib& rib, double thickness,
                        double clearance, double tol, bool apart_bound);

/// A rib row that is `undecided` or whose value is only a lower bound not saying `clear` (solver
/// `bound`: the scarred middle's enclosing piece decides; roller_rib_distance's `apart` path): E's
/// lower bound above (the levels in turn) is a lower bound of S too (apart solids: S = E), so when it
/// says `clear` the row is clear (a row that is not exact takes it as its value when larger: still a
/// lower bound); else the row is `undecided`. `roller` and `raise` as above.
void rib_euclid_decide_clear(AssemblyPairResult& row, const Cylinder& roller, double raise, const Rib& rib,
                             double thickness, double clearance, double tol);

/// rib_euclid_verdict where it can change the row (inline: the other rows pay a test or two).
inline void rib_euclid_row(AssemblyPairResult& row, const Cylinder& roller, double raise, const Rib& rib,
                           double thickness, double clearance, double tol, bool apart_bound) {
  if (row.exact && row.two_sided) return;
  if (row.verdict == Verdict::undecided) return rib_euclid_decide_clear(row, roller, raise, rib, thickness, clearance, tol);
  if (row.verdict != Verdict::clear && row.verdict != Verdict::clearance) return;
  rib_euclid_verdict(row, roller, raise, rib, thickness, clearance, tol, apart_bound);
}

}  // namespace interfere::bearing::detail
