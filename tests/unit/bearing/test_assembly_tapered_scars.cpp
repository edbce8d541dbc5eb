// Scarred rollers in tapered bearings (issue #27, deliverable 2; assembly_tapered_scars.h): with
// scar.fraction the tapered bearing's rollers carry scars; their roller-cone rows and the
// roller-roller rows of a scarred and an intact neighbour are the scarred solver against the
// frustum (exact forward value, two-sided when the reverse bound does not undercut it), checked
// against frustum_oracle.h's bracket to 1e-9; the roller-cup rows are the exact vertex maximum of
// the meridian distance (recomputed here); rows that stay bounds say so (exact = false, verdict
// undecided or the mesh engine's), and no row is clear where the mesh engine finds the meshes
// clashing (the ring and intact roller meshes are inscribed in their solids).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "assembly_fixture.h"
#include "frustum_oracle.h"
#include "interfere/bearing/assembly.h"
#include "interfere/query/clash.h"
#include "scarred_pair_parts.h"

using namespace interfere;
using namespace interfere::bearing;
using namespace frustum_oracle_ns;

namespace {

std::vector<std::array<Vec3, 3>> posed_triangles(const TriMesh& m, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

Cylinder posed_frustum(const Cylinder& c, const Transform& pose) {
  Cylinder out = c;
  out.base = pose.apply(c.base);
  out.axis = pose.rotate(c.axis);
  return out;
}

using test::meshes_clash;

std::string lively_tapered(bool raised, const char* fraction = "0.5") {
  std::string extra = test::kLively;
  extra.replace(extra.find("\"fraction\": 0.3"), 15, std::string("\"fraction\": ") + fraction);
  if (raised) extra.replace(extra.find("\"seed\": 5}"), 10, "\"seed\": 5, \"raised\": true}");
  return test::assembly_json(extra, test::kTaperedBearing);
}

}  // namespace

TEST(BearingAssemblyTaperedScars, ScarredRowsAgainstTheOracle) {
  std::map<std::string, int> seen;
  // half the rollers scarred (every roller pair has one scarred roller), inward and raised; then
  // every roller scarred (every roller pair has two)
  for (const int variant : {0, 1, 2}) {
    const bool raised = variant == 1;
    Expected<AssemblySpec> s = parse_assembly(lively_tapered(raised, variant == 2 ? "1" : "0.5"), "t.json");
    ASSERT_TRUE(s) << s.error().message();
    Expected<Assembly> built = build_assembly(*s);
    ASSERT_TRUE(built) << built.error().message();
    const Assembly& as = *built;
    int scarred = 0;
    for (const AssemblyPart& p : as.parts) scarred += p.scarred;
    EXPECT_EQ(scarred, variant == 2 ? 12 : 6);  // half of the 12 tapered rollers, or all
    const AssemblyMotion motion = generate_motion(as, 3, as.spec.seed);
    const BearingSpec& b = as.spec.bearings[0];
    const BearingGeometry& g = as.geometry[0];
    for (std::size_t frame = 0; frame < motion.poses.size(); ++frame) {
      const auto& poses = motion.poses[frame];
      for (const AssemblyPair& pair : as.pairs) {
        const AssemblyPart& pa = as.parts[pair.a];
        const AssemblyPart& pb = as.parts[pair.b];
        const bool involved = pa.scarred || (pair.kind == AssemblyPairKind::roller_roller && pb.scarred);
        if (!involved) continue;
        const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
        SCOPED_TRACE(std::string(assembly_pair_kind_name(pair.kind)) + " " + pa.id + " frame " + std::to_string(frame) +
                     (raised ? " raised" : " inward"));
        ASSERT_TRUE(std::isfinite(r.distance));
        // (a cage row is scarred only when the grown middle piece decides it)
        if (pair.kind != AssemblyPairKind::roller_cage) EXPECT_TRUE(r.scar);
        const Cylinder roller_a = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[pair.a]);
        const double scale = norm(poses[pair.a].t) + b.cup_outer + b.rollers.length;
        const auto in_bracket = [&](const TriMesh& mesh, const Transform& pose, const Cylinder& frustum) {
          const Bracket br = frustum_min_bracket(posed_triangles(mesh, pose), frustum, 1e-10 * scale);
          EXPECT_LE(br.upper - br.lower, 1e-9 * scale);
          // the forward value is exact; a two-sided S is not above it and equals it when exact
          EXPECT_LE(r.distance, br.upper + 1e-9 * scale);
          if (r.exact) EXPECT_GE(r.distance, br.lower - 1e-9 * scale);
          if (r.exact && r.distance < 0) ++seen["exact overlapping"];
          if (!r.exact) {
            ++seen[r.verdict == Verdict::undecided ? "bracketed, undecided" : "bracketed, decided"];
            EXPECT_TRUE(r.verdict == Verdict::undecided || r.verdict == distance_verdict(br.upper, 0x1p-36 * scale, 0.05) ||
                        r.verdict == Verdict::clash);
          }
        };
        switch (pair.kind) {
          case AssemblyPairKind::roller_cone: {
            EXPECT_EQ(r.solver, AssemblySolver::scarred);
            EXPECT_EQ(r.scar_part, 1);
            in_bracket(*pa.mesh, poses[pair.a], posed_frustum(g.raceway, poses[pair.b]));
            // never clear where the meshes (the cone ring's is inscribed in its solid) clash
            if (r.verdict == Verdict::clear) EXPECT_FALSE(meshes_clash(*pa.mesh, poses[pair.a], *pb.mesh, poses[pair.b]));
            ++seen["cone"];
            break;
          }
          case AssemblyPairKind::roller_roller: {
            const Cylinder roller_b =
                posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[pair.b]);
            if (pa.scarred && pb.scarred && r.exact) {  // apart: the meshes' exact distance (scarred_two_sided.h;
              // test_scarred_pairs_apart.cpp checks it against the brute force)
              EXPECT_EQ(r.solver, AssemblySolver::scarred);
              EXPECT_TRUE(r.two_sided);
              EXPECT_GT(r.distance, 0);
              ++seen["roller pair, both scarred, exact distance"];
            } else if (pa.scarred && pb.scarred) {
              EXPECT_FALSE(r.exact);
              EXPECT_TRUE(r.solver == AssemblySolver::bound || r.solver == AssemblySolver::mesh);
              // a lower bound: not above the scarred A against the intact B
              const Bracket br = frustum_min_bracket(posed_triangles(*pa.mesh, poses[pair.a]), roller_b, 1e-10 * scale);
              EXPECT_LE(r.distance, br.upper + 1e-9 * scale);
              if (r.verdict == Verdict::clear) EXPECT_GT(r.distance, 0);
              ++seen[r.solver == AssemblySolver::mesh ? "roller pair, both scarred, mesh engine"
                                                      : "roller pair, both scarred, clear by the bound"];
            } else {
              EXPECT_EQ(r.solver, AssemblySolver::scarred);
              if (pa.scarred) in_bracket(*pa.mesh, poses[pair.a], roller_b);
              else in_bracket(*pb.mesh, poses[pair.b], roller_a);
              EXPECT_EQ(r.scar_part, pa.scarred ? 1 : 2);
              ++seen["roller pair, one scarred"];
            }
            if (r.verdict == Verdict::clear) EXPECT_FALSE(meshes_clash(*pa.mesh, poses[pair.a], *pb.mesh, poses[pair.b]));
            break;
          }
          case AssemblyPairKind::roller_cup: {
            // -max over the mesh's vertices in the width of the meridian distance beyond the cone line
            const Vec3 axis = poses[pair.b].rotate({0, 0, 1}), centre = poses[pair.b].apply({0, 0, 0});
            const double k = std::tan(g.cup_half_angle);
            const double r0 = -g.apex_z * k + b.cup_clearance / std::cos(g.cup_half_angle);
            double best = -1e300;
            for (const Vec3& v : pa.mesh->positions) {
              const Vec3 p = poses[pair.a].apply(v);
              const double z = dot(p - centre, axis);
              ASSERT_TRUE(z >= g.ring_lo && z <= g.ring_hi);  // (the roller lies within the cup's width)
              best = std::max(best, (norm(cross(p - centre, axis)) - r0 - k * z) / std::sqrt(1 + k * k));
            }
            EXPECT_NEAR(r.distance, -best, 1e-9 * scale);
            EXPECT_EQ(r.solver, AssemblySolver::vertex);
            // two-sided where certified (test_scarred_two_sided_rings.cpp): an overlap's S, or apart the
            // Euclidean distance, realised by the witness pair
            if (r.two_sided && r.distance > 0) EXPECT_NEAR(norm(r.point_a - r.point_b), r.distance, 1e-9 * scale);
            ++seen["cup"];
            break;
          }
          case AssemblyPairKind::roller_cage:
            // (split into intact frustum ends and the grown middle: BearingAssemblyPairs checks it)
            EXPECT_TRUE(r.solver == AssemblySolver::web || r.solver == AssemblySolver::bound ||
                        r.solver == AssemblySolver::mesh);
            EXPECT_EQ(r.exact, r.solver == AssemblySolver::web);
            EXPECT_EQ(r.exact, !r.scar);
            ++seen["cage"];
            break;
          default: break;
        }
      }
    }
  }
  for (const auto& [what, n] : seen) std::printf("[ tapered scars ] %s: %d rows\n", what.c_str(), n);
  EXPECT_GT(seen["cone"], 0);
  EXPECT_GT(seen["cup"], 0);
  EXPECT_GT(seen["roller pair, one scarred"], 0);
  EXPECT_GT(seen["exact overlapping"], 0);  // the load presses scarred rollers into the cone
  EXPECT_GT(seen["roller pair, both scarred, exact distance"], 0);  // (before: clear by the bound)
}

TEST(BearingAssemblyTaperedScars, TwoScarredNeighboursPressedTogether) {
  // every roller scarred; roller 1 replaced by a parallel copy of roller 0 shifted toward roller 1's
  // place by 14 (the small ends' radii are 8: the solids overlap by about 2) or by 20.5 (the large
  // ends' radii are 9.5: apart by about 1.5): no exact solver; overlapping, the lower bound is not
  // clear and the bracket's upper end (a point of one surface inside the other, scarred_two_sided.h
  // (3)) decides clash; apart, the meshes' exact distance
  Expected<AssemblySpec> s = parse_assembly(lively_tapered(false, "1"), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> as = build_assembly(*s);
  ASSERT_TRUE(as) << as.error().message();
  const AssemblyMotion motion = generate_motion(*as, 1, as->spec.seed);
  for (const AssemblyPair& pair : as->pairs) {
    if (pair.kind != AssemblyPairKind::roller_roller) continue;
    for (const double shift : {14.0, 20.5}) {
      std::vector<Transform> poses = motion.poses[0];
      Transform moved = poses[pair.a];
      const Vec3 d = poses[pair.b].t - poses[pair.a].t;
      moved.t = poses[pair.a].t + d * (shift / norm(d));
      poses[pair.b] = moved;
      const AssemblyPairResult r = solve_pair(*as, pair, poses, as->spec.clearance);
      EXPECT_EQ(r.exact, shift > 16);  // apart: the meshes' exact distance (scarred_two_sided.h)
      EXPECT_EQ(r.two_sided, shift > 16);
      EXPECT_TRUE(r.scar);
      if (shift < 16) {
        EXPECT_EQ(r.solver, AssemblySolver::bound);
        EXPECT_EQ(r.verdict, Verdict::clash);
        EXPECT_LT(r.distance, -1);  // (the upper end of S)
        EXPECT_TRUE(meshes_clash(*as->parts[pair.a].mesh, poses[pair.a], *as->parts[pair.b].mesh, poses[pair.b]));
      } else {
        EXPECT_EQ(r.solver, AssemblySolver::scarred);
        EXPECT_EQ(r.verdict, Verdict::clear);
        EXPECT_FALSE(meshes_clash(*as->parts[pair.a].mesh, poses[pair.a], *as->parts[pair.b].mesh, poses[pair.b]));
      }
    }
    break;  // one pair is enough
  }
}

TEST(BearingAssemblyTaperedScars, ScarFractionScarsTaperedRollers) {
  // before issue #27's tapered scars, scar.fraction left a tapered bearing's rollers intact
  Expected<AssemblySpec> s =
      parse_assembly(test::assembly_json(R"("scar": {"fraction": 0.25},)", test::kTaperedBearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> as = build_assembly(*s);
  ASSERT_TRUE(as) << as.error().message();
  int scarred = 0;
  for (const AssemblyPart& p : as->parts)
    if (p.scarred) {
      ++scarred;
      EXPECT_TRUE(p.roller->params.tapered());
      EXPECT_TRUE(p.tree != nullptr && p.solid != nullptr);
    }
  EXPECT_EQ(scarred, 3);
  // a scar deeper than the small end's radius is an error naming the parameter
  Expected<AssemblySpec> deep =
      parse_assembly(test::assembly_json(R"("scar": {"fraction": 0.25, "depth": 8.5},)", test::kTaperedBearing), "t.json");
  ASSERT_FALSE(deep);
  EXPECT_NE(deep.error().message().find("depth"), std::string::npos) << deep.error().message();
}
