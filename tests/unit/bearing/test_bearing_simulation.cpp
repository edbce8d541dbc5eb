// Simulation and broad phases (issue #4, deliverables 7 and 9): every broad phase finds the same
// pairs as all-pairs testing; results identical for 1 and N threads and for a fixed seed; every
// row agrees with an independent recomputation (bearing_oracle.h: its own signed distance and a
// subdivision bracket of the scarred surface's minimum; issue #23, item 14).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/simulation.h"
#include "interfere/bearing/scarred.h"
#include "bearing_oracle.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {
SceneParams small_scene() {
  SceneParams p;
  p.pairs = 24;
  p.frames = 30;
  p.roller = {.radius = 10, .height = 40, .radial_segments = 32, .height_segments = 31};
  p.gap = -0.1;
  p.max_tilt_deg = 1.0;
  p.spin_deg_per_frame = 9.0;
  p.scar = {.angle_center_deg = 0, .angle_width_deg = 90, .z_min = 0, .z_max = 40, .depth = 0.2, .seed = 5};
  p.scar_fraction = 0.25;
  p.seed = 77;
  return p;
}

bool same(const PairFrame& a, const PairFrame& b) {
  return a.frame == b.frame && a.pair == b.pair && a.distance == b.distance && a.point_a == b.point_a &&
         a.point_b == b.point_b && a.solver == b.solver && a.scar_in_range == b.scar_in_range &&
         a.box_overlap == b.box_overlap && a.tilt_deg == b.tilt_deg;
}
}  // namespace

TEST(BearingBroadPhase, AllMethodsAgreeWithAllPairs) {
  SplitMix64 g{3};
  std::vector<Box3> boxes(300);
  auto brute = make_broad_phase(BroadPhaseKind::brute_force);
  std::vector<std::unique_ptr<BroadPhase>> others;
  for (auto k : {BroadPhaseKind::sweep_and_prune, BroadPhaseKind::loose_octree, BroadPhaseKind::bvh})
    others.push_back(make_broad_phase(k));
  for (int frame = 0; frame < 5; ++frame) {
    for (Box3& b : boxes) {
      const Vec3 c{100 * g.uniform(), 100 * g.uniform(), 20 * g.uniform()};
      const Vec3 e{0.5 + 4 * g.uniform(), 0.5 + 4 * g.uniform(), 0.5 + 4 * g.uniform()};
      b = {c - e, c + e};
    }
    const auto want = brute->update(boxes);
    EXPECT_GT(want.size(), 10u);
    for (auto& o : others) EXPECT_EQ(o->update(boxes), want);
  }
}

TEST(BearingSimulation, IdenticalForOneAndManyThreadsAndAcrossBroadPhases) {
  SceneParams p = small_scene();
  SimulationResult one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    auto r = simulate(p);
    ASSERT_TRUE(r.has_value()) << r.error().message();
    one = std::move(*r);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 4);
    auto r = simulate(p);
    ASSERT_TRUE(r.has_value());
    many = std::move(*r);
  }
  ASSERT_EQ(one.rows.size(), static_cast<std::size_t>(p.pairs * p.frames));
  ASSERT_EQ(one.rows.size(), many.rows.size());
  for (std::size_t k = 0; k < one.rows.size(); ++k) ASSERT_TRUE(same(one.rows[k], many.rows[k])) << k;
  EXPECT_GT(one.scarred_solves, 0u);
  EXPECT_GT(one.interfering_rows, 0u);
  EXPECT_EQ(one.cross_pairs, 0u);
  for (auto k : {BroadPhaseKind::brute_force, BroadPhaseKind::loose_octree, BroadPhaseKind::bvh}) {
    p.broad_phase = k;
    auto r = simulate(p);
    ASSERT_TRUE(r.has_value());
    for (std::size_t i = 0; i < one.rows.size(); ++i) ASSERT_TRUE(same(one.rows[i], r->rows[i]));
  }
  for (const PairFrame& row : one.rows) {
    EXPECT_TRUE(std::isfinite(row.distance));
    EXPECT_TRUE(is_finite(row.point_a) && is_finite(row.point_b));
  }
}

TEST(BearingSimulation, RowsMatchIndependentRecomputation) {
  SceneParams p = small_scene();
  p.pairs = 8, p.frames = 40;
  auto r = simulate(p);
  ASSERT_TRUE(r.has_value());
  // recompute every scarred-solver row with the exact surface reference on a rebuilt roller
  std::vector<Roller> variants;
  for (int v = 0; v < 2; ++v) {
    Roller roller = *make_roller(p.roller);
    ScarParams sp = p.scar;
    sp.seed = p.scar.seed + static_cast<std::uint64_t>(v);
    ASSERT_TRUE(apply_scar(roller, sp).has_value());
    variants.push_back(std::move(roller));
  }
  int checked = 0, out_of_range = 0, standard_checked = 0;
  for (const PairFrame& row : r->rows) {
    Cylinder b;
    b.base = {row.point_b.x, row.point_b.y, 0};  // placeholder, replaced below
    const double S = r->spacing;
    const int cols = 3;  // ceil(sqrt(8))
    const double ox = (row.pair % cols) * S, oy = (row.pair / cols) * S;
    b.base = {ox, oy, 0.5 * 40 - 0.5 * p.partner_height};
    b.axis = {0, 0, 1}, b.height = p.partner_height, b.radius = p.partner_radius;
    const double kDeg = std::numbers::pi / 180;
    const Transform pose = roller_pose({ox + 40 + p.gap, oy, 0}, row.tilt_deg * kDeg, row.azimuth_deg * kDeg,
                                       row.spin_deg * kDeg);
    // the witnesses attain the value (the oracle's own signed distance): A's point in B, or for an
    // intact roller's two-sided row where B's depth into A decided, B's point in A
    const double forward = bearing_oracle::oracle_sd(b, row.point_a).value;
    const double reverse =
        row.scarred_roller ? forward : bearing_oracle::oracle_sd(posed_cylinder(10, -1, 40, pose), row.point_b).value;
    EXPECT_TRUE(std::fabs(forward - row.distance) <= 1e-9 || std::fabs(reverse - row.distance) <= 1e-9)
        << "frame " << row.frame << " pair " << row.pair << ": " << row.distance << " vs " << forward << " / " << reverse;
    const int scarred_index = row.pair / 4;  // pairs 3 and 7 are scarred (fraction 1/4)
    if (!row.scarred_roller) {
      if (row.frame % 10 != 0) continue;
      // an intact roller: the independent bracket of the analytic value (fine tessellation, its
      // facet gap added below)
      // of both directions: the row is the two-sided S = min(s(A, B), s(B, A)) (issue #27)
      const Cylinder a = posed_cylinder(10, -1, 40, pose);
      bearing_oracle::Bracket br = bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(a, 4096), b, 1e-10);
      br.lower -= bearing_oracle::facet_gap(a, 4096);
      bearing_oracle::Bracket rev = bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(b, 4096), a, 1e-10);
      rev.lower -= bearing_oracle::facet_gap(b, 4096);
      br.lower = std::min(br.lower, rev.lower), br.upper = std::min(br.upper, rev.upper);
      EXPECT_LE(row.distance, br.upper + 1e-12) << "frame " << row.frame << " pair " << row.pair;
      EXPECT_GE(row.distance, br.lower - 1e-12) << "frame " << row.frame << " pair " << row.pair;
      ++standard_checked;
      continue;
    }
    // the scarred surface's minimum, bracketed independently (to 1e-9)
    std::vector<std::array<Vec3, 3>> tris;
    const Roller& variant = variants[static_cast<std::size_t>(scarred_index % 8)];
    for (std::size_t t = 0; t < variant.mesh.num_triangles(); ++t) {
      const auto c = variant.mesh.corners(t);
      tris.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
    }
    const bearing_oracle::Bracket ref = bearing_oracle::surface_min_bracket(tris, b, 1e-9);
    ASSERT_LE(ref.upper - ref.lower, 1e-9);
    if (row.solver == 1) {
      EXPECT_GE(row.distance, ref.lower - 1e-12) << "frame " << row.frame << " pair " << row.pair;
      EXPECT_LE(row.distance, ref.upper + 1e-12) << "frame " << row.frame << " pair " << row.pair;
      ++checked;
    } else {
      // the scar was judged out of range: the scarred mesh then differs from the intact cylinder's
      // analytic value by the facet sagitta at most (a scar at the contact would add its depth)
      const double sagitta = 10 * (1 - std::cos(std::numbers::pi / 32));
      EXPECT_GE(ref.upper, row.distance - 1e-12);
      EXPECT_LE(ref.lower, row.distance + sagitta + 1e-12) << "frame " << row.frame << " pair " << row.pair;
      ++out_of_range;
    }
  }
  EXPECT_GT(checked, 5);
  EXPECT_GT(out_of_range, 5);
  EXPECT_GT(standard_checked, 10);
}

TEST(BearingSimulation, FixedSeedIsReproducibleOtherSeedsDiffer) {
  SceneParams p = small_scene();
  p.pairs = 6, p.frames = 12;
  const auto a = simulate(p), b = simulate(p);
  p.seed += 1;
  const auto c = simulate(p);
  ASSERT_TRUE(a.has_value() && b.has_value() && c.has_value());
  bool any_difference = false;
  for (std::size_t k = 0; k < a->rows.size(); ++k) {
    EXPECT_TRUE(same(a->rows[k], b->rows[k]));
    any_difference |= a->rows[k].distance != c->rows[k].distance;
  }
  EXPECT_TRUE(any_difference);
}

TEST(BearingSimulation, BadParametersAreErrorsNamingThem) {
  SceneParams p = small_scene();
  p.max_tilt_deg = 95;
  EXPECT_NE(simulate(p).error().reason.find("max_tilt"), std::string::npos);
  p = small_scene();
  p.roller.radius = -2;
  EXPECT_NE(simulate(p).error().reason.find("roller.radius"), std::string::npos);
  p = small_scene();
  p.scar.z_max = 50;
  EXPECT_NE(simulate(p).error().reason.find("scar.z_max"), std::string::npos);
  p = small_scene();
  p.pairs = 0;
  EXPECT_NE(simulate(p).error().reason.find("pairs"), std::string::npos);
  p = small_scene();
  p.partner_radius = 0;
  EXPECT_NE(simulate(p).error().reason.find("partner.radius"), std::string::npos);
  p = small_scene();
  p.gap = std::numeric_limits<double>::infinity();
  EXPECT_NE(simulate(p).error().reason.find("gap"), std::string::npos);
  p = small_scene();
  p.roller.height = std::nan("");
  EXPECT_NE(simulate(p).error().reason.find("roller.height"), std::string::npos);
}

// Issue #27, Table 3's regression: the rows of intact rollers compute the reverse s(B, A) only when
// intact_reverse_lower_bound does not show it >= s(A, B). (1) The bound never exceeds s(B, A): checked
// against the independent facet bracket (B's inscribed tessellation lies in B, so the facets' minimum
// of sd_A is >= the solid's, and the bracket's upper end is an attained value) on 1,000 random poses, clear
// and overlapping, axes up to ~40 degrees apart. (2) intact_row_distance equals the two-sided value of
// both directions (two_sided_cylinder_distance) on many more poses, and (3) on the simulation's own
// rows (Table 3's geometry: r = 10, h = 40 pressed 0.05 into R = 30, tilt <= 1 degree).
TEST(BearingSimulation, IntactRowReverseBoundIsSound) {
  SplitMix64 g{2027};
  const auto u = [&] { return g.symmetric(); };
  const auto random_pair = [&] {
    Cylinder a, b;
    a.radius = 3 + 7 * (u() + 1), a.height = 6 + 20 * (u() + 1);
    b.radius = 3 + 14 * (u() + 1), b.height = 6 + 30 * (u() + 1);
    Vec3 ax{u(), u(), u()};
    ax = ax / norm(ax);
    Vec3 bx = ax + Vec3{u(), u(), u()} * (0.35 * (u() + 1));
    a.axis = ax, b.axis = bx / norm(bx);
    a.base = Vec3{u(), u(), u()} * 20, b.base = a.base + Vec3{u(), u(), u()} * 25;
    return std::pair{a, b};
  };
  int bracketed = 0, compared = 0, below = 0;
  for (int it = 0; it < 1000; ++it) {
    const auto [a, b] = random_pair();
    const double lb = intact_reverse_lower_bound(a, b);
    const double rev = cylinder_pair_distance(b, a).distance;
    const double tol = 1e-9 * (1 + std::fabs(rev));
    EXPECT_LE(lb, rev + tol) << "pose " << it;
    const double two = two_sided_cylinder_distance(a, b).distance;
    EXPECT_NEAR(intact_row_distance(a, b).distance, two, tol) << "pose " << it;
    ++compared, below += std::isfinite(lb) && lb >= cylinder_pair_distance(a, b).distance;
    if (it % 25 == 0 && std::isfinite(lb)) {  // the independent reference of s(B, A)
      const bearing_oracle::Bracket br =
          bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(b, 256), a, 1e-4);
      EXPECT_LE(lb, br.upper + 1e-12) << "pose " << it;
      ++bracketed;
    }
  }
  EXPECT_EQ(compared, 1000);
  EXPECT_GE(bracketed, 30);
  EXPECT_GT(below, 30);  // the skip is exercised

  SceneParams p = small_scene();
  p.pairs = 8, p.frames = 30, p.scar_fraction = 0;
  auto r = simulate(p);
  ASSERT_TRUE(r.has_value());
  for (std::size_t i = 0; i < r->rows.size(); ++i) {
    const PairFrame& row = r->rows[i];
    const Cylinder a = posed_cylinder(p.roller.radius, p.roller.top_radius, p.roller.height, r->roller_poses[i]);
    const Cylinder b = posed_cylinder(p.partner_radius, -1, p.partner_height, partner_pose(p, r->spacing, row.pair));
    const double two = two_sided_cylinder_distance(a, b).distance;
    EXPECT_NEAR(row.distance, two, 1e-9 * (1 + std::fabs(two))) << "frame " << row.frame << " pair " << row.pair;
    EXPECT_LE(intact_reverse_lower_bound(a, b), cylinder_pair_distance(b, a).distance + 1e-12);
  }
}

// Issue #27, Table 3 with the scars in range: intact_row_distance tries intact_reverse_tangent_bound
// before the secant bound. (1) The tangent bound never exceeds s(B, A) (the reverse standard solver,
// and on every 25th pose the independent facet bracket of B's surface); (2) on Table 3's geometry
// (r = 10, h = 40 pressed into R = 30 at the pivot, tilt <= 1 degree, any azimuth) it alone decides
// the skip for nearly every pose where the secant bound does; (3) where A and B overlap the row value
// equals two_sided_cylinder_distance bit for bit (the same numbers compared: a skip is proven by
// either bound with a margin far above the reverse solver's rounding).
TEST(BearingSimulation, IntactRowTangentBoundIsSound) {
  SplitMix64 g{4099};
  const auto u = [&] { return g.symmetric(); };
  int bracketed = 0, decided = 0, finite = 0;
  for (int it = 0; it < 1000; ++it) {
    Cylinder a, b;
    a.radius = 3 + 7 * (u() + 1), a.height = 6 + 20 * (u() + 1);
    b.radius = 3 + 14 * (u() + 1), b.height = 6 + 30 * (u() + 1);
    Vec3 ax{u(), u(), u()};
    ax = ax / norm(ax);
    const Vec3 bx = ax + Vec3{u(), u(), u()} * (0.35 * (u() + 1));
    a.axis = ax, b.axis = bx / norm(bx);
    a.base = Vec3{u(), u(), u()} * 20, b.base = a.base + Vec3{u(), u(), u()} * 25;
    const double tb = intact_reverse_tangent_bound(a, b);
    const double rev = cylinder_pair_distance(b, a).distance;
    EXPECT_LE(tb, rev + 1e-12 * (1 + std::fabs(rev))) << "pose " << it;
    const double fwd = cylinder_pair_distance(a, b).distance;
    EXPECT_LE(intact_reverse_tangent_bound(a, b, fwd), rev + 1e-12 * (1 + std::fabs(rev))) << "pose " << it;
    finite += std::isfinite(tb);
    if (it % 25 == 0 && std::isfinite(tb)) {
      const bearing_oracle::Bracket br =
          bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(b, 256), a, 1e-4);
      EXPECT_LE(tb, br.upper + 1e-12) << "pose " << it;
      ++bracketed;
    }
    if (fwd <= 0) {
      const PairDistance row = intact_row_distance(a, b), two = two_sided_cylinder_distance(a, b);
      EXPECT_EQ(row.distance, two.distance) << "pose " << it;
      EXPECT_EQ(row.point_a, two.point_a) << "pose " << it;
      EXPECT_EQ(row.point_b, two.point_b) << "pose " << it;
      decided += intact_reverse_tangent_bound(a, b, fwd) >= fwd;
    }
  }
  EXPECT_GE(bracketed, 30);
  EXPECT_GT(finite, 500);
  EXPECT_GT(decided, 10);  // the tangent skip is exercised on random poses too

  // Table 3's geometry: the roller pivots about its bottom centre at R + r - 0.05 from B's axis
  int skip_secant = 0, skip_tangent = 0, overlapping = 0;
  for (int it = 0; it < 2000; ++it) {
    const double tilt = (u() + 1) * 0.5 * 0.0174533, az = 3.2 * u(), spin = 3.2 * u();
    const Transform pose = roller_pose({39.95, 0, 0}, tilt, az, spin);
    const Cylinder a = posed_cylinder(10, -1, 40, pose);
    Cylinder b;
    b.base = {0, 0, -10}, b.axis = {0, 0, 1}, b.height = 60, b.radius = 30;
    const double fwd = cylinder_pair_distance(a, b).distance;
    const double rev = cylinder_pair_distance(b, a).distance;
    const double tb = intact_reverse_tangent_bound(a, b, fwd);
    EXPECT_LE(tb, rev + 1e-12) << "pose " << it;
    if (fwd > 0) continue;
    ++overlapping;
    skip_secant += intact_reverse_lower_bound(a, b) >= fwd;
    skip_tangent += tb >= fwd;
    const PairDistance row = intact_row_distance(a, b), two = two_sided_cylinder_distance(a, b);
    EXPECT_EQ(row.distance, two.distance) << "pose " << it;
    EXPECT_EQ(row.point_a, two.point_a) << "pose " << it;
  }
  EXPECT_GT(overlapping, 1900);
  EXPECT_GT(skip_secant, overlapping * 9 / 10);
  EXPECT_GE(skip_tangent, skip_secant - overlapping / 100);
}

// Issue #27, Table 3 with the scars in range (every scarred roller's scar band all around its side, so
// the scarred solver runs in every frame): the frame loop's blocked passes with the affinity
// partitioner give the same rows for 1, 2 and 3 threads, and every scarred row equals a cold solve
// (a fresh ScarredSolver: no previous triangle, no hint) and the exact surface reference bit for bit:
// the temporal coherence and the pruning change only the work, ties included.
TEST(BearingSimulation, ScarsInRangeRowsEqualColdSolvesForAnyThreadCount) {
  SceneParams p = small_scene();
  p.pairs = 40, p.frames = 12;
  p.spin_deg_per_frame = 3.0, p.gap = -0.05;
  p.scar = {.angle_center_deg = 0, .angle_width_deg = 359, .z_min = 0, .z_max = 40, .depth = 0.1, .seed = 3};
  p.broad_phase = BroadPhaseKind::bvh;
  std::vector<SimulationResult> runs;
  for (const int threads : {1, 2, 3}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    auto r = simulate(p);
    ASSERT_TRUE(r.has_value()) << r.error().message();
    runs.push_back(std::move(*r));
  }
  for (std::size_t t = 1; t < runs.size(); ++t) {
    ASSERT_EQ(runs[t].rows.size(), runs[0].rows.size());
    for (std::size_t k = 0; k < runs[0].rows.size(); ++k) {
      ASSERT_TRUE(same(runs[0].rows[k], runs[t].rows[k])) << "threads run " << t << " row " << k;
      ASSERT_EQ(runs[0].rows[k].evaluated, runs[t].rows[k].evaluated) << k;
      ASSERT_EQ(runs[0].rows[k].verdict, runs[t].rows[k].verdict) << k;
    }
  }
  const SimulationResult& r = runs[0];
  EXPECT_EQ(r.scarred_solves, static_cast<std::uint64_t>(r.scarred_rollers) * p.frames);
  std::vector<Roller> variants;
  std::vector<RollerQuadtree> trees;
  for (std::size_t v = 0; v < r.scar_meshes.size(); ++v) {
    Roller roller = *make_roller(p.roller);
    ScarParams sp = p.scar;
    sp.seed = p.scar.seed + v;
    ASSERT_TRUE(apply_scar(roller, sp).has_value());
    ASSERT_EQ(roller.mesh.positions, r.scar_meshes[v].positions);
    variants.push_back(std::move(roller));
  }
  for (const Roller& v : variants) trees.push_back(build_quadtree(v));
  int checked = 0;
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const PairFrame& row = r.rows[i];
    if (row.solver != 1) continue;
    const auto v = static_cast<std::size_t>(r.pair_variant[static_cast<std::size_t>(row.pair)]);
    const Cylinder b = posed_cylinder(p.partner_radius, -1, p.partner_height, partner_pose(p, r.spacing, row.pair));
    ScarredSolver cold(&variants[v], &trees[v]);
    const MeshPairResult c = cold.solve(r.roller_poses[i], b);
    const MeshPairResult ref = surface_reference(variants[v], r.roller_poses[i], b);
    ASSERT_EQ(row.distance, c.distance) << "frame " << row.frame << " pair " << row.pair;
    ASSERT_EQ(row.point_a, c.point_a) << "frame " << row.frame << " pair " << row.pair;
    ASSERT_EQ(c.distance, ref.distance) << "frame " << row.frame << " pair " << row.pair;
    ASSERT_EQ(c.triangle, ref.triangle) << "frame " << row.frame << " pair " << row.pair;
    ++checked;
  }
  EXPECT_EQ(checked, r.scarred_rollers * p.frames);
}
