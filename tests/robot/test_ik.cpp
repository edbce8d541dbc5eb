// Numerical inverse kinematics (issue #28, robot/ik.h): FK(IK(pose)) = pose to 1e-9 on the shipped
// UR5-type and industrial 6R arms (examples/probe) and on a UR5 DH table, the forward kinematics
// being the oracle (link_frames for URDF chains, already checked against a hand-derived closed form
// and an independent numpy composition; probe::forward_kinematics for DH tables, a separate
// implementation from chain_from_dh); a pose path follows the branch of its start (recovering a
// known joint path); unreachable points and points reachable only outside the limits are errors
// naming the file, the line and (for limits) the joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "interfere/probe/kinematics.h"
#include "interfere/probe/paper_machine.h"
#include "interfere/probe/path.h"
#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"

namespace fs = std::filesystem;
using namespace interfere;
using namespace interfere::robot;

namespace {

const fs::path kExamples = fs::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

/// Random joint values within the limits (revolute ones also within [-180, 180]).
std::vector<double> random_q(const Chain& c, std::mt19937_64& rng) {
  std::vector<double> q;
  for (std::size_t m : c.movable) {
    const ChainJoint& j = c.joints[m];
    const double lo = std::max(j.lower, -180.0), hi = std::min(j.upper, 180.0);
    q.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
  }
  return q;
}

/// The tool pose by the chain's forward kinematics, written out here from the frames.
probe::ProbePose fk_pose(const Chain& c, const Transform& base, const IkTool& t,
                         const std::vector<double>& q) {
  const std::vector<Transform> f = link_frames(c, q, base);
  probe::ProbePose p;
  p.tip = f[t.link].apply(t.tip);
  p.axis = f[t.link].rotate(t.axis);
  p.ref = f[t.link].rotate(t.ref);
  return p;
}

void expect_reaches(const Chain& c, const Transform& base, const IkTool& t,
                    const probe::ProbePose& target, const std::vector<double>& q, bool with_ref) {
  const probe::ProbePose got = fk_pose(c, base, t, q);
  EXPECT_LE(norm(got.tip - target.tip), 1e-9);
  EXPECT_LE(angle_between(got.axis, target.axis), 1e-9);
  if (with_ref) EXPECT_LE(angle_between(got.ref, target.ref), 1e-9);
  EXPECT_TRUE(check_limits(c, q));
}

#if INTERFERE_TEST_URDF
void round_trip_cell(const std::string& cell_file) {
  Expected<Cell> cell = read_cell_json(kExamples / cell_file);
  ASSERT_TRUE(cell) << cell.error().message();
  const IkTool tool = cell_ik_tool(*cell);
  std::mt19937_64 rng(28);
  int solved = 0;
  for (int k = 0; k < 40; ++k) {
    const std::vector<double> q0 = random_q(cell->robot, rng);
    for (const bool with_ref : {false, true}) {
      probe::ProbePose target = fk_pose(cell->robot, cell->base, tool, q0);
      if (!with_ref) target.ref = {};
      const IkSolution s = solve_ik(cell->robot, cell->base, tool, target, nullptr);
      ASSERT_TRUE(s.ok) << cell_file << " pose " << k << ": " << s.reason;
      expect_reaches(cell->robot, cell->base, tool, target, s.q, with_ref);
      ++solved;
    }
  }
  EXPECT_EQ(solved, 80);
}

TEST(RobotIk, Ur5TypeArmRoundTrip) {
  round_trip_cell("cell.json");
}

TEST(RobotIk, IndustrialArmRoundTrip) {
  round_trip_cell("cell_industrial.json");
}

// The shipped joint path: its poses (with the reference direction, so the pose fixes the joints up
// to the branch) turned back into joints from the first row as start give the same joint path, and
// without the reference the solver stays on the branch (small jumps) and still reaches every pose.
TEST(RobotIk, PosePathFollowsTheBranch) {
  Expected<Cell> cell = read_cell_json(kExamples / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  Expected<JointPath> jp = read_joint_csv(kExamples / "path.csv", cell->robot);
  ASSERT_TRUE(jp) << jp.error().message();
  const IkTool tool = cell_ik_tool(*cell);
  for (const bool with_ref : {true, false}) {
    probe::ProbePath poses;
    poses.joint_space = false;
    for (std::size_t i = 0; i < jp->size(); ++i) {
      probe::ProbePose p = fk_pose(cell->robot, cell->base, tool, jp->q[i]);
      if (!with_ref) p.ref = {};
      poses.poses.push_back(p);
      poses.lines.push_back(jp->lines[i]);
    }
    IkOptions o;
    o.start = jp->q[0];
    Expected<PoseIkPath> r = pose_path_to_joints(cell->robot, cell->base, tool, poses, "p.csv", o);
    ASSERT_TRUE(r) << r.error().message();
    ASSERT_EQ(r->path.size(), jp->size());
    EXPECT_EQ(r->path.lines, jp->lines);
    for (std::size_t i = 0; i < jp->size(); ++i) {
      expect_reaches(cell->robot, cell->base, tool, poses.poses[i], r->path.q[i], with_ref);
      if (i > 0) {
        EXPECT_EQ(r->seed[i], "previous") << i;
        EXPECT_LT(r->jump[i], 10.0) << i;
      }
      if (with_ref) {
        for (std::size_t m = 0; m < jp->q[i].size(); ++m)
          EXPECT_NEAR(r->path.q[i][m], jp->q[i][m], 1e-6) << "point " << i << " joint " << m;
      }
    }
  }
}

TEST(RobotIk, UnreachableAndLimitErrorsNameTheLine) {
  Expected<Cell> cell = read_cell_json(kExamples / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  const IkTool tool = cell_ik_tool(*cell);
  Expected<probe::ProbePath> path = probe::parse_path_csv(
      "# poses\npx,py,pz,ax,ay,az\n400,0,10,0,0,-1\n5000,0,10,0,0,-1\n", "far.csv", nullptr);
  ASSERT_TRUE(path) << path.error().message();
  Expected<PoseIkPath> r = pose_path_to_joints(cell->robot, cell->base, tool, *path, "far.csv");
  ASSERT_FALSE(r);
  const std::string m = r.error().message();
  EXPECT_NE(m.find("far.csv:4:"), std::string::npos) << m;
  EXPECT_NE(m.find("point 1"), std::string::npos) << m;
  EXPECT_NE(m.find("unreachable"), std::string::npos) << m;

  // Every solution of this pose (the arm's 8 branches) needs |elbow| well above 20 degrees: with
  // the elbow limited to [-20, 20] it is reachable only outside the limits.
  Chain tight = cell->robot;
  const std::int64_t elbow = tight.find_movable("elbow");
  ASSERT_GE(elbow, 0);
  tight.joints[tight.movable[static_cast<std::size_t>(elbow)]].lower = -20;
  tight.joints[tight.movable[static_cast<std::size_t>(elbow)]].upper = 20;
  Expected<probe::ProbePath> near = probe::parse_path_csv(
      "px,py,pz,ax,ay,az\n350,0,10,0,0,-1\n", "near.csv", nullptr);
  ASSERT_TRUE(near);
  Expected<PoseIkPath> r2 = pose_path_to_joints(tight, cell->base, tool, *near, "near.csv");
  ASSERT_FALSE(r2);
  const std::string m2 = r2.error().message();
  EXPECT_NE(m2.find("near.csv:2:"), std::string::npos) << m2;
  EXPECT_NE(m2.find("outside its limits"), std::string::npos) << m2;

  Expected<probe::ProbePath> joints = probe::parse_path_csv("a,b\n1,2\n", "j.csv", nullptr);
  if (joints) {
    Expected<PoseIkPath> r3 = pose_path_to_joints(cell->robot, cell->base, tool, *joints, "j.csv");
    ASSERT_FALSE(r3);
    EXPECT_NE(r3.error().message().find("not a pose path"), std::string::npos);
  }
}
#endif

// The UR5's standard DH table (Universal Robots' published parameters, mm and degrees).
probe::Robot ur5_dh() {
  probe::Robot r;
  r.name = "ur5-dh";
  const double d[6] = {89.159, 0, 0, 109.15, 94.65, 82.3};
  const double a[6] = {0, -425, -392.25, 0, 0, 0};
  const double alpha[6] = {90, 0, 0, 90, -90, 0};
  for (int i = 0; i < 6; ++i) {
    probe::DhJoint j;
    j.name = "q" + std::to_string(i + 1);
    j.type = probe::JointType::revolute;
    j.a = a[i], j.alpha = alpha[i], j.d = d[i];
    j.min = -360, j.max = 360;
    r.joints.push_back(j);
  }
  r.tool_tip = {0, 0, 150};
  r.tool_axis = {0, 0, 1};
  r.tool_ref = {1, 0, 0};
  return r;
}

// The same robot as a modified (Craig) table: a_{i-1}, alpha_{i-1} shifted down one row, the last
// row's Tx(a_n) Rx(alpha_n) moved into the tool.
probe::Robot modified_of(const probe::Robot& s) {
  probe::Robot m = s;
  m.name = s.name + "-modified";
  m.convention = probe::DhConvention::modified;
  const std::size_t n = s.joints.size();
  for (std::size_t i = 0; i < n; ++i) {
    m.joints[i].a = i ? s.joints[i - 1].a : 0;
    m.joints[i].alpha = i ? s.joints[i - 1].alpha : 0;
  }
  const double al = s.joints[n - 1].alpha * M_PI / 180, c = std::cos(al), sn = std::sin(al);
  const auto rx = [&](const Vec3& v) { return Vec3{v.x, c * v.y - sn * v.z, sn * v.y + c * v.z}; };
  m.tool_tip = rx(s.tool_tip) + Vec3{s.joints[n - 1].a, 0, 0};
  m.tool_axis = rx(s.tool_axis);
  m.tool_ref = rx(s.tool_ref);
  return m;
}

// chain_from_dh against probe::forward_kinematics (the DH module's own product of
// Rz Tz Tx Rx, or Rx Tx Rz Tz), its links frame0..frameN against the DH frames, then FK(IK(pose))
// = pose by that same independent forward kinematics.
TEST(RobotIk, DhTableChainAndRoundTrip) {
  for (const probe::Robot& robot :
       {ur5_dh(), modified_of(ur5_dh()), probe::paper_machine_31(), modified_of(probe::paper_machine_31())}) {
    IkTool tool;
    const Chain c = chain_from_dh(robot, &tool);
    ASSERT_EQ(c.dof(), robot.joints.size());
    {
      std::vector<double> q;
      for (const probe::DhJoint& j : robot.joints) q.push_back(std::clamp(17.0, j.min, j.max));
      const std::vector<Transform> want = probe::forward_frames(robot, q);
      const std::vector<Transform> got = link_frames(c, q, robot.base);
      for (std::size_t i = 0; i < want.size(); ++i) {
        const std::int64_t k = c.find_link("frame" + std::to_string(i));
        ASSERT_GE(k, 0) << i;
        EXPECT_LE(norm(got[k].t - want[i].t), 1e-9) << robot.name << " frame" << i;
        for (int r = 0; r < 3; ++r)
          for (int col = 0; col < 3; ++col)
            EXPECT_NEAR(got[k].r[r][col], want[i].r[r][col], 1e-12) << robot.name << " frame" << i;
      }
    }
    std::mt19937_64 rng(5);
    for (int k = 0; k < 30; ++k) {
      std::vector<double> q;
      for (const probe::DhJoint& j : robot.joints) {
        const double lo = std::max(j.min, j.type == probe::JointType::revolute ? -180.0 : -500.0);
        const double hi = std::min(j.max, j.type == probe::JointType::revolute ? 180.0 : 500.0);
        q.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
      }
      const probe::ProbePose want = probe::forward_kinematics(robot, q);
      const probe::ProbePose got = fk_pose(c, robot.base, tool, q);
      EXPECT_LE(norm(got.tip - want.tip), 1e-9);
      EXPECT_LE(angle_between(got.axis, want.axis), 1e-12);
      probe::ProbePose target = want;
      target.ref = {};
      const IkSolution s = solve_ik(c, robot.base, tool, target, nullptr);
      ASSERT_TRUE(s.ok) << robot.name << " pose " << k << ": " << s.reason;
      const probe::ProbePose back = probe::forward_kinematics(robot, s.q);
      EXPECT_LE(norm(back.tip - target.tip), 1e-9) << robot.name << " " << k;
      EXPECT_LE(angle_between(back.axis, target.axis), 1e-9) << robot.name << " " << k;
    }
  }
}

TEST(RobotIk, JointPathCsvReadsBack) {
  probe::Robot robot = ur5_dh();
  const Chain c = chain_from_dh(robot);
  JointPath p;
  p.q = {{1.0 / 3, -2, 3, 4, 5, 6}, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}};
  const std::string text = joint_path_csv(c, p, "test");
  Expected<JointPath> back = parse_joint_csv(text, "x.csv", c);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->q, p.q);
  EXPECT_EQ(back->lines, (std::vector<std::int64_t>{3, 4}));
}

}  // namespace
