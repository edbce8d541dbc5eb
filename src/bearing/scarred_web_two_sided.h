// The cage-web rows of scarred rollers, two-sided where certified (issue #27: "s(A, B) = s(B, A)";
// docs/bearing.md, "Scarred rollers: two-sided rows"; the paper's §3.3 Step 3 checks both parts,
// Jia & Zheng 2019).
//
// The solid. As for the rib (scarred_rib_two_sided.h), assembly_pairs.cpp measures a scarred roller
// against a web W by pieces: the intact end pieces E0 = [0, z0], E1 = [z1, L] and the middle bounded
// by the intact piece grown by the scar's raise. The row is exact when the ends decide; its value
// v = min over the end pieces of web_distance (the web's deepest point in the piece, on the web's
// triangles) is then the one-sided value of A' = E0 ∪ M_s ∪ E1 (M_s the scarred mesh's solid between
// z0 and z1), the solid these rows define. Apart (v > 0) it is the Euclidean distance (each piece's
// value is, the middle's bound is above): two-sided already.
//
// Overlapping (v <= 0), with S(X, W) = -max(fwd, rev) (fwd = max over X of depth_W, rev = max over W
// of depth_X; ring_two_sided.h):
//   S(A', W) <= v: the best end piece E_k lies in A', so depth_A' >= depth_E_k everywhere and
//     rev(A', W) >= max over W's surface of depth_E_k = -v.
//   S(C, W) <= S(A', W) for any solid C holding A': fwd and rev only grow with the solid (depth_X is
//     the signed distance to X, monotone in X). C = the whole intact roller grown radially by the
//     raise (its radii + raise; the intact roller itself for inward scars) holds E0, E1 and the
//     grown middle, so A'.
// So when the intact rows' own two-sided S of C (web_distance, then two_sided_web: exact, the
// intact rollers' code) is not below v (to 2^-44 of the scale), S(A', W) = v: `two_sided` 1 with
// the row's value unchanged. It fails where C reaches deeper than the ends, e.g. the web pressing
// the scar window of a raised scar, or where the roller reaches deeper into the web (fwd) than the
// web into the roller (the one-sided v): then S(A', W) < v and the row is not S. That case is
// refused first at a cost of a few dot products: fwd(A') >= F(x) = min_j (d_j - n_j.x) (the depth
// in the convex web, its six face planes) at each end piece's rim point lowest along each face
// normal n_j; F(x) above -v proves S(A') < v. Otherwise one more intact web row (S(C)); only
// overlapping rows that the ends decide get here.
#pragma once
#include <span>

#include "interfere/bearing/assembly.h"

namespace interfere::bearing::detail {

/// Whether the overlapping value `v` (<= 0) of a scarred roller's web row, decided by its intact
/// end pieces `ends`, is the two-sided S of A' and the web (above). `roller`: the posed intact
/// roller; `raise`: Roller::raise; `web_mesh`, `web`, `cage_pose`: the web as solve_one measures it.
bool scarred_web_two_sided(double v, const Cylinder& roller, double raise, std::span<const Cylinder> ends,
                           const TriMesh& web_mesh, const CageWeb& web, const Transform& cage_pose);

}  // namespace interfere::bearing::detail
