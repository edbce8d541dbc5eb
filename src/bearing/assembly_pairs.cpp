// The pair solvers of a bearing assembly (assembly.h, solve_pair; docs/bearing.md, "Bearing
// assemblies"). Every pair's value is s of analytic.h's convention (> 0 clearance, < 0 minus the
// interference depth), computed at the frame's poses by an exact solver:
//   roller-inner, roller-roller (cylindrical): part_pair.h (standard or scarred solver, two-sided);
//   roller-roller (tapered): min(cone_pair_distance(a, b), cone_pair_distance(b, a)) (two-sided);
//   roller-cone: the same two ways; roller-cup: roller_cup_distance; roller-outer:
//   roller_bore_distance, a scarred roller by the maximum over its mesh clipped to the ring's width
//   of the distance to the bore axis (rho is convex, so its maximum over a clipped triangle is at a
//   vertex in the width or an edge's crossing of a side face: exact for the mesh). A value with path
//   `apart` is a lower bound of the distance (raceway.h): it decides only a clear verdict, any
//   other is undecided;
//   roller-rib: roller_rib_distance; roller-cage: min over the web's triangles of the roller's signed
//   distance (scarred.h's exact triangle minimum for cylinders; a nested golden-section search of the
//   convex signed distance of a frustum for tapered rollers; assembly_cage_web.h).
// Scarred rollers against the rib and the cage web: the scar lies in the window z_min..z_max of the
// roller's length; the roller is split into its two intact end pieces (exact cylinders) and the
// middle piece, enclosed by the cylinder grown by the scar's largest outward displacement. When
// the middle's bound is above the ends' value the ends decide: exact. Otherwise the value is a
// bound (exact = false) and the verdict comes from the mesh engine (query/clash.h) on the meshes.
// A tapered roller's pieces are the frustums between their end radii (the middle grown radially).
// Scarred tapered rollers (issue #27; assembly_tapered_scars.h): roller-cone and roller-roller (one
// scarred) by the scarred solver against the intact frustum, two-sided through the grown frustum's
// bound (a bracket when it undercuts: verdict decided when both ends agree); two scarred neighbours:
// a lower bound (clear) or the mesh engine's verdict; roller-cup: the exact vertex maximum of the
// meridian distance beyond the cone line over the clipped mesh (the bore's code with k = tan alpha).
#include <algorithm>
#include <array>
#include <vector>
#include <cmath>
#include <limits>
#include <optional>

#include "assembly_cage_web.h"
#include "assembly_frame.h"
#include "assembly_raceway_scars.h"
#include "assembly_tapered_scars.h"
#include "raceway_detail.h"
#include "rib_euclid_bound.h"
#include "scarred_rib_two_sided.h"
#include "scarred_two_sided.h"
#include "scarred_web_two_sided.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/raceway.h"
#include "interfere/bearing/ring_two_sided.h"
#include "interfere/bearing/scarred.h"
#include "interfere/query/clash.h"

namespace interfere::bearing {
namespace {

using detail::two_sided_web;
using detail::web_distance;
using detail::WebValue;

Cylinder posed(const Cylinder& c, const Transform& pose) {
  Cylinder out = c;
  out.base = pose.apply(c.base);
  out.axis = pose.rotate(c.axis);
  out.axis = out.axis / norm(out.axis);
  return out;
}

double tolerance_of(const Cylinder& roller, double ring_radius) {
  const Vec3 m = roller.center();
  return 0x1p-36 * (std::max({std::fabs(m.x), std::fabs(m.y), std::fabs(m.z)}) + roller.height + roller.max_radius() +
                    ring_radius);
}

double ring_radius(const BearingSpec& b) {
  return b.type == BearingType::cylindrical ? b.outer_radius : b.cup_outer;
}

/// A scarred roller split along its axis: the intact end pieces [0, z0], [z1, L] and the middle
/// piece [z0, z1] grown by `raise` (the scar's largest outward displacement).
struct Pieces {
  /// (an array, not a vector: no allocation per call; issue #27, speed)
  struct Ends {
    std::array<Cylinder, 2> e;
    std::size_t n = 0;
    std::size_t size() const { return n; }
    const Cylinder& operator[](std::size_t i) const { return e[i]; }
    const Cylinder* begin() const { return e.data(); }
    const Cylinder* end() const { return e.data() + n; }
    void push_back(const Cylinder& c) { e[n++] = c; }
  } ends;
  Cylinder middle;
};
Pieces split(const Cylinder& c, const Roller& r, const ScarParams& scar) {
  // the scar's largest outward displacement, max(0, -min displacement): Roller::raise, set by
  // update_positions() with the same loop (issue #27, speed: it was recomputed here per call)
  const double raise = r.raise;
  const double z0 = std::clamp(scar.z_min, 0.0, c.height), z1 = std::clamp(scar.z_max, z0, c.height);
  // a tapered roller (issue #27): each piece is the frustum between its end radii
  const auto r_at = [&](double z) { return c.radius + (c.top() - c.radius) * (z / c.height); };
  Pieces out;
  if (z0 > 0) {
    Cylinder e = c;
    e.height = z0;
    if (c.tapered()) e.top_radius = r_at(z0);
    out.ends.push_back(e);
  }
  if (z1 < c.height) {
    Cylinder e = c;
    e.base = c.base + c.axis * z1;
    e.height = c.height - z1;
    if (c.tapered()) e.radius = r_at(z1);
    out.ends.push_back(e);
  }
  out.middle = c;
  out.middle.base = c.base + c.axis * z0;
  out.middle.height = std::max(z1 - z0, 1e-300);
  out.middle.radius = c.radius + raise;
  if (c.tapered()) out.middle.radius = r_at(z0) + raise, out.middle.top_radius = r_at(z1) + raise;
  return out;
}

ScarParams scar_of(const AssemblySpec& s, const BearingSpec& b) {
  ScarParams sc = s.scar;
  if (sc.z_min < 0) sc.z_min = 0.25 * b.rollers.length;
  if (sc.z_max < 0) sc.z_max = 0.75 * b.rollers.length;
  return sc;
}

/// The verdict of two meshes by the mesh engine (closed parts: containment decided).
Verdict mesh_verdict(const TriMesh& a, const Transform& pa, const TriMesh& b, const Transform& pb, double clearance) {
  const Model ma = make_model(transformed(a, pa)), mb = make_model(transformed(b, pb));
  ClashRequest rq;
  rq.parallel = false;
  rq.regions = false;
  rq.clearance = clearance;
  return clash(ma, mb, rq).verdict;
}

AssemblyPairResult from_part_pair(const PartPairResult& r, double clearance, double tol) {
  AssemblyPairResult out;
  out.distance = r.distance;
  out.point_a = r.swapped ? r.point_b : r.point_a;
  out.point_b = r.swapped ? r.point_a : r.point_b;
  out.solver = r.solver == PartPairSolver::scarred ? AssemblySolver::scarred
               : r.solver == PartPairSolver::bound ? AssemblySolver::bound
                                                    : AssemblySolver::standard;
  out.path = r.path;
  out.scar = r.solver == PartPairSolver::scarred;
  out.exact = r.two_sided_exact && r.solver != PartPairSolver::bound;
  out.verdict = r.verdict;
  (void)clearance, (void)tol;
  return out;
}

AssemblyPairResult from_distance(const PairDistance& d, AssemblySolver solver, double clearance, double tol) {
  AssemblyPairResult out;
  out.distance = d.distance, out.point_a = d.point_a, out.point_b = d.point_b;
  out.solver = solver, out.path = d.path;
  out.verdict = distance_verdict(d.distance, tol, clearance);
  if (d.path == AnalyticPath::apart) {  // a lower bound of the distance (raceway.h): decides only clear
    out.exact = false;
    if (out.verdict != Verdict::clear) out.verdict = Verdict::undecided;
  }
  return out;
}

/// A ring pair's two-sided value (ring_two_sided.h): a lower bound (the solver's `apart`) decides
/// only `clear`; `two_sided` is set by solve_pair.
AssemblyPairResult from_two_sided(const TwoSidedRing& t, double clearance, double tol) {
  AssemblyPairResult out = from_distance(t.value, AssemblySolver::raceway, clearance, tol);
  out.two_sided = t.exact;  // the value is S: the two-sided depth, or the Euclidean distance
  if (t.value.distance <= 0 && !t.exact) out.exact = false;  // (a depth the ring's thinness could bound)
  return out;
}

/// The row of two intact cylinders a, b whose two-sided S is `f` (the standard solver's value):
/// what decide_part_pair returns for them (solver standard, exact, the verdict of S).
AssemblyPairResult standard_row(const PairDistance& f, const Cylinder& a, const Cylinder& b, double clearance) {
  AssemblyPairResult out;
  out.distance = f.distance, out.point_a = f.point_a, out.point_b = f.point_b;
  out.solver = AssemblySolver::standard, out.path = f.path;
  out.verdict = distance_verdict(f.distance, touch_tolerance(a, b), clearance);
  return out;
}

/// Two intact cylinders apart: s(a, b) > 0 is their Euclidean distance, equal to s(b, a), so the
/// two-sided S is the forward value (part_pair.h would also compute the reverse, often by the slow
/// general path). nullopt when they are not apart (then part_pair.h decides).
std::optional<AssemblyPairResult> apart(const Cylinder& a, const Cylinder& b, double clearance) {
  const PairDistance f = cylinder_pair_distance(a, b);
  if (!(f.distance > 0)) return std::nullopt;
  return standard_row(f, a, b, clearance);
}

/// A scarred roller against an intact frustum (assembly_tapered_scars.h): solver `scarred`, exact
/// when the two-sided bracket closes; its verdict when both ends agree, else undecided. `swapped`:
/// the scarred roller is the row's part b.
AssemblyPairResult from_scarred_frustum(const detail::ScarredFrustumValue& v, bool swapped, double clearance,
                                        double tol) {
  AssemblyPairResult out;
  out.distance = v.distance;
  out.point_a = swapped ? v.point_b : v.point_a;
  out.point_b = swapped ? v.point_a : v.point_b;
  out.solver = AssemblySolver::scarred;
  out.scar = true;
  out.exact = v.exact;
  if (v.contained == 1) {
    out.verdict = Verdict::clash;  // B inside the scarred roller's solid
  } else if (v.contained < 0) {
    out.verdict = Verdict::undecided, out.exact = false;
  } else {
    out.verdict = bracket_verdict(v.lower, v.distance, tol, clearance);
  }
  return out;
}

ScenePart roller_part(const AssemblyPart& p, const Cylinder& c, const Transform& pose, bool scarred) {
  ScenePart s;
  s.cylinder = c;
  if (scarred) {
    s.mesh = p.roller.get();
    s.tree = p.tree.get();
    s.solid = p.solid.get();
  }
  s.pose = pose;
  return s;
}

/// Two neighbouring tapered rollers of which at least one is scarred (issue #27). One scarred: the
/// scarred solver against the other's intact frustum (from_scarred_frustum). Both scarred: no exact
/// solver (each is measured against the other's grown intact solid), so
///   S >= L = min( s(A mesh, B0), s(B mesh, A0) ),  A0, B0 the grown intact frustums,
/// a lower bound that decides `clear`; the meshes' exact distance when they are apart; below the
/// tolerance the bracket [L, U*] (scarred_two_sided.h (3), the cylindrical rows' function) when
/// both ends agree (solver `bound`, distance U*); otherwise the mesh engine's verdict on the two
/// meshes (solver `mesh`, not exact), as the cage rows of scarred rollers.
AssemblyPairResult scarred_tapered_rollers(const AssemblyPart& ra, const Cylinder& a, const Transform& pose_a,
                                           const AssemblyPart& rb, const Cylinder& b, const Transform& pose_b,
                                           double clearance, double tol) {
  if (!rb.scarred)
    return from_scarred_frustum(
        detail::scarred_against_frustum(*ra.roller, *ra.tree, ra.solid.get(), pose_a, a, b, tol), false, clearance, tol);
  if (!ra.scarred)
    return from_scarred_frustum(
        detail::scarred_against_frustum(*rb.roller, *rb.tree, rb.solid.get(), pose_b, b, a, tol), true, clearance, tol);
  const detail::TwoScarredValue v = detail::two_scarred_value(roller_part(ra, a, pose_a, true), roller_part(rb, b, pose_b, true), tol);
  AssemblyPairResult out;
  out.distance = v.upper, out.point_a = v.point_a, out.point_b = v.point_b;
  out.scar = true;
  if (v.exact) {  // the solids are apart: their exact distance (scarred_two_sided.h)
    out.solver = AssemblySolver::scarred, out.exact = true, out.two_sided = true;
    out.verdict = distance_verdict(out.distance, tol, clearance);
    return out;
  }
  out.solver = AssemblySolver::bound, out.exact = false, out.two_sided = false;
  out.verdict = bracket_verdict(v.lower, v.upper, tol, clearance);  // (L alone: upper = lower)
  // a lower bound alone decides only `clear`, a bracket when its ends agree; else, or one solid
  // holding the other, the mesh engine
  const bool decided = v.upper_known ? out.verdict != Verdict::undecided : out.verdict == Verdict::clear;
  if (v.contained != 0 || !decided) {
    out.verdict = mesh_verdict(*ra.mesh, pose_a, *rb.mesh, pose_b, clearance);
    out.solver = AssemblySolver::mesh;
  }
  return out;
}

}  // namespace

namespace {
/// One row. `intact_roller`: the roller's intact cylinder instead of its scarred mesh (the
/// raceway-scar rows' check, solve_pair).
AssemblyPairResult solve_one(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                             double clearance, bool intact_roller = false) {
  const AssemblyPart& ra = as.parts[pair.a];
  const bool scarred = ra.scarred && !intact_roller;
  const AssemblyPart& pb = as.parts[pair.b];
  const BearingSpec& b = as.spec.bearings[ra.bearing];
  const BearingGeometry& g = as.geometry[ra.bearing];
  const Transform& pose_a = poses[pair.a];
  const Transform& pose_b = poses[pair.b];
  const Cylinder roller = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, pose_a);
  const double tol = tolerance_of(roller, ring_radius(b));
  const Vec3 z{0, 0, 1};
  switch (pair.kind) {
    case AssemblyPairKind::roller_inner: {
      ScenePart race;
      race.cylinder = posed(g.raceway, pose_b);
      race.partner = true;
      // an intact roller (issue #27, speed): S by intact_row_distance (part_pair.h; the simulation's
      // roller-partner rows), which is decide_part_pair's intact branch (the roller as A, the raceway
      // as B: s(A, B); apart, that value; else the reverse only when neither the tangent bound nor
      // the secant bound of s(B, A) shows it >= s(A, B)) with the cheap tangent bound tried first.
      // A skipped reverse could not have been below s(A, B) (both bounds are proven, with margins
      // above the reverse solver's rounding): the same value, points and path bit for bit
      if (!scarred) return standard_row(intact_row_distance(roller, race.cylinder), roller, race.cylinder, clearance);
      // a scarred roller: the row carries no lower end (LowerEnd::decision, part_pair.h; issue #27, speed)
      return from_part_pair(
          decide_part_pair(roller_part(ra, roller, pose_a, scarred), race, clearance, nullptr, LowerEnd::decision),
          clearance, tol);
    }
    case AssemblyPairKind::roller_roller: {
      const Cylinder other = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, pose_b);
      if (b.type == BearingType::tapered) {
        if (scarred || pb.scarred) return scarred_tapered_rollers(ra, roller, pose_a, pb, other, pose_b, clearance, tol);
        return from_distance(two_sided_frustum_distance(roller, other), AssemblySolver::raceway, clearance, tol);
      }
      if (!scarred && !pb.scarred)
        if (auto r = apart(roller, other, clearance)) return *r;
      return from_part_pair(
          decide_part_pair(roller_part(ra, roller, pose_a, scarred), roller_part(pb, other, pose_b, pb.scarred), clearance), clearance, tol);
    }
    case AssemblyPairKind::roller_cone:
      if (scarred)  // issue #27: the scarred solver against the cone's frustum (exact), two-sided bracket
        return from_scarred_frustum(detail::scarred_against_frustum(*ra.roller, *ra.tree, ra.solid.get(), pose_a, roller,
                                                                    posed(g.raceway, pose_b), tol),
                                    false, clearance, tol);
      return from_distance(two_sided_frustum_distance(roller, posed(g.raceway, pose_b)), AssemblySolver::raceway, clearance, tol);
    case AssemblyPairKind::roller_cup: {
      Cup cup;
      const auto cup_r = [&](double zz) {
        return (zz - g.apex_z) * std::tan(g.cup_half_angle) + b.cup_clearance / std::cos(g.cup_half_angle);
      };
      cup.base = pose_b.apply({0, 0, g.ring_lo});
      cup.axis = pose_b.rotate(z);
      cup.radius = cup_r(g.ring_lo), cup.top_radius = cup_r(g.ring_hi), cup.width = g.ring_hi - g.ring_lo;
      if (!scarred) return from_two_sided(two_sided_cup(roller, cup, b.cup_outer), clearance, tol);
      // a scarred tapered roller (issue #27): the largest meridian distance beyond the cup's cone
      // line over its mesh clipped to the width (exact for the mesh, one-sided; as the bore's)
      bool found = false;
      const PairDistance d = detail::mesh_in_conical_bore(*ra.mesh, pose_a, cup.base, cup.axis, cup.radius,
                                                          (cup.top_radius - cup.radius) / cup.width, cup.width, found);
      if (!found) return from_distance(roller_cup_distance(roller, cup), AssemblySolver::raceway, clearance, tol);
      AssemblyPairResult out = from_distance(d, AssemblySolver::vertex, clearance, tol);
      out.scar = true;
      out.two_sided = detail::scarred_ring_two_sided(d, cup.base, cup.axis, (cup.top_radius - cup.radius) / cup.width,
                                                     cup.width, b.cup_outer, *ra.mesh, pose_a);  // (scarred_two_sided.h)
      return out;
    }
    case AssemblyPairKind::roller_outer: {
      Bore bore;
      bore.base = pose_b.apply({0, 0, -0.5 * b.outer_width});
      bore.axis = pose_b.rotate(z);
      bore.radius = b.outer_raceway, bore.width = b.outer_width;
      if (!scarred) return from_two_sided(two_sided_bore(roller, bore, b.outer_radius), clearance, tol);
      // the scarred mesh: s = R - max of rho over the mesh's solid within the ring's width. rho is
      // convex, so its maximum over a triangle clipped to the slab is at a vertex of the clipped
      // polygon: a vertex in the slab or an edge's crossing of a side face (raceway.h's argument;
      // assembly_tapered_scars.h, the cup's k = 0)
      // (issue #27, speed: the roller's side columns that cannot hold the maximiser are skipped,
      // the same value and witness; the whole mesh when that does not apply)
      if (const auto by_columns =
              detail::roller_in_bore_by_columns(*ra.roller, pose_a, bore.base, bore.axis, bore.radius, bore.width,
                                                ra.scar_height)) {
        AssemblyPairResult out = from_distance(*by_columns, AssemblySolver::vertex, clearance, tol);
        out.scar = true;
        out.two_sided = detail::scarred_ring_two_sided(*by_columns, bore.base, bore.axis, 0, bore.width, b.outer_radius,
                                                       *ra.mesh, pose_a);
        return out;
      }
      bool found = false;
      const PairDistance d =
          detail::mesh_in_conical_bore(*ra.mesh, pose_a, bore.base, bore.axis, bore.radius, 0.0, bore.width, found);
      if (!found) return from_distance(roller_bore_distance(roller, bore), AssemblySolver::raceway, clearance, tol);
      AssemblyPairResult out = from_distance(d, AssemblySolver::vertex, clearance, tol);
      out.scar = true;
      out.two_sided = detail::scarred_ring_two_sided(d, bore.base, bore.axis, 0, bore.width, b.outer_radius, *ra.mesh, pose_a);
      return out;
    }
    case AssemblyPairKind::roller_rib:
    case AssemblyPairKind::roller_cage: {
      const bool rib = pair.kind == AssemblyPairKind::roller_rib;
      Rib face;
      if (rib) {
        const double zf = pair.feature == 0 ? -0.5 * b.inner_width + b.rib_width : 0.5 * b.inner_width - b.rib_width;
        face.center = pose_b.apply({0, 0, zf});
        face.axis = pose_b.rotate(z);
        face.normal = pair.feature == 0 ? face.axis : -face.axis;
        face.inner_radius = b.inner_raceway;
        face.outer_radius = b.inner_raceway + b.rib_height;
      }
      const TriMesh* web = rib ? nullptr : &as.webs[as.web_offset[ra.bearing] + pair.feature].mesh;
      const auto one = [&](const Cylinder& c) -> AssemblyPairResult {
        if (rib) return from_distance(roller_rib_distance(c, face), AssemblySolver::raceway, clearance, tol);
        const WebValue w = web_distance(c, *web, pose_b, &g.webs[pair.feature]);
        PairDistance d;
        d.distance = w.distance, d.point_a = w.point_a, d.point_b = w.point_b;
        return from_distance(d, AssemblySolver::web, clearance, tol);
      };
      if (!scarred) {  // intact roller: two-sided (ring_two_sided.h)
        if (rib) {  // (not S: the verdict of the Euclidean distance's bracket; rib_euclid_bound.h)
          AssemblyPairResult r = from_two_sided(two_sided_rib(roller, face, b.rib_width), clearance, tol);
          detail::rib_euclid_row(r, roller, 0, face, b.rib_width, clearance, tol, true);
          return r;
        }
        const WebValue rev = web_distance(roller, *web, pose_b, &g.webs[pair.feature]);
        // apart (rev > 0): the Euclidean distance, symmetric
        const WebValue w = rev.distance > 0 ? rev : two_sided_web(roller, g.webs[pair.feature], pose_b, rev);
        PairDistance d;
        d.distance = w.distance, d.point_a = w.point_a, d.point_b = w.point_b;
        return from_distance(d, AssemblySolver::web, clearance, tol);
      }
      const Pieces pieces = split(roller, *ra.roller, scar_of(as.spec, b));
      AssemblyPairResult best;
      best.distance = std::numeric_limits<double>::infinity();
      // rib (issue #27, speed): a piece's value is at least the lowest height over the face plane of
      // the whole piece (roller_rib_distance: min over K of l, or a lower bound >= that), a closed
      // form; a piece whose bound is above a value already known (with a margin far above rounding)
      // cannot be below it: not solved. Pieces are solved lowest bound first, and the best is still
      // the first smallest in the pieces' order, so the result is the same as solving them all.
      const auto rib_low = [&](const Cylinder& c) {
        return detail::lowest_height(c, face.center, face.normal) - 1e-9 * (1 + norm(c.center() - face.center) + c.height);
      };
      // a rib row that is not S: the verdict of the Euclidean distance's bracket, its lower bound from
      // the roller grown by its raise (holding A'; rib_euclid_bound.h)
      const auto rib_bracket = [&](AssemblyPairResult& e) {
        detail::rib_euclid_row(e, roller, ra.roller->raise, face, b.rib_width, clearance, tol, false);
      };
      // the ends decide: a rib or web row is S where certified (issue #27; scarred_rib_two_sided.h,
      // scarred_web_two_sided.h)
      const auto ends_decide = [&](AssemblyPairResult e) {
        if (rib) {
          e.two_sided = detail::scarred_rib_two_sided({e.distance, e.point_a, e.point_b, e.path}, face, b.rib_width,
                                                      {pieces.ends.begin(), pieces.ends.end()}, pieces.middle);
          rib_bracket(e);
        } else if (e.exact && e.distance <= 0)  // (apart: the Euclidean distance; scarred_web_two_sided.h)
          e.two_sided = detail::scarred_web_two_sided(e.distance, roller, ra.roller->raise,
                                                      {pieces.ends.begin(), pieces.ends.end()}, *web, g.webs[pair.feature], pose_b);
        return e;
      };
      if (rib) {
        const std::size_t ne = pieces.ends.size();  // (at most 2)
        std::array<double, 2> low{};
        std::array<AssemblyPairResult, 2> r{};
        std::array<bool, 2> solved{};
        for (std::size_t i = 0; i < ne; ++i) low[i] = rib_low(pieces.ends[i]);
        const std::size_t first = ne == 2 && low[1] < low[0] ? 1 : 0;
        double known = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < ne; ++k) {
          const std::size_t i = k == 0 ? first : 1 - first;
          if (low[i] > known) continue;
          r[i] = one(pieces.ends[i]), solved[i] = true;
          known = std::min(known, r[i].distance);
        }
        for (std::size_t i = 0; i < ne; ++i)
          if (solved[i] && r[i].distance < best.distance) best = r[i];
        if (rib_low(pieces.middle) > best.distance) return ends_decide(best);  // mid.distance > best: the ends decide
      } else {
        for (const Cylinder& e : pieces.ends)
          if (AssemblyPairResult r = one(e); r.distance < best.distance) best = r;
      }
      const AssemblyPairResult mid = one(pieces.middle);
      if (mid.distance > best.distance) return ends_decide(best);  // the intact ends decide: exact
      // the scarred middle may decide: a bound (the enclosing middle) and the mesh engine's verdict
      AssemblyPairResult out = mid;
      out.exact = false;
      out.scar = true;
      out.solver = AssemblySolver::bound;
      if (out.verdict != Verdict::clear) {  // a lower bound decides only `clear`
        if (rib) {  // E's lower bound may still say clear (rib_euclid_bound.h), else undecided
          detail::rib_euclid_decide_clear(out, roller, ra.roller->raise, face, b.rib_width, clearance, tol);
        } else {
          out.verdict = mesh_verdict(*ra.mesh, pose_a, *web, pose_b, clearance);
          out.solver = AssemblySolver::mesh;
        }
      } else if (rib) {
        rib_bracket(out);  // (clear only when E's lower bound is too)
      }
      return out;
    }
    default: break;  // (the structural kinds: solve_structural)
  }
  return {};
}

/// A lower bound of a distance decides `clear` above the clearance (and the touch tolerance), else
/// nothing: `undecided` (solver `bound`, not exact).
AssemblyPairResult bound_result(double bound, const Vec3& a, const Vec3& b, double clearance, double tol) {
  AssemblyPairResult out;
  out.distance = bound, out.point_a = a, out.point_b = b;
  out.solver = AssemblySolver::bound, out.path = AnalyticPath::apart;
  out.exact = false, out.two_sided = false;
  out.verdict = bound > tol && bound >= clearance ? Verdict::clear : Verdict::undecided;
  return out;
}

/// cage-inner / cage-outer (issue #27, item 2): min over the webs' corners of a function that is a
/// lower bound of the distance to the ring and linear or concave over a web (so its minimum over the
/// convex web is at a corner):
///   inner ring (cylindrical: inside the infinite cylinder rho <= r_i + rib height; tapered: inside
///   the cone's infinite cone rho <= R0 + k z): the distance from x outside a convex cone region is at
///   least g(x) = (rho - R0 - k z)/sqrt(1 + k^2) (the tangent plane along x's meridian supports it),
///   and rho >= n.(x - O) for any unit n across the axis (the web centre's radial direction): linear;
///   outer ring (material rho >= R(z), bore or cup): for x inside, the distance is the meridian
///   distance to the raceway line, (R(z) - rho)/sqrt(1 + k^2): concave.
/// bearing-bearing: min over the part pairs of the two bearings of |c_p - c_q| - r_p - r_q (bounding
/// spheres, assembly.h PartSphere).
AssemblyPairResult solve_structural(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                                    double clearance, const detail::BearingSphere* spheres) {
  const AssemblyPart& pa = as.parts[pair.a];
  const BearingSpec& b = as.spec.bearings[pa.bearing];
  const BearingGeometry& g = as.geometry[pa.bearing];
  const double tol = 0x1p-36 * (norm(poses[pair.a].t) + norm(poses[pair.b].t) + ring_radius(b) + b.rollers.length);
  if (pair.kind == AssemblyPairKind::bearing_bearing) {
    // a bearing's parts are contiguous in as.parts: inner, outer, cage, its rollers (build_assembly)
    const auto range = [&](std::uint32_t outer) {
      const std::size_t first = outer - 1;
      return std::pair{first, first + 3 + static_cast<std::size_t>(as.spec.bearings[as.parts[outer].bearing].rollers.count)};
    };
    const auto [i0, i1] = range(pair.a);
    const auto [j0, j1] = range(pair.b);
    // first the two bearings' spheres (about their outer rings' centres, holding every part's
    // sphere; assembly_frame.h: run_assembly's once per frame, the same values)
    const detail::BearingSphere si = spheres ? spheres[as.parts[pair.a].bearing] : detail::bearing_sphere(as, pair.a, poses);
    const detail::BearingSphere sj = spheres ? spheres[as.parts[pair.b].bearing] : detail::bearing_sphere(as, pair.b, poses);
    const Vec3 ci = si.centre, cj = sj.centre;
    const double ri = si.radius, rj = sj.radius;
    if (const double v = norm(cj - ci) - ri - rj; v > tol && v >= clearance) {
      const Vec3 u = (cj - ci) / norm(cj - ci);
      return bound_result(v, ci + u * ri, cj - u * rj, clearance, tol);
    }
    // the parts' posed sphere centres, once per row (issue #27, speed: they were posed again for
    // every part pair; the same operations, so the same values)
    std::vector<Vec3> posed_j(j1 - j0);
    for (std::size_t j = j0; j < j1; ++j) posed_j[j - j0] = poses[j].apply(as.parts[j].sphere.centre);
    double best = std::numeric_limits<double>::infinity();
    Vec3 wa, wb;
    for (std::size_t i = i0; i < i1; ++i) {
      const Vec3 ci = poses[i].apply(as.parts[i].sphere.centre);
      for (std::size_t j = j0; j < j1; ++j) {
        const Vec3& cj = posed_j[j - j0];
        const double d = norm(cj - ci), v = d - as.parts[i].sphere.radius - as.parts[j].sphere.radius;
        if (v >= best) continue;
        if (v > tol && v >= clearance) {  // the spheres decide
          best = v;
          const Vec3 u = d > 0 ? (cj - ci) / d : Vec3{1, 0, 0};
          wa = ci + u * as.parts[i].sphere.radius, wb = cj - u * as.parts[j].sphere.radius;
          continue;
        }
        // the enclosing cylinders (their distance when apart is Euclidean: analytic.h)
        const auto cyl = [&](std::size_t q) {
          const PartSphere& sp = as.parts[q].sphere;
          Cylinder c;
          c.base = poses[q].apply({0, 0, sp.z_lo});
          c.axis = poses[q].rotate({0, 0, 1});
          c.height = sp.z_hi - sp.z_lo, c.radius = sp.cylinder_radius;
          return c;
        };
        const PairDistance pd = cylinder_pair_distance(cyl(i), cyl(j));
        const double w = std::max(v, std::min(pd.distance, std::max(pd.distance, 0.0)));
        if (w < best) best = w, wa = pd.point_a, wb = pd.point_b;
      }
    }
    return bound_result(best, wa, wb, clearance, tol);
  }
  const Transform& cage = poses[pair.a];
  const Transform& ring = poses[pair.b];
  const Vec3 axis = ring.rotate({0, 0, 1});
  const bool inner = pair.kind == AssemblyPairKind::cage_inner;
  // the raceway line in the ring frame: rho = R0 + k (z - z0)
  double R0, k = 0, z0 = 0;
  if (b.type == BearingType::cylindrical) {
    R0 = inner ? b.inner_raceway + b.rib_height : b.outer_raceway;
  } else if (inner) {
    z0 = g.raceway.base.z, R0 = g.raceway.radius, k = (g.raceway.top() - g.raceway.radius) / g.raceway.height;
  } else {
    z0 = 0, k = std::tan(g.cup_half_angle);
    R0 = (0 - g.apex_z) * k + b.cup_clearance / std::cos(g.cup_half_angle);
  }
  if (const auto& rs = as.parts[pair.b].raceway_scar) R0 += inner ? rs->raise : -rs->raise;  // a raised raceway scar
  const double nk = std::sqrt(1 + k * k);
  const Vec3 origin = ring.apply({0, 0, 0});
  double best = std::numeric_limits<double>::infinity();
  Vec3 wa, wb;
  for (const CageWeb& web : g.webs) {
    std::array<Vec3, 8> x;
    Vec3 centre;
    for (int i = 0; i < 8; ++i) x[i] = cage.apply(web.corners[i]), centre += x[i];
    centre = centre / 8.0;
    Vec3 n = (centre - origin) - axis * dot(centre - origin, axis);
    const double nn = norm(n);
    n = nn > 0 ? n / nn : Vec3{};
    for (int i = 0; i < 8; ++i) {
      const Vec3 d = x[i] - origin;
      const double z = dot(d, axis);
      const Vec3 radial = d - axis * z;
      const double rho = inner ? 0.0 : norm(radial);  // (the outer ring's only)
      const double raceway = R0 + k * (z - z0);
      const double v = inner ? (dot(n, d) - raceway) / nk : (raceway - rho) / nk;
      if (!(v < best)) continue;
      // the witness only for a new best (issue #27, speed: its divisions were half of the row; the
      // same operations): the unit direction from the corner toward the ring
      const Vec3 toward = inner ? (axis * k - n) / nk : rho > 0 ? (radial / rho - axis * k) / nk : Vec3{};
      best = v, wa = x[i], wb = x[i] + toward * v;
    }
  }
  return bound_result(best, wa, wb, clearance, tol);
}

/// The largest radial distance of a faceted scarred surface from its intact cylinder: the largest
/// |height| plus the facets' sagitta r (1 - cos(pi / n)) (its vertices lie on the scarred surface).
double facet_deviation(double largest_height, double radius, int segments) {
  return largest_height + radius * (1 - std::cos(3.14159265358979323846 / segments));
}

/// A roller row in range of a scarred raceway (raceway_scar_solver.h) measures the roller against
/// the raceway's faceted surface only: a roller sunk into the ring's material without crossing that
/// surface (through the bore or a side face, e.g. a pose from a motion file) was reported clear
/// (review of 2026-11-29). Check: the scarred ring and roller lie within delta (their largest
/// heights and sagittas) of the intact ones, so S lies within delta of the intact row's value S0
/// (the intact cylinder against the intact ring, exact and cheap). A value above S0 + delta (or
/// below S0 - 2 delta: with two scarred parts the row's S may lie up to delta below the scarred
/// solids' value, docs/bearing.md "Two scarred parts") is out of the solver's model: the row
/// becomes S0's bracket (not exact, solver
/// `bound`, the lower end reported): clash when its upper end is below the touch tolerance, else
/// undecided. Never clear.
AssemblyPairResult check_raceway_scar_row(const Assembly& as, const AssemblyPair& pair,
                                          const std::vector<Transform>& poses, double clearance,
                                          const AssemblyPairResult& scarred_row) {
  const AssemblyPart& ra = as.parts[pair.a];
  const AssemblyPart& pb = as.parts[pair.b];
  const BearingSpec& b = as.spec.bearings[ra.bearing];
  const RacewayScar& rs = *pb.raceway_scar;
  double delta = facet_deviation(std::max(rs.window.depth, rs.raise),
                                 std::max(rs.geometry.radius, rs.geometry.top_radius), rs.grid.radial_segments);
  if (ra.scarred && ra.roller) {
    const double h = ra.scar_height;  // max(raise, largest |displacement|), build_assembly
    delta += facet_deviation(h, std::max(b.rollers.radius, b.rollers.top_radius), ra.roller->n());
  }
  const AssemblyPairResult intact = solve_one(as, pair, poses, clearance, true);
  const Cylinder roller = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[pair.a]);
  const double tol = tolerance_of(roller, ring_radius(b));
  const double slack = delta * 1e-9 + tol;
  if (intact.exact && scarred_row.distance <= intact.distance + delta + slack &&
      scarred_row.distance >= intact.distance - 2 * delta - slack)
    return scarred_row;
  AssemblyPairResult out = intact;
  out.distance = intact.distance - delta;
  out.exact = false;
  out.two_sided = false;
  out.scar = true;
  out.scar_part = scarred_row.scar_part ? scarred_row.scar_part : 2;
  out.solver = AssemblySolver::bound;
  out.verdict = intact.exact && intact.distance + delta < -tol ? Verdict::clash : Verdict::undecided;
  return out;
}

}  // namespace

namespace detail {

BearingSphere bearing_sphere(const Assembly& as, std::uint32_t outer, const std::vector<Transform>& poses) {
  // a bearing's parts are contiguous in as.parts: inner, outer, cage, its rollers (build_assembly)
  const std::size_t first = outer - 1;
  const std::size_t last = first + 3 + static_cast<std::size_t>(as.spec.bearings[as.parts[outer].bearing].rollers.count);
  BearingSphere s;
  s.centre = poses[outer].apply(as.parts[outer].sphere.centre);
  for (std::size_t q = first; q < last; ++q)
    s.radius = std::max(s.radius, norm(poses[q].apply(as.parts[q].sphere.centre) - s.centre) + as.parts[q].sphere.radius);
  return s;
}

AssemblyPairResult solve_pair_in_frame(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                                       double clearance, const BearingSphere* spheres) {
  if (pair.kind == AssemblyPairKind::cage_inner || pair.kind == AssemblyPairKind::cage_outer ||
      pair.kind == AssemblyPairKind::bearing_bearing)
    return solve_structural(as, pair, poses, clearance, spheres);
  // a roller in range of a scarred raceway (issue #27; raceway_scar_solver.h)
  if (auto scarred_raceway = detail::solve_raceway_scar_row(as, pair, poses, clearance))
    return check_raceway_scar_row(as, pair, poses, clearance, *scarred_raceway);
  AssemblyPairResult r = solve_one(as, pair, poses, clearance);
  if (r.scar) r.scar_part = as.parts[pair.a].scarred ? 1 : 2;  // which part's scarred mesh was measured
  switch (pair.kind) {  // which rows are two-sided (assembly.h, AssemblyPairResult::two_sided)
    case AssemblyPairKind::roller_inner:
    case AssemblyPairKind::roller_cone: r.two_sided = true; break;
    case AssemblyPairKind::roller_roller:  // (two scarred tapered rollers: a lower bound, one-sided)
      r.two_sided = r.solver != AssemblySolver::bound && r.solver != AssemblySolver::mesh;
      break;
    // intact rollers: solve_one set it (ring_two_sided.h: S, or a clearance that is the Euclidean
    // distance); scarred rollers' ring rows stay one-sided (the ring's depth into the scarred mesh
    // is not computed), except clearances that are the Euclidean distance
    case AssemblyPairKind::roller_outer:
      if (as.parts[pair.a].scarred)  // (or S certified, scarred_two_sided.h)
        r.two_sided = r.exact && ((r.distance > 0 && r.path == AnalyticPath::bore) ||
                                  (r.distance <= 0 && r.two_sided && r.solver == AssemblySolver::vertex));
      break;
    case AssemblyPairKind::roller_cage:  // scarred rollers: apart, or S where certified (solve_one)
      if (r.scar || as.parts[pair.a].scarred) r.two_sided = r.exact && (r.distance > 0 || r.two_sided);
      break;
    case AssemblyPairKind::roller_rib:  // scarred rollers: S or the Euclidean distance where certified (solve_one)
      if (as.parts[pair.a].scarred) r.two_sided = r.exact && r.two_sided && r.solver == AssemblySolver::raceway;
      break;
    case AssemblyPairKind::roller_cup:  // scarred rollers: S or the Euclidean distance where certified (scarred_two_sided.h)
      if (as.parts[pair.a].scarred) r.two_sided = r.exact && r.two_sided && r.solver == AssemblySolver::vertex;
      break;
    default: break;  // (the structural kinds return above)
  }
  return r;
}

}  // namespace detail

AssemblyPairResult solve_pair(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                              double clearance) {
  return detail::solve_pair_in_frame(as, pair, poses, clearance, nullptr);
}

}  // namespace interfere::bearing
