// URDF serial chains (issue #28, deliverable 2): forward kinematics against a closed form derived
// by hand (planar 2R + prismatic, joint axes set by origin rpy), joint paths by name, and bad input
// (missing file and mesh, unknown joint type, branches, loops, limits), each error naming the file
// and the element. The 6R example arm's forward kinematics is checked against an independent numpy
// composition in tests/cli/test_cell.py.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/robot/chain.h"

namespace fs = std::filesystem;
using namespace interfere;
using namespace interfere::robot;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("interfere_robot_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

fs::path write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p;
}

// Planar 2R in the x-z plane plus a prismatic joint along the last link: joint axes z turned into
// -y by the first origin's rpy (pi/2, 0, 0). Lengths in metres: base height h, links l1, l2.
const char* kPlanar = R"(<?xml version="1.0"?>
<robot name="planar">
  <link name="base"/>
  <link name="l1"><collision><origin xyz="0.1 0 0"/><geometry><box size="0.2 0.02 0.02"/></geometry></collision></link>
  <link name="l2"/>
  <link name="l3"/>
  <link name="tip"/>
  <joint name="q1" type="revolute">
    <parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.5" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="q2" type="continuous">
    <parent link="l1"/><child link="l2"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="d3" type="prismatic">
    <parent link="l2"/><child link="l3"/>
    <origin xyz="0.2 0 0"/><axis xyz="2 0 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
  </joint>
  <joint name="flange" type="fixed">
    <parent link="l3"/><child link="tip"/>
    <origin xyz="0.05 0 0"/>
  </joint>
</robot>
)";

}  // namespace

#if INTERFERE_TEST_URDF

TEST(UrdfChain, PlanarArmAgainstClosedForm) {
  const fs::path d = temp_dir("planar");
  Expected<Chain> c = read_urdf(write(d / "planar.urdf", kPlanar));
  ASSERT_TRUE(c) << c.error().message();
  ASSERT_EQ(c->links.size(), 5u);
  ASSERT_EQ(c->dof(), 3u);
  EXPECT_EQ(c->joints[0].kind, JointKind::revolute);
  EXPECT_NEAR(c->joints[0].upper, 3 * 180 / std::numbers::pi, 1e-9);  // radians -> degrees
  EXPECT_NEAR(c->joints[2].upper, 100, 1e-12);                        // metres -> mm
  ASSERT_TRUE(c->links[1].mesh);                                      // the box
  EXPECT_EQ(c->links[1].mesh->num_triangles(), 12u);
  for (const auto& q :
       std::vector<std::vector<double>>{{0, 0, 0}, {30, -45, 20}, {-100, 170, 99}, {12.5, 7, 3}}) {
    const std::vector<Transform> f = link_frames(*c, q);
    const double a = q[0] * std::numbers::pi / 180, b = (q[0] + q[1]) * std::numbers::pi / 180;
    const double l2 = 200 + q[2] + 50;  // mm: link 2, the prismatic stroke, the flange
    const Vec3 expected{300 * std::cos(a) + l2 * std::cos(b), 0,
                        500 + 300 * std::sin(a) + l2 * std::sin(b)};
    const Vec3 got = f.back().t;
    EXPECT_NEAR(got.x, expected.x, 1e-9);
    EXPECT_NEAR(got.y, expected.y, 1e-9);
    EXPECT_NEAR(got.z, expected.z, 1e-9);
    // The box of link 1 spans x in [0, 200] mm of its frame: its far end is at distance 200 along
    // the link.
    const Vec3 far = f[1].apply({200, 0, 0});
    EXPECT_NEAR(far.x, 200 * std::cos(a), 1e-9);
    EXPECT_NEAR(far.z, 500 + 200 * std::sin(a), 1e-9);
  }
  EXPECT_TRUE(check_limits(*c, {0, 720, 50}));  // continuous: no limits
  const Status s = check_limits(*c, {0, 0, 150});
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message().find("d3"), std::string::npos) << s.error().message();
}

TEST(UrdfChain, MeshesRelativeAndPackagePaths) {
  const fs::path d = temp_dir("meshes");
  fs::create_directories(d / "meshes");
  fs::create_directories(d / "pkgs" / "my_robot" / "meshes");
  ASSERT_TRUE(write_mesh(d / "meshes" / "cube.obj", make_box({0, 0, 0}, {1, 1, 1})));
  ASSERT_TRUE(
      write_mesh(d / "pkgs" / "my_robot" / "meshes" / "cube.stl", make_box({0, 0, 0}, {1, 1, 1})));
  const std::string urdf = R"(<robot name="m">
  <link name="a"><visual><geometry><mesh filename="meshes/cube.obj" scale="0.01 0.02 0.03"/></geometry></visual></link>
  <link name="b"><collision><origin xyz="0 0 1"/><geometry><mesh filename="package://my_robot/meshes/cube.stl"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>)";
  write(d / "m.urdf", urdf);
  UrdfOptions none;
  none.use_ros_package_path = false;
  Expected<Chain> bad = read_urdf(d / "m.urdf", none);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message().find("package://my_robot/meshes/cube.stl"), std::string::npos);
  EXPECT_NE(bad.error().message().find("link 'b'"), std::string::npos) << bad.error().message();
  EXPECT_NE(bad.error().message().find("m.urdf:3:"), std::string::npos) << bad.error().message();
  UrdfOptions o = none;
  o.package_paths = {d / "pkgs"};
  Expected<Chain> c = read_urdf(d / "m.urdf", o);
  ASSERT_TRUE(c) << c.error().message();
  ASSERT_TRUE(c->links[0].mesh && c->links[1].mesh);
  Aabb box;
  for (const Vec3& p : c->links[0].mesh->positions) box.expand(p);
  EXPECT_NEAR(box.hi.x, 10, 1e-12);  // scale 0.01 m -> 10 mm
  EXPECT_NEAR(box.hi.z, 30, 1e-12);
  Aabb box2;
  for (const Vec3& p : c->links[1].mesh->positions) box2.expand(p);
  EXPECT_NEAR(box2.lo.z, 1000, 1e-9);  // collision origin 1 m; mesh in metres (scale 1) -> 1000 mm
  EXPECT_NEAR(box2.hi.z, 2000, 1e-9);
}

TEST(UrdfChain, BadInputNamesFileAndElement) {
  const fs::path d = temp_dir("bad");
  auto expect_error = [&](const std::string& name, const std::string& text,
                          const std::vector<std::string>& parts) {
    Expected<Chain> c = read_urdf(write(d / name, text));
    ASSERT_FALSE(c) << name;
    const std::string m = c.error().message();
    EXPECT_NE(m.find(name), std::string::npos) << m;
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << name << ": " << m;
  };
  EXPECT_FALSE(read_urdf(d / "missing.urdf"));
  EXPECT_NE(read_urdf(d / "missing.urdf").error().message().find("missing.urdf"),
            std::string::npos);
  const std::string head =
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n";
  expect_error(
      "screw.urdf",
      head + R"(<joint name="j1" type="screw"><parent link="a"/><child link="b"/></joint></robot>)",
      {"j1", "screw"});
  expect_error("branch.urdf",
               head + R"(<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint></robot>)",
               {"link 'a'", "j1", "j2", "serial"});
  expect_error(
      "floating.urdf",
      head + R"(<joint name="free" type="floating"><parent link="a"/><child link="b"/></joint>
<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)",
      {"joint 'free'", "floating", ":2:"});
  expect_error(
      "nolimit.urdf",
      head + R"(<joint name="j1" type="revolute"><parent link="a"/><child link="b"/></joint>
<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)",
      {"j1"});
  expect_error("loop.urdf",
               head + R"(<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>
<joint name="j3" type="fixed"><parent link="c"/><child link="a"/></joint></robot>)",
               {});
  expect_error(
      "nomesh.urdf",
      R"(<robot name="r"><link name="a"><visual><geometry><mesh filename="gone.stl"/></geometry></visual></link></robot>)",
      {"link 'a'", "gone.stl", "not found"});
  expect_error("notxml.urdf", "this is not XML", {"urdfdom"});
}

TEST(UrdfChain, JointCsvByName) {
  const fs::path d = temp_dir("csv");
  Expected<Chain> c = read_urdf(write(d / "planar.urdf", kPlanar));
  ASSERT_TRUE(c) << c.error().message();
  Expected<JointPath> p =
      parse_joint_csv("# comment\nd3, q1 ,q2\n10,20,30\n\n0,-5,400\n", "p.csv", *c);
  ASSERT_TRUE(p) << p.error().message();
  ASSERT_EQ(p->size(), 2u);
  EXPECT_EQ(p->q[0], (std::vector<double>{20, 30, 10}));
  EXPECT_EQ(p->lines[1], 5);
  auto err = [&](const std::string& text) {
    Expected<JointPath> e = parse_joint_csv(text, "p.csv", *c);
    EXPECT_FALSE(e) << text;
    return e ? std::string() : e.error().message();
  };
  EXPECT_NE(err("q1,q2,q4\n1,2,3\n").find("p.csv:1: column 3 'q4': not a movable joint"),
            std::string::npos);
  EXPECT_NE(err("q1,q2,flange\n1,2,3\n").find("'flange'"),
            std::string::npos);  // fixed joints have no column
  EXPECT_NE(err("q1,q2\n1,2\n").find("joint 'd3' has no column"), std::string::npos);
  EXPECT_NE(err("q1,q2,q1\n1,2,3\n").find("named twice"), std::string::npos);
  EXPECT_NE(err("q1,q2,d3\n1,2\n").find("p.csv:2: 2 values, expected 3"), std::string::npos);
  EXPECT_NE(err("q1,q2,d3\n1,x,3\n").find("column 2 'q2': 'x' is not a finite number"),
            std::string::npos);
  EXPECT_NE(err("q1,q2,d3\n1,2,3\n1,2,101\n")
                .find("p.csv:3: column 3 'd3': 101 outside the joint's limits [0, 100]"),
            std::string::npos);
  EXPECT_NE(err("q1,q2,d3\n").find("no path points"), std::string::npos);
}

#else

TEST(UrdfChain, BuildWithoutUrdfdomSaysSo) {
  Expected<Chain> c = parse_urdf("<robot/>", "x.urdf");
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().message().find("no URDF reader"), std::string::npos);
}

#endif
