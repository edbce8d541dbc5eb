// The paper's 3P+2R machine (Li, Zhou & Zheng 2008, §3.1; issue #28, deliverables 1-2): the shipped
// robot file and the builder against §3.1's rear end-circle formula written out here (not the DH
// code), the analytic inverse kinematics checked through forward kinematics, limits and
// reachability errors, and a segment whose collision outcome differs between the machine's own
// motion (joint interpolation) and straight pose interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "interfere/probe/paper_machine.h"
#include "interfere/probe/sweep.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// §3.1, verbatim: centre of the probe's rear end circle; angles in degrees.
Vec3 rear_centre_31(double x, double y, double z, double a_deg, double b_deg, double d1, double d2) {
  const double a = a_deg * kPi / 180, b = b_deg * kPi / 180;
  return {x + d1 * std::cos(a) + d2 * std::sin(a) * std::cos(b), y - d1 * std::sin(a) + d2 * std::cos(a) * std::cos(b),
          -z + d2 * std::sin(b)};
}

/// Unit direction from the wrist to the rear centre along d2 (the probe axis).
Vec3 clamp_direction_31(double a_deg, double b_deg) {
  const double a = a_deg * kPi / 180, b = b_deg * kPi / 180;
  return {std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b)};
}

void expect_rel(const Vec3& got, const Vec3& want, double rel, const char* what) {
  const double scale = std::max({1.0, std::fabs(want.x), std::fabs(want.y), std::fabs(want.z)});
  EXPECT_LE(norm(got - want), rel * scale) << what << ": got (" << got.x << ", " << got.y << ", " << got.z
                                           << ") want (" << want.x << ", " << want.y << ", " << want.z << ")";
}

const std::filesystem::path kRobotFile =
    std::filesystem::path(INTERFERE_SOURCE_DIR) / "data" / "examples" / "probe_paper_machine.json";

}  // namespace

TEST(PaperMachine, ShippedRobotFileIsSection31) {
  auto r = read_robot_json(kRobotFile);
  ASSERT_TRUE(r) << r.error().message();
  const double d1 = 30, d2 = 120, l = 40;  // the file's documented constants
  std::mt19937_64 g(28);
  std::uniform_real_distribution<double> len(-2000, 2000), ang(-360, 360), tilt(-120, 120);
  for (int it = 0; it < 500; ++it) {
    const double x = len(g), y = len(g), z = len(g), a = ang(g), b = tilt(g);
    const ProbePose p = forward_kinematics(*r, {x, y, z, a, b});
    expect_rel(p.tip - p.axis * l, rear_centre_31(x, y, z, a, b, d1, d2), 1e-12, "rear centre");
    expect_rel(p.axis, clamp_direction_31(a, b), 1e-12, "axis");
  }
  // Horizontal probe at a = b = 0 (world +y), rear at (x + d1, y + d2, -z).
  const ProbePose h = forward_kinematics(*r, {1, 2, 3, 0, 0});
  expect_rel(h.axis, {0, 1, 0}, 1e-15, "horizontal axis");
  expect_rel(h.tip - h.axis * l, {1 + d1, 2 + d2, -3}, 1e-15, "rear at a = b = 0");
  // The earlier bundled machine (probe_5axis.json, the pivot reconstruction) is not §3.1: its end
  // circle at (0, 0, 0, 0, 0) is 150 mm below the pivot, §3.1's rear circle is at (30, 120, 0).
  auto old = read_robot_json(std::filesystem::path(INTERFERE_SOURCE_DIR) / "data" / "examples" / "probe_5axis.json");
  ASSERT_TRUE(old) << old.error().message();
  EXPECT_GT(norm(forward_kinematics(*old, {0, 0, 0, 0, 0}).tip - rear_centre_31(0, 0, 0, 0, 0, d1, d2)), 100);
  EXPECT_TRUE(has_inverse_kinematics(*r));
  EXPECT_FALSE(has_inverse_kinematics(*old));
}

TEST(PaperMachine, BuilderMatchesSection31ForAnyConstants) {
  std::mt19937_64 g(281);
  std::uniform_real_distribution<double> len(-1500, 1500), ang(-360, 360), tilt(-120, 120), c(-200, 200), pos(1, 300);
  for (int it = 0; it < 300; ++it) {
    const PaperMachine m{.d1 = c(g), .d2 = c(g), .probe_length = pos(g), .origin = {c(g), c(g), c(g)}};
    const Robot r = paper_machine_31(m);
    // Through the JSON writer and reader, as a user's file would be.
    auto again = parse_robot_json(robot_to_json(r), "mem.json");
    ASSERT_TRUE(again) << again.error().message();
    const double x = len(g), y = len(g), z = len(g), a = ang(g), b = tilt(g);
    for (const Robot* robot : std::vector<const Robot*>{&r, &*again}) {
      const ProbePose p = forward_kinematics(*robot, {x, y, z, a, b});
      expect_rel(p.tip - p.axis * m.probe_length, m.origin + rear_centre_31(x, y, z, a, b, m.d1, m.d2), 1e-12,
                 "rear centre");
      expect_rel(p.axis, clamp_direction_31(a, b), 1e-12, "axis");
    }
    const auto geo = paper_geometry(*again);
    ASSERT_TRUE(geo);
    EXPECT_EQ(geo->d1, m.d1);
  }
}

TEST(PaperMachine, InverseOfForwardOnRandomJoints) {
  auto r = read_robot_json(kRobotFile);
  ASSERT_TRUE(r) << r.error().message();
  std::mt19937_64 g(2828);
  std::uniform_real_distribution<double> len(-1800, 1800), ang(-360, 360), tilt(-120, 120);
  for (int it = 0; it < 1000; ++it) {
    const std::vector<double> q{len(g), len(g), len(g), ang(g), tilt(g)};
    const ProbePose p = forward_kinematics(*r, q);
    // Without a previous point: some solution within the limits reproducing the pose (checked by
    // forward kinematics, not by the inverse's own formulas).
    auto s = inverse_kinematics(*r, p);
    ASSERT_TRUE(s) << s.error().message();
    ASSERT_TRUE(check_joint_limits(*r, *s));
    const ProbePose back = forward_kinematics(*r, *s);
    expect_rel(back.tip, p.tip, 1e-12, "tip");
    expect_rel(back.axis, p.axis, 1e-12, "axis");
    // With the true joints as the previous point: the same joints (nearest solution).
    auto same = inverse_kinematics(*r, p, &q);
    ASSERT_TRUE(same) << same.error().message();
    for (int i = 0; i < 5; ++i) EXPECT_NEAR((*same)[i], q[i], 1e-9 * std::max(1.0, std::fabs(q[i]))) << i;
  }
  // Vertical axis: a is free, the previous point's a is kept.
  const std::vector<double> prev{0, 0, 0, 37, 80};
  auto v = inverse_kinematics(*r, {{10, 20, 30}, {0, 0, 1}}, &prev);
  ASSERT_TRUE(v);
  EXPECT_NEAR((*v)[3], 37, 1e-12);
  EXPECT_NEAR((*v)[4], 90, 1e-12);
  expect_rel(forward_kinematics(*r, *v).tip, {10, 20, 30}, 1e-12, "vertical tip");
}

TEST(PaperMachine, UnreachableAndOutOfLimitPosesRejected) {
  PaperMachine m;
  m.b_limit = 30;  // tilt at most 30 degrees up or down
  const Robot r = paper_machine_31(m);
  // Too far: the wrist would need z beyond the travel.
  auto far = inverse_kinematics(r, {{0, 0, -2500}, {0, 1, 0}});
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().reason.find("joint z"), std::string::npos) << far.error().reason;
  EXPECT_NE(far.error().reason.find("[-2000, 2000]"), std::string::npos) << far.error().reason;
  // Pointing straight down needs |b| = 90 on either branch: outside [-30, 30].
  auto down = inverse_kinematics(r, {{0, 0, 0}, {0, 0, -1}});
  ASSERT_FALSE(down);
  EXPECT_NE(down.error().reason.find("joint b"), std::string::npos) << down.error().reason;
  // A robot without inverse kinematics says so.
  Robot other = r;
  other.joints[4].alpha = 90;
  auto none = inverse_kinematics(other, {{0, 0, 0}, {0, 1, 0}});
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().reason.find("no inverse kinematics"), std::string::npos);
  // A pose path: the error names the file, the line and the point.
  auto path = parse_path_csv("px,py,pz,ax,ay,az\n0,0,0,0,1,0\n# comment\n0,0,0,0,0,-1\n", "path.csv", nullptr);
  ASSERT_TRUE(path) << path.error().message();
  auto joints = pose_path_to_joint_path(*path, r, "path.csv");
  ASSERT_FALSE(joints);
  const std::string msg = joints.error().message();
  EXPECT_NE(msg.find("path.csv:4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("point 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("joint b"), std::string::npos) << msg;
}

TEST(PaperMachine, PosePathBecomesJointPath) {
  const Robot r = paper_machine_31({});
  auto path = parse_path_csv("px,py,pz,ax,ay,az\n100,200,-300,0,1,0\n100,250,-300,1,1,0\n90,250,-280,1,1,1\n",
                             "p.csv", nullptr);
  ASSERT_TRUE(path);
  auto j = pose_path_to_joint_path(*path, r, "p.csv");
  ASSERT_TRUE(j) << j.error().message();
  EXPECT_TRUE(j->joint_space);
  ASSERT_EQ(j->joints.size(), 3u);
  EXPECT_EQ(j->lines, path->lines);
  for (std::size_t i = 0; i < 3; ++i) {
    expect_rel(j->poses[i].tip, path->poses[i].tip, 1e-12, "tip");
    expect_rel(j->poses[i].axis, path->poses[i].axis, 1e-12, "axis");
  }
}

TEST(PaperMachine, JointInterpolationDecidesTheSegment) {
  // Two poses with the same tip T, the probe horizontal, turned from a = -60 to a = +60. Pose
  // interpolation keeps the tip at T (the axis swings): the probe stays inside the ball of radius
  // sqrt(l^2 + r^2) about T. The machine interpolates its joints: the wrist moves on a straight line
  // and at the middle (a = 0) the tip is at T + (d1 (1 - cos 60), reach (1 - cos 60), 0) =
  // T + (15, 80, 0), 81 mm from T. A small triangle there is struck only by the machine's motion.
  const PaperMachine m{.d1 = 30, .d2 = 120, .probe_length = 40};
  const Robot r = paper_machine_31(m);
  const ProbeShape shape{.radius = 5, .length = 40};
  const Vec3 T{100, 200, -300};
  auto path = parse_path_csv("px,py,pz,ax,ay,az\n100,200,-300,-0.86602540378443865,0.5,0\n"
                             "100,200,-300,0.86602540378443865,0.5,0\n",
                             "p.csv", nullptr);
  ASSERT_TRUE(path);
  auto joints = pose_path_to_joint_path(*path, r, "p.csv");
  ASSERT_TRUE(joints) << joints.error().message();
  EXPECT_NEAR(joints->joints[0][3], -60, 1e-9);
  EXPECT_NEAR(joints->joints[1][3], 60, 1e-9);
  // The machine's pose at the middle, by forward kinematics of the joint midpoint.
  std::vector<double> mid(5);
  for (int i = 0; i < 5; ++i) mid[i] = 0.5 * (joints->joints[0][i] + joints->joints[1][i]);
  const ProbePose pm = forward_kinematics(r, mid);
  expect_rel(pm.tip, T + Vec3{15, 80, 0}, 1e-9, "middle tip");
  // A 2 mm triangle across the probe 2 mm behind that tip, perpendicular to the axis.
  const Vec3 c = pm.tip - pm.axis * 2.0;
  TriMesh mesh;
  mesh.positions = {c + Vec3{-1, 0, -1}, c + Vec3{1, 0, -1}, c + Vec3{0, 0, 1}};
  mesh.triangles = {{0, 1, 2}};
  ASSERT_TRUE(cylinder_triangle_intersect(cylinder_from_tip(pm.tip, pm.axis, shape.length, shape.radius),
                                          mesh.corners(0)));
  const double ball = std::hypot(shape.length, shape.radius);
  for (const Vec3& v : mesh.positions) ASSERT_GT(norm(v - T), ball + 30);  // clear of every tip-at-T pose
  const Workpiece w = prepare_workpiece(mesh, shape);
  const SweepResult joint = sweep(w, *joints, &r, {.probe = shape, .clearance = false});
  const SweepResult pose = sweep(w, *path, nullptr, {.probe = shape, .clearance = false});
  EXPECT_EQ(joint.colliding_points, 0u);
  EXPECT_EQ(pose.colliding_points, 0u);
  ASSERT_EQ(joint.segments.size(), 1u);
  EXPECT_EQ(joint.segments[0].state, SegmentState::collides);
  EXPECT_TRUE(joint.segments[0].between_samples);
  ASSERT_FALSE(joint.segments[0].intervals.empty());
  EXPECT_LE(joint.segments[0].intervals[0][0], 0.5);
  EXPECT_GE(joint.segments[0].intervals.back()[1], 0.5);
  EXPECT_EQ(pose.colliding_segments, 0u);
  EXPECT_EQ(pose.verdict, Verdict::clear);
}
