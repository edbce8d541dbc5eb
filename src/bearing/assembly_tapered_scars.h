// Scarred rollers of tapered bearings (issue #27, deliverable 2: scars on any part): the values of
// a scarred roller's mesh against the intact frustums of a tapered bearing (its cone raceway, an
// intact neighbouring tapered roller) and inside its cup, for the assembly's rows
// (assembly_pairs.cpp). The scarred solver (scarred.h) takes the frustum B exactly; the reverse
// direction (B's depth into the scarred roller) only has a bound, as in part_pair.h.
#pragma once
#include <optional>
#include <cstdint>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/cylinder.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/roller.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {
struct Model;
}

namespace interfere::bearing::detail {

/// The intact solid holding a scarred roller's mesh: its frustum (or cylinder) grown radially by
/// the scar's raise (Roller::raise; inward scars and the inscribed facets lie inside the intact one).
Cylinder grown_roller_solid(const Cylinder& intact, double raise);

/// S of a scarred roller A (mesh, quadtree, closed solid, pose; `intact` its posed intact frustum)
/// and an intact frustum or cylinder B (part_pair.h's two-sided rule, B a frustum):
///   s(A, B) = min over A's triangle surface of sd_B (scarred.h, exact);
///   when that is > tol the surfaces are apart, and B lies inside A's solid (a clash) or outside
///   (then S = s(A, B), the Euclidean distance): decided by mesh_containment (part_pair.h) with B's
///   inscribed cylinder of its smaller radius (its centre is B's, at a smaller depth);
///   else s(B, A) >= s(B, A0), A0 = grown_roller_solid (cone_pair_distance, raceway.h): when that
///   bound is not below s(A, B), S = s(A, B) exactly, else S lies in [lower, distance] (exact false).
struct ScarredFrustumValue {
  double distance = 0;  ///< S, or the upper end of its bracket
  double lower = 0;     ///< the bracket's lower end (== distance when exact)
  Vec3 point_a, point_b;  ///< on A (the scarred roller), on B
  bool exact = true;
  int contained = 0;    ///< 1: B inside A's solid (clash), -1: undecided containment, 0: no
  std::uint32_t evaluated = 0;  ///< triangles the scarred solver evaluated exactly
};
ScarredFrustumValue scarred_against_frustum(const Roller& mesh, const RollerQuadtree& tree, const Model* solid,
                                            const Transform& pose, const Cylinder& intact, const Cylinder& b,
                                            double tol);

/// A closed mesh (posed by `pose`) inside a conical bore (a cylindrical bore when k = 0): material
/// rho >= R0 + k z for z in [0, width] (z along the unit `axis` from `base`). With g(x) = (rho -
/// R(z)) / sqrt(1 + k^2) (convex: its maximum over a triangle clipped to the slab lies at a vertex
/// of the clipped polygon, a mesh vertex in the slab or an edge's crossing of a side face):
///   s = -max over the mesh clipped to the width of g   (path `bore`; exact for the mesh, one-sided)
/// when the whole mesh's maximiser lies in the width or the clipped maximum reaches the raceway;
/// else max(-max over the whole mesh of g, 0), a lower bound of the distance (path `apart`).
/// found = false when no part of the mesh lies in the width.
PairDistance mesh_in_conical_bore(const TriMesh& mesh, const Transform& pose, const Vec3& base, const Vec3& axis,
                                  double R0, double k, double width, bool& found);

/// mesh_in_conical_bore for a cylindrical bore (k = 0) and a meshed roller (roller.h's vertex
/// layout), the same value and witness (issue #27, speed): a side column i (the vertices at angle
/// theta_i) lies at x = t + z u + r w_i, 0 <= z <= h, 0 <= r <= r_max (the largest radius plus the
/// raise), so with q(z) the projection of t + z u - base across the bore axis,
///   rho^2 = |q(z)|^2 + 2 r q(z).w_i + r^2 |P w_i|^2
///        <= max(|q(0)|^2, |q(h)|^2) + max(0, 2 r_max max(q(0).w_i, q(h).w_i) + r_max^2 |P w_i|^2)
/// (convex in r and in z, linear q.w): a column whose bound is below the largest rho^2 found (by a
/// relative margin far above rounding) holds no maximiser and is skipped; within a column the same
/// bound at each vertex's own height z_j (q(z_j) instead of the maximum over z) skips the vertices
/// below the best so far, unread (issue #27, speed: a column's vertices are a cache line apart).
/// The vertices compared are those mesh_in_conical_bore compares (rho^2, ties to the lowest
/// index), in any order (the maxima do not depend on it). nullopt when the
/// mesh does not have the roller's layout, `scar_height` (the largest |displacement|,
/// AssemblyPart::scar_height) is not below the smallest radius (r >= 0 is needed), or the
/// maximiser lies outside the width (the caller then runs mesh_in_conical_bore).
std::optional<PairDistance> roller_in_bore_by_columns(const Roller& roller, const Transform& pose, const Vec3& base,
                                                      const Vec3& axis, double R0, double width, double scar_height);

}  // namespace interfere::bearing::detail
