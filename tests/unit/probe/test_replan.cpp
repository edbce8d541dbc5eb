// Re-planning of colliding path points (probe/replan.h; issue #28, deliverable 4). The oracle is
// independent of the exact cylinder-triangle test: points sampled densely through the probe
// cylinder's volume against the analytic boxes the workpiece is made of (a sampled point strictly
// inside a box proves a collision; the suggestion must show none), and the smallest tilt that
// clears the overhang measured by that sampling on a fine grid of tilts.
#include <gtest/gtest.h>

#include <cmath>

#include "interfere/mesh/generate.h"
#include "interfere/probe/paper_machine.h"
#include "interfere/probe/replan.h"
#include "interfere/probe/sweep.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

struct Box {
  Vec3 lo, hi;
};

// A plate (top at z = 0) and an overhang above the measured point: x in [2, 20], z in [20, 30].
const std::vector<Box> kBoxes{{{-50, -50, -10}, {50, 50, 0}}, {{2, -50, 20}, {20, 50, 30}}};
const ProbeShape kProbe{.radius = 5, .length = 40};

TriMesh workpiece_mesh() {
  TriMesh m;
  for (const Box& b : kBoxes) {
    const TriMesh x = make_box(b.lo, b.hi, 2);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), x.positions.begin(), x.positions.end());
    for (Tri t : x.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return m;
}

// Sampled: does the probe cylinder at `pose` have a point strictly inside one of the boxes?
bool sampled_hit(const ProbePose& pose) {
  const Vec3 a = pose.axis / norm(pose.axis);
  Vec3 u = cross(a, Vec3{0, 1, 0});
  if (norm(u) < 1e-9) u = cross(a, Vec3{1, 0, 0});
  u = u / norm(u);
  const Vec3 v = cross(a, u);
  const double e = 1e-9;
  for (int i = 0; i <= 200; ++i) {            // along the body, from the tip back
    const Vec3 c = pose.tip - a * (kProbe.length * i / 200.0);
    for (int r = 0; r <= 10; ++r)
      for (int k = 0; k < 72; ++k) {
        const double rad = kProbe.radius * r / 10.0, phi = 2 * M_PI * k / 72;
        const Vec3 p = c + u * (rad * std::cos(phi)) + v * (rad * std::sin(phi));
        for (const Box& b : kBoxes)
          if (p.x > b.lo.x + e && p.x < b.hi.x - e && p.y > b.lo.y + e && p.y < b.hi.y - e && p.z > b.lo.z + e &&
              p.z < b.hi.z - e)
            return true;
      }
  }
  return false;
}

ProbePath one_pose(const ProbePose& p) {
  ProbePath path;
  path.joint_space = false;
  path.columns = {"px", "py", "pz", "ax", "ay", "az"};
  path.poses = {p};
  path.lines = {2};
  return path;
}

ProbePose vertical_at(double standoff) { return {.tip = {0, 0, standoff}, .axis = {0, 0, -1}}; }

}  // namespace

TEST(Replan, FindsTheSmallestTiltThatClearsTheOverhangKeepingTheSurfacePoint) {
  const Workpiece w = prepare_workpiece(workpiece_mesh(), kProbe);
  const ProbePath path = one_pose(vertical_at(2));
  ASSERT_TRUE(sampled_hit(path.poses[0]));  // the oracle sees the collision too
  SweepRequest sr{.probe = kProbe, .continuous = false};
  const SweepResult s = sweep(w, path, nullptr, sr);
  ASSERT_EQ(s.colliding_points, 1u);
  ReplanRequest rq{.max_tilt_deg = 30, .tilt_rings = 60, .azimuth_steps = 36};
  ASSERT_TRUE(validate(rq));
  const ReplanResult r = replan(w, path, nullptr, kProbe, s, rq);
  ASSERT_EQ(r.points.size(), 1u);
  const ReplannedPoint& p = r.points[0];
  ASSERT_TRUE(p.found) << p.reason;
  EXPECT_EQ(p.line, 2);
  EXPECT_NEAR(norm(p.target - Vec3{0, 0, 0}), 0, 1e-12);               // the surface point below the tip
  EXPECT_NEAR(norm(p.pose.tip - p.target), 2, 1e-9);                  // the same stand-off
  EXPECT_NEAR(norm(p.target - (p.pose.tip + p.pose.axis * 2)), 0, 1e-9);  // still aiming at it
  EXPECT_FALSE(sampled_hit(p.pose));
  EXPECT_FALSE(pose_collides(w, kProbe, p.pose));
  // Nearest: the sampled oracle's smallest clearing tilt (leaning away from the overhang, the best
  // direction here) on a 0.05-degree grid; the search's rings are 0.5 degrees apart.
  double oracle = -1;
  for (double t = 0.05; t <= 30; t += 0.05) {
    const double th = t * M_PI / 180;
    const Vec3 axis{std::sin(th), 0, -std::cos(th)};  // body leans to -x
    if (!sampled_hit({.tip = Vec3{0, 0, 0} - axis * 2, .axis = axis})) {
      oracle = t;
      break;
    }
  }
  ASSERT_GT(oracle, 0);
  EXPECT_LE(p.tilt_deg, oracle + 0.5 + 1e-9);
  EXPECT_GE(p.tilt_deg, oracle - 0.5);  // (no smaller tilt can clear: the sampled oracle would too)
}

TEST(Replan, NoFreePoseInsideAClosedPocketSaysWhy) {
  // A probe whose tip is inside the plate's material: every tilt keeps it there.
  const Workpiece w = prepare_workpiece(workpiece_mesh(), kProbe);
  const ProbePath path = one_pose({.tip = {0, 0, -5}, .axis = {0, 0, -1}});
  const SweepResult s = sweep(w, path, nullptr, {.probe = kProbe, .continuous = false});
  ASSERT_EQ(s.colliding_points, 1u);
  const ReplanResult r = replan(w, path, nullptr, kProbe, s, {.max_tilt_deg = 20, .tilt_rings = 4, .azimuth_steps = 8});
  ASSERT_EQ(r.points.size(), 1u);
  EXPECT_FALSE(r.points[0].found);
  EXPECT_NE(r.points[0].reason.find("no collision-free pose within 20 degrees"), std::string::npos) << r.points[0].reason;
  EXPECT_EQ(r.found, 0u);
}

TEST(Replan, JointPathOfThePaperMachineGetsReachableJointsAndACleanPath) {
  const Robot robot = paper_machine_31({.probe_length = kProbe.length});
  const ProbePose want = vertical_at(2);
  auto q = inverse_kinematics(robot, want);
  ASSERT_TRUE(q) << q.error().message();
  ProbePath path;
  path.joint_space = true;
  for (const auto& j : robot.joints) path.columns.push_back(j.name);
  path.joints = {*q};
  path.lines = {2};
  resolve_poses(path, robot);
  const Workpiece w = prepare_workpiece(workpiece_mesh(), kProbe);
  const SweepResult s = sweep(w, path, &robot, {.probe = kProbe, .continuous = false});
  ASSERT_EQ(s.colliding_points, 1u);
  const ReplanResult r = replan(w, path, &robot, kProbe, s, {.max_tilt_deg = 30, .standoff_min = 0, .standoff_max = 4});
  ASSERT_EQ(r.found, 1u) << r.points[0].reason;
  const ReplannedPoint& p = r.points[0];
  ASSERT_EQ(p.joints.size(), robot.joints.size());
  EXPECT_TRUE(check_joint_limits(robot, p.joints));
  const ProbePose fk = forward_kinematics(robot, p.joints);
  EXPECT_NEAR(norm(fk.tip - p.pose.tip), 0, 1e-9);
  EXPECT_FALSE(sampled_hit(fk));
  const ProbePath fixed = replanned_path(path, r);
  const SweepResult again = sweep(w, fixed, &robot, {.probe = kProbe, .continuous = false});
  EXPECT_EQ(again.colliding_points, 0u);
  EXPECT_NE(path_to_csv(fixed), path_to_csv(path));
}

TEST(Replan, BadRequestsNameTheField) {
  EXPECT_NE(validate({.max_tilt_deg = 0}).error().reason.find("tilt cone"), std::string::npos);
  EXPECT_NE(validate({.max_tilt_deg = 90}).error().reason.find("tilt cone"), std::string::npos);
  EXPECT_NE(validate({.max_tilt_deg = NAN}).error().reason.find("tilt cone"), std::string::npos);
  EXPECT_NE(validate({.standoff_min = 2, .standoff_max = 1}).error().reason.find("stand-off range"), std::string::npos);
  EXPECT_NE(validate({.azimuth_steps = 0}).error().reason.find("steps"), std::string::npos);
}
