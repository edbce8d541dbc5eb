// Scars on raceways and the roller-scarred raceway pair solver (issue #27, deliverable 2;
// raceway_scar.h, raceway_scar_solver.h). Each term of the pair value is checked against an
// independent oracle: bearing_oracle.h's best-first subdivision of the posed triangles with a
// convexity lower bound and its own signed distance (the bracket refined to 1e-9 around the
// minimum), and for a concave raceway's roller term a dense sampling of every roller triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "interfere/bearing/raceway_scar.h"
#include "interfere/bearing/raceway_scar_solver.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scar_import.h"
#include "bearing_oracle.h"
#include "frustum_oracle.h"

using namespace interfere;
using namespace interfere::bearing;
using bearing_oracle::oracle_sd;
using bearing_oracle::surface_min_bracket;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

RacewayGeometry inner_race() { return {.surface = RacewaySurface::inner, .z0 = -25, .width = 50, .radius = 80, .top_radius = 80}; }
RacewayGeometry outer_race() { return {.surface = RacewaySurface::outer, .z0 = -25, .width = 50, .radius = 100.1, .top_radius = 100.1}; }

ScarParams window(bool raised, std::uint64_t seed) {
  return {.angle_center_deg = 0, .angle_width_deg = 45, .z_min = 5, .z_max = 45, .depth = 0.05,
          .roughness = 0.6, .border = 2, .seed = seed, .raised = raised};
}

RacewayScar scar_on(const RacewayGeometry& g, bool raised, std::uint64_t seed, RacewayGrid grid = {}) {
  Expected<RacewayScar> s = make_raceway_scar(g, grid, window(raised, seed));
  EXPECT_TRUE(s.has_value()) << (s ? "" : s.error().message());
  return std::move(*s);
}

Roller scarred_roller(std::uint64_t seed, bool raised) {
  Expected<Roller> r = make_roller({.radius = 10, .height = 38, .radial_segments = 64, .height_segments = 63});
  EXPECT_TRUE(r.has_value());
  ScarParams s{.angle_center_deg = 0, .angle_width_deg = 359, .z_min = 2, .z_max = 36, .depth = 0.04,
               .roughness = 0.6, .border = 2, .seed = seed, .raised = raised};
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

/// The raceway's triangles in the world (a concave raceway's end caps left out, as the solver).
std::vector<std::array<Vec3, 3>> raceway_triangles(const RacewayScar& s, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  const std::size_t sides = 2u * s.surface.n() * s.surface.m();
  const std::size_t count = raceway_concave(s.geometry.surface) ? sides : s.surface.mesh.num_triangles();
  for (std::size_t t = 0; t < count; ++t) {
    const auto c = s.surface.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

std::vector<std::array<Vec3, 3>> roller_triangles(const Roller& r, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const auto c = r.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

/// A roller pose against a raceway of radius R about the world z axis: its mid point at angle phi,
/// at distance R + side * (10 - press) from the axis (side +1 outside a convex raceway, -1 inside a
/// bore), tilted by `tilt` about the radial direction.
Transform roller_at(double R, int side, double phi, double press, double tilt, double spin) {
  const Vec3 radial{std::cos(phi), std::sin(phi), 0};
  const Vec3 mid = radial * (R + side * (10 - press)) + Vec3{0, 0, 0.7};
  // roller_pose tilts about (-sin az, cos az, 0): azimuth phi + 90 deg tilts in the tangential plane
  const double az = phi + 0.5 * std::numbers::pi;
  const Vec3 axis{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
  return roller_pose(mid - axis * 19.0, tilt, az, spin);
}

void expect_in_bracket(double value, const bearing_oracle::Bracket& br, const char* what, int trial) {
  ASSERT_LE(br.upper - br.lower, 1e-9) << what << " " << trial;
  EXPECT_GE(value, br.lower - 1e-12) << what << " " << trial;
  EXPECT_LE(value, br.upper + 1e-12) << what << " " << trial;
}

}  // namespace

TEST(RacewayScar, GeneratedScarLiesInItsWindowWithTheRightSign) {
  for (const bool raised : {false, true})
    for (const RacewayGeometry& g : {inner_race(), outer_race()}) {
      const RacewayScar s = scar_on(g, raised, 3);
      ASSERT_GT(s.scar_vertices, 0);
      const Roller& r = s.surface;
      double toward_max = 0, toward_min = 0;
      for (int j = 0; j <= r.m(); ++j)
        for (int i = 0; i < r.n(); ++i) {
          const std::uint32_t v = r.side_vertex(i, j);
          const Vec3 p = r.mesh.positions[v];
          const double rho = std::hypot(p.x, p.y);
          // toward the rollers: away from the axis for the inner raceway, toward it for the bore
          const double toward = (rho - g.radius) * (raceway_concave(g.surface) ? -1 : 1);
          if (!r.scar[v]) {
            EXPECT_NEAR(rho, g.radius, 1e-12 * g.radius);
            continue;
          }
          const double ang = std::atan2(p.y, p.x) / kDeg;
          EXPECT_LE(std::fabs(ang), 22.5 + 1e-9);
          EXPECT_GE(p.z, 5 - 1e-9);
          EXPECT_LE(p.z, 45 + 1e-9);
          toward_max = std::max(toward_max, toward), toward_min = std::min(toward_min, toward);
        }
      if (raised) {
        EXPECT_GT(toward_max, 0.01);
        EXPECT_GE(toward_min, -1e-12);
        EXPECT_NEAR(s.raise, toward_max, 1e-12);
      } else {
        EXPECT_LT(toward_min, -0.01);
        EXPECT_LE(toward_max, 1e-12);
        EXPECT_EQ(s.raise, 0);
      }
      // the window of the scar: inside the generated one
      EXPECT_LE(s.window.angle_width_deg, 45 + 1e-9);
      EXPECT_GE(s.window.z_min, 5 - 1e-9);
      EXPECT_LE(s.window.z_max, 45 + 1e-9);
    }
}

TEST(RacewayScar, IntactRollerOnScarredInnerRacewayMatchesOracle) {
  const RacewayGeometry g = inner_race();
  int trial = 0;
  for (const bool raised : {false, true}) {
    const RacewayScar s = scar_on(g, raised, 5);
    RacewayPairRing ring{&s, Transform::identity()};
    const auto tris = raceway_triangles(s, raceway_surface_pose(ring));
    for (const double phi : {-8.0, 0.0, 3.5, 15.0})
      for (const double press : {-0.02, 0.01, 0.06}) {
        const Transform pose = roller_at(g.radius, +1, phi * kDeg, press, 0.1 * kDeg * (trial % 3), 0.3 * trial);
        RacewayPairRoller roller{posed_cylinder(10, -1, 38, pose), nullptr, nullptr, pose};
        ASSERT_TRUE(raceway_scar_in_range(roller, ring));
        const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
        EXPECT_TRUE(r.exact);
        EXPECT_EQ(r.roller_term, std::numeric_limits<double>::infinity());
        expect_in_bracket(r.distance, surface_min_bracket(tris, roller.cylinder, 1e-9), "inner", trial);
        // witnesses: point_raceway on a raceway triangle, point_roller its nearest on the roller
        EXPECT_NEAR(oracle_sd(roller.cylinder, r.point_raceway).value, r.distance, 1e-9) << trial;
        EXPECT_NEAR(std::fabs(norm(r.point_raceway - r.point_roller)), std::fabs(r.distance), 1e-9) << trial;
        // one number for the pair, whichever part is first (bitwise)
        const RacewayScarPairResult q = raceway_scar_pair(ring, roller);
        EXPECT_EQ(q.distance, r.distance);
        EXPECT_EQ(q.point_roller, r.point_roller);
        EXPECT_EQ(q.carrier, r.carrier);
        ++trial;
      }
  }
}

TEST(RacewayScar, ScarredRollerOnScarredInnerRacewayMatchesOracle) {
  const RacewayGeometry g = inner_race();
  int trial = 0;
  for (const bool raised : {false, true}) {
    const RacewayScar s = scar_on(g, raised, 7);
    const Roller rl = scarred_roller(9, !raised);
    const RollerQuadtree tree = build_quadtree(rl);
    RacewayPairRing ring{&s, Transform::identity()};
    const auto tris = raceway_triangles(s, raceway_surface_pose(ring));
    for (const double phi : {-4.0, 2.0})
      for (const double press : {0.0, 0.05}) {
        const Transform pose = roller_at(g.radius, +1, phi * kDeg, press, 0.05 * kDeg, 0.7 * trial);
        RacewayPairRoller roller{posed_cylinder(10, -1, 38, pose), &rl, &tree, pose};
        const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
        // raceway term: against the roller's cylinder grown by its raise
        Cylinder a = roller.cylinder;
        a.radius += rl.raise;
        expect_in_bracket(r.raceway_term, surface_min_bracket(tris, a, 1e-9), "raceway term", trial);
        // roller term: the roller's triangles against the raceway cylinder grown by the scar's raise
        Cylinder b;
        b.base = {0, 0, g.z0}, b.axis = {0, 0, 1}, b.height = g.width, b.radius = g.radius + s.raise;
        expect_in_bracket(r.roller_term, surface_min_bracket(roller_triangles(rl, pose), b, 1e-9), "roller term", trial);
        EXPECT_EQ(r.distance, std::min(r.raceway_term, r.roller_term));
        EXPECT_TRUE(r.scar);  // a scar triangle, or a solid grown by the other scar's raise
        EXPECT_EQ(raceway_scar_pair(ring, roller).distance, r.distance);
        ++trial;
      }
  }
}

TEST(RacewayScar, RollersInAScarredBoreMatchOracle) {
  const RacewayGeometry g = outer_race();
  int trial = 0;
  for (const bool raised : {false, true}) {
    const RacewayScar s = scar_on(g, raised, 11);
    const Roller rl = scarred_roller(13, raised);
    const RollerQuadtree tree = build_quadtree(rl);
    RacewayPairRing ring{&s, Transform::identity()};
    const auto tris = raceway_triangles(s, raceway_surface_pose(ring));
    for (const double phi : {-6.0, 1.0, 9.0})
      for (const double press : {-0.03, 0.04}) {
        const Transform pose = roller_at(g.radius, -1, phi * kDeg, press, 0.08 * kDeg, 0.4 * trial);
        // intact roller: the raceway term only
        RacewayPairRoller intact{posed_cylinder(10, -1, 38, pose), nullptr, nullptr, pose};
        const RacewayScarPairResult ri = raceway_scar_pair(intact, ring);
        expect_in_bracket(ri.distance, surface_min_bracket(tris, intact.cylinder, 1e-9), "bore intact", trial);
        // scarred roller: both terms
        RacewayPairRoller roller{intact.cylinder, &rl, &tree, pose};
        const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
        Cylinder a = roller.cylinder;
        a.radius += rl.raise;
        expect_in_bracket(r.raceway_term, surface_min_bracket(tris, a, 1e-9), "bore raceway term", trial);
        // roller term, independently: the roller lies in the width here, so it is minus the
        // largest of rho - (R - raise) over the roller's surface; dense samples of every triangle
        // (rho is convex: no sample may exceed the solver's maximum, and the vertices reach it)
        double sampled = -1e300;
        for (const auto& t : roller_triangles(rl, pose))
          for (int u = 0; u <= 6; ++u)
            for (int v = 0; u + v <= 6; ++v) {
              const Vec3 p = t[0] + (t[1] - t[0]) * (u / 6.0) + (t[2] - t[0]) * (v / 6.0);
              ASSERT_GT(p.z, g.z0);
              ASSERT_LT(p.z, g.z0 + g.width);
              sampled = std::max(sampled, std::hypot(p.x, p.y) - (g.radius - s.raise));
            }
        EXPECT_NEAR(r.roller_term, -sampled, 1e-9 * std::max(1.0, std::fabs(sampled))) << trial;
        EXPECT_EQ(r.distance, std::min(r.raceway_term, r.roller_term));
        EXPECT_EQ(raceway_scar_pair(ring, roller).distance, r.distance);
        ++trial;
      }
  }
}

TEST(RacewayScar, APitRelievesAndARaisedScarDeepens) {
  // the same pressed roller over an intact, a pitted and a raised stretch of the same raceway grid
  const RacewayGeometry g = inner_race();
  const Transform pose = roller_at(g.radius, +1, 0, 0.02, 0, 0);
  RacewayPairRoller roller{posed_cylinder(10, -1, 38, pose), nullptr, nullptr, pose};
  ScarParams far = window(false, 1);
  far.angle_center_deg = 180;  // the scar away from the roller
  const RacewayScar intact = *make_raceway_scar(g, {}, far);
  const RacewayScar pit = scar_on(g, false, 1), bump = scar_on(g, true, 1);
  const double v0 = raceway_scar_pair(roller, RacewayPairRing{&intact, Transform::identity()}).distance;
  const RacewayScarPairResult vp = raceway_scar_pair(roller, RacewayPairRing{&pit, Transform::identity()});
  const RacewayScarPairResult vb = raceway_scar_pair(roller, RacewayPairRing{&bump, Transform::identity()});
  // intact: the depth 0.02 to within the facets' sagitta (80 (1 - cos(pi / 512)) = 1.5e-3)
  EXPECT_NEAR(v0, -0.02, 80 * (1 - std::cos(std::numbers::pi / 512)) + 1e-9);
  EXPECT_GT(vp.distance, v0);
  EXPECT_LT(vb.distance, v0);
  EXPECT_TRUE(vb.scar);
  EXPECT_EQ(vb.carrier, ScarCarrier::raceway);
}

TEST(RacewayScar, ImportedMapsPointCloudsAndBadInput) {
  const std::string dir = ::testing::TempDir();
  const std::string csv = dir + "/raceway_scar.csv";
  {
    std::ofstream f(csv);
    f << "# a raised bump on the raceway\nz\\angle_deg, -5, 0, 5\n10, 0, 0, 0\n20, 0, 0.03, 0\n30, 0, 0, 0\n";
  }
  const Expected<HeightMap> map = read_scar_csv(csv);
  ASSERT_TRUE(map.has_value());
  for (const RacewayGeometry& g : {inner_race(), outer_race()}) {
    const Expected<RacewayScar> s = make_raceway_scar(g, {}, *map);
    ASSERT_TRUE(s.has_value()) << s.error().message();
    EXPECT_NEAR(s->raise, 0.03, 1e-3);  // the node at (0 deg, z 20) lands on a vertex or next to it
    // raised toward the rollers: outward for the inner raceway, inward for the bore
    const Roller& r = s->surface;
    double toward = 0;
    for (std::size_t v = 0; v < r.scar.size(); ++v) {
      const Vec3 p = r.mesh.positions[v];
      toward = std::max(toward, (std::hypot(p.x, p.y) - g.radius) * (raceway_concave(g.surface) ? -1 : 1));
    }
    EXPECT_NEAR(toward, s->raise, 1e-12);
  }
  // a map row off the raceway: the file and its line
  const std::string off = dir + "/raceway_scar_off.csv";
  {
    std::ofstream f(off);
    f << "z\\angle_deg, -5, 0, 5\n10, 0, 0, 0\n60, 0, 0.03, 0\n";
  }
  const Expected<RacewayScar> e = make_raceway_scar(inner_race(), {}, *read_scar_csv(off));
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().file, off);
  EXPECT_EQ(e.error().line, 3);
  EXPECT_NE(e.error().reason.find("outside the inner raceway"), std::string::npos) << e.error().reason;
  // non-finite heights: the reader's error names the line
  const std::string nan = dir + "/raceway_scar_nan.csv";
  {
    std::ofstream f(nan);
    f << "z\\angle_deg, -5, 0, 5\n10, 0, nan, 0\n20, 0, 0, 0\n";
  }
  const Expected<HeightMap> bad = read_scar_csv(nan);
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().line, 2);
  // a generated window off the raceway names the parameter
  ScarParams w = window(false, 1);
  w.z_max = 55;
  const Expected<RacewayScar> e2 = make_raceway_scar(inner_race(), {}, w, "bearings[0].scars[0]");
  ASSERT_FALSE(e2.has_value());
  EXPECT_NE(e2.error().reason.find("bearings[0].scars[0].z_max"), std::string::npos) << e2.error().reason;
  // heights of the wrong grid size
  Expected<RacewayScar> s = make_raceway_scar(inner_race(), {}, window(false, 1));
  ASSERT_TRUE(s.has_value());
  VertexHeights wrong;
  wrong.n = 64, wrong.m = 63, wrong.height.assign(64 * 64, 0.0), wrong.covered.assign(64 * 64, 1), wrong.source = "map.csv";
  const Expected<int> e3 = apply_vertex_heights(s->surface, wrong);
  ASSERT_FALSE(e3.has_value());
  EXPECT_EQ(e3.error().file, "map.csv");
  // a point cloud of a pit in the bore (ring frame): radial deviation +0.02 (into the ring)
  std::vector<Vec3> pts;
  for (int a = -10; a <= 10; ++a)
    for (int zz = -10; zz <= 10; ++zz) {
      const double phi = a * 0.2 * kDeg, z = zz * 0.5;
      const double dev = 0.02 * std::max(0.0, 1 - (a * a + zz * zz) / 100.0);
      pts.push_back({(100.1 + dev) * std::cos(phi), (100.1 + dev) * std::sin(phi), z});
    }
  const Expected<RacewayScar> pc = make_raceway_scar(outer_race(), {}, pts);
  ASSERT_TRUE(pc.has_value()) << pc.error().message();
  EXPECT_GT(pc->scar_vertices, 0);
  EXPECT_LT(pc->raise, 1e-12);  // a pit: nothing toward the rollers (to rounding)
  pts.push_back({100, 0, 40});  // off the raceway (z0 = -25, width 50)
  const Expected<RacewayScar> pc2 = make_raceway_scar(outer_race(), {}, pts, {}, "scan.xyz");
  ASSERT_FALSE(pc2.has_value());
  EXPECT_NE(pc2.error().reason.find("point 441"), std::string::npos) << pc2.error().reason;
}

TEST(RacewayScar, TaperedRollerOnAScarredConeIsExact) {
  const RacewayGeometry g{.surface = RacewaySurface::cone, .z0 = 0, .width = 30, .radius = 40, .top_radius = 50};
  Expected<RacewayScar> s = make_raceway_scar(g, {.radial_segments = 256, .height_segments = 31},
                                              ScarParams{.angle_center_deg = 0, .angle_width_deg = 60, .z_min = 5,
                                                         .z_max = 25, .depth = 0.05, .border = 1, .seed = 2});
  ASSERT_TRUE(s.has_value()) << s.error().message();
  RacewayPairRing ring{&*s, Transform::identity()};
  const Transform pose = roller_pose({55, 0, 0}, 0, 0, 0);
  RacewayPairRoller roller{posed_cylinder(8, 9.5, 30, pose), nullptr, nullptr, pose};
  const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
  // exact since issue #27's tapered scars (scarred.h takes the roller's frustum): the raceway's
  // triangles against the frustum, in frustum_oracle.h's bracket
  EXPECT_TRUE(r.exact);
  const frustum_oracle_ns::Bracket br =
      frustum_oracle_ns::frustum_min_bracket(raceway_triangles(*s, raceway_surface_pose(ring)), roller.cylinder, 1e-10);
  ASSERT_LE(br.upper - br.lower, 1e-9);
  EXPECT_GE(r.distance, br.lower - 1e-12);
  EXPECT_LE(r.distance, br.upper + 1e-12);
  // a scarred (raised) tapered roller: its roller term against the cone's frustum grown by the
  // raceway scar's raise, exact too
  Expected<Roller> rl = make_roller({.radius = 8, .top_radius = 9.5, .height = 30, .radial_segments = 32,
                                     .height_segments = 31});
  ASSERT_TRUE(rl.has_value());
  ASSERT_TRUE(apply_scar(*rl, {.angle_center_deg = 180, .angle_width_deg = 120, .z_min = 2, .z_max = 28,
                               .depth = 0.03, .border = 2, .seed = 9, .raised = true})
                  .has_value());
  const RollerQuadtree tree = build_quadtree(*rl);
  const RacewayScarPairResult rs = raceway_scar_pair(RacewayPairRoller{roller.cylinder, &*rl, &tree, pose}, ring);
  EXPECT_TRUE(rs.exact);
  Cylinder cone;
  cone.base = {0, 0, 0}, cone.axis = {0, 0, 1}, cone.height = 30, cone.radius = 40 + s->raise, cone.top_radius = 50 + s->raise;
  const frustum_oracle_ns::Bracket bt = frustum_oracle_ns::frustum_min_bracket(roller_triangles(*rl, pose), cone, 1e-10);
  ASSERT_LE(bt.upper - bt.lower, 1e-9);
  EXPECT_GE(rs.roller_term, bt.lower - 1e-12);
  EXPECT_LE(rs.roller_term, bt.upper + 1e-12);
  EXPECT_LT(rs.roller_term, 0);  // the roller's top end reaches into the cone
  EXPECT_EQ(rs.distance, std::min(rs.raceway_term, rs.roller_term));
}

// ---- in bearing assemblies (bearings[i].scars; assembly_raceway_scars.h) ----

#include "interfere/bearing/assembly.h"
#include "assembly_fixture.h"

namespace {
std::string with_scars(const char* bearing, const std::string& scars) {
  std::string b = bearing;
  b.insert(b.rfind('}'), ", \"scars\": [" + scars + "]");
  return b;
}
}  // namespace

TEST(RacewayScarAssembly, RowsInRangeUseTheScarredRacewaySolver) {
  using namespace interfere::bearing::test;
  const std::string scars =
      R"({"part": "inner", "angle_center_deg": 30, "angle_width_deg": 100, "depth": 0.04, "raised": true, "seed": 3,
          "radial_segments": 256, "height_segments": 31},
         {"part": "outer", "angle_center_deg": 250, "angle_width_deg": 120, "depth": 0.03, "seed": 4,
          "radial_segments": 256, "height_segments": 31})";
  const Expected<AssemblySpec> spec =
      parse_assembly(assembly_json(kLively, with_scars(kCylindricalBearing, scars) + "," + kTaperedBearing), "a.json");
  ASSERT_TRUE(spec.has_value()) << spec.error().message();
  const Expected<AssemblySpec> plain_spec = parse_assembly(assembly_json(kLively, both_bearings()), "a.json");
  ASSERT_TRUE(plain_spec.has_value());
  const Expected<Assembly> as = build_assembly(*spec);
  const Expected<Assembly> plain = build_assembly(*plain_spec);
  ASSERT_TRUE(as.has_value()) << as.error().message();
  ASSERT_TRUE(plain.has_value());
  ASSERT_TRUE(as->parts[static_cast<std::size_t>(as->find("cyl/inner"))].raceway_scar);
  ASSERT_TRUE(as->parts[static_cast<std::size_t>(as->find("cyl/outer"))].raceway_scar);
  const AssemblyMotion motion = generate_motion(*as, 4, 3);
  int scarred_rows = 0, intact_rows = 0;
  for (const auto& poses : motion.poses)
    for (std::size_t k = 0; k < as->pairs.size(); ++k) {
      const AssemblyPair& pair = as->pairs[k];
      const AssemblyPart& ring = as->parts[pair.b];
      if (pair.kind != AssemblyPairKind::roller_inner && pair.kind != AssemblyPairKind::roller_outer) continue;
      const AssemblyPairResult r = solve_pair(*as, pair, poses, 0.05);
      const AssemblyPart& roller = as->parts[pair.a];
      RacewayPairRoller rp{posed_cylinder(10, -1, 20, poses[pair.a]), roller.scarred ? roller.roller.get() : nullptr,
                           roller.scarred ? roller.tree.get() : nullptr, poses[pair.a]};
      const RacewayPairRing rr{ring.raceway_scar.get(), poses[pair.b]};
      if (raceway_scar_in_range(rp, rr)) {
        const RacewayScarPairResult d = raceway_scar_pair(rr, rp);
        EXPECT_EQ(r.solver, AssemblySolver::scarred);
        EXPECT_EQ(r.distance, d.distance);
        EXPECT_EQ(r.point_a, d.point_roller);
        EXPECT_EQ(r.scar, d.scar);
        if (d.carrier == ScarCarrier::raceway) EXPECT_EQ(r.scar_part, 2);
        ++scarred_rows;
      } else {  // out of range: the intact ring's row, bitwise
        const AssemblyPairResult q = solve_pair(*plain, plain->pairs[k], poses, 0.05);
        EXPECT_EQ(r.distance, q.distance);
        EXPECT_EQ(r.solver, q.solver);
        ++intact_rows;
      }
    }
  EXPECT_GT(scarred_rows, 0);
  EXPECT_GT(intact_rows, 0);
}

TEST(RacewayScarAssembly, DescriptionErrorsNameThePath) {
  using namespace interfere::bearing::test;
  const auto error_of = [](const std::string& scars, const char* bearing = kCylindricalBearing) -> std::string {
    const Expected<AssemblySpec> spec = parse_assembly(assembly_json("", with_scars(bearing, scars)), "a.json");
    if (!spec) return spec.error().message();
    const Expected<Assembly> as = build_assembly(*spec);
    return as ? std::string() : as.error().message();
  };
  EXPECT_NE(error_of(R"({"part": "cup"})").find("bearings[0].scars[0].part"), std::string::npos);
  EXPECT_NE(error_of(R"({"part": "inner"})", kTaperedBearing).find("bearings[0].scars[0].part"), std::string::npos);
  EXPECT_NE(error_of(R"({"part": "inner", "bogus": 1})").find("bearings[0].scars[0].bogus: unknown key"), std::string::npos);
  EXPECT_NE(error_of(R"({"part": "inner", "raised": 1})").find("bearings[0].scars[0].raised"), std::string::npos);
  EXPECT_NE(error_of(R"({"part": "outer", "z_min": 2, "z_max": 30.5})").find("bearings[0].scars[0].z_max"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"part": "outer", "map": "m.csv", "depth": 0.1})").find("bearings[0].scars[0].depth"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"part": "inner"}, {"part": "inner", "seed": 2})").find("bearings[0].scars[1].part"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"part": "inner", "radial_segments": 4})").find("radial_segments"), std::string::npos);
  EXPECT_NE(error_of(R"({"part": "outer", "map": "/nonexistent/m.csv"})").find("/nonexistent/m.csv"), std::string::npos);
  EXPECT_EQ(error_of(R"({"part": "cone"}, {"part": "cup", "raised": true})", kTaperedBearing), "");
}

TEST(RacewayScar, ScarredTaperedRollerInAScarredCup) {
  // a tapered roller with a (raised) scar of its own (roller.h, scar.h: tapered rollers carry scars
  // as cylinders do) in a cup whose raceway carries a pit: the roller term (exact: the vertex maximum
  // of the meridian distance) against dense samples, the raceway term (the tapered roller's frustum
  // grown by its raise, exact since issue #27's tapered scars) against frustum_oracle.h's bracket
  const RacewayGeometry g{.surface = RacewaySurface::cup, .z0 = 0, .width = 40, .radius = 60, .top_radius = 70};
  Expected<RacewayScar> s = make_raceway_scar(g, {.radial_segments = 512, .height_segments = 63},
                                              ScarParams{.angle_center_deg = 0, .angle_width_deg = 40, .z_min = 2,
                                                         .z_max = 38, .depth = 0.04, .border = 2, .seed = 8});
  ASSERT_TRUE(s.has_value()) << s.error().message();
  Expected<Roller> rl = make_roller({.radius = 8, .top_radius = 9.5, .height = 30, .radial_segments = 64,
                                     .height_segments = 63});
  ASSERT_TRUE(rl.has_value());
  ASSERT_TRUE(apply_scar(*rl, {.angle_center_deg = 0, .angle_width_deg = 359, .z_min = 2, .z_max = 28,
                               .depth = 0.03, .border = 2, .seed = 4, .raised = true})
                  .has_value());
  const RollerQuadtree tree = build_quadtree(*rl);
  const double k = (g.top_radius - g.radius) / g.width, nk = std::sqrt(1 + k * k);
  const RacewayPairRing ring{&*s, Transform::identity()};
  int trial = 0;
  for (const double press : {-0.02, 0.03})
    for (const double spin : {0.0, 1.3}) {
      const double tilt = std::atan(6.0 / 30.0);  // the outer generator along the cup's line
      const double zr = 5 - 8 * std::sin(tilt);
      const Transform pose = roller_pose({g.radius + k * zr - press - 8 * std::cos(tilt), 0, 5}, tilt, 0, spin);
      RacewayPairRoller roller{posed_cylinder(8, 9.5, 30, pose), &*rl, &tree, pose};
      const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
      EXPECT_TRUE(r.exact);
      double sampled = -1e300;
      for (const auto& t : roller_triangles(*rl, pose))
        for (int u = 0; u <= 6; ++u)
          for (int v = 0; u + v <= 6; ++v) {
            const Vec3 p = t[0] + (t[1] - t[0]) * (u / 6.0) + (t[2] - t[0]) * (v / 6.0);
            ASSERT_GT(p.z, 0);
            ASSERT_LT(p.z, g.width);
            sampled = std::max(sampled, (std::hypot(p.x, p.y) - (g.radius_at(p.z) - s->raise)) / nk);
          }
      EXPECT_NEAR(r.roller_term, -sampled, 1e-9 * std::max(1.0, std::fabs(sampled))) << trial;
      Cylinder a = roller.cylinder;
      a.radius = 8 + rl->raise, a.top_radius = 9.5 + rl->raise;
      const frustum_oracle_ns::Bracket br =
          frustum_oracle_ns::frustum_min_bracket(raceway_triangles(*s, raceway_surface_pose(ring)), a, 1e-10);
      ASSERT_LE(br.upper - br.lower, 1e-9) << trial;
      EXPECT_GE(r.raceway_term, br.lower - 1e-12) << trial;
      EXPECT_LE(r.raceway_term, br.upper + 1e-12) << trial;
      EXPECT_EQ(r.distance, std::min(r.raceway_term, r.roller_term));
      ++trial;
    }
}
