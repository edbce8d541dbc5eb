// Path and robot files read by meaning, not position (issue #23, item 9): joint CSV columns are
// matched to the robot's joints by header name (a header "b,a,z,y,x" used to be read as x..b by
// position), unknown, missing and repeated names are errors naming file, line and column; the
// robot's base must be a rigid transform, unknown keys are errors with their JSON path, and a
// `units` other than mm is refused instead of ignored. Oracle for the poses: the closed
// form of the pivot machine's end circle (pivot_end_circle), not the DH chain the parser feeds.
#include <gtest/gtest.h>

#include <cmath>

#include "interfere/probe/path.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

std::string path_error(const std::string& text, const Robot* robot) {
  auto p = parse_path_csv(text, "path.csv", robot);
  EXPECT_FALSE(p) << text;
  return p ? std::string() : p.error().message();
}

std::string robot_error(const std::string& text) {
  auto r = parse_robot_json(text, "robot.json");
  EXPECT_FALSE(r) << text;
  return r ? std::string() : r.error().message();
}

void expect_has(const std::string& m, const std::string& part) {
  EXPECT_NE(m.find(part), std::string::npos) << m;
}

const char* kJoints =
    R"("joints": [{"name": "q1", "type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}])";
const char* kTool = R"("tool": {"tip": [0, 0, 10], "axis": [0, 0, 1]})";

std::string robot_with(const std::string& extra) {
  return std::string("{\n") + extra + (extra.empty() ? "" : ",\n") + kJoints + ",\n" + kTool +
         "\n}\n";
}

}  // namespace

TEST(ProbePathByName, JointColumnsInAnyOrder) {
  const Robot r = pivot_machine(150);
  auto a = parse_path_csv("x,y,z,a,b\n1,2,170,30,10\n", "a.csv", &r);
  auto b = parse_path_csv("b,a,z,y,x\n10,30,170,2,1\n", "b.csv", &r);
  ASSERT_TRUE(a) << a.error().message();
  ASSERT_TRUE(b) << b.error().message();
  EXPECT_EQ(b->joints, a->joints);
  EXPECT_EQ(b->columns, (std::vector<std::string>{"x", "y", "z", "a", "b"}));  // the robot's order
  resolve_poses(*b, r);
  const ProbePose ref = pivot_end_circle({1, 2, 170, 30, 10}, 150);
  EXPECT_NEAR(b->poses[0].tip.x, ref.tip.x, 1e-9);
  EXPECT_NEAR(b->poses[0].tip.y, ref.tip.y, 1e-9);
  EXPECT_NEAR(b->poses[0].tip.z, ref.tip.z, 1e-9);
  // Limits are checked against the joint the column names (b in [-120, 120]), reported by name.
  const std::string m = path_error("b,a,z,y,x\n130,0,170,0,0\n", &r);
  expect_has(m, "path.csv:2");
  expect_has(m, "field 'b' (column 1");
  expect_has(m, "limits");
}

TEST(ProbePathByName, UnknownMissingAndRepeatedColumns) {
  const Robot r = pivot_machine(150);
  std::string m = path_error("x,y,z,a,q\n0,0,0,0,0\n", &r);
  expect_has(m, "path.csv:1");
  expect_has(m, "column 5");
  expect_has(m, "unknown column 'q'");
  m = path_error("x,y,z,a\n0,0,0,0\n", &r);
  expect_has(m, "path.csv:1");
  expect_has(m, "missing column b");
  m = path_error("x,y,z,a,a\n0,0,0,0,0\n", &r);
  expect_has(m, "column 5");
  expect_has(m, "given twice");
  m = path_error("x,y,z,a,b,c\n0,0,0,0,0,0\n", &r);
  expect_has(m, "unknown column 'c'");
  // Pose columns: by name too, any order; the reference columns all or none.
  auto p = parse_path_csv("az,ay,ax,pz,py,px\n-2,0,0,3,2,1\n", "p.csv", nullptr);
  ASSERT_TRUE(p) << p.error().message();
  EXPECT_FALSE(p->joint_space);
  EXPECT_EQ(p->poses[0].tip, (Vec3{1, 2, 3}));
  EXPECT_EQ(p->poses[0].axis, (Vec3{0, 0, -1}));
  m = path_error("px,py,pz,ax,ay,az,rx,ry\n0,0,0,0,0,1,1,0\n", nullptr);
  expect_has(m, "missing column rz");
  m = path_error("px,py,pz,ax,ay,az,x\n0,0,0,0,0,1,1\n", &r);
  expect_has(m, "column 7");
  expect_has(m, "unknown column 'x'");
  m = path_error("px,py,pz,ax,ay\n0,0,0,0,0\n", nullptr);
  expect_has(m, "missing column az");
}

TEST(ProbeRobotFile, BaseMustBeRigid) {
  auto base = [](const char* twelve) {
    return robot_with(std::string("\"base\": [") + twelve + "]");
  };
  // A rotation about z by 90 degrees: fine; written with 7 decimals (cos 30 = 0.8660254): fine.
  EXPECT_TRUE(parse_robot_json(base("0,-1,0,5, 1,0,0,6, 0,0,1,7"), "robot.json"));
  EXPECT_TRUE(
      parse_robot_json(base("0.8660254,-0.5,0,0, 0.5,0.8660254,0,0, 0,0,1,0"), "robot.json"));
  // Scaled, sheared, reflected, singular: errors naming the field and line.
  for (const char* bad : {"2,0,0,0, 0,2,0,0, 0,0,2,0", "1,0.1,0,0, 0,1,0,0, 0,0,1,0",
                          "-1,0,0,0, 0,1,0,0, 0,0,1,0", "0,0,0,0, 0,0,0,0, 0,0,0,0"}) {
    const std::string m = robot_error(base(bad));
    expect_has(m, "robot.json:2");
    expect_has(m, "base: not a rigid transform");
  }
}

TEST(ProbeRobotFile, UnknownKeysAreErrorsWithTheirPath) {
  std::string m = robot_error(robot_with("\"nmae\": \"r\""));
  expect_has(m, "robot.json:2");
  expect_has(m, "nmae: unknown key");
  m = robot_error(R"({"joints": [
 {"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0},
 {"type": "revolute", "a": 0, "alfa": 0, "d": 0, "theta": 0}],
 "tool": {"tip": [0, 0, 0], "axis": [0, 0, 1]}})");
  expect_has(m, "robot.json:3");
  expect_has(m, "joints[1].alfa: unknown key");
  m = robot_error(R"({"joints": [{"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}],
 "tool": {"tip": [0, 0, 0], "axis": [0, 0, 1],
  "rfe": [1, 0, 0]}})");
  expect_has(m, "robot.json:3");
  expect_has(m, "tool.rfe: unknown key");
  // Two joints with one name: path columns could not tell them apart.
  m = robot_error(R"({"joints": [
 {"name": "j", "type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0},
 {"name": "j", "type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}],
 "tool": {"tip": [0, 0, 0], "axis": [0, 0, 1]}})");
  expect_has(m, "joints[1].name");
}

TEST(ProbeRobotFile, UnitsAreMillimetresOrAnError) {
  auto r = parse_robot_json(robot_with("\"units\": \"mm\""), "robot.json");
  ASSERT_TRUE(r) << r.error().message();
  std::string m = robot_error(robot_with("\"units\": \"m\""));
  expect_has(m, "robot.json:2");
  expect_has(m, "units: 'm'");
  expect_has(m, "mm");
  m = robot_error(robot_with("\"units\": \"furlong\""));
  expect_has(m, "not a known unit");
  m = robot_error(robot_with("\"units\": 1"));
  expect_has(m, "units: expected a string");
}
