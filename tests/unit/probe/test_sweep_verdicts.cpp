// Sweep verdicts (issue #23, items 3 and 4): a probe inside a closed workpiece collides (it touches
// no triangle, so only the solid decides), an open workpiece is warned about; between path points
// each segment is `collides`, `clear` or `unresolved`, and a pass at a constant 5 um gap is never
// called a collision (before: the interval [0, 1], only because the refinement depth ran out).
// Oracles: the geometry is axis-aligned, so inside/outside and every gap are known analytically.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "interfere/mesh/generate.h"
#include "interfere/probe/sweep.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

ProbePath poses(std::vector<ProbePose> p) {
  ProbePath path;
  path.joint_space = false;
  path.columns = {"px", "py", "pz", "ax", "ay", "az"};
  path.poses = std::move(p);
  for (std::size_t i = 0; i < path.poses.size(); ++i)
    path.lines.push_back(static_cast<std::int64_t>(i) + 2);
  return path;
}

/// The cube [0, 100]^3 without its top face (z = 100): open.
TriMesh open_cube() {
  TriMesh m = make_box({0, 0, 0}, {100, 100, 100});
  std::vector<Tri> kept;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    if (!(c[0].z == 100 && c[1].z == 100 && c[2].z == 100)) kept.push_back(m.triangles[t]);
  }
  m.triangles = kept;
  return m;
}

TriMesh plate(double z, double half) {
  TriMesh m;
  m.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

const ProbeShape kProbe{.radius = 5, .length = 40};
const Vec3 kDown{0, 0, -1};

}  // namespace

TEST(ProbeSweepSolids, ProbeInsideClosedCubeCollides) {
  // The case: cube 0-100 mm, probe at its centre pointing down (body z in [50, 90]): it
  // touches no face (10 mm from the top), yet it lies inside the solid.
  const Workpiece w = prepare_workpiece(make_box({0, 0, 0}, {100, 100, 100}), kProbe);
  ASSERT_EQ(w.solids.size(), 1u);
  EXPECT_EQ(w.open_components, 0u);
  EXPECT_TRUE(w.warnings.empty());
  const ProbePath path =
      poses({{{50, 50, 50}, kDown}, {{50, 50, 150}, kDown}, {{150, 50, 50}, kDown}});
  const SweepResult r = sweep(w, path, nullptr, {.probe = kProbe, .continuous = false});
  EXPECT_TRUE(r.points[0].collides);
  EXPECT_TRUE(r.points[0].inside);
  EXPECT_TRUE(r.points[0].hits.empty());
  EXPECT_EQ(r.points[0].clearance, 0.0);
  EXPECT_EQ(r.points[0].verdict, Verdict::clash);
  EXPECT_FALSE(r.points[1].collides);  // above the cube: 50 mm clear
  EXPECT_NEAR(r.points[1].clearance, 50.0, 1e-9);
  EXPECT_FALSE(r.points[2].collides);  // beside it: 45 mm from the face x = 100
  EXPECT_NEAR(r.points[2].clearance, 45.0, 1e-9);
  EXPECT_EQ(r.inside_points, 1u);
  EXPECT_EQ(r.verdict, Verdict::clash);
  bool inside = false;
  EXPECT_TRUE(pose_collides(w, kProbe, path.poses[0], nullptr, nullptr, &inside));
  EXPECT_TRUE(inside);
}

TEST(ProbeSweepSolids, SegmentInsideTheSolidCollides) {
  // Both ends inside, the motion between them touches no face: the whole segment collides.
  const Workpiece w = prepare_workpiece(make_box({0, 0, 0}, {100, 100, 100}), kProbe);
  const ProbePath path = poses({{{30, 50, 30}, kDown}, {{70, 50, 30}, kDown}});
  const SweepResult r = sweep(w, path, nullptr, {.probe = kProbe});
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_EQ(r.segments[0].state, SegmentState::collides);
  ASSERT_EQ(r.segments[0].intervals.size(), 1u);
  EXPECT_EQ(r.segments[0].intervals[0], (std::array<double, 2>{0.0, 1.0}));
}

TEST(ProbeSweepSolids, OpenWorkpieceIsWarnedAbout) {
  // Without its top face the cube bounds nothing: the same pose touches no triangle and is
  // reported clear, with a warning that inside/behind is not checked.
  const Workpiece w = prepare_workpiece(open_cube(), kProbe);
  EXPECT_TRUE(w.solids.empty());
  EXPECT_EQ(w.open_components, 1u);
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(w.warnings[0].find("not checked"), std::string::npos) << w.warnings[0];
  const SweepResult r = sweep(w, poses({{{50, 50, 50}, kDown}}), nullptr, {.probe = kProbe});
  EXPECT_FALSE(r.points[0].collides);
  EXPECT_NEAR(r.points[0].clearance, 45.0, 1e-9);  // to the side faces x, y = 0, 100 (radius 5)
}

TEST(ProbeSweepSolids, ClosedAndOpenComponents) {
  // A closed cube and an open plate in one mesh: the cube is a solid, the plate is warned about.
  TriMesh m = make_box({0, 0, 0}, {100, 100, 100});
  const TriMesh p = plate(-50, 40);
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), p.positions.begin(), p.positions.end());
  for (Tri t : p.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const Workpiece w = prepare_workpiece(m, kProbe);
  EXPECT_EQ(w.solids.size(), 1u);
  EXPECT_EQ(w.open_components, 1u);
  EXPECT_FALSE(w.warnings.empty());
  const SweepResult r = sweep(w, poses({{{20, 80, 45}, kDown}}), nullptr, {.probe = kProbe});
  EXPECT_TRUE(r.points[0].inside);
}

namespace {
void append(TriMesh& m, const TriMesh& other, bool flip) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), other.positions.begin(), other.positions.end());
  for (Tri t : other.triangles) {
    if (flip) std::swap(t[1], t[2]);
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}
}  // namespace

TEST(ProbeSweepSolids, CavitiesOverlapsAndInsideOutShells) {
  const ProbeShape small{.radius = 2, .length = 5};
  // A hollow cube: outer [0, 100]^3 outward, a cavity [20, 80]^3 with inward normals (another
  // component). In the cavity: empty space; in the wall: material.
  TriMesh hollow;
  append(hollow, make_box({0, 0, 0}, {100, 100, 100}), false);
  append(hollow, make_box({20, 20, 20}, {80, 80, 80}), true);
  const Workpiece w = prepare_workpiece(hollow, small);
  ASSERT_EQ(w.solids.size(), 2u);
  EXPECT_EQ(w.solid_sign, (std::vector<int>{1, -1}));
  EXPECT_TRUE(w.warnings.empty());
  const SweepResult r =
      sweep(w, poses({{{50, 50, 50}, kDown}, {{10, 50, 50}, kDown}}), nullptr, {.probe = small});
  EXPECT_FALSE(r.points[0].collides);  // in the cavity: body z in [50, 55], 25 below its top
  EXPECT_NEAR(r.points[0].clearance, 25.0, 1e-9);
  EXPECT_TRUE(r.points[1].inside);  // in the wall x in [0, 20]
  // Two overlapping outward cubes: a pose in their common part is in the material.
  TriMesh two;
  append(two, make_box({0, 0, 0}, {60, 60, 60}), false);
  append(two, make_box({40, 40, 40}, {100, 100, 100}), false);
  const Workpiece w2 = prepare_workpiece(two, small);
  EXPECT_TRUE(
      sweep(w2, poses({{{50, 50, 50}, kDown}}), nullptr, {.probe = small}).points[0].inside);
  // One inside-out cube: still a solid, with a warning.
  TriMesh inverted;
  append(inverted, make_box({0, 0, 0}, {100, 100, 100}), true);
  const Workpiece w3 = prepare_workpiece(inverted, small);
  ASSERT_EQ(w3.warnings.size(), 1u);
  EXPECT_NE(w3.warnings[0].find("inside out"), std::string::npos);
  EXPECT_TRUE(
      sweep(w3, poses({{{50, 50, 50}, kDown}}), nullptr, {.probe = small}).points[0].inside);
}

TEST(ProbeSweepStates, ConstantGapPassIsNeverACollision) {
  // The case: a 100 mm pass with the probe's end face 5 um above a plate. The end face is
  // parallel to the plate, so the gap is 0.005 at every pose (analytic).
  const Workpiece w = prepare_workpiece(plate(0, 500), kProbe);
  const ProbePath path = poses({{{-50, 0, 0.005}, kDown}, {{50, 0, 0.005}, kDown}});
  // At the old depth (12) the motion of the finest intervals (100 mm / 2^14 = 6.1 um) exceeds the
  // gap: unresolved, with the smallest gap measured, never a collision.
  // (the isotropic bound alone: the plane filter, below, proves this pass clear at once)
  const SweepResult coarse = sweep(w, path, nullptr, {.probe = kProbe, .max_depth = 12, .plane_filter = false});
  EXPECT_EQ(coarse.colliding_segments, 0u);
  EXPECT_FALSE(coarse.any_collision());
  ASSERT_EQ(coarse.segments.size(), 1u);
  const SegmentResult& s = coarse.segments[0];
  EXPECT_EQ(s.state, SegmentState::unresolved);
  EXPECT_EQ(s.verdict, Verdict::undecided);
  EXPECT_TRUE(s.intervals.empty());
  ASSERT_EQ(s.unresolved.size(), 1u);
  EXPECT_EQ(s.unresolved[0], (std::array<double, 2>{0.0, 1.0}));
  EXPECT_NEAR(s.smallest_gap, 0.005, 1e-12);
  EXPECT_GT(s.unresolved_motion, 0.005);  // why it could not be separated
  EXPECT_EQ(coarse.verdict, Verdict::undecided);
  // With the default resolution (2^-16) the motion bound falls below the gap: proved clear.
  const SweepResult fine = sweep(w, path, nullptr, {.probe = kProbe, .plane_filter = false});
  EXPECT_TRUE(fine.segments.empty());
  EXPECT_EQ(fine.verdict, Verdict::clear);
  // A pose budget too small for that proof: unresolved again, never clear or colliding.
  const SweepResult budget = sweep(w, path, nullptr, {.probe = kProbe, .max_poses = 1000, .plane_filter = false});
  ASSERT_EQ(budget.segments.size(), 1u);
  EXPECT_EQ(budget.segments[0].state, SegmentState::unresolved);
  EXPECT_EQ(budget.segments[0].poses_tested, 1000u);
  // The plane filter (issue #28, the default): the motion is parallel to the plate and the axis does
  // not turn, so the swept probe stays 5 um above the plate's plane: clear at the first middle,
  // even at depth 12 and with a budget of one pose.
  const SweepResult plane = sweep(w, path, nullptr, {.probe = kProbe, .max_depth = 12, .max_poses = 1});
  EXPECT_TRUE(plane.segments.empty());
  EXPECT_EQ(plane.verdict, Verdict::clear);
}

TEST(ProbeSweepStates, RealCrossingStillCollides) {
  // The same pass over a 10 um step at x in [-1, 1] (a box on the plate, top at z = 0.01): the end
  // face (radius 5) is over it for tip x in [-6, 6], i.e. t in [0.44, 0.56], at any depth.
  TriMesh m = plate(0, 500);
  const TriMesh step = make_box({-1, -20, -1}, {1, 20, 0.01});
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), step.positions.begin(), step.positions.end());
  for (Tri t : step.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const Workpiece w = prepare_workpiece(m, kProbe);
  const ProbePath path = poses({{{-50, 0, 0.005}, kDown}, {{50, 0, 0.005}, kDown}});
  for (int depth : {12, 16}) {
    const SweepResult r = sweep(w, path, nullptr, {.probe = kProbe, .max_depth = depth});
    ASSERT_EQ(r.segments.size(), 1u) << depth;
    const SegmentResult& s = r.segments[0];
    EXPECT_EQ(s.state, SegmentState::collides) << depth;
    EXPECT_EQ(s.verdict, Verdict::clash);
    EXPECT_TRUE(s.between_samples);
    ASSERT_FALSE(s.intervals.empty());
    EXPECT_LE(s.intervals.front()[0], 0.44 + 1e-9);  // the collision lies inside the intervals
    EXPECT_GE(s.intervals.back()[1], 0.56 - 1e-9);
    EXPECT_EQ(r.verdict, Verdict::clash);
  }
}

TEST(ProbeSweepStates, RequestedClearance) {
  // Tip 20 above a plate: points get `clearance` below a requested 25 and `clear` below 15; the
  // segment between two such points too (the gap is 20 all along).
  const Workpiece w = prepare_workpiece(plate(0, 500), kProbe);
  const ProbePath path = poses({{{-50, 0, 20}, kDown}, {{50, 0, 20}, kDown}});
  const SweepResult near = sweep(w, path, nullptr, {.probe = kProbe, .clearance_limit = 25});
  EXPECT_EQ(near.points[0].verdict, Verdict::clearance);
  ASSERT_EQ(near.segments.size(), 1u);
  EXPECT_EQ(near.segments[0].verdict, Verdict::clearance);
  EXPECT_EQ(near.verdict, Verdict::clearance);
  const SweepResult far = sweep(w, path, nullptr, {.probe = kProbe, .clearance_limit = 15});
  EXPECT_EQ(far.verdict, Verdict::clear);
  EXPECT_TRUE(far.segments.empty());
  // A segment that dips closer than the limit only between its points: a tilted pass whose ends
  // are 30 above the plate over a 10 mm high block in the middle (gap 20 over it).
  TriMesh m = plate(0, 500);
  const TriMesh block = make_box({-5, -5, 0}, {5, 5, 10});
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), block.positions.begin(), block.positions.end());
  for (Tri t : block.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const Workpiece wb = prepare_workpiece(m, kProbe);
  const ProbePath over = poses({{{-100, 0, 30}, kDown}, {{100, 0, 30}, kDown}});
  const SweepResult dip = sweep(wb, over, nullptr, {.probe = kProbe, .clearance_limit = 25});
  EXPECT_EQ(dip.points[0].verdict, Verdict::clear);
  ASSERT_EQ(dip.segments.size(), 1u);
  EXPECT_EQ(dip.segments[0].verdict, Verdict::clearance);
  EXPECT_EQ(dip.segments[0].clearance_state, SegmentState::collides);
}

TEST(ProbeSweepStates, ThreadIndependent) {
  const Workpiece w = prepare_workpiece(plate(0, 500), kProbe);
  const ProbePath path =
      poses({{{-50, 0, 0.005}, kDown}, {{50, 0, 0.005}, kDown}, {{50, 50, 0.004}, kDown}});
  SweepResult a;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a = sweep(w, path, nullptr, {.probe = kProbe, .max_depth = 12});
  }
  const SweepResult b = sweep(w, path, nullptr, {.probe = kProbe, .max_depth = 12});
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t s = 0; s < a.segments.size(); ++s) {
    EXPECT_EQ(a.segments[s].unresolved, b.segments[s].unresolved);
    EXPECT_EQ(a.segments[s].smallest_gap, b.segments[s].smallest_gap);
    EXPECT_EQ(a.segments[s].poses_tested, b.segments[s].poses_tested);
  }
}
