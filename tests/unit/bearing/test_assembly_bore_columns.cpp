// A scarred cylindrical roller in the outer ring's bore (issue #27, speed; assembly_tapered_scars.h
// roller_in_bore_by_columns: side columns whose bound is below the largest radius found are
// skipped): the roller-outer rows of scarred rollers (inward and raised scars) at random poses
// (tilted up to 3 degrees about any axis across the roller, spun, pushed radially into the bore and
// away from it, shifted along the axis) against a brute-force reference written here: every vertex
// of the posed mesh, its distance to the ring axis from the description (position and axis), the
// value R_o - the largest of them, and the witness that vertex (where it lies within the ring's width;
// otherwise the row is the clipped mesh's, tested in test_assembly_outer_clip.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "unit/bearing/assembly_fixture.h"
#include "unit/bearing/splitmix.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

std::array<std::array<double, 3>, 3> rotation(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  return {{{c + k.x * k.x * v, k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s},
           {k.y * k.x * v + k.z * s, c + k.y * k.y * v, k.y * k.z * v - k.x * s},
           {k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v}}};
}

void check(bool raised) {
  const std::string extra = std::string(R"("frames": 1, "seed": 3, "clearance": 0.05, "scar": {"fraction": 1, "angle_width_deg": 120, "depth": 0.08, "seed": 9)") +
                            (raised ? R"(, "raised": true)" : "") + "},";
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, test::kCylindricalBearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  const BearingSpec& b = as.spec.bearings[0];
  const Vec3 ring_axis = as.geometry[0].frame.rotate({0, 0, 1}), centre = as.geometry[0].frame.t;
  test::SplitMix rng{raised ? 11u : 7u};
  int compared = 0;
  for (int round = 0; round < 12; ++round) {
    std::vector<Transform> poses;
    for (const AssemblyPart& p : as.parts) poses.push_back(p.rest);
    for (std::size_t i = 0; i < as.parts.size(); ++i) {
      if (as.parts[i].kind != PartKind::roller) continue;
      const Transform& p0 = as.parts[i].rest;
      const Vec3 u = p0.rotate({0, 0, 1}), mid = p0.apply({0, 0, 0.5 * b.rollers.length});
      Vec3 radial = (mid - centre) - ring_axis * dot(mid - centre, ring_axis);
      radial = radial / norm(radial);
      const Vec3 t = cross(ring_axis, radial);
      const double a = rng.in(0, 2 * kPi);
      const auto tilt = rotation(t * std::cos(a) + radial * std::sin(a), rng.in(0, 3) * kPi / 180);
      const auto spin = rotation(u, rng.in(0, 2 * kPi));
      std::array<std::array<double, 3>, 3> rot{};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rot[r][c] = tilt[r][0] * spin[0][c] + tilt[r][1] * spin[1][c] + tilt[r][2] * spin[2][c];
      const Vec3 shift = radial * rng.in(-0.3, 0.4) + u * rng.in(-6, 6) + t * rng.in(-0.5, 0.5);
      Transform q;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) q.r[r][c] = rot[r][0] * p0.r[0][c] + rot[r][1] * p0.r[1][c] + rot[r][2] * p0.r[2][c];
      const Vec3 off = p0.t - mid;
      q.t = mid + shift + Vec3{rot[0][0] * off.x + rot[0][1] * off.y + rot[0][2] * off.z,
                               rot[1][0] * off.x + rot[1][1] * off.y + rot[1][2] * off.z,
                               rot[2][0] * off.x + rot[2][1] * off.y + rot[2][2] * off.z};
      poses[i] = q;
    }
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_outer || !as.parts[pair.a].scarred) continue;
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      // the brute force: every vertex
      const TriMesh& mesh = *as.parts[pair.a].mesh;
      double best = -1;
      Vec3 far;
      for (const Vec3& v : mesh.positions) {
        const Vec3 x = poses[pair.a].apply(v);
        const Vec3 d = x - centre;
        const double rho = norm(d - ring_axis * dot(d, ring_axis));
        if (rho > best) best = rho, far = x;
      }
      const double z = dot(far - centre, ring_axis);
      if (!(z >= -0.5 * b.outer_width && z <= 0.5 * b.outer_width)) continue;  // (the clipped mesh decides)
      SCOPED_TRACE(as.parts[pair.a].id + " round " + std::to_string(round));
      EXPECT_NEAR(r.distance, b.outer_raceway - best, 1e-12 * b.outer_raceway);
      EXPECT_LT(norm(r.point_a - far), 1e-9);
      EXPECT_TRUE(r.exact);
      EXPECT_EQ(r.solver, AssemblySolver::vertex);
      ++compared;
    }
  }
  EXPECT_GT(compared, 60);
}

TEST(BearingAssemblyBoreColumns, InwardScarsAgainstEveryVertex) { check(false); }
TEST(BearingAssemblyBoreColumns, RaisedScarsAgainstEveryVertex) { check(true); }

}  // namespace
}  // namespace interfere::bearing
