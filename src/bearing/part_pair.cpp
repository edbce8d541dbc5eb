// Deciding any pair of bearing parts in the verdict model (part_pair.h; issue #23, items 5 and 13),
// with the solvers of Jia & Zheng 2019: the standard solver (§3.1, analytic.h) and the scarred
// solver (§3.2, scarred.h).
#include "interfere/bearing/part_pair.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "assembly_tapered_scars.h"
#include "scarred_two_sided.h"
#include "interfere/bearing/raceway.h"
#include "interfere/bearing/scarred.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere::bearing {
namespace {

double scale(const Cylinder& c) {
  const Vec3 m = c.center();
  return std::max({std::fabs(m.x), std::fabs(m.y), std::fabs(m.z)}) + c.height + c.max_radius();
}

/// The intact cylinder enclosing a roller (a frustum lies in the cylinder of its larger radius; a
/// scarred surface lies in its intact cylinder grown by its raise: inward scars and facets lie
/// inside it, a raised scar (issue #27) reaches out by at most `raise`).
Cylinder enclosing(const Cylinder& c, double raise = 0) {
  Cylinder out = c;
  out.radius = c.max_radius() + raise;
  out.top_radius = -1;
  return out;
}
Cylinder enclosing(const ScenePart& p) { return enclosing(p.cylinder, p.mesh ? p.mesh->raise : 0.0); }

/// A against the intact cylinder b: the scarred solver on A's surface, else the standard solver.
/// `intact` (optional): set to s(A's cylinder, b), the scarred solver's hint.
PartPairResult solve(const ScenePart& a, const Cylinder& b, const PairDistance* known = nullptr,
                     PairDistance* intact = nullptr) {
  PartPairResult out;
  const PairDistance pd = known ? *known : cylinder_pair_distance(a.cylinder, b);  // (known: that same call's result)
  if (intact) *intact = pd;
  out.path = pd.path;
  if (a.mesh == nullptr) {
    out.distance = pd.distance, out.point_a = pd.point_a, out.point_b = pd.point_b;
    return out;
  }
  // no temporal state: a fresh solver, hinted by the intact cylinder's witness (the value does not
  // depend on the hint)
  ScarredSolver solver(a.mesh, a.tree);
  const MeshPairResult mr = solver.solve(a.pose, b, pd.point_a);
  out.distance = mr.distance, out.point_a = mr.point_a, out.point_b = mr.point_b;
  out.solver = PartPairSolver::scarred, out.evaluated = mr.evaluated;
  return out;
}

}  // namespace

double touch_tolerance(const Cylinder& a, const Cylinder& b) {
  return 0x1p-36 * std::max(scale(a), scale(b));
}

Verdict distance_verdict(double s, double tolerance, double clearance) {
  if (s < -tolerance) return Verdict::clash;
  if (s <= tolerance) return Verdict::contact;
  if (clearance > 0 && s < clearance) return Verdict::clearance;
  return Verdict::clear;
}

int mesh_containment(const ScenePart& a, const Cylinder& b) {
  // B does not meet A's surface, so B is wholly inside A's solid or wholly outside it: one point
  // decides, B's centre. It lies at depth min(R, h/2) in B, hence at least that far from A's
  // surface, and A's solid lies in its enclosing cylinder (grown by a raised scar's raise): a
  // centre outside that cylinder (by more than half that depth, far beyond rounding) is outside A.
  const Vec3 c = b.center();
  const double depth = std::min(b.radius, 0.5 * b.height);
  if (point_signed_distance(enclosing(a), c) > -0.5 * depth) return 0;
  if (a.solid == nullptr) return -1;
  const Transform& T = a.pose;  // world -> body: R^T (c - t)
  const Vec3 w = c - T.t;
  const Vec3 body{T.r[0][0] * w.x + T.r[1][0] * w.y + T.r[2][0] * w.z,
                  T.r[0][1] * w.x + T.r[1][1] * w.y + T.r[2][1] * w.z,
                  T.r[0][2] * w.x + T.r[1][2] * w.y + T.r[2][2] * w.z};
  return point_in_solid(*a.solid, body);
}

const char* part_pair_solver_name(PartPairSolver s) {
  switch (s) {
    case PartPairSolver::standard:
      return "standard";
    case PartPairSolver::scarred:
      return "scarred";
    case PartPairSolver::bound:
      return "bound";
  }
  return "?";
}

namespace {

/// A canonical order of parts, so that the roles of two parts of the same kind do not depend on
/// the order they are given in (S(A, B) = S(B, A) bitwise).
bool canonical_less(const ScenePart& x, const ScenePart& y) {
  const Cylinder& a = x.cylinder;
  const Cylinder& b = y.cylinder;
  const double ka[] = {a.base.x, a.base.y, a.base.z, a.axis.x, a.axis.y, a.axis.z, a.height, a.radius, a.top()};
  const double kb[] = {b.base.x, b.base.y, b.base.z, b.axis.x, b.axis.y, b.axis.z, b.height, b.radius, b.top()};
  for (int k = 0; k < 9; ++k)
    if (ka[k] != kb[k]) return ka[k] < kb[k];
  return std::less<const void*>()(x.mesh, y.mesh);  // same solid: either order gives the same value
}

}  // namespace

Verdict bracket_verdict(double lo, double hi, double tol, double clearance) {
  const Verdict vh = distance_verdict(hi, tol, clearance);
  return distance_verdict(lo, tol, clearance) == vh ? vh : Verdict::undecided;
}

PairDistance two_sided_frustum_distance(const Cylinder& a, const Cylinder& b, bool* reverse) {
  if (reverse) *reverse = false;
  const PairDistance f = cone_pair_distance(a, b);
  if (f.distance > 0) return f;  // apart: both one-sided values are the Euclidean distance
  PairDistance r = cone_pair_distance(b, a);
  if (f.distance <= r.distance) return f;
  std::swap(r.point_a, r.point_b);
  if (reverse) *reverse = true;
  return r;
}

namespace {

/// A scarred roller A against an intact frustum (or cylinder) B, as the assemblies' tapered rows
/// (assembly_tapered_scars.h, issue #27): the scarred solver's exact s(A, B), B's depth into A
/// bracketed through A's grown intact frustum, containment of B in A's solid when apart.
PartPairResult scarred_frustum_pair(const ScenePart& a, const ScenePart& b, bool swapped, double clearance) {
  const double tol = touch_tolerance(a.cylinder, b.cylinder);
  const detail::ScarredFrustumValue v =
      detail::scarred_against_frustum(*a.mesh, *a.tree, a.solid, a.pose, a.cylinder, b.cylinder, tol);
  PartPairResult out;
  out.swapped = swapped;
  out.solver = PartPairSolver::scarred;
  out.distance = v.distance, out.distance_lower = v.lower;
  out.point_a = v.point_a, out.point_b = v.point_b;
  out.two_sided_exact = v.exact;
  out.evaluated = v.evaluated;
  if (v.contained == 1) {
    out.verdict = Verdict::clash;
  } else if (v.contained < 0) {
    out.verdict = Verdict::undecided;
    out.reason = "whether the partner lies inside the scarred roller: every ray direction was degenerate";
  } else {
    out.verdict = bracket_verdict(v.lower, v.distance, tol, clearance);
    if (out.verdict == Verdict::undecided)
      out.reason =
          "two-sided depth: the frustum's depth into the scarred roller is only bounded (by its grown "
          "intact frustum), and the bounds give different verdicts";
  }
  return out;
}

/// Two scarred rollers (part_pair.h): no exact solver (each is B of the other's solver only through
/// its grown intact solid), so S >= L = min(s(A mesh, B0), s(B mesh, A0)), A0 and B0 the intact
/// frustums (or cylinders) grown by their raises (assembly_tapered_scars.h, grown_roller_solid): the
/// lower bound the tapered assemblies take for two scarred neighbours. Clear when that is clear and
/// neither solid holds the other (a grown solid apart from the other's surface lies wholly inside
/// that solid or outside it: mesh_containment of its inscribed cylinder's centre; inside is a
/// clash); apart, the meshes' exact distance. Below the tolerance, the bracket [L, U*] of
/// scarred_two_sided.h (3) (distance U*, distance_lower L; the meshes' distance when they turn out
/// apart): decided when both ends agree (issue #27).
PartPairResult two_scarred_rollers(const ScenePart& a, const ScenePart& b, bool swapped, double clearance) {
  const double tol = touch_tolerance(a.cylinder, b.cylinder);
  const detail::TwoScarredValue v = detail::two_scarred_value(a, b, tol);
  PartPairResult out;
  out.swapped = swapped, out.solver = v.exact ? PartPairSolver::scarred : PartPairSolver::bound;
  out.two_sided_exact = v.exact;
  out.evaluated = v.evaluated;
  out.distance = v.upper, out.distance_lower = v.lower;
  out.point_a = v.point_a, out.point_b = v.point_b, out.reverse = v.reverse;
  if (v.contained == 1) {
    out.verdict = Verdict::clash;
    return out;
  }
  if (v.contained < 0) {
    out.verdict = Verdict::undecided;
    out.reason = "whether one scarred roller lies inside the other: every ray direction was degenerate";
    return out;
  }
  out.verdict = v.upper_known ? bracket_verdict(v.lower, v.upper, tol, clearance)
                              : distance_verdict(v.lower, tol, clearance);
  if (v.exact || out.verdict == Verdict::clear) return out;  // (a lower bound alone decides only clear)
  if (!v.upper_known) {
    out.verdict = Verdict::undecided;
    out.reason =
        "two scarred rollers: no exact solver (B must be intact); each mesh against the other's grown "
        "intact solid is not clear";
  } else if (out.verdict == Verdict::undecided) {
    out.reason =
        "two scarred rollers: no exact solver (B must be intact); the bracket of S (each mesh against "
        "the other's grown intact solid, a point of one surface inside the other's) gives different verdicts";
  }
  return out;
}

/// Whether s(B, A0) < target is certified by one point of B (LowerEnd::decision; issue #27, speed):
/// for any point c, s(B, A0) = min over B of sd_A0 <= sd_A0(c) + dist(c, B) <= sd_A0(c) +
/// max(0, sd_B(c)) (sd_A0 is 1-Lipschitz). The point (any point is sound; this one is usually
/// near the deepest): on B's surface at the foot of A's intact witness (`intact`: s(A's intact
/// cylinder, B); point_b on B's boundary, often at an end of A, where B is barely inside A0),
/// moved along B's axis toward A's centre by that depth. The margin, 1e-10 of the scene's scale (as
/// intact_reverse_lower_bound's), is far above the rounding of these evaluations and of the reverse
/// solver's minimum, so the solver's s(B, A0) would have been below `target` too.
bool reverse_certified_below(const Cylinder& a0, const Cylinder& b, const PairDistance& intact, double target) {
  const double depth = std::max(-intact.distance, 0.0);
  const double toward = dot(a0.center() - intact.point_b, b.axis) > 0 ? depth : -depth;
  const Vec3 c = intact.point_b + b.axis * toward;
  const double v = point_signed_distance(a0, c) + std::max(0.0, point_signed_distance(b, c));
  const double scale = 1 + std::max({std::fabs(a0.base.x), std::fabs(a0.base.y), std::fabs(a0.base.z),
                                     std::fabs(b.base.x), std::fabs(b.base.y), std::fabs(b.base.z)}) +
                       a0.height + b.height + a0.radius + b.radius;
  return v < target - 1e-10 * scale;
}

}  // namespace

PartPairResult decide_part_pair(const ScenePart& x, const ScenePart& y, double clearance, const PairDistance* forward,
                                LowerEnd lower) {
  // roles: B must be an intact part (a cylinder for the standard solver, a cylinder or frustum for
  // the scarred one and for cone_pair_distance); prefer a partner as B (a roller against a partner
  // is the paper's pair), then an intact cylinder, then an intact (tapered) frustum; between parts
  // of the same kind, the canonical order
  const auto rank = [](const ScenePart& p) {
    return p.partner ? 3 : p.intact() ? 2 : p.mesh == nullptr ? 1 : 0;
  };
  const int rx = rank(x), ry = rank(y);
  const bool swapped = rx != ry ? rx > ry : canonical_less(y, x);
  const ScenePart& a = swapped ? y : x;
  const ScenePart& b = swapped ? x : y;
  // a tapered part and no scar, or one scar: the exact solvers of the tapered assemblies (issue #27,
  // assembly_pairs.cpp's tapered rows; the same functions, hence the same values)
  if (b.mesh == nullptr && (a.cylinder.tapered() || b.cylinder.tapered())) {
    if (a.mesh != nullptr) return scarred_frustum_pair(a, b, swapped, clearance);
    PartPairResult out;
    const PairDistance d = two_sided_frustum_distance(a.cylinder, b.cylinder, &out.reverse);
    out.swapped = swapped;
    out.distance = out.distance_lower = d.distance;
    out.point_a = d.point_a, out.point_b = d.point_b, out.path = d.path;
    out.verdict = distance_verdict(d.distance, touch_tolerance(a.cylinder, b.cylinder), clearance);
    return out;
  }
  if (b.mesh != nullptr) return two_scarred_rollers(a, b, swapped, clearance);
  // B is an intact cylinder (a partner or an untapered roller), A an intact cylinder or a scarred
  // untapered roller
  const Cylinder& bc = b.cylinder;
  PairDistance intact;  // s(A's cylinder, B) (for LowerEnd::decision)
  PartPairResult out = solve(a, bc, swapped ? nullptr : forward, &intact);  // s(A, B) (A = x: forward is that call)
  out.swapped = swapped;
  const double tol = touch_tolerance(a.cylinder, bc);
  out.distance_lower = out.distance;
  bool contained = false;
  if (out.solver == PartPairSolver::scarred && out.distance > tol) {
    const int inside = mesh_containment(a, bc);
    if (inside == 1) {
      contained = true;
    } else if (inside < 0) {
      out.verdict = Verdict::undecided;
      out.reason =
          "whether the partner lies inside the scarred roller: every ray direction was degenerate";
      return out;
    }
  }
  // the reverse direction, B's depth into A (issue #27; the paper's Step 3: all four end circles)
  if (a.intact()) {
    // two_sided_cylinder_distance(a, bc) without recomputing the forward value solve() just gave
    // (the same function of the same cylinders: bitwise the same result). The reverse (often the
    // slow slice path) only when it can be the smaller one: skipped when intact_reverse_tangent_bound
    // or, where that is not enough, intact_reverse_lower_bound (part_pair.h: the cheap tangents
    // first, as intact_row_distance) is not below s(A, B), so then s(B, A) >= s(A, B) and the
    // result is the same bit for bit (issue #27, the assemblies' roller-inner and roller-roller pairs).
    if (!(intact_reverse_tangent_bound(a.cylinder, bc, out.distance) >= out.distance ||
          intact_reverse_lower_bound(a.cylinder, bc) >= out.distance)) {
      const PairDistance rev = cylinder_pair_distance(bc, a.cylinder);
      out.reverse = rev.distance < out.distance;
      if (out.reverse) out.distance = rev.distance, out.point_a = rev.point_b, out.point_b = rev.point_a, out.path = rev.path;
    }
    out.distance_lower = out.distance;
  } else if (!(out.distance > tol) && !contained) {
    // A scarred (untapered: a tapered one is scarred_frustum_pair's) lies in its enclosing
    // cylinder A0 (grown by a raised scar's raise):
    // s(B, A) >= s(B, A0). (Apart,
    // s(A, B) > tol, both one-sided values are the distance of the solids: nothing to add.)
    const Cylinder a0 = enclosing(a);
    if (lower == LowerEnd::decision && reverse_certified_below(a0, bc, intact, std::min(out.distance, -tol))) {
      // s(B, A0) < s(A, B) and < -tol: the verdict is the bracket's either way (clash, or
      // undecided for a contact), not exact; the lower end only as the inradius bound (part_pair.h)
      out.distance_lower = -std::min(a0.radius, 0.5 * a0.height), out.two_sided_exact = false;
    } else {
      const double lo = cylinder_pair_distance(bc, a0).distance;
      if (lo < out.distance) out.distance_lower = lo, out.two_sided_exact = false;
    }
  }
  out.verdict = contained ? Verdict::clash
                          : bracket_verdict(out.distance_lower, out.distance, tol, clearance);
  if (out.verdict == Verdict::undecided)
    out.reason =
        "two-sided depth: the partner's depth into the scarred roller is only bounded "
        "(by its enclosing cylinder), and the bounds give different verdicts";
  return out;
}

}  // namespace interfere::bearing
