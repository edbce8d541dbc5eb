// A cell whose robot is a DH table (issue #28, deliverable 2: "standard and modified DH tables
// (JSON) and URDF"; robot/cell.h): the same 3R arm written as a standard DH table with meshes on
// its DH frames and, independently, as a URDF file (read by urdfdom) whose links are those frames;
// both cells along one random joint path give the same bodies, the same world poses (1e-9 mm) and
// the same pair verdicts in every frame. Bad "robot" sections are errors naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/probe/export.h"
#include "interfere/robot/cell.h"

namespace fs = std::filesystem;
using namespace interfere;
using namespace interfere::robot;

namespace {

// Rows (a, alpha, d, theta) of the arm, mm and degrees: a yaw joint 200 mm up, twisted 90 degrees,
// a 400 mm upper arm and a 300 mm forearm whose joint angle is offset by 10 degrees.
struct Row {
  double a, alpha, d, theta;
};
constexpr Row kRows[3] = {{0, 90, 200, 0}, {400, 0, 0, 0}, {300, 0, 0, 10}};

fs::path write_files(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("interfere_cell_dh_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  // link meshes in their DH frames (mm): the base, the turret, upper arm and forearm along -x
  // (DH frame i sits at the far end of link i)
  const TriMesh meshes[4] = {make_box({-100, -100, 0}, {100, 100, 100}), make_box({-50, -50, -50}, {50, 50, 50}),
                             make_box({-380, -30, -30}, {-20, 30, 30}), make_box({-280, -25, -25}, {-20, 25, 25})};
  for (int i = 0; i < 4; ++i) {
    Status s = write_mesh(dir / ("frame" + std::to_string(i) + ".obj"), meshes[i]);
    EXPECT_TRUE(s) << s.error().message();
  }
  EXPECT_TRUE(write_mesh(dir / "plate.obj", make_box({-150, -150, 0}, {150, 150, 40})));
  EXPECT_TRUE(write_mesh(dir / "post.obj", make_box({-20, -20, 0}, {20, 20, 450})));
  std::ofstream dh(dir / "arm.json");
  dh << R"({"name": "arm3", "convention": "standard", "joints": [)";
  for (int i = 0; i < 3; ++i)
    dh << (i ? "," : "") << "\n {\"name\": \"j" << i + 1 << "\", \"type\": \"revolute\", \"a\": " << kRows[i].a
       << ", \"alpha\": " << kRows[i].alpha << ", \"d\": " << kRows[i].d << ", \"theta\": " << kRows[i].theta
       << ", \"min\": -180, \"max\": 180}";
  dh << "],\n \"tool\": {\"tip\": [0, 0, 0], \"axis\": [1, 0, 0]}}\n";
  // The same arm as URDF (metres, radians): per row a movable joint about z with origin rpy (0 0
  // theta), then a fixed joint with the rest of the row, Tz(d) Tx(a) Rx(alpha) = xyz (a 0 d) rpy
  // (alpha 0 0).
  std::ofstream u(dir / "arm.urdf");
  u.precision(17);
  const double rad = std::numbers::pi / 180;
  u << "<robot name=\"arm3\">\n";
  for (int i = 0; i < 4; ++i) {
    u << " <link name=\"frame" << i << "\"><collision><geometry><mesh filename=\"frame" << i
      << ".obj\" scale=\"0.001 0.001 0.001\"/></geometry></collision></link>\n";
    if (i) u << " <link name=\"moving" << i << "\"/>\n";
  }
  for (int i = 0; i < 3; ++i) {
    u << " <joint name=\"j" << i + 1 << "\" type=\"revolute\"><parent link=\"frame" << i << "\"/><child link=\"moving"
      << i + 1 << "\"/><origin xyz=\"0 0 0\" rpy=\"0 0 " << kRows[i].theta * rad
      << "\"/><axis xyz=\"0 0 1\"/><limit lower=\"" << -std::numbers::pi << "\" upper=\"" << std::numbers::pi
      << "\" effort=\"1\" velocity=\"1\"/></joint>\n";
    u << " <joint name=\"dh_frame" << i + 1 << "\" type=\"fixed\"><parent link=\"moving" << i + 1
      << "\"/><child link=\"frame" << i + 1 << "\"/><origin xyz=\"" << kRows[i].a / 1000 << " 0 " << kRows[i].d / 1000
      << "\" rpy=\"" << kRows[i].alpha * rad << " 0 0\"/></joint>\n";
  }
  u << "</robot>\n";
  const std::string rest = R"(,
 "tool": {"tip": [0, 0, 0], "axis": [1, 0, 0], "probe_radius": 8, "probe_length": 60,
          "holder_radius": 20, "holder_length": 60, "sides": 12},
 "workpiece": {"mesh": "plate.obj", "pose": [1,0,0,550, 0,1,0,0, 0,0,1,0]},
 "fixtures": [{"id": "post", "mesh": "post.obj", "pose": [1,0,0,300, 0,1,0,250, 0,0,1,0]}]}
)";
  std::ofstream(dir / "dh_cell.json")
      << R"({"robot": {"dh": "arm.json", "base": [1,0,0,5, 0,1,0,-3, 0,0,1,2], "links": {)"
      << R"("frame0": {"mesh": "frame0.obj"}, "frame1": {"mesh": "frame1.obj"},)"
      << R"("frame2": {"mesh": "frame2.obj"}, "frame3": {"mesh": "frame3.obj", "pose": [1,0,0,0, 0,1,0,0, 0,0,1,0]}}})"
      << rest;
  std::ofstream(dir / "urdf_cell.json") << R"({"robot": {"urdf": "arm.urdf", "base": [1,0,0,5, 0,1,0,-3, 0,0,1,2]})"
                                        << rest;
  return dir;
}

using PairKey = std::tuple<std::uint32_t, std::string, std::string, std::string, int>;

std::set<PairKey> frame_verdicts(const CellScene& cs) {
  scene::SceneClashOptions opt;
  opt.depth = false;
  opt.curves = false;
  const scene::SceneClashResult r = scene::clash_scene(cs.scene, cs.tests, opt);
  std::set<PairKey> out;
  for (const scene::FramePairRow& row : r.frame_pairs)
    out.insert({row.frame, cs.tests[row.test].name, cs.scene.bodies[row.a].id, cs.scene.bodies[row.b].id,
                static_cast<int>(row.verdict)});
  return out;
}

}  // namespace

TEST(CellDh, ReadsTheTableAndItsLinkMeshes) {
  const fs::path dir = write_files("read");
  Expected<Cell> cell = read_cell_json(dir / "dh_cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  EXPECT_EQ(cell->robot_format, "dh");
  EXPECT_EQ(cell->robot.dof(), 3u);
  EXPECT_EQ(cell->tool.link, "frame3");
  std::size_t with_mesh = 0;
  for (const ChainLink& l : cell->robot.links) with_mesh += l.mesh != nullptr;
  EXPECT_EQ(with_mesh, 4u);
  fs::remove_all(dir);
}

#if INTERFERE_TEST_URDF
TEST(CellDh, SameVerdictsAsTheSameArmInUrdf) {
  const fs::path dir = write_files("urdf");
  Expected<Cell> dh = read_cell_json(dir / "dh_cell.json");
  Expected<Cell> urdf = read_cell_json(dir / "urdf_cell.json");
  ASSERT_TRUE(dh) << dh.error().message();
  ASSERT_TRUE(urdf) << urdf.error().message();
  EXPECT_EQ(urdf->robot_format, "urdf");
  JointPath path;
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> yaw(-60, 60), pitch(-20, 120), elbow(-150, 0);
  for (int i = 0; i < 60; ++i) {
    path.q.push_back({yaw(g), pitch(g), elbow(g)});
    path.lines.push_back(i + 2);
  }
  const CellScene a = cell_scene(*dh, path), b = cell_scene(*urdf, path);
  ASSERT_EQ(a.scene.bodies.size(), b.scene.bodies.size());
  std::map<std::string, std::size_t> index_b;
  for (std::size_t i = 0; i < b.scene.bodies.size(); ++i) index_b[b.scene.bodies[i].id] = i;
  for (std::size_t f = 0; f < a.scene.frames.size(); ++f) {
    for (const scene::Frame::Pose& p : a.scene.frames[f].poses) {
      const std::string& id = a.scene.bodies[p.body].id;
      ASSERT_TRUE(index_b.count(id)) << id;
      const auto& pb = b.scene.frames[f].poses;
      const auto it = std::find_if(pb.begin(), pb.end(), [&](const scene::Frame::Pose& x) { return x.body == index_b[id]; });
      ASSERT_NE(it, pb.end()) << id;
      // a body's world position of a far corner (2,000 mm) within 1e-9 mm
      const Vec3 x{1000, -700, 1200};
      EXPECT_LE(norm(p.pose.apply(x) - it->pose.apply(x)), 1e-9) << id << " frame " << f;
    }
  }
  const std::set<PairKey> va = frame_verdicts(a), vb = frame_verdicts(b);
  EXPECT_EQ(va, vb);
  // rows are the pairs with findings: some frames have them, some have none
  std::set<std::uint32_t> frames_meeting;
  for (const PairKey& k : va) frames_meeting.insert(std::get<0>(k));
  EXPECT_GT(frames_meeting.size(), 5u) << "the path should make bodies meet";
  EXPECT_LT(frames_meeting.size(), path.q.size()) << "and leave some frames clear";
  fs::remove_all(dir);
}
#endif

// The probe and holder are closed outward solids (probe::cylinder_mesh): a tool wholly inside a
// fixture is a clash, not undecided (their sides faced inward before 2026-11-29: open bodies).
TEST(CellDh, ToolInsideAFixtureIsAClash) {
  const probe::Cylinder c{{1, 2, 3}, {4, -5, 30}, 7};
  const TriMesh m = probe::cylinder_mesh(c, 24);
  double volume = 0;  // signed, divergence theorem
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto q = m.corners(t);
    volume += dot(q[0], cross(q[1], q[2])) / 6;
  }
  const double inscribed = 0.5 * 24 * std::sin(2 * std::numbers::pi / 24) * 49 * norm(c.c1 - c.c0);
  EXPECT_NEAR(volume, inscribed, 1e-9 * inscribed);  // positive: outward

  const fs::path dir = write_files("inside");
  Expected<Cell> cell = read_cell_json(dir / "dh_cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  const std::vector<double> q{0, 0, 0};
  const Transform tool = link_frames(cell->robot, q, cell->base)[cell->tool_link];
  // a box around the probe (tool x in [-60, 0]) and holder ([-120, -60]), radius <= 20, posed at the tool
  ASSERT_TRUE(write_mesh(dir / "enclosure.obj", make_box({-130, -30, -30}, {10, 30, 30})));
  std::ostringstream pose;
  pose.precision(17);
  for (int r = 0; r < 3; ++r)
    pose << (r ? "," : "") << tool.r[r][0] << "," << tool.r[r][1] << "," << tool.r[r][2] << "," << tool.t[r];
  std::ofstream(dir / "inside.json")
      << R"({"robot": {"dh": "arm.json", "base": [1,0,0,5, 0,1,0,-3, 0,0,1,2]},
 "tool": {"tip": [0, 0, 0], "axis": [1, 0, 0], "probe_radius": 8, "probe_length": 60,
          "holder_radius": 20, "holder_length": 60, "sides": 12},
 "workpiece": {"mesh": "plate.obj", "pose": [1,0,0,550, 0,1,0,0, 0,0,1,-500]},
 "fixtures": [{"id": "enclosure", "mesh": "enclosure.obj", "pose": [)"
      << pose.str() << "]}]}\n";
  Expected<Cell> inside = read_cell_json(dir / "inside.json");
  ASSERT_TRUE(inside) << inside.error().message();
  JointPath path;
  path.q = {q};
  path.lines = {2};
  const CellScene cs = cell_scene(*inside, path);
  std::map<std::string, int> verdict;
  for (const PairKey& k : frame_verdicts(cs)) verdict[std::get<2>(k) + "|" + std::get<3>(k)] = std::get<4>(k);
  for (const char* body : {"probe", "holder"}) {
    const std::string key = std::min<std::string>(body, "fixture:enclosure") + "|" + std::max<std::string>(body, "fixture:enclosure");
    ASSERT_TRUE(verdict.count(key)) << key;
    EXPECT_EQ(verdict[key], static_cast<int>(Verdict::clash)) << key;
  }
  fs::remove_all(dir);
}

TEST(CellDh, BadRobotSectionsNameTheField) {
  const fs::path dir = write_files("bad");
  const std::string rest = R"(, "tool": {"tip": [0,0,0], "axis": [1,0,0], "probe_radius": 8, "probe_length": 60},
 "workpiece": {"mesh": "plate.obj"}})";
  auto msg = [&](const std::string& robot) {
    std::ofstream(dir / "c.json") << "{\"robot\": " << robot << rest;
    Expected<Cell> c = read_cell_json(dir / "c.json");
    EXPECT_FALSE(c) << robot;
    return c ? std::string() : c.error().message();
  };
  EXPECT_NE(msg(R"({"dh": "arm.json", "urdf": "arm.urdf"})").find("not both"), std::string::npos);
  EXPECT_NE(msg(R"({"base": [1,0,0,0, 0,1,0,0, 0,0,1,0]})").find("robot: missing"), std::string::npos);
  EXPECT_NE(msg(R"({"dh": "arm.json", "links": {"frame9": {"mesh": "frame0.obj"}}})").find("robot.links.frame9"),
            std::string::npos);
  EXPECT_NE(msg(R"({"dh": "arm.json", "links": {"moving1": {"mesh": "frame0.obj"}}})").find("not a DH frame"),
            std::string::npos);
  EXPECT_NE(msg(R"({"dh": "arm.json", "links": {"frame1": {"mesh": "nope.obj"}}})").find("nope.obj"),
            std::string::npos);
  EXPECT_NE(msg(R"({"dh": "arm.json", "links": {"frame1": {"mesh": "frame1.obj", "pose": [1,0,0]}}})")
                .find("robot.links.frame1.pose"),
            std::string::npos);
  EXPECT_NE(msg(R"({"dh": "arm.json", "package_paths": ["x"]})").find("only for a URDF robot"), std::string::npos);
  EXPECT_NE(msg(R"({"urdf": "arm.urdf", "links": {}})").find("only for a DH robot"), std::string::npos);
  std::ofstream(dir / "craig.json") << R"({"convention": "Craig", "joints": [{"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}], "tool": {"tip": [0,0,0], "axis": [1,0,0]}})";
  const std::string craig = msg(R"({"dh": "craig.json"})");
  EXPECT_NE(craig.find("craig.json:1"), std::string::npos) << craig;
  EXPECT_NE(craig.find("convention"), std::string::npos) << craig;
  fs::remove_all(dir);
}
