// Kinematics (issue #5, items 1, 2, 7): DH forward kinematics against hand-computed poses, the
// pivot machine against its closed-form end circle (the paper's §3.1 machine: test_paper_machine.cpp), the bundled pivot robot file, and bad inputs naming
// file, line and field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"
#include "interfere/probe/sweep.h"

using namespace interfere;
using namespace interfere::probe;

namespace {
void expect_vec(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(ProbeKinematics, PlanarTwoLinkByHand) {
  // Planar RR arm, a1 = 2, a2 = 1: tip at (2 cos q1 + cos(q1 + q2), 2 sin q1 + sin(q1 + q2), 0).
  Robot r;
  r.joints = {{"q1", JointType::revolute, 2, 0, 0, 0}, {"q2", JointType::revolute, 1, 0, 0, 0}};
  r.tool_tip = {0, 0, 0};
  r.tool_axis = {1, 0, 0};
  const ProbePose p = forward_kinematics(r, {30, 60});
  const double q1 = M_PI / 6, q12 = M_PI / 2;
  expect_vec(p.tip, {2 * std::cos(q1) + std::cos(q12), 2 * std::sin(q1) + std::sin(q12), 0}, 1e-12);
  expect_vec(p.axis, {std::cos(q12), std::sin(q12), 0}, 1e-12);  // x of the last frame
}

TEST(ProbeKinematics, PrismaticAndTwistByHand) {
  // Joint 1 prismatic along z0 with alpha = 90: z1 = -y0; joint 2 prismatic moves along -y.
  Robot r;
  r.joints = {{"d1", JointType::prismatic, 0, 90, 1, 0}, {"d2", JointType::prismatic, 0, 0, 0, 0}};
  r.tool_tip = {0, 0, 0};
  r.tool_axis = {0, 0, 1};
  const ProbePose p = forward_kinematics(r, {3, 5});
  expect_vec(p.tip, {0, -5, 4}, 1e-12);
  expect_vec(p.axis, {0, -1, 0}, 1e-12);
}

TEST(ProbeKinematics, PivotMachineMatchesItsClosedForm) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> len(-500, 500), ang(-180, 180), tilt(-110, 110);
  const Vec3 base{10, -20, 300};
  const Robot r = pivot_machine(150, base);
  for (int it = 0; it < 200; ++it) {
    const std::array<double, 5> q{len(g), len(g), len(g), ang(g), tilt(g)};
    const ProbePose fk = forward_kinematics(r, {q.begin(), q.end()});
    const ProbePose ref = pivot_end_circle(q, 150, base);
    expect_vec(fk.tip, ref.tip, 1e-9);
    expect_vec(fk.axis, ref.axis, 1e-12);
    // And the inverse used by the path generator.
    const auto back = pivot_inverse(ref, 150, base);
    const ProbePose again = pivot_end_circle(back, 150, base);
    expect_vec(again.tip, ref.tip, 1e-9);
    expect_vec(again.axis, ref.axis, 1e-12);
  }
  // Hand-computed: a = 90, b = 90: axis (-sin b cos a, -sin b sin a, -cos b) = (0, -1, 0).
  const ProbePose p = forward_kinematics(r, {1, 2, 3, 90, 90});
  expect_vec(p.axis, {0, -1, 0}, 1e-15);
  expect_vec(p.tip, base + Vec3{1, 2 - 150, 3}, 1e-12);
}

TEST(ProbeKinematics, BundledPivotRobotFile) {
  auto r = read_robot_json(std::filesystem::path(INTERFERE_SOURCE_DIR) / "data" / "examples" / "probe_5axis.json");
  ASSERT_TRUE(r) << r.error().message();
  const Robot ref = pivot_machine(150);
  ASSERT_EQ(r->joints.size(), 5u);
  for (const std::vector<double> q : {std::vector<double>{0, 0, 0, 0, 0}, {12, -40, 250, 33, -21}}) {
    const ProbePose a = forward_kinematics(*r, q), b = forward_kinematics(ref, q);
    expect_vec(a.tip, b.tip, 1e-12);
    expect_vec(a.axis, b.axis, 1e-15);
  }
  // Round trip through robot_to_json.
  auto again = parse_robot_json(robot_to_json(*r), "mem");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->joints[4].max, r->joints[4].max);
}

TEST(ProbeKinematics, BadRobotFiles) {
  auto msg = [](const char* text) {
    auto r = parse_robot_json(text, "robot.json");
    EXPECT_FALSE(r);
    return r ? std::string() : r.error().message();
  };
  const std::string unknown = msg(R"({"joints": [
  {"type": "spherical", "a": 0, "alpha": 0, "d": 0, "theta": 0}], "tool": {"tip": [0,0,0], "axis": [0,0,1]}})");
  EXPECT_NE(unknown.find("robot.json:2"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("joints[0].type"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("spherical"), std::string::npos) << unknown;
  const std::string missing = msg(R"({"joints": [
  {"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0},
  {"type": "prismatic", "a": 0, "d": 0, "theta": 0}], "tool": {"tip": [0,0,0], "axis": [0,0,1]}})");
  EXPECT_NE(missing.find("robot.json:3"), std::string::npos) << missing;
  EXPECT_NE(missing.find("joints[1].alpha: missing"), std::string::npos) << missing;
  EXPECT_NE(msg(R"({"joints": []})").find("joints"), std::string::npos);
  EXPECT_NE(msg("{\"joints\": [\n").find("robot.json:"), std::string::npos);
  // A number beyond double is an error naming the file, not an exception.
  EXPECT_NE(msg(R"({"joints": [9e999]})").find("robot.json: invalid JSON"), std::string::npos);
  EXPECT_NE(msg(R"({"joints": [{"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}]})").find("tool"),
            std::string::npos);
}

// Modified (Craig) DH, issue #28 deliverable 2: T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i).
TEST(ProbeKinematics, ModifiedConventionByHand) {
  // Planar RR arm: row 2 carries a_1 = 2 (the link before joint 2); the tool is 1 along x_2.
  Robot r;
  r.convention = DhConvention::modified;
  r.joints = {{"q1", JointType::revolute, 0, 0, 0, 0}, {"q2", JointType::revolute, 2, 0, 0, 0}};
  r.tool_tip = {1, 0, 0};
  r.tool_axis = {1, 0, 0};
  const ProbePose p = forward_kinematics(r, {30, 60});
  const double q1 = M_PI / 6, q12 = M_PI / 2;
  expect_vec(p.tip, {2 * std::cos(q1) + std::cos(q12), 2 * std::sin(q1) + std::sin(q12), 0}, 1e-12);
  expect_vec(p.axis, {std::cos(q12), std::sin(q12), 0}, 1e-12);
  // A prismatic joint after a 90 degree twist moves along Rx(90) z = -y: d = 1 + 3.
  Robot t;
  t.convention = DhConvention::modified;
  t.joints = {{"d1", JointType::prismatic, 0, 90, 1, 0}};
  t.tool_tip = {0, 0, 0};
  t.tool_axis = {0, 0, 1};
  const ProbePose pt = forward_kinematics(t, {3});
  expect_vec(pt.tip, {0, -4, 0}, 1e-12);
  expect_vec(pt.axis, {0, -1, 0}, 1e-12);
  EXPECT_EQ(joint_axis_frame(t, 0), 1u);
}

// A standard table and its modified form describe the same robot: the products
// prod Rz Tz Tx Rx and prod Rx Tx Rz Tz (with a_{i-1}, alpha_{i-1} shifted down one row) differ only by
// the last row's Tx(a_n) Rx(alpha_n), moved into the tool. Same poses, and the joint-path motion
// bound of the sweep (about each joint's own axis: joint_axis_frame) is the same.
TEST(ProbeKinematics, ModifiedTableOfAStandardRobot) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> len(-300, 300), ang(-180, 180);
  for (int robot_no = 0; robot_no < 20; ++robot_no) {
    Robot s, m;
    m.convention = DhConvention::modified;
    const int n = 6;
    for (int i = 0; i < n; ++i) {
      DhJoint j{"j" + std::to_string(i + 1), (robot_no + i) % 4 == 0 ? JointType::prismatic : JointType::revolute,
                len(g), ang(g), len(g), ang(g)};
      s.joints.push_back(j);
    }
    for (int i = 0; i < n; ++i) {
      DhJoint j = s.joints[i];
      j.a = i ? s.joints[i - 1].a : 0;
      j.alpha = i ? s.joints[i - 1].alpha : 0;
      m.joints.push_back(j);
    }
    s.tool_tip = {len(g), len(g), len(g)};
    s.tool_axis = Vec3{0.3, -0.5, 0.81} / norm(Vec3{0.3, -0.5, 0.81});
    // tool in the modified last frame: Tx(a_n) Rx(alpha_n) applied to the standard one
    const double al = s.joints[n - 1].alpha * M_PI / 180, c = std::cos(al), sn = std::sin(al);
    const auto rx = [&](const Vec3& v) { return Vec3{v.x, c * v.y - sn * v.z, sn * v.y + c * v.z}; };
    m.tool_tip = rx(s.tool_tip) + Vec3{s.joints[n - 1].a, 0, 0};
    m.tool_axis = rx(s.tool_axis);
    m.tool_ref = rx(s.tool_ref);
    std::vector<double> qa(n), qb(n);
    for (int i = 0; i < n; ++i) qa[i] = ang(g), qb[i] = ang(g);
    const ProbePose ps = forward_kinematics(s, qa), pm = forward_kinematics(m, qa);
    expect_vec(pm.tip, ps.tip, 1e-9);
    expect_vec(pm.axis, ps.axis, 1e-12);
    ProbePath path;
    path.joint_space = true;
    path.joints = {qa, qb};
    path.lines = {1, 2};
    ProbeShape shape;
    shape.holder_radius = 20, shape.holder_length = 60;
    const double bs = motion_bound(path, &s, shape, 0, 0.25, 0.5);
    const double bm = motion_bound(path, &m, shape, 0, 0.25, 0.5);
    EXPECT_NEAR(bm, bs, 1e-9 * bs) << robot_no;
  }
}

TEST(ProbeKinematics, ConventionKey) {
  const char* body = R"(, "joints": [{"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}],
 "tool": {"tip": [0,0,0], "axis": [0,0,1]}})";
  for (const char* c : {"\"modified\"", "\"modified DH: T_i = Rx(alpha) Tx(a) Rz(theta) Tz(d)\""}) {
    auto r = parse_robot_json(std::string("{\"convention\": ") + c + body, "r.json");
    ASSERT_TRUE(r) << r.error().message();
    EXPECT_EQ(r->convention, DhConvention::modified);
    auto again = parse_robot_json(robot_to_json(*r), "again.json");
    ASSERT_TRUE(again) << again.error().message();
    EXPECT_EQ(again->convention, DhConvention::modified);
  }
  auto s = parse_robot_json(std::string("{\"convention\": \"standard\"") + body, "r.json");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->convention, DhConvention::standard);
  for (const char* c : {"\"Craig\"", "\"proximal\"", "3"}) {
    auto bad = parse_robot_json(std::string("{\n\"convention\": ") + c + body, "r.json");
    ASSERT_FALSE(bad) << c;
    EXPECT_NE(bad.error().message().find("r.json:2"), std::string::npos) << bad.error().message();
    EXPECT_NE(bad.error().message().find("convention"), std::string::npos) << bad.error().message();
  }
}

TEST(ProbePath, JointAndPosePaths) {
  const Robot r = pivot_machine(150);
  auto p = parse_path_csv("# comment\nx,y,z,a,b\n1,2,3,0,0\n\n4, 5, 6, 10, 20\n", "p.csv", &r);
  ASSERT_TRUE(p) << p.error().message();
  EXPECT_TRUE(p->joint_space);
  ASSERT_EQ(p->size(), 2u);
  EXPECT_EQ(p->lines[1], 5);
  resolve_poses(*p, r);
  expect_vec(p->poses[0].tip, {1, 2, 3 - 150}, 1e-12);
  auto q = parse_path_csv("px,py,pz,ax,ay,az\n0,0,1,0,0,-2\n", "q.csv", nullptr);
  ASSERT_TRUE(q) << q.error().message();
  EXPECT_FALSE(q->joint_space);
  expect_vec(q->poses[0].axis, {0, 0, -1}, 0);
  auto again = parse_path_csv(path_to_csv(*p), "again.csv", &r);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->joints, p->joints);
}

TEST(ProbePath, BadRowsNameFileLineAndField) {
  const Robot r = pivot_machine(150);
  auto err = [&](const char* text, const Robot* robot) {
    auto p = parse_path_csv(text, "path.csv", robot);
    EXPECT_FALSE(p);
    return p ? std::string() : p.error().message();
  };
  std::string m = err("x,y,z,a,b\n1,2,3,4,5\n1,2,3,4\n", &r);
  EXPECT_NE(m.find("path.csv:3"), std::string::npos) << m;
  EXPECT_NE(m.find("4 values, expected 5"), std::string::npos) << m;
  m = err("x,y,z,a,b\n1,2,3,4,500\n", &r);
  EXPECT_NE(m.find("path.csv:2"), std::string::npos) << m;
  EXPECT_NE(m.find("field 'b'"), std::string::npos) << m;
  EXPECT_NE(m.find("limits"), std::string::npos) << m;
  m = err("x,y,z,a,b\n1,2,abc,4,5\n", &r);
  EXPECT_NE(m.find("field 'z'"), std::string::npos) << m;
  m = err("x,y,z\n1,2,3\n", &r);
  EXPECT_NE(m.find("path.csv:1"), std::string::npos) << m;
  m = err("px,py,pz,ax,ay,az\n0,0,0,0,0,0\n", nullptr);
  EXPECT_NE(m.find("zero probe axis"), std::string::npos) << m;
  m = err("x,y,z,a,b\n", &r);
  EXPECT_NE(m.find("no path points"), std::string::npos) << m;
  m = err("x,y,z,a,b\n1,2,3,4,5\n", nullptr);
  EXPECT_NE(m.find("needs a robot"), std::string::npos) << m;
}
