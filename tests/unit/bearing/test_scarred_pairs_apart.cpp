// Two scarred neighbouring rollers that are apart (issue #27; scarred_two_sided.h (2)): the rows
// reported exact must equal the Euclidean distance of the two posed closed meshes, here the
// brute-force minimum over all triangle pairs of the triangle-triangle distance written in
// scarred_reference.h (pairs whose bounding spheres are farther than the best found are skipped:
// a valid bound), to 1e-9 relative. Cylindrical and tapered bearings, inward and raised scars, rest poses and random ones (tilts to 1 degree,
// tangential shifts to +-0.5 mm, so that some neighbours overlap: those stay bounds). Also
// decide_part_pair(x, y) and (y, x) give the same value bit for bit (s(A, B) = s(B, A)).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "interfere/bearing/assembly.h"
#include "interfere/bearing/cylinder.h"
#include "interfere/bearing/part_pair.h"
#include "unit/bearing/assembly_fixture.h"
#include "unit/bearing/scarred_pair_parts.h"
#include "unit/bearing/scarred_reference.h"

namespace interfere::bearing {
namespace {

using test::scene_part;

void check(const std::string& bearing, int& exact_rows, int& other_rows, double& worst) {
  for (const bool raised : {false, true}) {
    const Assembly as = test::scarred_assembly(bearing, raised);
    test::SplitMix rng{raised ? 5u : 3u};
    for (int round = 0; round < 3; ++round) {
      std::vector<Transform> poses;
      if (round == 0) {
        for (const AssemblyPart& p : as.parts) poses.push_back(p.rest);
      } else {
        poses = test::random_poses(as, rng, 1.0, -0.05, 0.05, 0.5, round == 1 ? 0.5 : 3.0);  // (3 mm: some overlap)
      }
      for (const AssemblyPair& pair : as.pairs) {
        if (pair.kind != AssemblyPairKind::roller_roller) continue;
        ASSERT_TRUE(as.parts[pair.a].scarred && as.parts[pair.b].scarred);
        const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
        if (!r.exact) {
          ++other_rows;
          EXPECT_FALSE(r.two_sided);
          continue;
        }
        ++exact_rows;
        SCOPED_TRACE(as.parts[pair.a].id + " / " + as.parts[pair.b].id + " round " + std::to_string(round));
        EXPECT_TRUE(r.two_sided);
        EXPECT_EQ(r.solver, AssemblySolver::scarred);
        const TriMesh& ma = *as.parts[pair.a].mesh;
        const TriMesh& mb = *as.parts[pair.b].mesh;
        const double ref = test::ref_mesh_distance(ma, test::posed_positions(ma, poses[pair.a]), mb,
                                                test::posed_positions(mb, poses[pair.b]));
        const double diff = test::relative_difference(ref, r.distance);
        worst = std::max(worst, diff);
        EXPECT_LE(diff, 1e-9) << "row " << r.distance << " brute force " << ref;
        EXPECT_GT(r.distance, 0);
        EXPECT_NEAR(norm(r.point_a - r.point_b), r.distance, 1e-9 * (1 + r.distance));
        // s(A, B) = s(B, A): both orders of decide_part_pair (the cylindrical rows' function)
        const ScenePart x = scene_part(as, pair.a, poses[pair.a]), y = scene_part(as, pair.b, poses[pair.b]);
        const PartPairResult xy = decide_part_pair(x, y, as.spec.clearance), yx = decide_part_pair(y, x, as.spec.clearance);
        EXPECT_EQ(xy.distance, yx.distance);
        EXPECT_EQ(xy.verdict, yx.verdict);
        EXPECT_TRUE(xy.two_sided_exact);
        EXPECT_LE(test::relative_difference(xy.distance, ref), 1e-9);
      }
    }
  }
}

TEST(BearingScarredPairsApart, CylindricalNeighboursAgainstTheBruteForce) {
  int exact_rows = 0, other = 0;
  double worst = 0;
  check(test::kCylindricalBearing, exact_rows, other, worst);
  std::printf("cylindrical: %d exact rows, %d others, largest relative difference %.3g\n", exact_rows, other, worst);
  EXPECT_GT(exact_rows, 30);
}

TEST(BearingScarredPairsApart, TaperedNeighboursAgainstTheBruteForce) {
  int exact_rows = 0, other = 0;
  double worst = 0;
  check(test::kTaperedBearing, exact_rows, other, worst);
  std::printf("tapered: %d exact rows, %d others, largest relative difference %.3g\n", exact_rows, other, worst);
  EXPECT_GT(exact_rows, 30);
}

}  // namespace
}  // namespace interfere::bearing
