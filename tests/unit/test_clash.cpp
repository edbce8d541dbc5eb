// Clash query against brute force (all |A|·|B| pairs through the exact test), determinism across
// thread counts, regions/curves on analytic cases, containment, clearance and distance.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <numbers>
#include <random>

#include "interfere/mesh/generate.h"
#include "interfere/np/distance.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "unit/reference_distance.h"

namespace interfere {
namespace {

std::vector<TrianglePair> brute_force_pairs(const TriMesh& a, const TriMesh& b) {
  std::vector<TrianglePair> out;
  for (std::uint32_t i = 0; i < a.num_triangles(); ++i) {
    for (std::uint32_t j = 0; j < b.num_triangles(); ++j) {
      const ContactKind k = tri_tri_exact(a.corners(i), b.corners(j)).kind;
      if (k != ContactKind::none) out.push_back({i, j, k});
    }
  }
  return out;
}

Transform random_pose(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> g;
  // Random rotation from a normalised quaternion.
  double q[4] = {g(rng), g(rng), g(rng), g(rng)};
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& x : q) x /= n;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Transform t;
  t.r = {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
  std::uniform_real_distribution<double> u(-spread, spread);
  t.t = {u(rng), u(rng), u(rng)};
  return t;
}

TEST(Clash, OverlappingSpheresMatchBruteForceAndFormOneClosedCurve) {
  SpherePair p = make_overlapping_spheres(3000);
  const auto expected = brute_force_pairs(p.a, p.b);
  const Model a = make_model(p.a), b = make_model(p.b);
  const ClashResult r = clash(a, b);
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(r.pairs, expected);
  ASSERT_EQ(r.regions.size(), 1u);
  ASSERT_EQ(r.regions[0].curves.size(), 1u);
  EXPECT_TRUE(r.regions[0].curves[0].closed);
  // Circle of radius sqrt(1 - 0.98²) ≈ 0.199, perturbed by the 1 % bumps and the facets.
  const double circle = 2 * std::numbers::pi * std::sqrt(1 - 0.98 * 0.98);
  EXPECT_NEAR(r.regions[0].curve_length, circle, 0.1 * circle);
  EXPECT_EQ(r.containment, Containment::none);
  EXPECT_TRUE(r.interference());
}

TEST(Clash, ResultIdenticalForOneAndTwoThreadsAndAllBuilders) {
  SpherePair p = make_overlapping_spheres(20000);
  std::vector<TrianglePair> reference;
  for (BvhBuilder builder : {BvhBuilder::lbvh, BvhBuilder::lbvh_treelet, BvhBuilder::binned_sah,
                             BvhBuilder::median_split, BvhBuilder::insertion}) {
    const Model a = make_model(p.a, {.builder = builder}), b = make_model(p.b, {.builder = builder});
    for (int threads : {1, 2}) {
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
      const ClashResult r = clash(a, b);
      if (reference.empty()) reference = r.pairs;
      EXPECT_EQ(r.pairs, reference) << bvh_builder_name(builder) << " threads=" << threads;
      const ClashResult serial = clash(a, b, {.parallel = false});
      EXPECT_EQ(serial.pairs, reference);
    }
  }
  EXPECT_FALSE(reference.empty());
}

TEST(Model, ConcurrentBuildOfTwoPartsGivesTheSameTreesAsSeparateBuilds) {
  const SpherePair p = make_overlapping_spheres(30000);
  for (int threads : {1, 2}) {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
    const auto [a, b] = make_models(p.a, p.b);
    const Model ra = make_model(p.a), rb = make_model(p.b);
    for (const auto& [m, ref] : {std::pair{&a, &ra}, std::pair{&b, &rb}}) {
      ASSERT_EQ(m->bvh.nodes.size(), ref->bvh.nodes.size());
      EXPECT_EQ(m->bvh.prims, ref->bvh.prims);
      for (std::size_t i = 0; i < m->bvh.nodes.size(); ++i) {
        EXPECT_EQ(m->bvh.nodes[i].first, ref->bvh.nodes[i].first);
        EXPECT_EQ(m->bvh.nodes[i].count, ref->bvh.nodes[i].count);
        EXPECT_TRUE(std::ranges::equal(m->bvh.nodes[i].box.lo, ref->bvh.nodes[i].box.lo));
        EXPECT_TRUE(std::ranges::equal(m->bvh.nodes[i].box.hi, ref->bvh.nodes[i].box.hi));
      }
      EXPECT_EQ(m->stats.open_edges, ref->stats.open_edges);
      EXPECT_EQ(m->mesh.positions.size(), ref->mesh.positions.size());
    }
    EXPECT_EQ(clash(a, b).pairs, clash(ra, rb).pairs);
  }
}

TEST(Clash, BroadPhasesAgree) {
  SpherePair p = make_overlapping_spheres(2000);
  const Model a = make_model(p.a), b = make_model(p.b);
  const ClashResult bvh = clash(a, b);
  const ClashResult brute = clash(a, b, {.broadphase = Broadphase::brute_force});
  const ClashResult box = clash(a, b, {.broadphase = Broadphase::box_pretest});
  EXPECT_EQ(bvh.pairs, brute.pairs);
  EXPECT_EQ(bvh.pairs, box.pairs);
  EXPECT_EQ(brute.candidate_pairs, a.mesh.num_triangles() * b.mesh.num_triangles());
  EXPECT_LT(bvh.candidate_pairs, box.candidate_pairs + 1);
}

TEST(Clash, FloatTestsFindTheCrossingPairsOnGenericInput) {
  SpherePair p = make_overlapping_spheres(5000);
  const Model a = make_model(p.a), b = make_model(p.b);
  const ClashResult exact = clash(a, b);
  for (TriTest t : {TriTest::moller, TriTest::guigue_devillers}) {
    const ClashResult f = clash(a, b, {.test = t});
    ASSERT_EQ(f.pairs.size(), exact.pairs.size());
    for (std::size_t i = 0; i < f.pairs.size(); ++i) {
      EXPECT_EQ(f.pairs[i].a, exact.pairs[i].a);
      EXPECT_EQ(f.pairs[i].b, exact.pairs[i].b);
    }
  }
}

TEST(Clash, MeshAgainstItselfTranslatedAlongItsFaceTouches) {
  // Two unit boxes sharing the face x = 1: only touch pairs, exactly the pairs brute force finds.
  const TriMesh a = make_box({0, 0, 0}, {1, 1, 1}, 3);
  const TriMesh b = transformed(a, Transform{.t = {1, 0, 0}});
  const ClashResult r = clash(make_model(a), make_model(b));
  EXPECT_EQ(r.pairs, brute_force_pairs(a, b));
  EXPECT_GT(r.touch_pairs, 0u);
  EXPECT_EQ(r.cross_pairs, 0u);
  for (const ClashRegion& g : r.regions) EXPECT_TRUE(g.curves.empty());
}

TEST(Clash, MeshAgainstItselfIsAllTouch) {
  const TriMesh a = make_sphere({.target_triangles = 800});
  const ClashResult r = clash(make_model(a), make_model(a));
  EXPECT_EQ(r.pairs, brute_force_pairs(a, a));
  EXPECT_EQ(r.cross_pairs, 0u);
}

TEST(Clash, EnvironmentSoupAgainstRobotUnderRandomPoses) {
  // A triangle soup "environment" and a small closed "robot", 1,000 random poses, against brute force.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-3, 3), small(-0.6, 0.6);
  TriMesh env;
  for (int t = 0; t < 150; ++t) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    for (int k = 0; k < 3; ++k) env.positions.push_back(c + Vec3{small(rng), small(rng), small(rng)});
    env.triangles.push_back({3u * t, 3u * t + 1, 3u * t + 2});
  }
  const Model env_model = make_model(env);
  const TriMesh robot = make_sphere({.target_triangles = 60, .radius = 0.7, .bump_amplitude = 0.2});
  std::size_t poses_with_contact = 0;
  for (int pose = 0; pose < 1000; ++pose) {
    const TriMesh posed = transformed(robot, random_pose(rng, 3.0));
    const ClashResult r = clash(env_model, make_model(posed), {.regions = pose % 10 == 0});
    ASSERT_EQ(r.pairs, brute_force_pairs(env, posed)) << "pose " << pose;
    poses_with_contact += !r.pairs.empty();
  }
  EXPECT_GT(poses_with_contact, 50u);
  EXPECT_LT(poses_with_contact, 1000u);
}

TEST(Clash, ContainmentOfClosedParts) {
  const Model outer = make_model(make_sphere({.target_triangles = 2000, .radius = 2.0}));
  const Model inner = make_model(make_box({-0.5, -0.4, -0.3}, {0.5, 0.6, 0.7}, 2));
  const Model far = make_model(make_box({5, 5, 5}, {6, 6, 6}));
  const ClashResult r1 = clash(inner, outer);
  EXPECT_TRUE(r1.pairs.empty());
  EXPECT_EQ(r1.containment, Containment::a_inside_b);
  EXPECT_TRUE(r1.interference());
  EXPECT_EQ(clash(outer, inner).containment, Containment::b_inside_a);
  const ClashResult r3 = clash(inner, far);
  EXPECT_EQ(r3.containment, Containment::none);
  EXPECT_FALSE(r3.interference());
}

TEST(Clash, ContainmentSkippedForOpenMeshWithWarning) {
  TriMesh open = make_sphere({.target_triangles = 500, .radius = 2.0});
  open.triangles.pop_back();
  const ClashResult r = clash(make_model(make_box({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1})), make_model(open));
  EXPECT_EQ(r.containment, Containment::not_checked);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("not closed"), std::string::npos);
}

TEST(Clash, ClearancePairsMatchBruteForce) {
  const TriMesh a = make_sphere({.target_triangles = 600, .radius = 1.0});
  const TriMesh b = make_sphere({.target_triangles = 600, .radius = 1.0, .center = {2.05, 0.1, 0}});
  const double d = 0.2;
  const ClashResult r = clash(make_model(a), make_model(b), {.clearance = d});
  EXPECT_TRUE(r.pairs.empty());
  // Oracle: every pair's distance by the independent reference (unit/reference_distance.h, not
  // np/distance.h, which the clearance query uses). A pair within 1e-12 of d may go either way.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sure, possible, got;
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> ref;
  for (std::uint32_t i = 0; i < a.num_triangles(); ++i) {
    for (std::uint32_t j = 0; j < b.num_triangles(); ++j) {
      const double dij = reference::triangle_triangle_distance(a.corners(i), b.corners(j));
      if (dij < d - 1e-12) sure.emplace_back(i, j);
      if (dij < d + 1e-12) possible.emplace_back(i, j), ref[{i, j}] = dij;
    }
  }
  for (const ClearancePair& c : r.clearance) {
    got.emplace_back(c.a, c.b);
    EXPECT_LT(c.distance, d);
    EXPECT_NEAR(distance(c.point_a, c.point_b), c.distance, 1e-12);
    ASSERT_TRUE(ref.count({c.a, c.b})) << "pair " << c.a << " " << c.b << " is not within the clearance";
    EXPECT_NEAR(c.distance, (ref[{c.a, c.b}]), 1e-12);
  }
  std::sort(got.begin(), got.end());
  EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair reported twice";
  EXPECT_GT(sure.size(), 10u);
  EXPECT_TRUE(std::includes(got.begin(), got.end(), sure.begin(), sure.end())) << "a pair closer than d is missing";
  EXPECT_TRUE(std::includes(possible.begin(), possible.end(), got.begin(), got.end()));
}

TEST(Distance, MatchesBruteForceUnderRandomPoses) {
  std::mt19937_64 rng(7);
  const TriMesh a = make_sphere({.target_triangles = 300, .radius = 1.0, .bump_amplitude = 0.1});
  const TriMesh b0 = make_box({-0.3, -0.3, -0.3}, {0.3, 0.3, 0.3}, 2);
  const Model ma = make_model(a);
  for (int pose = 0; pose < 40; ++pose) {
    Transform t = random_pose(rng, 1.0);
    t.t = t.t + Vec3{3.0, 0, 0};
    const TriMesh b = transformed(b0, t);
    const DistanceResult r = distance(ma, make_model(b));
    double best = INFINITY;
    for (std::uint32_t i = 0; i < a.num_triangles(); ++i) {
      for (std::uint32_t j = 0; j < b.num_triangles(); ++j) {
        // Independent of np/distance.h, which distance() uses at its leaves.
        best = std::min(best, reference::triangle_triangle_distance(a.corners(i), b.corners(j)));
      }
    }
    EXPECT_FALSE(r.intersecting);
    EXPECT_NEAR(r.distance, best, 1e-12);
    EXPECT_NEAR(distance(r.point_a, r.point_b), r.distance, 1e-12);
  }
}

TEST(Distance, ReportsIntersection) {
  SpherePair p = make_overlapping_spheres(1000);
  const DistanceResult r = distance(make_model(p.a), make_model(p.b));
  EXPECT_TRUE(r.intersecting);
  EXPECT_EQ(r.distance, 0.0);
}

TEST(Clash, EmptyPartsGiveNoPairs) {
  const Model empty = make_model(TriMesh{});
  const Model box = make_model(make_box({0, 0, 0}, {1, 1, 1}));
  const ClashResult r = clash(empty, box);
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_FALSE(r.interference());
}

// The verdict model (issue #23, item 13): clash versus contact, and undecided (never clear) where
// an open part makes inside/outside undecidable. The expectations are the geometry's, by hand.
TEST(ClashVerdict, OneModelForEveryCase) {
  const Model unit = make_model(make_box({0, 0, 0}, {1, 1, 1}));
  auto verdict = [&](const TriMesh& other, ClashRequest request = {}) { return clash(unit, make_model(other), request); };
  EXPECT_EQ(verdict(make_box({0.5, 0.5, 0.5}, {2, 2, 2})).verdict, Verdict::clash);  // crossing
  EXPECT_EQ(verdict(make_box({1, 0, 0}, {2, 1, 1})).verdict, Verdict::contact);       // a shared face
  EXPECT_EQ(verdict(make_box({0.5, 0, 0}, {2, 1, 1})).verdict, Verdict::clash);       // coincident faces, overlap
  EXPECT_EQ(verdict(make_box({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8})).verdict, Verdict::clash);  // contained
  EXPECT_EQ(verdict(make_box({3, 0, 0}, {4, 1, 1})).verdict, Verdict::clear);
  EXPECT_EQ(verdict(make_box({1.5, 0, 0}, {2, 1, 1}), {.clearance = 0.75}).verdict, Verdict::clearance);
}

TEST(ClashVerdict, OpenPartsAreUndecidedNotClear) {
  // A box with one triangle removed around a small closed box: it was "clear".
  TriMesh open_box = make_box({0, 0, 0}, {10, 10, 10});
  open_box.triangles.pop_back();
  const Model open = make_model(open_box);
  const Model small = make_model(make_box({2, 3, 4}, {5, 6, 7}));
  const ClashResult r = clash(small, open);
  EXPECT_EQ(r.verdict, Verdict::undecided);
  ASSERT_FALSE(r.verdict_reasons.empty());
  EXPECT_NE(r.verdict_reasons[0].find("part B is not closed"), std::string::npos);
  // Not asking for containment is the caller's choice: clear.
  EXPECT_EQ(clash(small, open, {.containment = false}).verdict, Verdict::clear);
  // A closed part decides whether an open one lies inside it (one point, ray parity).
  const Model huge = make_model(make_box({-5, -5, -5}, {20, 20, 20}));
  const ClashResult in = clash(open, huge);
  EXPECT_EQ(in.containment, Containment::a_inside_b);
  EXPECT_EQ(in.verdict, Verdict::clash);
  // Touching an open part: whether the solids overlap behind the common faces is undecided.
  TriMesh open_unit = make_box({0, 0, 0}, {1, 1, 1});
  open_unit.triangles.erase(open_unit.triangles.begin());
  EXPECT_EQ(clash(make_model(open_unit), make_model(make_box({1, 0, 0}, {2, 1, 1}))).verdict, Verdict::undecided);
}

TEST(ClashVerdict, NamesAndExitStatus) {
  for (Verdict v : {Verdict::clear, Verdict::clearance, Verdict::contact, Verdict::undecided, Verdict::clash})
    EXPECT_EQ(verdict_from_name(verdict_name(v)), v);
  EXPECT_FALSE(verdict_from_name("interference"));
  EXPECT_EQ(worst(Verdict::contact, Verdict::undecided), Verdict::undecided);
  EXPECT_EQ(worst(Verdict::clash, Verdict::undecided), Verdict::clash);
  EXPECT_EQ(verdict_exit_status(Verdict::clash), 1);
  EXPECT_EQ(verdict_exit_status(Verdict::undecided), 3);
  EXPECT_EQ(verdict_exit_status(Verdict::contact), 0);
  EXPECT_EQ(verdict_exit_status(Verdict::contact, {.contact = true}), 1);
  EXPECT_EQ(verdict_exit_status(Verdict::clearance, {.contact = true}), 0);
  EXPECT_EQ(verdict_exit_status(Verdict::clearance, *parse_fail_on("contact,clearance")), 1);
  EXPECT_FALSE(parse_fail_on("contact,"));
  EXPECT_FALSE(parse_fail_on("touch"));
}

// A part of two components (as a bolt and its nut in one file), one inside the other part and one
// outside it, with no surface pair: a clash. The first component alone was tested, so the part was
// "clear" whenever its first triangle's component lay outside.
TEST(ClashVerdict, EveryComponentIsTestedForContainment) {
  const Model big = make_model(make_box({0, 0, 0}, {10, 10, 10}));
  TriMesh two = make_box({20, 0, 0}, {21, 1, 1});  // outside, first in the triangle order
  const TriMesh inner = make_box({4, 4, 4}, {5, 5, 5});
  const auto base = static_cast<std::uint32_t>(two.positions.size());
  two.positions.insert(two.positions.end(), inner.positions.begin(), inner.positions.end());
  for (auto t : inner.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const Model part = make_model(two);
  const ClashResult r = clash(part, big);
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_EQ(r.containment, Containment::a_inside_b);
  EXPECT_EQ(r.verdict, Verdict::clash);
  EXPECT_EQ(clash(big, part).containment, Containment::b_inside_a);
}

// Parts above 4,096 triangles first look for one triangle wholly in the other part's box before
// their components are computed (issue #28): the same answers as by construction. A finely divided
// part with one component far away and one inside the big box is inside; one whose components
// all reach outside the box (a large sphere crossing nothing) is not; a 4,800-triangle inner box
// with the roles swapped is inside.
TEST(ClashVerdict, LargePartsContainmentByConstruction) {
  const Model big = make_model(make_box({0, 0, 0}, {10, 10, 10}));
  TriMesh two = make_box({20, 0, 0}, {21, 1, 1}, 20);  // 4,800 triangles, outside
  const TriMesh inner = make_box({4, 4, 4}, {5, 5, 5}, 20);
  const auto base = static_cast<std::uint32_t>(two.positions.size());
  two.positions.insert(two.positions.end(), inner.positions.begin(), inner.positions.end());
  for (auto t : inner.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  ASSERT_GT(two.num_triangles(), 4096u);
  const Model part = make_model(two);
  EXPECT_EQ(clash(part, big).containment, Containment::a_inside_b);
  EXPECT_EQ(clash(big, part).containment, Containment::b_inside_a);
  // A large closed shell around the small box, touching nothing: the box is inside it, it is not
  // inside the box (none of its triangles lies in the box's bounds).
  const Model shell = make_model(make_sphere({.target_triangles = 20000, .radius = 30.0, .center = {5, 5, 5}}));
  ASSERT_GT(shell.mesh.num_triangles(), 4096u);
  EXPECT_EQ(clash(big, shell).containment, Containment::a_inside_b);
  EXPECT_EQ(clash(shell, big).containment, Containment::b_inside_a);
  // Apart: a large part beside the box.
  const Model beside = make_model(make_box({11, 0, 0}, {12, 10, 10}, 20));
  EXPECT_EQ(clash(beside, big).containment, Containment::none);
  EXPECT_EQ(clash(big, beside).containment, Containment::none);
  const Model inner_big = make_model(make_box({2, 2, 2}, {3, 3, 3}, 20));
  EXPECT_EQ(clash(inner_big, big).containment, Containment::a_inside_b);
}

}  // namespace
}  // namespace interfere
