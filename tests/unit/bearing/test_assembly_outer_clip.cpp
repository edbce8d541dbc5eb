// A roller lying across the outer ring's side face in a bearing assembly (issue #27): its axis
// wholly outside the ring's width, its rim reaching into it. The roller-outer pair must see the
// roller's SOLID within the width (raceway.h), for an intact roller (roller_bore_distance) and for a
// scarred roller's mesh (every triangle clipped to the width). Independent references: the intact
// value in closed form (worked out below), the mesh's by sampling every triangle on a barycentric
// grid and keeping the points within the width (a sample never exceeds the exact maximum).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "interfere/bearing/assembly.h"
#include "unit/bearing/assembly_fixture.h"

namespace interfere::bearing {
namespace {

/// max of the distance to the z axis over the mesh's sampled points with |z| <= half_width.
double sampled_max_rho(const TriMesh& m, const Transform& pose, double half_width) {
  double best = -1;
  constexpr int kN = 60;
  for (const Tri& t : m.triangles) {
    const Vec3 a = pose.apply(m.positions[t[0]]), b = pose.apply(m.positions[t[1]]), c = pose.apply(m.positions[t[2]]);
    for (int i = 0; i <= kN; ++i)
      for (int j = 0; i + j <= kN; ++j) {
        const Vec3 p = a + (b - a) * (double(i) / kN) + (c - a) * (double(j) / kN);
        if (std::fabs(p.z) <= half_width) best = std::max(best, std::hypot(p.x, p.y));
      }
  }
  return best;
}

TEST(BearingAssemblyOuterClip, RollerAcrossTheOuterRingFace) {
  const std::string scar = R"("scar": {"fraction": 0.5, "angle_width_deg": 90, "depth": 0.05, "seed": 5},)";
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(scar, test::kCylindricalBearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  ASSERT_TRUE(a) << a.error().message();
  const Assembly& as = *a;
  std::vector<Transform> poses;
  for (const AssemblyPart& p : as.parts) poses.push_back(p.rest);
  // the outer ring: raceway radius 50.1, width 30 about z = 0 (rest pose: identity)
  // the roller (radius 10, length 20) along +x, axis at z = -19 (4 beyond the face z = -15)
  Transform lying;
  lying.r = {{{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}}};  // body z -> world x
  int intact = 0, scarred = 0;
  for (const AssemblyPair& pair : as.pairs) {
    if (pair.kind != AssemblyPairKind::roller_outer) continue;
    const AssemblyPart& part = as.parts[pair.a];
    if (part.scarred ? scarred : intact) continue;
    ASSERT_TRUE(as.parts[pair.b].rest.is_identity());
    for (const double x0 : {35.0, 25.0}) {  // far end at x = 55 (beyond the raceway) or 45 (inside)
      std::vector<Transform> p = poses;
      lying.t = {x0, 0, -19};
      p[pair.a] = lying;
      const AssemblyPairResult r = solve_pair(as, pair, p, as.spec.clearance);
      SCOPED_TRACE(part.id + " x0 " + std::to_string(x0));
      if (!part.scarred) {
        if (x0 == 35) {
          // within the width (z >= -15) the end disk x = 55 reaches y^2 <= 100 - 4^2: radially
          // 50.1 - sqrt(55^2 + 84) beyond the raceway, an upper bound of both depths; the two-sided
          // value (issue #27) is the ring corner's depth in the roller, 4.9908197141373 by the dense
          // reference of test_ring_two_sided.cpp (its "lying roller" case)
          EXPECT_GT(r.distance, 50.1 - std::sqrt(55.0 * 55 + 84));
          EXPECT_NEAR(r.distance, -4.9908197141373, 1e-9);
          EXPECT_TRUE(r.two_sided);
          EXPECT_EQ(r.verdict, Verdict::clash);
          EXPECT_TRUE(r.exact);
        } else {
          // apart: a lower bound, R - the whole roller's farthest point sqrt(45^2 + 10^2)
          EXPECT_NEAR(r.distance, 50.1 - std::sqrt(45.0 * 45 + 100), 1e-9);
          EXPECT_EQ(r.verdict, Verdict::clear);
          EXPECT_FALSE(r.exact);
        }
      } else {
        const double ref = 50.1 - sampled_max_rho(*part.mesh, lying, 15);
        if (x0 == 35) {
          EXPECT_LE(r.distance, ref + 1e-9);
          EXPECT_GE(r.distance, ref - 0.05);
          EXPECT_EQ(r.verdict, Verdict::clash);
        } else {
          EXPECT_GT(r.distance, 0);
          EXPECT_LE(r.distance, ref + 1e-9);
          EXPECT_EQ(r.verdict, Verdict::clear);
        }
      }
    }
    (part.scarred ? scarred : intact) = 1;
  }
  EXPECT_EQ(intact, 1);
  EXPECT_EQ(scarred, 1);
}

}  // namespace
}  // namespace interfere::bearing
