// The rib rows of scarred rollers, two-sided (issue #27: "s(A, B) = s(B, A)"; docs/bearing.md,
// "Scarred rollers: two-sided rows"; the paper's §3.3 Step 3 checks both parts, Jia & Zheng 2019).
//
// The solid. assembly_pairs.cpp measures a scarred roller against a rib by pieces: the scar lies in
// the axial window [z0, z1]; the end pieces E0 = [0, z0] and E1 = [z1, L] are the intact cylinders
// and the middle is bounded by the intact cylinder grown by the scar's raise, G ⊇ M_s (M_s the
// scarred mesh's solid between z0 and z1). The row is exact only when the ends decide (the middle's
// bound is above their value); its value v is then, exactly, min over K of l for the solid
//     A' = E0 ∪ M_s ∪ E1,   K = A' ∩ {r_i <= rho <= r_o},   l = (x - face centre).n
// (M_s contributes nothing below v: G's value, a lower bound of M_s's, is above; an end piece left
// unsolved had a lower bound above v). A' is the scarred roller with its intact ends as the cylinders
// they are made from (the faceted mesh's ends are inscribed prisms, within the sagitta r (1 -
// cos(pi / n)) of them): the solid these rows define, and the one certified here.
//
// The rib block B = {r_i <= rho <= r_o, -T <= l <= 0} (rho = r_i joins the ring body, not a free
// surface; ring_two_sided.h). With depth_X the distance to X's free boundary,
// fwd = max over A' of depth_B, rev = max over B of depth_A', S = -max(fwd, rev) (overlapping):
//   rev <= r_f = -v: a rib point q at depth t in A' has the closed ball B(q, t) in A'; the face normal
//     n is the ring's axis (+-), so p = q - t n lies in the ball (in A'), keeps q's rho (in K) and has
//     l(p) = l(q) - t <= -t: v <= -t. (Only that A' is a closed solid is used: no convexity.)
//   fwd <= r_f: a point of A' in B lies in K, its depth is at most -l <= r_f.
//   fwd = r_f when the witness p* (on an end piece's boundary, in A', l(p*) = v) is at least r_f from
//     B's other free surfaces: r_o - rho(p*) >= r_f and T - r_f >= r_f (its depth in B, a meridian
//     rectangle, is the smallest distance to the free edges' lines).
// Then S = -r_f = v. Apart (v > 0, not roller_rib_distance's `apart` bound): every point of A'
// lies at or above the lowest point of the pieces E0, E1, G (a rim point, closed form); when that is
// not below v (to 2^-44 of the scale, the intact rows' rule in ring_two_sided.cpp) every point of A' is
// at least v from the half-space l <= 0 that holds B, and p*'s foot p* - v n (same rho, on the
// annulus) is a rib point at v: v is the Euclidean distance, the same both ways. Otherwise (a witness
// near the rib's top edge, a thick reach, the roller's lowest point off the annulus) the row stays
// one-sided with the same value.
#pragma once
#include <span>

#include "interfere/bearing/raceway.h"

namespace interfere::bearing::detail {

/// Whether a scarred roller's rib row `d` (the end pieces' value, which decides: above) is the
/// two-sided S of A' and the rib block of thickness `thickness` (overlapping) or their Euclidean
/// distance (apart). `ends` (the intact end cylinders) and `middle` (the grown middle), pieces of one
/// axis, hold A'; used only when apart (2^-44 of the scale: the middle's centre, length and radius). O(1) per row (no search). false for a bound (path `apart`).
bool scarred_rib_two_sided(const PairDistance& d, const Rib& rib, double thickness, std::span<const Cylinder> ends,
                           const Cylinder& middle);

}  // namespace interfere::bearing::detail
