// decide_part_pair with tapered and scarred parts (part_pair.h; issue #27): the exact solvers of
// the tapered assemblies instead of enclosing-cylinder bounds, so that `interfere bearing
// --params` (its cross pairs) gives the value an assembly gives for the same pair.
//   * two intact frustums (or a frustum and a cylinder): the two-sided S = min(s(A, B), s(B, A))
//     against an independent reference over both solids (frustum_oracle.h's frustum_solid_min:
//     the ellipsoid method on the convex program min over A of sd_B, with the oracle's own
//     point-to-frustum distance and subgradients), to 1e-9;
//   * a scarred roller (tapered or not) against an intact frustum: the forward value inside
//     frustum_oracle.h's bracket over the mesh's triangles, refined to 1e-9 of the scale; the
//     bracket's lower end through the grown intact frustum (the same reference);
//   * the rows of a tapered assembly (roller-cone, roller-roller with at most one scarred roller)
//     decided again as scene parts: the same value (bitwise when overlapping; apart, the two
//     directions' Euclidean distances to rounding).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "assembly_fixture.h"
#include "frustum_oracle.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/simulation.h"
#include "interfere/query/model.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;
using namespace frustum_oracle_ns;

namespace {

/// splitmix64 uniform numbers (deterministic poses).
using Rng = interfere::bearing::test::SplitMix;

Vec3 unit(const Vec3& v) { return v / norm(v); }

Cylinder frustum(const Vec3& base, const Vec3& axis, double r0, double r1, double h) {
  Cylinder c;
  c.base = base, c.axis = unit(axis), c.radius = r0, c.top_radius = r1 < 0 ? -1 : r1, c.height = h;
  return c;
}

/// The second part of a random pair: beside the first (axes within ~8 degrees), its surface about
/// `gap` from the first's along the line between their mid points (so that most pairs overlap or
/// nearly touch); every fifth pair crosses at a large angle.
Cylinder neighbour(Rng& g, const Cylinder& a, double r0, double r1, double h, double gap) {
  const Vec3 mid = a.base + a.axis * (0.5 * a.height);
  const Vec3 t = std::fabs(a.axis.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = unit(cross(a.axis, t)), e2 = cross(a.axis, e1);
  const double phi = g.in(0, 6.283185307179586);
  const Vec3 out = e1 * std::cos(phi) + e2 * std::sin(phi);
  const bool cross_pair = g.uniform() < 0.2;
  const Vec3 axis = cross_pair ? unit(a.axis * g.in(-0.3, 0.3) + cross(out, a.axis))
                               : unit(a.axis + e1 * g.in(-0.1, 0.1) + e2 * g.in(-0.1, 0.1));
  const double reach = 0.5 * (a.radius + a.top()) + 0.5 * (r0 + r1);
  const Vec3 mid_b = mid + out * (reach + gap) + a.axis * g.in(-0.2, 0.2) * a.height;
  return frustum(mid_b - axis * (0.5 * h), axis, r0, r1, h);
}

}  // namespace

TEST(PartPairFrustums, IntactFrustumsTwoSidedAgainstTheDenseReference) {
  Rng g{2027};
  int overlapping = 0, apart = 0, reverse = 0;
  constexpr int kPairs = 40;
  for (int i = 0; i < kPairs; ++i) {
    const double ra = g.in(7, 10), rb = g.in(7, 10);
    const Cylinder a = frustum({g.in(-5, 5), g.in(-5, 5), g.in(-5, 5)},
                               {g.in(-0.3, 0.3), g.in(-0.3, 0.3), 1}, ra, i % 4 == 3 ? -1 : ra + g.in(-2.5, 2.5), g.in(25, 35));
    // every fourth: a tapered B against an untapered A (then A is B of the solver's roles)
    const Cylinder b = neighbour(g, a, rb, i % 4 == 1 ? -1 : rb + g.in(-2.5, 2.5), g.in(25, 35), g.in(-3, 4));
    const ScenePart x{.cylinder = a}, y{.cylinder = b};
    const PartPairResult d = decide_part_pair(x, y, 0);
    const PartPairResult e = decide_part_pair(y, x, 0);
    SCOPED_TRACE("pair " + std::to_string(i));
    ASSERT_TRUE(std::isfinite(d.distance));
    EXPECT_EQ(d.solver, PartPairSolver::standard);
    EXPECT_TRUE(d.two_sided_exact);
    // the same computation either way (roles by the canonical order): bitwise
    EXPECT_EQ(d.distance, e.distance);
    EXPECT_NE(d.swapped, e.swapped);
    const double ref = std::min(frustum_solid_min(a, b), frustum_solid_min(b, a));
    const double scale = std::max({norm(a.base), norm(b.base), a.height, b.height}) + 10;
    EXPECT_NEAR(d.distance, ref, 1e-9 * scale);
    // witnesses: on A (the first or second part given) and B, S apart along them when apart
    const Cylinder& pa = d.swapped ? b : a;
    const Cylinder& pb = d.swapped ? a : b;
    EXPECT_LE(frustum_oracle(pa, d.point_a).value, 1e-9 * scale);
    EXPECT_LE(frustum_oracle(pb, d.point_b).value, 1e-9 * scale);
    if (d.distance > 0) EXPECT_NEAR(norm(d.point_a - d.point_b), d.distance, 1e-9 * scale);
    EXPECT_EQ(d.verdict, distance_verdict(ref, touch_tolerance(a, b), 0));
    overlapping += ref < -1e-6, apart += ref > 1e-6, reverse += d.reverse;
  }
  std::printf("[ frustum pairs ] %d overlapping, %d apart, %d decided by the reverse direction\n", overlapping,
              apart, reverse);
  EXPECT_GT(overlapping, kPairs / 4);
  EXPECT_GT(apart, kPairs / 8);
  EXPECT_GT(reverse, 0);
}

TEST(PartPairFrustums, ScarredRollerAgainstAFrustumAgainstTheOracle) {
  Rng g{91};
  std::map<std::string, int> seen;
  for (const bool tapered : {true, false}) {
    for (const bool raised : {false, true}) {
      Expected<Roller> made = make_roller({.radius = 8, .top_radius = tapered ? 9.5 : -1, .height = 30,
                                           .radial_segments = 24, .height_segments = 23});
      ASSERT_TRUE(made.has_value());
      Roller mesh = std::move(*made);
      ASSERT_TRUE(apply_scar(mesh, {.angle_center_deg = 0, .angle_width_deg = 300, .z_min = 2, .z_max = 28,
                                    .depth = 0.08, .roughness = 0.6, .border = 2, .seed = 4, .raised = raised})
                      .has_value());
      const RollerQuadtree tree = build_quadtree(mesh);
      const Model solid = make_model(mesh.mesh);
      std::vector<std::array<Vec3, 3>> body;
      for (std::size_t t = 0; t < mesh.mesh.num_triangles(); ++t) {
        const auto c = mesh.mesh.corners(t);
        body.push_back({c[0], c[1], c[2]});
      }
      for (int i = 0; i < 10; ++i) {
        const Transform pose = roller_pose({g.in(-3, 3), g.in(-3, 3), g.in(-3, 3)}, g.in(0, 0.3), g.in(0, 6.28), g.in(0, 6.28));
        const ScenePart a{.cylinder = posed_cylinder(8, tapered ? 9.5 : -1, 30, pose), .mesh = &mesh, .tree = &tree,
                          .solid = &solid, .pose = pose};
        // the intact partner: a tapered roller (an untapered scarred roller has a tapered one as B),
        // or, for a tapered scarred roller, every other one an untapered roller
        const double rb = g.in(7, 9);
        const Cylinder bc = neighbour(g, a.cylinder, rb, tapered && i % 2 ? -1 : rb + g.in(1, 2), 30, g.in(-1.5, 1));
        const ScenePart b{.cylinder = bc};
        const PartPairResult d = decide_part_pair(b, a, 0);
        const PartPairResult e = decide_part_pair(a, b, 0);
        SCOPED_TRACE(std::string(tapered ? "tapered" : "cylindrical") + (raised ? " raised " : " inward ") +
                     std::to_string(i));
        EXPECT_TRUE(d.swapped);  // the scarred roller is A
        EXPECT_FALSE(e.swapped);
        EXPECT_EQ(d.distance, e.distance);
        EXPECT_EQ(d.distance_lower, e.distance_lower);
        EXPECT_EQ(d.solver, PartPairSolver::scarred);
        ASSERT_TRUE(std::isfinite(d.distance) && std::isfinite(d.distance_lower));
        const double scale = norm(pose.t) + 40;
        // the forward value: the minimum of sd_B over the posed mesh
        std::vector<std::array<Vec3, 3>> posed;
        for (const auto& t : body) posed.push_back({pose.apply(t[0]), pose.apply(t[1]), pose.apply(t[2])});
        const Bracket br = frustum_min_bracket(posed, bc, 1e-10 * scale);
        EXPECT_LE(br.upper - br.lower, 1e-9 * scale);
        EXPECT_GE(d.distance, br.lower - 1e-9 * scale);
        EXPECT_LE(d.distance, br.upper + 1e-9 * scale);
        EXPECT_LE(d.distance_lower, d.distance);
        if (d.two_sided_exact) {
          EXPECT_EQ(d.distance_lower, d.distance);
        } else {
          // the lower end: B against A's intact frustum grown by the raise
          Cylinder grown = a.cylinder;
          grown.radius += mesh.raise;
          if (tapered) grown.top_radius += mesh.raise;
          EXPECT_NEAR(d.distance_lower, frustum_solid_min(bc, grown), 1e-9 * scale);
        }
        if (d.verdict == Verdict::undecided) EXPECT_FALSE(d.reason.empty());
        else if (d.distance > touch_tolerance(a.cylinder, bc)) EXPECT_EQ(d.verdict, Verdict::clear);
        else EXPECT_NE(d.verdict, Verdict::clear);
        ++seen[d.distance < 0 ? (d.two_sided_exact ? "overlapping, exact" : "overlapping, bracketed") : "apart"];
      }
    }
  }
  for (const auto& [what, n] : seen) std::printf("[ scarred vs frustum ] %s: %d\n", what.c_str(), n);
  EXPECT_GT(seen["apart"], 0);
  EXPECT_GT(seen["overlapping, exact"] + seen["overlapping, bracketed"], 10);
}

TEST(PartPairFrustums, SameValuesAsTheTaperedAssemblyRows) {
  std::string extra = test::kLively;
  extra.replace(extra.find("\"fraction\": 0.3"), 15, "\"fraction\": 0.5");
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, test::kTaperedBearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  const BearingSpec& b = as.spec.bearings[0];
  const BearingGeometry& g = as.geometry[0];
  const AssemblyMotion motion = generate_motion(as, 3, as.spec.seed);
  std::map<std::string, int> seen;
  for (const auto& poses : motion.poses) {
    const auto roller = [&](std::uint32_t k) {
      const AssemblyPart& p = as.parts[k];
      ScenePart out;
      out.cylinder = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[k]);
      if (p.scarred) out.mesh = p.roller.get(), out.tree = p.tree.get(), out.solid = p.solid.get();
      out.pose = poses[k];
      return out;
    };
    for (const AssemblyPair& pair : as.pairs) {
      const bool cone = pair.kind == AssemblyPairKind::roller_cone;
      if (!cone && pair.kind != AssemblyPairKind::roller_roller) continue;
      if (!cone && as.parts[pair.a].scarred && as.parts[pair.b].scarred) continue;  // no exact solver
      ScenePart other;
      if (cone) {
        other.cylinder = g.raceway;
        other.cylinder.base = poses[pair.b].apply(g.raceway.base);
        other.cylinder.axis = poses[pair.b].rotate(g.raceway.axis);
        other.cylinder.axis = other.cylinder.axis / norm(other.cylinder.axis);  // (as the assembly's rows)
      } else {
        other = roller(pair.b);
      }
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      const PartPairResult d = decide_part_pair(roller(pair.a), other, as.spec.clearance);
      SCOPED_TRACE(std::string(assembly_pair_kind_name(pair.kind)) + " " + as.parts[pair.a].id);
      if (r.distance <= 0) EXPECT_EQ(d.distance, r.distance);
      else EXPECT_NEAR(d.distance, r.distance, 1e-12 * (norm(poses[pair.a].t) + 100));
      EXPECT_EQ(d.solver == PartPairSolver::scarred, r.solver == AssemblySolver::scarred);
      EXPECT_NE(d.solver, PartPairSolver::bound);
      if (std::fabs(r.distance) > 1e-6) {
        EXPECT_EQ(d.two_sided_exact, r.exact);
        EXPECT_EQ(d.verdict, r.verdict);
      }
      ++seen[std::string(cone ? "cone" : "roller pair") + (d.solver == PartPairSolver::scarred ? ", scarred" : ", intact") +
             (r.distance < 0 ? ", overlapping" : ", apart")];
    }
  }
  for (const auto& [what, n] : seen) std::printf("[ assembly rows ] %s: %d\n", what.c_str(), n);
  EXPECT_GT(seen["cone, scarred, overlapping"], 0);
  EXPECT_GT(seen["cone, intact, overlapping"], 0);
  EXPECT_GT(seen["roller pair, scarred, apart"] + seen["roller pair, scarred, overlapping"], 0);
}

TEST(PartPairFrustums, SimulationRowsOfTaperedRollersAreTwoSided) {
  // interfere bearing --params with tapered rollers: an intact roller's own row is the two-sided S of
  // two_sided_frustum_distance, the value decide_part_pair gives the same two parts (a cross pair), and
  // the dense reference's
  SceneParams p;
  p.pairs = 4, p.frames = 4;
  p.roller = {.radius = 10, .top_radius = 8, .height = 40, .radial_segments = 16, .height_segments = 15};
  p.gap = -0.3, p.max_tilt_deg = 1, p.scar_fraction = 0;
  const Expected<SimulationResult> r = simulate(p);
  ASSERT_TRUE(r) << r.error().message();
  ASSERT_EQ(r->rows.size(), 16u);
  int reverse = 0;
  for (std::size_t i = 0; i < r->rows.size(); ++i) {
    const PairFrame& row = r->rows[i];
    const Cylinder roller = posed_cylinder(10, 8, 40, r->roller_poses[i]);
    const Cylinder partner = posed_cylinder(p.partner_radius, -1, p.partner_height, partner_pose(p, r->spacing, row.pair));
    const PartPairResult d = decide_part_pair(ScenePart{.cylinder = partner, .partner = true}, ScenePart{.cylinder = roller}, 0);
    EXPECT_EQ(row.distance, d.distance) << i;
    EXPECT_TRUE(d.two_sided_exact);
    reverse += d.reverse;
    if (i % 4 == 0) {
      const double ref = std::min(frustum_solid_min(roller, partner), frustum_solid_min(partner, roller));
      EXPECT_NEAR(row.distance, ref, 1e-9 * (norm(roller.base) + 100)) << i;
    }
  }
  std::printf("[ tapered rows ] %d of 16 decided by the partner's depth in the roller\n", reverse);
}

TEST(PartPairFrustums, TwoScarredRollersTakeTheAssemblysBound) {
  // every tapered roller scarred: neighbouring rollers have no exact solver; decide_part_pair's lower
  // bound is the assembly's (each mesh against the other's grown intact frustum), clear when the
  // assembly's bound is, never clear where the assembly asks the mesh engine and it is not clear
  std::string extra = test::kLively;
  extra.replace(extra.find("\"fraction\": 0.3"), 15, "\"fraction\": 1");
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, test::kTaperedBearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  const BearingSpec& b = as.spec.bearings[0];
  const AssemblyMotion motion = generate_motion(as, 2, as.spec.seed);
  int rows = 0;
  for (const auto& poses : motion.poses)
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_roller) continue;
      const auto part = [&](std::uint32_t k) {
        const AssemblyPart& p = as.parts[k];
        return ScenePart{.cylinder = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[k]),
                         .mesh = p.roller.get(), .tree = p.tree.get(), .solid = p.solid.get(), .pose = poses[k]};
      };
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      const PartPairResult d = decide_part_pair(part(pair.a), part(pair.b), as.spec.clearance);
      if (r.solver == AssemblySolver::scarred) {  // apart: both take the meshes' exact distance
        // (scarred_two_sided.h; the roles may differ, so equal to rounding)
        EXPECT_EQ(d.solver, PartPairSolver::scarred);
        EXPECT_TRUE(d.two_sided_exact);
        EXPECT_NEAR(d.distance, r.distance, 1e-12 * (norm(poses[pair.a].t) + 100));
        EXPECT_EQ(d.verdict, r.verdict);
        ++rows;
        continue;
      }
      EXPECT_EQ(d.solver, PartPairSolver::bound);
      EXPECT_FALSE(d.two_sided_exact);
      if (r.solver == AssemblySolver::bound) {  // the assembly's bound decided: the same value, clear
        EXPECT_EQ(d.distance, r.distance);
        EXPECT_EQ(d.verdict, Verdict::clear);
      } else {  // the mesh engine decided there: the bound did not
        EXPECT_NE(d.verdict, Verdict::clear);
      }
      ++rows;
    }
  EXPECT_EQ(rows, 24);
}
