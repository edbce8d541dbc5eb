// Two-sided values of scarred rollers' rows (issue #27, "every solver equal to an independent dense
// reference; s(A, B) = s(B, A)"): docs/bearing.md, "Scarred rollers: two-sided rows".
//
// (1) A scarred roller in the outer ring's bore or a tapered bearing's cup. The row's one-sided
//     value (assembly_tapered_scars.h: mesh_in_conical_bore / roller_in_bore_by_columns) is
//     -r_f, r_f = max over K of g, K = A_s ∩ {0 <= z <= width} the scarred mesh's solid clipped to
//     the ring's width and g(x) = (rho - R(z)) / sqrt(1 + k^2) the meridian distance beyond the
//     raceway's line (k = 0: rho - R_o). ring_two_sided.h's argument for intact rollers uses only
//     that the roller is a closed solid and that the pushed point lies in K, so it holds for A_s:
//       rev <= r_f: a ring point q at depth t in A_s has the closed ball B(q, t) in A_s, so
//         p = q + t n (n the raceway's outward normal in q's meridian plane) is a point of A_s with
//         g(p) = g(q) + t >= t; p keeps q's z in a bore (so p in K); in a cup z moves by -k t /
//         sqrt(1 + k^2), and p in K needs the whole of A_s within the width (its vertices' z).
//       fwd <= r_f: a point of A_s in B lies in K and its depth in B's convex meridian polygon is
//         at most its distance g to the raceway's line; fwd = r_f when the witness p* (a vertex
//         of the clipped surface, a point of A_s with g(p*) = r_f) is at least r_f from the other
//         free edges' lines (side faces z = 0 and z = width, the outside rho = outer radius).
//     Then S = -max(fwd, rev) = -r_f: the row's value is the two-sided S.
//     Apart (d.distance > 0, path bore: the solvers' maximum G of g over every vertex of the mesh,
//     which lies within the width): the ring's meridian polygon lies in the half-plane g >= 0
//     beyond the raceway's line (extended past the width), and rotating a ring point into another
//     meridian plane never increases its distance, so every point x of A_s is at least -g(x) >= -G
//     from the ring (g is convex: its maximum over the solid is at a vertex). The witness's foot on
//     the line (point_b) is a ring point at distance -G when it lies within the width: then -G is
//     the Euclidean distance, the same in both directions. (The whole roller need not lie within
//     the width, unlike ring_two_sided.h's intact cup rows, whose solver maximises over K only.)
//
// (2) Two scarred rollers that are apart. When the caller's lower bound L (each mesh against the
//     other's grown intact solid, part_pair.h) is above the touch tolerance, the surfaces do not
//     meet; when also neither solid holds the other (the caller's containment test), the solids
//     are apart and S = s(A, B) = s(B, A) is their Euclidean distance: the smallest distance of a
//     triangle of A and a triangle of B, which the mesh engine computes (query/distance.h,
//     `distance`, its BVH branch and bound) on the triangles that can hold the closest pair: U, an
//     upper bound of the distance, is the distance from a point of A's surface to B's surface
//     (nearest_triangle_d2); a triangle of either roller is dropped when it lies farther than U
//     from the other's enclosing cylinder (which holds the other's solid): a lower bound of that
//     distance, max(min over its corners of n.x - R, -max z, min z - h) in the other's body frame
//     (rho >= n.x for the unit n across the axis toward the triangle's centroid; linear pieces
//     take their minimum at a corner). Then two small BVHs (B's corners in A's body frame). The
//     filter holds whatever L is (a closest pair lies within U of both rollers), and the engine's
//     exact triangle-triangle test reports surfaces that meet (`meeting`).
//
// (3) Two scarred rollers that come close: L <= tol, no exact solver (B must be intact). The
//     bracket [L, U*] of S (two_scarred_value): for any point p of A's surface S <= s(A, B) <=
//     sd_B(p), sd_B the signed distance to B's closed mesh (its size the nearest triangle's
//     distance, its sign exact ray parity, query/clash.h point_in_solid), and the same with the
//     roles exchanged; p: the bound's two witnesses, the points of each surface deepest in the
//     other's grown intact solid (where, away from a scar, the depth in the scarred solid differs
//     by the facets' sagitta). U* < -tol decides clash (a point of A's surface deep inside B: the
//     interiors overlap). Otherwise the engine of (2): surfaces that meet give S <= 0 (a common
//     point p has sd_B(p) = 0), so U* <= 0; surfaces that do not meet, with neither solid holding
//     the other (the centre test above), are apart and S is their distance (exact, now also below
//     the tolerance). [L, U*] decides when both ends give the same verdict (clash, contact).
#pragma once
#include <cstdint>
#include <optional>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/roller.h"

namespace interfere {
struct Model;
}

namespace interfere::bearing::detail {

/// (1): whether the one-sided ring value `d` of a scarred roller (path bore, d.point_a its witness,
/// d.point_b its foot on the raceway's line) is the two-sided S (overlapping) or the Euclidean
/// distance (apart, d.distance > 0), for a ring of raceway line R(z) = R0 + k z over
/// 0 <= z <= width (z along the unit `axis` from `base`) and outside radius `outer_radius`.
/// `mesh`/`pose`: the roller's closed mesh, needed for a cup (k != 0: every vertex within the width).
bool scarred_ring_two_sided(const PairDistance& d, const Vec3& base, const Vec3& axis, double k, double width,
                            double outer_radius, const TriMesh& mesh, const Transform& pose);

/// (2): the Euclidean distance of two scarred rollers' closed meshes (ra posed by pa; rb posed by
/// pb, sb its body-frame model), for surfaces the caller certified apart with neither solid inside
/// the other. `on_a`: a point of A's surface (world frame), e.g. the lower bound's witness (only
/// the work depends on it). point_a on A's surface, point_b on B's (world). `meeting`: the engine
/// found the surfaces meeting (distance 0, point_a = point_b a common point; the caller keeps its
/// bound). nullopt when no point of B's surface was found (empty mesh).
struct MeshesApart {
  double distance = 0;
  Vec3 point_a, point_b;
  std::uint32_t evaluated = 0;  ///< B's triangles handed to the engine
  bool meeting = false;
};
std::optional<MeshesApart> scarred_meshes_apart(const Roller& ra, const Transform& pa,
                                                const Roller& rb, const Model& sb, const Transform& pb,
                                                const Vec3& on_a);

/// (3): two scarred rollers A and B (ScenePart with mesh, tree, solid and pose each), `tol` the
/// pair's touch tolerance. The caller's verdict: `contained` 1 clash, -1 undecided; `exact` the
/// value S (the meshes' distance); `upper_known` false: only S >= lower (L > tol and the distance
/// not found), else the bracket lower <= S <= upper. The witnesses (world) are the reported
/// value's: L's (the deeper of the two bounds, `reverse` when B's), the distance's, or U*'s (a
/// point of one surface and the nearest point of the other's; `reverse`: a point of B's surface).
struct TwoScarredValue {
  double lower = 0;
  double upper = 0;  ///< = lower when !upper_known
  Vec3 point_a, point_b;
  bool reverse = false;
  bool exact = false;
  bool upper_known = false;
  int contained = 0;  ///< one solid holds the other: 1, -1 every ray degenerate, 0 not (or not tested)
  std::uint32_t evaluated = 0;
};
TwoScarredValue two_scarred_value(const ScenePart& a, const ScenePart& b, double tol);

}  // namespace interfere::bearing::detail
