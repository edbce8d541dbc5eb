// Rollers, scars, quadtree and the scarred solver (issue #4, deliverables 1, 2, 4, 6, 9): the
// temporally coherent solver equals the exact surface reference on seeded scars, and both lie in
// the bracket of an independent oracle (bearing_oracle.h: best-first subdivision of the posed
// triangles with a convexity lower bound, its own signed distance); vertex methods never beat it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "interfere/bearing/scarred.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/window.h"
#include "interfere/core/predicates.h"
#include "interfere/query/distance.h"
#include "bearing_oracle.h"

using namespace interfere;
using namespace interfere::bearing;
using bearing_oracle::oracle_sd;
using bearing_oracle::surface_min_bracket;

namespace {
Roller scarred_roller(int n, int m, std::uint64_t seed, double depth = 0.08) {
  Expected<Roller> r = make_roller({.radius = 10, .height = 40, .radial_segments = n, .height_segments = m});
  EXPECT_TRUE(r.has_value());
  ScarParams s{.angle_center_deg = 180, .angle_width_deg = 60, .z_min = 4, .z_max = 40, .depth = depth,
               .roughness = 0.6, .border = 2, .seed = seed};
  Expected<int> k = apply_scar(*r, s);
  EXPECT_TRUE(k.has_value());
  EXPECT_GT(*k, 0);
  return std::move(*r);
}

std::vector<std::array<Vec3, 3>> posed_triangles(const Roller& r, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const auto c = r.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

Cylinder partner() {
  Cylinder b;
  b.base = {0, 0, -10}, b.axis = {0, 0, 1}, b.height = 60, b.radius = 30;
  return b;
}
}  // namespace

TEST(BearingRoller, MeshIsClosedOutwardAndOnTheCylinder) {
  Expected<Roller> r = make_roller({.radius = 10, .height = 40, .radial_segments = 16, .height_segments = 5});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->mesh.num_triangles(), 2u * 16 * 5 + 2 * 16);
  // outward: every triangle's normal points away from the axis point at its height (exact sign)
  for (std::size_t t = 0; t < r->mesh.num_triangles(); ++t) {
    const auto c = r->mesh.corners(t);
    const Vec3 centroid = (c[0] + c[1] + c[2]) / 3.0;
    const Vec3 inner{0, 0, std::clamp(centroid.z, 1.0, 39.0)};
    EXPECT_GT(orient3d(c[0], c[1], c[2], inner), 0) << t;  // the inner point is below (behind) it
  }
  // signed volume = prism of the 16-gon
  double vol = 0;
  for (std::size_t t = 0; t < r->mesh.num_triangles(); ++t) {
    const auto c = r->mesh.corners(t);
    vol += dot(c[0], cross(c[1], c[2])) / 6;
  }
  EXPECT_NEAR(vol, 0.5 * 16 * 100 * std::sin(2 * std::numbers::pi / 16) * 40, 1e-9);
  // tapered roller
  Expected<Roller> t = make_roller({.radius = 10, .top_radius = 6, .height = 40, .radial_segments = 8, .height_segments = 4});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(norm(t->mesh.positions[t->side_vertex(0, 4)] - Vec3{0, 0, 40}), 6, 1e-12);
}

TEST(BearingRoller, BadParametersNameTheParameter) {
  EXPECT_NE(validate(RollerParams{.radius = 0}).error().reason.find("roller.radius"), std::string::npos);
  EXPECT_NE(validate(RollerParams{.height = -1}).error().reason.find("roller.height"), std::string::npos);
  EXPECT_NE(validate(RollerParams{.radial_segments = 2}).error().reason.find("radial_segments"), std::string::npos);
  EXPECT_NE(validate(RollerParams{.height_segments = 0}).error().reason.find("height_segments"), std::string::npos);
  EXPECT_NE(validate(RollerParams{.radius = std::nan("")}).error().reason.find("radius"), std::string::npos);
  const RollerParams rp;
  EXPECT_NE(validate(ScarParams{.z_min = -1}, rp).error().reason.find("scar.z_min"), std::string::npos);
  EXPECT_NE(validate(ScarParams{.z_max = 41}, rp).error().reason.find("scar.z_max"), std::string::npos);
  EXPECT_NE(validate(ScarParams{.angle_width_deg = 400}, rp).error().reason.find("angle_width"), std::string::npos);
  EXPECT_NE(validate(ScarParams{.depth = 20}, rp).error().reason.find("scar.depth"), std::string::npos);
  EXPECT_NE(validate(WindowParams{.max_tilt = 1.6}).error().reason.find("max_tilt"), std::string::npos);
  // h_b tan(alpha) > 2 min(r, R): beyond Eq. (1) (test_bearing_window.cpp has the range itself)
  EXPECT_FALSE(validate(WindowParams{.roller_radius = 1, .partner_radius = 1, .height = 40, .max_tilt = 0.2}).ok());
}

TEST(BearingScar, DiamondSquareIsSeededAndNormalised) {
  const auto a = diamond_square(5, 0.6, 7), b = diamond_square(5, 0.6, 7), c = diamond_square(5, 0.6, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a.size(), 33u * 33u);
  EXPECT_EQ(*std::min_element(a.begin(), a.end()), 0.0);
  EXPECT_EQ(*std::max_element(a.begin(), a.end()), 1.0);
}

TEST(BearingScar, DisplacementInsideWindowOnlyAndBorderJoinsSmoothly) {
  const Roller r = scarred_roller(64, 63, 3);
  double inside_max = 0;
  for (int j = 0; j <= r.m(); ++j)
    for (int i = 0; i < r.n(); ++i) {
      const std::uint32_t v = r.side_vertex(i, j);
      const double phi = r.angle(i) * 180 / std::numbers::pi;
      const bool in = std::fabs(phi - 180) <= 30 && r.z(j) >= 4;
      if (!in) EXPECT_EQ(r.displacement[v], 0.0) << i << "," << j;
      EXPECT_EQ(r.scar[v] != 0, in);
      EXPECT_GE(r.displacement[v], 0.0);
      EXPECT_LE(r.displacement[v], 0.08);
      inside_max = std::max(inside_max, r.displacement[v]);
      // the median-filtered border: the outermost window ring is at most the median of a
      // neighbourhood that is at least 2/5 zeros ... so never the unfiltered extreme
    }
  EXPECT_GT(inside_max, 0.0);
  // The border band against an independent median: the same scar without the filter (border 0)
  // gives the raw displacements; every window vertex within 2 grid steps of a vertex outside the
  // window (or beyond the roller's ends) must hold the median of the raw 5x5 neighbourhood
  // (outside = 0), every other vertex its raw value.
  Roller raw = *make_roller({.radius = 10, .height = 40, .radial_segments = 64, .height_segments = 63});
  ASSERT_TRUE(apply_scar(raw, {.angle_center_deg = 180, .angle_width_deg = 60, .z_min = 4, .z_max = 40,
                               .depth = 0.08, .roughness = 0.6, .border = 0, .seed = 3})
                  .has_value());
  int band = 0, filtered_changed = 0;
  for (int j = 0; j <= r.m(); ++j)
    for (int i = 0; i < r.n(); ++i) {
      const std::uint32_t v = r.side_vertex(i, j);
      if (!r.scar[v]) continue;
      std::vector<double> nb;
      bool near = false;
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
          const int jj = j + dj;
          const bool in = jj >= 0 && jj <= r.m() && raw.scar[raw.side_vertex(i + di, jj)] != 0;
          near |= !in;
          nb.push_back(in ? raw.displacement[raw.side_vertex(i + di, jj)] : 0.0);
        }
      std::sort(nb.begin(), nb.end());
      const double want = near ? nb[12] : raw.displacement[v];
      EXPECT_EQ(r.displacement[v], want) << i << "," << j;
      band += near;
      filtered_changed += near && want != raw.displacement[v];
    }
  EXPECT_GT(band, 100);
  EXPECT_GT(filtered_changed, 10);  // the filter did something on this seed
}

TEST(BearingQuadtree, LabelsBoundsAndLayers) {
  const Roller r = scarred_roller(32, 31, 5);
  const RollerQuadtree t = build_quadtree(r);
  // scar labels propagate to ancestors; bounds contain every vertex of their cells
  std::vector<std::int32_t> stack{t.side_root, t.bottom_root, t.top_root};
  int leaves = 0;
  std::size_t reached = 0;
  while (!stack.empty()) {
    const QuadNode& q = t.nodes[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    ++reached;
    bool any_scar = false;
    for (int j = q.j0; j < q.j1; ++j)
      for (int i = q.i0; i < q.i1; ++i) any_scar |= r.scar[r.side_vertex(i, j)] != 0;
    EXPECT_EQ(q.scar != 0, any_scar);
    if (q.half_r >= 0 && q.tri_count > 0) {
      for (std::uint32_t k = 0; k < q.tri_count; ++k)
        for (const std::uint32_t v : r.mesh.triangles[q.tri_first + k]) {
          const Vec3 p = r.mesh.positions[v] - q.box_center;
          EXPECT_LE(std::fabs(p.x * q.cos_mid + p.y * q.sin_mid), q.half_r);
          EXPECT_LE(std::fabs(-p.x * q.sin_mid + p.y * q.cos_mid), q.half_t);
          EXPECT_LE(std::fabs(p.z), q.half_z);
        }
    }
    if (q.child_count == 0) ++leaves;
    for (std::int32_t k = 0; k < q.child_count; ++k) stack.push_back(q.first_child + k);
  }
  EXPECT_EQ(leaves, 32 * 32 + 2 * 16);  // one leaf per side vertex, fan leaves of 2 triangles
  EXPECT_EQ(reached, t.nodes.size());   // every node is reachable (no orphans)
  // the former calculation layer rule (the paper's is tested in test_bearing_quadtree_layer.cpp):
  // nodes at that level still span 2*theta, the next level does not
  const double theta = 0.3;
  const std::int32_t L = t.calculation_layer(theta, 32, CalculationLayerRule::spanning_window);
  EXPECT_GE(2 * std::numbers::pi * std::ceil(32 / std::pow(2.0, L)) / 32, 2 * theta);
  EXPECT_LT(2 * std::numbers::pi * std::ceil(32 / std::pow(2.0, L + 1)) / 32, 2 * theta);
}

TEST(BearingScarred, TriangleMinimumAgainstDenseSampling) {
  const Cylinder b = partner();
  SplitMix64 g{11};
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 base{29 + 2 * g.uniform(), 3 * g.symmetric(), 50 * g.uniform() - 5};
    const Vec3 t0 = base, t1 = base + Vec3{g.symmetric(), g.symmetric(), 3 * g.symmetric()},
               t2 = base + Vec3{g.symmetric(), g.symmetric(), 3 * g.symmetric()};
    const TriangleMin tm = triangle_min_signed_distance(b, t0, t1, t2);
    // independent: subdivision with a convexity lower bound and its own signed distance
    const auto br = surface_min_bracket({{t0, t1, t2}}, b, 1e-10);
    ASSERT_LE(br.upper - br.lower, 1e-10) << trial;
    EXPECT_LE(tm.value, br.upper + 1e-12) << trial;
    EXPECT_GE(tm.value, br.lower - 1e-12) << trial;
    EXPECT_NEAR(oracle_sd(b, tm.point).value, tm.value, 1e-9) << trial;
  }
}

TEST(BearingScarred, CoherentSolverEqualsSurfaceReference) {
  const Cylinder b = partner();
  for (const std::uint64_t seed : {1ull, 2ull, 3ull}) {
    const Roller r = scarred_roller(32, 31, seed, 0.3);
    const RollerQuadtree t = build_quadtree(r);
    ScarredSolver solver(&r, &t), hinted(&r, &t);
    SplitMix64 g{seed};
    for (int frame = 0; frame < 40; ++frame) {
      // the scar (centred at 180 degrees) faces B (at -x) when the spin is near 0
      const double spin = (frame - 20) * 0.04;
      const double tilt = 0.02 * g.uniform(), az = 2 * std::numbers::pi * g.uniform();
      const Transform pose = roller_pose({40 - 0.2, 0, 0}, tilt, az, spin);
      const MeshPairResult fast = solver.solve(pose, b);
      const MeshPairResult ref = surface_reference(r, pose, b);
      // the pruning loses nothing: the branch and bound equals the all-triangle reference
      EXPECT_NEAR(fast.distance, ref.distance, 1e-9 * std::max(1.0, std::fabs(ref.distance))) << frame;
      // both share local_triangle_min, so the value itself is checked against the independent
      // oracle's bracket (bearing_oracle.h), refined to 1e-9
      const auto br = surface_min_bracket(posed_triangles(r, pose), b, 1e-9);
      ASSERT_LE(br.upper - br.lower, 1e-9) << frame;
      EXPECT_GE(ref.distance, br.lower - 1e-12) << frame;
      EXPECT_LE(ref.distance, br.upper + 1e-12) << frame;
      EXPECT_LT(fast.evaluated, ref.evaluated);
      // with the standard solver's witness as a hint (as the simulation does): same value
      const PairDistance pd = cylinder_pair_distance(posed_cylinder(10, -1, 40, pose), b);
      EXPECT_NEAR(hinted.solve(pose, b, pd.point_a).distance, ref.distance, 1e-9 * std::max(1.0, std::fabs(ref.distance)));
      EXPECT_NEAR(oracle_sd(b, fast.point_a).value, fast.distance, 1e-9);
      // vertices lie on the surface: a vertex method can only overestimate
      EXPECT_GE(vertex_brute_force(r, pose, b).distance, br.lower - 1e-12);
      EXPECT_GE(vertex_quadtree_method(r, t, pose, b, 0.1).distance, br.lower - 1e-12);
      EXPECT_NEAR(vertex_barbier_galin(r, pose, b).distance, vertex_brute_force(r, pose, b).distance, 1e-9);
      double vmin = 1e300;  // the vertex minimum by the oracle's own signed distance
      for (const Vec3& v : r.mesh.positions) vmin = std::min(vmin, oracle_sd(b, pose.apply(v)).value);
      EXPECT_NEAR(vertex_brute_force(r, pose, b).distance, vmin, 1e-12);
    }
  }
}

TEST(BearingScarred, IntactMeshBracketsTheAnalyticCylinder) {
  // the faceted mesh lies inside the cylinder: s(mesh) >= s(cylinder), within the facet sagitta
  Expected<Roller> r = make_roller({.radius = 10, .height = 40, .radial_segments = 48, .height_segments = 8});
  const Cylinder b = partner();
  SplitMix64 g{9};
  for (int k = 0; k < 20; ++k) {
    const Transform pose = roller_pose({40 + g.symmetric(), 0, 0}, 0.05 * g.uniform(), 6.3 * g.uniform(), 6.3 * g.uniform());
    const Cylinder a = posed_cylinder(10, -1, 40, pose);
    const double exact = cylinder_pair_distance(a, b).distance;
    const double mesh = surface_reference(*r, pose, b).distance;
    // the mesh value itself against the independent bracket (bearing_oracle.h)
    const auto br = surface_min_bracket(posed_triangles(*r, pose), b, 1e-9);
    ASSERT_LE(br.upper - br.lower, 1e-9);
    EXPECT_GE(mesh, br.lower - 1e-12);
    EXPECT_LE(mesh, br.upper + 1e-12);
    EXPECT_GE(mesh, exact - 1e-12);
    EXPECT_LE(mesh, exact + 10 * (1 - std::cos(std::numbers::pi / 48)) + 1e-12);
  }
}

TEST(BearingScarred, AgreesWithTheEngineMeshDistance) {
  // Independent oracle: the engine's own mesh distance (query/distance.h, exact tri-tri intersection
  // test) between the posed scarred roller mesh and a finely tessellated partner. The tessellated
  // partner lies inside the true one by at most its sagitta, so for separated parts the engine's
  // distance is within [s, s + sagitta]; for interpenetrating parts the engine reports intersection.
  const Cylinder b = partner();
  Roller pr = *make_roller({.radius = 30, .height = 60, .radial_segments = 2048, .height_segments = 1});
  TriMesh partner_mesh = transformed(pr.mesh, Transform{.t = b.base});
  const Model partner_model = make_model(partner_mesh);
  const double sagitta = 30 * (1 - std::cos(std::numbers::pi / 2048));
  const Roller r = scarred_roller(48, 47, 4, 0.2);
  SplitMix64 g{21};
  for (int k = 0; k < 12; ++k) {
    const bool apart = k % 2 == 0;
    const Transform pose = roller_pose({40 + (apart ? 0.5 : -0.3), 0, 0}, 0.02 * g.uniform(), 6.3 * g.uniform(),
                                       6.3 * g.uniform());
    const MeshPairResult s = surface_reference(r, pose, b);
    const DistanceResult d = distance(make_model(transformed(r.mesh, pose)), partner_model);
    if (apart) {
      ASSERT_GT(s.distance, 0);
      EXPECT_FALSE(d.intersecting);
      EXPECT_GE(d.distance, s.distance - 1e-9);
      EXPECT_LE(d.distance, s.distance + sagitta + 1e-9);
    } else {
      EXPECT_LT(s.distance, -0.1);
      EXPECT_TRUE(d.intersecting);
    }
  }
}
