// Deciding any pair of bearing parts in the verdict model (part_pair.h; issue #23, items 5 and 13),
// with the solvers of Jia & Zheng 2019: the standard solver (§3.1, analytic.h) and the scarred
// solver (§3.2, scarred.h).
#include "interfere/bearing/part_pair.h"

#include <algorithm>
#include <cmath>

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
/// scarred surface lies in its intact cylinder: scars displace inwards, facets lie inside).
Cylinder enclosing(const Cylinder& c) {
  Cylinder out = c;
  out.radius = c.max_radius();
  out.top_radius = -1;
  return out;
}

/// A against the intact cylinder b: the scarred solver on A's surface, else the standard solver.
PartPairResult solve(const ScenePart& a, const Cylinder& b) {
  PartPairResult out;
  const PairDistance pd = cylinder_pair_distance(a.cylinder, b);
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
  // surface, and A's solid lies in its intact cylinder: a centre outside that cylinder (by more
  // than half that depth, far beyond rounding) is outside A.
  const Vec3 c = b.center();
  const double depth = std::min(b.radius, 0.5 * b.height);
  if (point_signed_distance(enclosing(a.cylinder), c) > -0.5 * depth) return 0;
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

PartPairResult decide_part_pair(const ScenePart& x, const ScenePart& y, double clearance) {
  // roles: B must be an intact cylinder; prefer a partner as B (a roller against a partner is the
  // paper's pair), then the second part
  bool swapped = false;
  if (y.partner)
    swapped = false;
  else if (x.partner)
    swapped = true;
  else if (y.intact())
    swapped = false;
  else if (x.intact())
    swapped = true;
  const ScenePart& a = swapped ? y : x;
  const ScenePart& b = swapped ? x : y;
  const bool exact = b.intact();
  const Cylinder bc = exact ? b.cylinder : enclosing(b.cylinder);
  PartPairResult out = solve(a, bc);
  out.swapped = swapped;
  const double tol = touch_tolerance(a.cylinder, bc);
  out.verdict = distance_verdict(out.distance, tol, clearance);
  bool contained = false;
  if (out.solver == PartPairSolver::scarred && out.distance > tol) {
    const int inside = mesh_containment(a, bc);
    if (inside == 1) {
      out.verdict = Verdict::clash, contained = true;
    } else if (inside < 0) {
      out.verdict = Verdict::undecided;
      out.reason =
          "whether the partner lies inside the scarred roller: every ray direction was degenerate";
    }
  }
  if (!exact) {
    out.solver = PartPairSolver::bound;
    // the enclosing cylinder's distance is a lower bound: only a clear bound decides (or B's
    // enclosing cylinder inside A's solid: then B is too)
    if (out.verdict != Verdict::clear && !contained && b.mesh == nullptr) {
      // a tapered B contains the cylinder of its smaller radius: A reaching into that one's
      // interior reaches into B's (s(A, B) <= s(A, inner), an upper bound of s)
      Cylinder inner = b.cylinder;
      inner.radius = std::min(b.cylinder.radius, b.cylinder.top());
      inner.top_radius = -1;
      const PartPairResult in = solve(a, inner);
      if (in.distance < -touch_tolerance(a.cylinder, inner)) {
        out = in;
        out.swapped = swapped, out.solver = PartPairSolver::bound, out.verdict = Verdict::clash;
        return out;
      }
    }
    if (out.verdict != Verdict::clear && !contained) {
      out.verdict = Verdict::undecided;
      out.reason =
          "two rollers that are both scarred or both tapered: no exact solver (B must be an intact "
          "cylinder); against the cylinder enclosing the second one they are not clear";
    }
  }
  return out;
}

}  // namespace interfere::bearing
