// Deciding a pair of bearing parts in the verdict model (query/verdict.h; issue #23, items 5 and
// 13): the quantity is s(A, B) of analytic.h (the paper's maximum interference distance, Jia &
// Zheng 2019, §3), computed by the exact solver the pair belongs to, and its verdict:
//
//   clash      s < -tol          (A's solid reaches into B's interior: the roller penetrates)
//   contact    |s| <= tol        (touching: the solvers' rounding cannot tell the sign)
//   clearance  tol < s < c       (apart, closer than the requested clearance c > 0)
//   clear      s >= c (and s > tol)
//   undecided  no exact solver for the pair, or a containment test was degenerate
//
// tol = touch_tolerance(A, B) = 2^-36 (~1.5e-11) times the coordinate scale of the pair: the
// closed forms are exact to a few ulps of it and the golden-section paths converge to about
// 4e-14 of their interval (docs/bearing.md, "Verdicts").
//
// Parts of one scene (simulation.h): part 2k is the roller of pair k, part 2k + 1 its partner.
// decide_part_pair decides any two of them, not only a roller and its own partner:
//   * roller against any partner: the roller is A, the partner B (scarred rollers: the scarred
//     solver on the triangle surface, else the standard solver);
//   * two partners, or two rollers of which one is an intact (untapered, unscarred) cylinder: the
//     intact one is B, the standard (or scarred) solver as above;
//   * a tapered part and no scarred one (two tapered rollers, a tapered roller against a partner or
//     an intact roller): the two-sided S of cone_pair_distance both ways (raceway.h; exact), the
//     tapered assemblies' intact roller-cone and roller-roller value (issue #27);
//   * a scarred roller against an intact tapered roller, or a scarred tapered roller against an
//     intact cylinder: the scarred solver with B the intact frustum (scarred.h), exact forward,
//     B's depth into A bracketed through A's grown intact frustum (assembly_tapered_scars.h,
//     scarred_against_frustum: the tapered assemblies' scarred rows, the same function);
//   * two scarred rollers: no exact solver exists (B must be intact); each mesh is solved against
//     the other's intact frustum or cylinder grown by its raise (assembly_tapered_scars.h,
//     grown_roller_solid), the smaller a lower bound of S (the tapered assemblies' two scarred
//     neighbours' bound); when that is above the touch tolerance and neither solid holds the
//     other's centre (mesh_containment; inside: clash) the solids are apart and the value is their
//     exact Euclidean distance, the smallest triangle-triangle distance by the mesh engine
//     (src/bearing/scarred_two_sided.h; solver scarred, two_sided_exact; issue #27). When the bound
//     is not above the tolerance: the bracket [distance_lower, distance] = [L, U*] (solver bound),
//     U* the signed distance of a point of one surface to the other's closed mesh (the bound's
//     witnesses; 0 when the surfaces meet), or the meshes' exact distance when they turn out apart
//     (scarred_two_sided.h (3)); the verdict when both ends agree (a clash when U* < -tol), else
//     undecided.
// A triangle-surface solver reports the minimum over A's surface; when that is > 0, B could still
// lie wholly inside A's solid: mesh_containment decides it (B's centre by exact ray parity).
//
// Two-sided (issue #27, "the depth is one-sided"; the paper's §3.3 Step 3 checks all four end
// circles, i.e. both parts against the other): the pair's maximum interference distance is
//     S(A, B) = min( s(A, B), s(B, A) ) = S(B, A)
// (the deeper of A's deepest point in B and B's deepest point in A; when the solids are apart both
// one-sided values are their Euclidean distance, so S = s). decide_part_pair(x, y) and
// decide_part_pair(y, x) run the same computation (roles by part type, ties broken by a canonical
// order of the parts), so the value, witnesses and verdict are bitwise the same, only `swapped`
// differs. s(B, A) is exact (the standard solver, or cone_pair_distance, with the roles exchanged)
// when A is an intact cylinder or frustum. When A is scarred no exact solver of B's depth into A
// exists (A must then be B of a solver); A lies in its intact solid grown by a raised scar's raise
// (Roller::raise) A0 — its enclosing cylinder, or its grown frustum when a frustum is involved — so
// s(B, A) >= s(B, A0): when that bound is not below s(A, B), S = s(A, B) exactly, else S is
// bracketed by [distance_lower, distance] and `two_sided_exact` is false (the verdict is decided
// only when both ends give the same one; else undecided).
#pragma once
#include <cstdint>
#include <limits>
#include <string>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/roller.h"
#include "interfere/query/verdict.h"

namespace interfere {
struct Model;
}

namespace interfere::bearing {

/// The touch tolerance of a pair: 2^-36 times the largest coordinate magnitude of either part
/// (centre coordinates plus height and radius).
double touch_tolerance(const Cylinder& a, const Cylinder& b);

/// The verdict of s (see above). `clearance` <= 0: no clearance verdict.
Verdict distance_verdict(double s, double tolerance, double clearance);

/// The verdict of a bracket [lo, hi] of S: the verdict both ends give, else `undecided`.
Verdict bracket_verdict(double lo, double hi, double tolerance, double clearance);

/// One part of a scene.
struct ScenePart {
  /// Its solid; a scarred roller: its intact cylinder, which its solid lies in when the scar is
  /// inward; a raised scar reaches out by mesh->raise (issue #27), and the solid lies in the
  /// cylinder of radius max_radius() + mesh->raise.
  Cylinder cylinder;
  bool partner = false;          ///< a partner (always an intact cylinder)
  const Roller* mesh = nullptr;  ///< a scarred roller's triangle surface (body frame), else null
  const RollerQuadtree* tree = nullptr;  ///< its quadtree (with mesh)
  const Model* solid = nullptr;  ///< its closed mesh as a Model (body frame), for containment
  Transform pose;                ///< body -> world (with mesh)

  /// An intact (untapered) cylinder: can be B of the solvers.
  bool intact() const { return partner || (mesh == nullptr && !cylinder.tapered()); }
};

/// For a scarred roller A (mesh, posed) whose surface minimum s > 0 against B: whether B lies
/// inside A's solid (then the pair is a clash). 1 inside, 0 outside, -1 undecided (no solid given,
/// or every ray direction degenerate).
int mesh_containment(const ScenePart& a, const Cylinder& b);

enum class PartPairSolver : std::uint8_t {
  standard,  ///< analytic.h on A's cylinder
  scarred,   ///< scarred.h on A's triangle surface
  bound,     ///< two scarred rollers: a lower bound, or the bracket [distance_lower, distance] (above)
};
const char* part_pair_solver_name(PartPairSolver s);

struct PartPairResult {
  double distance =
      0;  ///< S(A, B) (two-sided, above); `bound`: a lower bound where distance_lower equals it, else the upper end
  Vec3 point_a,
      point_b;  ///< witnesses (world frame), on A and on B's (or its enclosing cylinder's) boundary
  bool swapped = false;  ///< A is the second part given (y), B the first
  /// false: S is only bracketed, distance_lower <= S <= distance (see above)
  bool two_sided_exact = true;
  double distance_lower = 0;  ///< equals distance when two_sided_exact
  bool reverse = false;  ///< B's depth into A decided S (point_a, point_b still on A, on B)
  PartPairSolver solver = PartPairSolver::standard;
  AnalyticPath path = AnalyticPath::side;  ///< standard solver path
  std::uint32_t evaluated = 0;             ///< triangles evaluated exactly (scarred solver)
  Verdict verdict = Verdict::clear;
  std::string reason;  ///< for undecided: why
};

/// S(a, b) = min(s(a, b), s(b, a)) for two intact (untapered) cylinders with the standard solver
/// both ways (issue #27): the value does not depend on the order of the arguments (the same two
/// numbers are compared); point_a lies on a, point_b on b; `path` is that of the direction taken
/// (the forward one on a tie). For the simulation's own roller-partner rows.
PairDistance two_sided_cylinder_distance(const Cylinder& a, const Cylinder& b);

/// The two-sided value S = min(s(A, B), s(B, A)) of an intact untapered roller A and an untapered
/// partner B, as the simulation's rows use it (issue #27): the value of two_sided_cylinder_distance
/// (above; bitwise when the reverse is computed or skipped by the bound, to rounding when apart),
/// the reverse direction computed only when it can be the smaller one. Skipped when A and B are
/// apart (s(A, B) > 0: two convex solids at their Euclidean distance, which is symmetric) or when
/// intact_reverse_tangent_bound or intact_reverse_lower_bound is not below s(A, B).
PairDistance intact_row_distance(const Cylinder& a, const Cylinder& b);

/// A lower bound of s(B, A) for untapered A and B (-inf when their axes are more than 60 degrees
/// apart): planes across A's axis, sd_A >= max(rho_A - r, -z, z - h) on them, rho_A at least the
/// distance from A's axis to the section of B's infinite cylinder (convex in z: secants of exact
/// samples extended below it); cylinder_two_sided.cpp.
double intact_reverse_lower_bound(const Cylinder& a, const Cylinder& b);

/// The same kind of lower bound of s(B, A) (untapered A and B, axes within 60 degrees, else -inf),
/// from tangents of the section distance instead of secants of exact samples: any supporting line
/// of B's elliptic section gives a line below it (cylinder_two_sided.cpp), no root finding; refined
/// (at most two more tangents) while below `target`. Issue #27: intact_row_distance tries it first.
double intact_reverse_tangent_bound(const Cylinder& a, const Cylinder& b,
                                    double target = std::numeric_limits<double>::infinity());

/// S(a, b) = min(s(a, b), s(b, a)) for two intact cylinders or cone frustums with
/// cone_pair_distance both ways (raceway.h); the reverse skipped when s(a, b) > 0 (apart: the
/// Euclidean distance both ways). point_a on a, point_b on b; `reverse` (optional) set when
/// s(b, a) is the smaller one. The tapered assemblies' intact rows and decide_part_pair.
PairDistance two_sided_frustum_distance(const Cylinder& a, const Cylinder& b, bool* reverse = nullptr);

/// What a caller reads of a bracket's lower end (issue #27, speed).
enum class LowerEnd : std::uint8_t {
  value,     ///< distance_lower = s(B, A0) whenever that is below s(A, B) (above)
  /// Only what the verdict and two_sided_exact need (the assemblies' rows, which carry no lower
  /// end): when a point of B is certified deeper in A0 than min(s(A, B), -tol) by a margin far above
  /// the reverse solver's rounding, s(B, A0) would be below both (two_sided_exact false, the verdict
  /// that of the bracket either way), and s(B, A0) is not computed: distance_lower is then the
  /// looser -min(R0, h0 / 2) (no point is deeper in A0 than its inradius). Everything else is the
  /// same as with `value`, bit for bit.
  decision,
};

/// Decides any two distinct parts of a scene (above). Deterministic (no temporal state).
/// `forward` (optional): cylinder_pair_distance(x.cylinder, y.cylinder) when the caller already
/// has it (issue #27, speed: the assemblies' intact roller-inner rows compute it first to find apart
/// pairs); used only where this function would make that same call (x in the role of A), so the
/// result is bitwise the same with or without it. `lower`: above.
PartPairResult decide_part_pair(const ScenePart& x, const ScenePart& y, double clearance,
                                const PairDistance* forward = nullptr, LowerEnd lower = LowerEnd::value);

}  // namespace interfere::bearing
