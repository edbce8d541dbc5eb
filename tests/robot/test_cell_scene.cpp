// The inspection cell as a scene (issue #28, deliverable 3): a generated small cell (3-link arm of
// URDF boxes and an OBJ link, probe and holder on the flange, a workpiece and two fixtures) along
// a random joint path, decided by the scene engine, against a brute-force oracle that poses every
// body itself from its own homogeneous transforms, and checks every pair the cell should check
// (tool vs workpiece/fixtures, links vs workpiece/fixtures, non-adjacent links and tool among
// themselves) with all triangle pairs (segment/triangle crossings by orient3d signs) plus a ray
// parity test for a body lying inside another.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>

#include <tbb/global_control.h>

#include "interfere/core/predicates.h"
#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/probe/export.h"
#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"
#include "interfere/probe/path.h"
#include "cell_checks.h"

namespace fs = std::filesystem;
using namespace interfere;
using namespace interfere::robot;
using namespace interfere::robot::checks;

#if INTERFERE_TEST_URDF

namespace {

// Oracle transforms: 4x4 row-major matrices built from the URDF numbers written below.
using M4 = std::array<std::array<double, 4>, 4>;
M4 mul(const M4& a, const M4& b) {
  M4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}
M4 eye() {
  return {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
}
M4 trans(double x, double y, double z) {
  M4 m = eye();
  m[0][3] = x, m[1][3] = y, m[2][3] = z;
  return m;
}
M4 rot_z(double deg) {
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  M4 m = eye();
  m[0][0] = c, m[0][1] = -s, m[1][0] = s, m[1][1] = c;
  return m;
}
M4 rot_y(double deg) {
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  M4 m = eye();
  m[0][0] = c, m[0][2] = s, m[2][0] = -s, m[2][2] = c;
  return m;
}
Vec3 apply_m4(const M4& m, const Vec3& p) {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}

// The arm (metres in the URDF, mm here): base box; yaw joint about z at height 0.2 (link "turret",
// box); pitch joint about y (link "upper", box along x, 0.4 long); pitch joint about y at x = 0.4
// (link "fore", an OBJ box along x, 0.3 long); fixed flange at x = 0.3 with rpy (0, pi/2, 0): the
// flange z axis points along the forearm's x... turned down by the pitch joints.
const char* kArm = R"(<robot name="arm3">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="turret"><collision><origin xyz="0 0 -0.03"/><geometry><box size="0.12 0.12 0.06"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.36 0.06 0.06"/></geometry></collision></link>
  <link name="fore"><collision><geometry><mesh filename="fore.obj" scale="0.001 0.001 0.001"/></geometry></collision></link>
  <link name="flange"/>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="turret"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="turret"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.4 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="tool" type="fixed"><parent link="fore"/><child link="flange"/><origin xyz="0.3 0 0" rpy="0 1.5707963267948966 0"/></joint>
</robot>)";

// Oracle link frames (mm, degrees), written from the URDF above by hand.
std::vector<M4> oracle_frames(const std::vector<double>& q) {
  std::vector<M4> f(5);
  f[0] = eye();
  f[1] = mul(mul(f[0], trans(0, 0, 200)), rot_z(q[0]));
  f[2] = mul(f[1], rot_y(q[1]));
  f[3] = mul(mul(f[2], trans(400, 0, 0)), rot_y(q[2]));
  f[4] = mul(f[3], mul(trans(300, 0, 0), rot_y(90)));
  return f;
}

/// The oracle frame (oracle_frames) a cell body moves with: 1 turret, 2 upper arm, 3 forearm, 4 the
/// tool (probe, holder); -1: fixed (workpiece, fixtures, base).
int oracle_link(const std::string& id) {
  if (id == "link:turret") return 1;
  if (id == "link:upper") return 2;
  if (id == "link:fore") return 3;
  if (id == "probe" || id == "holder") return 4;
  return -1;
}

struct Solid {
  std::string id;
  std::string tag;
  TriMesh local;
  int link = -1;  // -1: static
  M4 pose = eye();
};

bool segment_crosses(const Vec3& p, const Vec3& q, const std::array<Vec3, 3>& t, bool& degenerate) {
  const int sp = orient3d(t[0], t[1], t[2], p), sq = orient3d(t[0], t[1], t[2], q);
  if (sp == 0 || sq == 0) {
    if (sp == 0 && sq == 0) {  // coplanar: a touch only when their boxes meet
      Aabb bs, bt;
      bs.expand(p), bs.expand(q);
      for (const Vec3& v : t) bt.expand(v);
      degenerate = degenerate || (bs.lo.x <= bt.hi.x && bt.lo.x <= bs.hi.x && bs.lo.y <= bt.hi.y &&
                                  bt.lo.y <= bs.hi.y && bs.lo.z <= bt.hi.z && bt.lo.z <= bs.hi.z);
    } else {
      const int a = orient3d(p, q, t[0], t[1]), b = orient3d(p, q, t[1], t[2]),
                c = orient3d(p, q, t[2], t[0]);
      if ((a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0)) degenerate = true;
    }
    return false;
  }
  if (sp == sq) return false;
  const int a = orient3d(p, q, t[0], t[1]), b = orient3d(p, q, t[1], t[2]),
            c = orient3d(p, q, t[2], t[0]);
  if (a == 0 || b == 0 || c == 0) {
    if ((a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0)) degenerate = true;
    return false;
  }
  return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0);
}

TriMesh posed(const Solid& s) {
  TriMesh m = s.local;
  for (Vec3& p : m.positions) p = apply_m4(s.pose, p);
  return m;
}

/// 1: the surfaces cross or one lies inside the other; 0: apart; -1: degenerate (touching).
int brute_meets(const TriMesh& a, const TriMesh& b) {
  bool degenerate = false;
  for (std::size_t i = 0; i < a.num_triangles(); ++i) {
    const auto ta = a.corners(i);
    for (std::size_t j = 0; j < b.num_triangles(); ++j) {
      const auto tb = b.corners(j);
      for (int e = 0; e < 3; ++e) {
        if (segment_crosses(ta[e], ta[(e + 1) % 3], tb, degenerate)) return 1;
        if (segment_crosses(tb[e], tb[(e + 1) % 3], ta, degenerate)) return 1;
      }
    }
  }
  if (degenerate) return -1;
  // No crossing: one inside the other iff a vertex of it is inside (ray parity along an odd
  // direction).
  auto inside = [&](const Vec3& p, const TriMesh& m) {
    const Vec3 far = p + Vec3{1e5 * 0.5772, 1e5 * 0.3141, 1e5 * 0.7071};
    int n = 0;
    for (std::size_t t = 0; t < m.num_triangles(); ++t)
      n += segment_crosses(p, far, m.corners(t), degenerate);
    return n % 2 == 1;
  };
  const bool in = inside(a.positions[0], b) || inside(b.positions[0], a);
  if (degenerate) return -1;
  return in ? 1 : 0;
}

}  // namespace

TEST(CellScene, RandomPathAgainstBruteForcePairs) {
  const fs::path d = fs::temp_directory_path() / "interfere_robot_cell";
  fs::remove_all(d);
  fs::create_directories(d);
  const TriMesh fore =
      make_box({0, -25, -25}, {300, 25, 25});  // mm (OBJ read with scale 0.001 m -> mm)
  ASSERT_TRUE(write_mesh(d / "fore.obj", fore));
  std::ofstream(d / "arm3.urdf") << kArm;
  const TriMesh plate = make_box({-150, -150, 0}, {150, 150, 30});
  const TriMesh block = make_box({-20, -20, 0}, {20, 20, 120});
  ASSERT_TRUE(write_mesh(d / "plate.stl", plate));
  ASSERT_TRUE(write_mesh(d / "block.stl", block));
  std::ofstream(d / "cell.json") << R"({
  "robot": {"urdf": "arm3.urdf", "tool_link": "flange"},
  "tool": {"tip": [0, 0, 120], "axis": [0, 0, 1], "probe_radius": 8, "probe_length": 50,
           "holder_radius": 20, "holder_length": 70, "sides": 12},
  "workpiece": {"mesh": "plate.stl", "pose": [1,0,0,600, 0,1,0,0, 0,0,1,0]},
  "fixtures": [{"id": "post", "mesh": "block.stl", "pose": [0,-1,0,450, 1,0,0,180, 0,0,1,0]},
               {"id": "post2", "mesh": "block.stl", "pose": [1,0,0,700, 0,1,0,-190, 0,0,1,0]}]
})";
  Expected<Cell> cell = read_cell_json(d / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  ASSERT_EQ(cell->robot.dof(), 3u);

  // A random joint path around a pose reaching down towards the plate.
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> yaw(-40, 40), sh(10, 60), el(20, 120);
  JointPath path;
  for (int i = 0; i < 40; ++i) {
    path.q.push_back({yaw(rng), sh(rng), el(rng)});
    path.lines.push_back(i + 2);
  }
  const CellScene cs = cell_scene(*cell, path);
  ASSERT_EQ(cs.scene.frames.size(), path.size());
  scene::SceneClashOptions opt;
  opt.depth = false;
  opt.curves = false;
  const scene::SceneClashResult r = scene::clash_scene(cs.scene, cs.tests, opt);

  // The oracle's own bodies and poses.
  std::vector<Solid> solids;
  const int link_of_body[] = {0, 1, 2, 3};
  const TriMesh link_meshes[] = {make_box({-100, -100, 0}, {100, 100, 100}),
                                 make_box({-60, -60, -60}, {60, 60, 0}),
                                 make_box({20, -30, -30}, {380, 30, 30}), fore};
  const char* link_names[] = {"base", "turret", "upper", "fore"};
  for (int i = 0; i < 4; ++i)
    solids.push_back(
        {std::string("link:") + link_names[i], "link", link_meshes[i], link_of_body[i]});
  // The tool in the flange frame: probe z in [70, 120], holder z in [0, 70] (same tessellation as
  // the cell: the oracle checks the pair decisions, not the tessellation).
  solids.push_back({"probe", "tool", probe::cylinder_mesh({{0, 0, 120}, {0, 0, 70}, 8}, 12), 4});
  solids.push_back({"holder", "tool", probe::cylinder_mesh({{0, 0, 70}, {0, 0, 0}, 20}, 12), 4});
  solids.push_back({"workpiece", "workpiece", plate, -1, mul(trans(600, 0, 0), eye())});
  solids.push_back({"fixture:post", "fixture", block, -1, mul(trans(450, 180, 0), rot_z(90))});
  solids.push_back({"fixture:post2", "fixture", block, -1, trans(700, -190, 0)});
  auto adjacent = [&](const Solid& a, const Solid& b) {
    if (a.tag == "tool" && b.tag == "tool") return true;
    if (a.tag == "tool" || b.tag == "tool")
      return (a.tag == "tool" ? b : a).link == 3;  // mounted on "fore"
    return std::abs(a.link - b.link) == 1;
  };
  std::set<std::pair<std::string, std::string>> checked_pairs;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    for (std::size_t j = i + 1; j < solids.size(); ++j) {
      const Solid &a = solids[i], &b = solids[j];
      const bool a_static = a.link < 0, b_static = b.link < 0;
      if (a_static && b_static) continue;  // workpiece/fixtures are not checked among themselves
      if (!a_static && !b_static && adjacent(a, b)) continue;
      checked_pairs.insert(std::pair<std::string, std::string>(std::minmax(a.id, b.id)));
    }
  }
  std::map<std::pair<std::size_t, std::pair<std::string, std::string>>, Verdict> engine;
  for (const scene::FramePairRow& row : r.frame_pairs) {
    const std::pair<std::string, std::string> key =
        std::minmax(cs.scene.bodies[row.a].id, cs.scene.bodies[row.b].id);
    EXPECT_TRUE(checked_pairs.count(key))
        << key.first << " " << key.second << " reported but not a checked pair";
    engine[{row.frame, key}] = row.verdict;
  }
  std::size_t meets = 0, apart = 0, degenerate = 0, disagreements = 0;
  for (std::size_t f = 0; f < path.size(); ++f) {
    const std::vector<M4> frames = oracle_frames(path.q[f]);
    std::map<std::string, TriMesh> world;
    for (Solid s : solids) {
      if (s.link >= 0) s.pose = frames[static_cast<std::size_t>(s.link)];
      world[s.id] = posed(s);
    }
    for (const auto& pair : checked_pairs) {
      const int b = brute_meets(world[pair.first], world[pair.second]);
      auto it = engine.find({f, pair});
      const bool e =
          it != engine.end() && (it->second == Verdict::clash || it->second == Verdict::contact);
      if (b < 0) {
        ++degenerate;
        continue;
      }
      (b ? meets : apart) += 1;
      if (e != (b == 1)) {
        ++disagreements;
        ADD_FAILURE() << "frame " << f << " pair " << pair.first << " / " << pair.second
                      << ": engine " << e << ", brute force " << b;
      }
    }
  }
  EXPECT_EQ(disagreements, 0u);
  EXPECT_GT(meets, 10u);  // the path does strike things
  EXPECT_GT(apart, 100u);
  EXPECT_EQ(degenerate, 0u);
  RecordProperty("pairs_meeting", static_cast<int>(meets));
  RecordProperty("pairs_apart", static_cast<int>(apart));
}

TEST(CellScene, SuppressedAdjacentPairsAndBetweenFrames) {
  const fs::path d = fs::temp_directory_path() / "interfere_robot_cell2";
  fs::remove_all(d);
  fs::create_directories(d);
  ASSERT_TRUE(write_mesh(d / "fore.obj", make_box({0, -25, -25}, {300, 25, 25})));
  std::ofstream(d / "arm3.urdf") << kArm;
  ASSERT_TRUE(write_mesh(d / "plate.stl", make_box({-150, -150, 0}, {150, 150, 30})));
  std::ofstream(d / "cell.json") << R"({"robot": {"urdf": "arm3.urdf"},
  "tool": {"tip": [0, 0, 120], "probe_radius": 8, "probe_length": 50},
  "workpiece": {"mesh": "plate.stl"}})";
  Expected<Cell> cell = read_cell_json(d / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  EXPECT_EQ(cell->tool_link, 4u);  // the last link by default
  JointPath path{{{0, 10, 20}, {10, 30, 60}}, {2, 3}};
  const CellScene cs = cell_scene(*cell, path, 3);
  ASSERT_EQ(cs.scene.frames.size(), 5u);  // 2 points + 3 between
  EXPECT_EQ(cs.frame_point, (std::vector<std::size_t>{0, 0, 0, 0, 1}));
  EXPECT_DOUBLE_EQ(cs.frame_t[2], 0.5);
  ASSERT_EQ(cs.tests.size(), 3u);
  EXPECT_EQ(cs.tests[2].name, "self");
  // base-turret, turret-upper, upper-fore, fore-probe (no holder).
  EXPECT_EQ(cs.tests[2].suppressions.size(), 4u);
  // The between frame's poses are the joint interpolation's: the turret at yaw 5.
  const std::vector<Transform> mid = link_frames(cell->robot, {5, 20, 40});
  const auto& poses = cs.scene.frames[2].poses;
  bool found = false;
  for (const auto& p : poses) {
    if (cs.scene.bodies[p.body].id == "link:turret") {
      found = true;
      EXPECT_TRUE(p.pose == mid[1]);
    }
  }
  EXPECT_TRUE(found);
}

TEST(CellScene, BadCellFilesNameTheField) {
  const fs::path d = fs::temp_directory_path() / "interfere_robot_cell3";
  fs::remove_all(d);
  fs::create_directories(d);
  ASSERT_TRUE(write_mesh(d / "fore.obj", make_box({0, -25, -25}, {300, 25, 25})));
  std::ofstream(d / "arm3.urdf") << kArm;
  ASSERT_TRUE(write_mesh(d / "plate.stl", make_box({-150, -150, 0}, {150, 150, 30})));
  auto err = [&](const std::string& text) {
    std::ofstream(d / "c.json") << text;
    Expected<Cell> c = read_cell_json(d / "c.json");
    EXPECT_FALSE(c) << text;
    return c ? std::string() : c.error().message();
  };
  const std::string robot = R"("robot": {"urdf": "arm3.urdf"}, )";
  const std::string wp = R"(, "workpiece": {"mesh": "plate.stl"})";
  EXPECT_NE(err("{" + robot + R"("tool": {"probe_radius": 0, "probe_length": 5})" + wp + "}")
                .find("tool.probe_radius: must be > 0"),
            std::string::npos);
  EXPECT_NE(
      err("{" + robot + R"("tool": {"probe_radius": 1, "probe_length": 5, "colour": 1})" + wp + "}")
          .find("tool.colour: unknown key"),
      std::string::npos);
  EXPECT_NE(
      err(R"({"robot": {"urdf": "arm3.urdf", "tool_link": "hand"}, "tool": {"probe_radius": 1, "probe_length": 5})" +
          wp + "}")
          .find("robot.tool_link: 'hand' is not a link"),
      std::string::npos);
  EXPECT_NE(
      err(R"({"robot": {"urdf": "none.urdf"}, "tool": {"probe_radius": 1, "probe_length": 5})" +
          wp + "}")
          .find("none.urdf"),
      std::string::npos);
  EXPECT_NE(
      err("{" + robot +
          R"("tool": {"probe_radius": 1, "probe_length": 5}, "workpiece": {"mesh": "gone.stl"}})")
          .find("gone.stl"),
      std::string::npos);
  EXPECT_NE(
      err("{" + robot +
          R"("tool": {"probe_radius": 1, "probe_length": 5}, "workpiece": {"mesh": "plate.stl", "pose": [2,0,0,0, 0,1,0,0, 0,0,1,0]}})")
          .find("workpiece.pose: not a rigid transform"),
      std::string::npos);
}

#endif

#if INTERFERE_TEST_URDF

namespace {

/// The arm3 cell of the tests above (plate and two posts), written to `d`.
Expected<Cell> arm3_cell(const fs::path& d) {
  fs::remove_all(d);
  fs::create_directories(d);
  if (Status s = write_mesh(d / "fore.obj", make_box({0, -25, -25}, {300, 25, 25})); !s) return s.error();
  std::ofstream(d / "arm3.urdf") << kArm;
  if (Status s = write_mesh(d / "plate.stl", make_box({-150, -150, 0}, {150, 150, 30})); !s) return s.error();
  if (Status s = write_mesh(d / "block.stl", make_box({-20, -20, 0}, {20, 20, 120})); !s) return s.error();
  std::ofstream(d / "cell.json") << R"({
  "robot": {"urdf": "arm3.urdf", "tool_link": "flange"},
  "tool": {"tip": [0, 0, 120], "axis": [0, 0, 1], "probe_radius": 8, "probe_length": 50,
           "holder_radius": 20, "holder_length": 70, "sides": 12},
  "workpiece": {"mesh": "plate.stl", "pose": [1,0,0,600, 0,1,0,0, 0,0,1,0]},
  "fixtures": [{"id": "post", "mesh": "block.stl", "pose": [0,-1,0,450, 1,0,0,180, 0,0,1,0]},
               {"id": "post2", "mesh": "block.stl", "pose": [1,0,0,700, 0,1,0,-190, 0,0,1,0]}]
})";
  return read_cell_json(d / "cell.json");
}

}  // namespace

TEST(CellBetween, MotionBoundContainsEveryVertexMotion) {
  Expected<Cell> cell = arm3_cell(fs::temp_directory_path() / "interfere_robot_between1");
  ASSERT_TRUE(cell) << cell.error().message();
  std::mt19937_64 rng(281);
  std::uniform_real_distribution<double> u(-60, 60);
  JointPath one{{{0, 0, 0}}, {1}};
  const CellScene cs = cell_scene(*cell, one);
  double tightest = 1e300;
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<double> q0{u(rng), u(rng), u(rng)}, dq{u(rng) / 4, u(rng) / 4, u(rng) / 4};
    const std::vector<double> bound = motion_bounds(*cell, cs, dq);
    const std::vector<M4> f0 = oracle_frames(q0);
    for (int s = 1; s <= 16; ++s) {  // along the joint-space line q0 + t dq, t in (0, 1]
      const double t = s / 16.0;
      const std::vector<M4> f1 = oracle_frames({q0[0] + t * dq[0], q0[1] + t * dq[1], q0[2] + t * dq[2]});
      for (std::size_t b = 0; b < cs.scene.bodies.size(); ++b) {
        const scene::Body& body = cs.scene.bodies[b];
        const int link = oracle_link(body.id);
        if (link < 0) continue;
        double moved = 0;
        for (const Vec3& p : body.mesh->positions) {
          moved = std::max(moved, norm(apply_m4(f1[link], p) - apply_m4(f0[link], p)));
        }
        EXPECT_LE(moved, bound[b] + 1e-9) << body.id << " trial " << trial;
        if (s == 16 && moved > 1) tightest = std::min(tightest, bound[b] / moved);
      }
    }
  }
  EXPECT_LT(tightest, 10);  // not uselessly loose
}

TEST(CellBetween, ConservativeAgainstDenseSampling) {
  Expected<Cell> cell = arm3_cell(fs::temp_directory_path() / "interfere_robot_between2");
  ASSERT_TRUE(cell) << cell.error().message();
  // A random walk in small steps around a pose reaching down towards the plate.
  JointPath path;
  std::mt19937_64 rng(282);
  std::uniform_real_distribution<double> step(-6, 6);
  std::vector<double> q{0, 35, 70};
  for (int i = 0; i < 16; ++i) {
    path.q.push_back(q);
    path.lines.push_back(i + 2);
    for (double& v : q) v += step(rng);
  }
  const CellScene cs = cell_scene(*cell, path);
  BetweenOptions bo;
  bo.max_depth = 8;
  const std::vector<SegmentResult> seg = check_between_points(*cell, cs, path, bo);
  ASSERT_EQ(seg.size(), path.size() - 1);
  // Dense sampling: 63 frames inside each segment.
  const std::vector<bool> meets = dense_meets(*cell, path, 63);
  std::size_t collides = 0, clear = 0;
  for (std::size_t s = 0; s < seg.size(); ++s) {
    if (seg[s].state == SegmentState::clear) {
      EXPECT_FALSE(meets[s]) << "segment " << s << " proven clear but a sample meets";
      ++clear;
    }
    if (meets[s]) EXPECT_NE(seg[s].state, SegmentState::clear) << s;
    if (seg[s].state == SegmentState::collides) {
      ++collides;
      EXPECT_FALSE(seg[s].pairs.empty());
      EXPECT_GT(seg[s].t, 0);
      EXPECT_LT(seg[s].t, 1);
    }
  }
  EXPECT_GT(collides, 0u);
  EXPECT_GT(clear, 0u);
  RecordProperty("segments_collide", static_cast<int>(collides));
  RecordProperty("segments_clear", static_cast<int>(clear));
}

TEST(CellBetween, CollisionOnlyBetweenPoints) {
  // The shipped example (examples/probe): points 4 (x = 450) and 8 (x = 550) of its path are both
  // clear; joint interpolation between them carries the probe through the rib (x 480..520).
  const fs::path ex = fs::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";
  Expected<Cell> cell = read_cell_json(ex / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  Expected<JointPath> full = read_joint_csv(ex / "path.csv", cell->robot);
  ASSERT_TRUE(full) << full.error().message();
  JointPath path{{full->q[4], full->q[8]}, {full->lines[4], full->lines[8]}};
  const CellScene cs = cell_scene(*cell, path);
  scene::SceneClashOptions opt;
  opt.depth = false;
  const scene::SceneClashResult ends = scene::clash_scene(cs.scene, cs.tests, opt);
  EXPECT_EQ(ends.verdict, Verdict::clear);
  const std::vector<SegmentResult> seg = check_between_points(*cell, cs, path);
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_EQ(seg[0].state, SegmentState::collides);
  ASSERT_EQ(seg[0].pairs.size(), 1u);
  EXPECT_EQ(seg[0].pairs[0].a, "probe");
  EXPECT_EQ(seg[0].pairs[0].b, "workpiece");
  EXPECT_EQ(seg[0].pairs[0].test, "tool");
  // And the whole example path: segments 4-7 (into, over and out of the rib) and 11-13 (the clamp)
  // collide, the others are proven clear.
  const CellScene all = cell_scene(*cell, *full);
  const std::vector<SegmentResult> segs = check_between_points(*cell, all, *full);
  std::vector<std::size_t> colliding, unresolved;
  for (const SegmentResult& r : segs) {
    if (r.state == SegmentState::collides) colliding.push_back(r.from);
    if (r.state == SegmentState::unresolved) unresolved.push_back(r.from);
  }
  EXPECT_EQ(colliding, (std::vector<std::size_t>{4, 5, 6, 7, 11, 12, 13}));
  EXPECT_TRUE(unresolved.empty());
}


namespace {

/// The advancement against the subdivision on one path: where the subdivision resolves a segment,
/// the same state, pairs and parameters; where it leaves one unresolved, the advancement never
/// reports a collision there that ... (it may prove it clear). Also 1 thread vs the default.
void expect_same_as_subdivision(const Cell& cell, const JointPath& path, int max_depth,
                                std::size_t* resolved_only_by_advancement = nullptr) {
  const CellScene cs = cell_scene(cell, path);
  BetweenOptions sub;
  sub.method = BetweenMethod::subdivision;
  sub.max_depth = max_depth;
  BetweenOptions adv;
  adv.max_depth = max_depth;
  const std::vector<SegmentResult> a = check_between_points(cell, cs, path, sub);
  const std::vector<SegmentResult> b = check_between_points(cell, cs, path, adv);
  ASSERT_EQ(a.size(), b.size());
  const std::vector<std::string> da = describe(a), db = describe(b);
  for (std::size_t s = 0; s < a.size(); ++s) {
    if (a[s].state != SegmentState::unresolved) {
      EXPECT_EQ(da[s], db[s]) << "segment " << s;
    } else {
      EXPECT_NE(b[s].state, SegmentState::collides) << db[s];
      if (resolved_only_by_advancement && b[s].state == SegmentState::clear) ++*resolved_only_by_advancement;
    }
    EXPECT_LE(b[s].frames, a[s].frames) << "segment " << s;
  }
  // One thread, middles in order: identical, frames included.
  std::vector<SegmentResult> one;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    BetweenOptions serial = adv;
    serial.parallel = false;
    one = check_between_points(cell, cs, path, serial);
  }
  EXPECT_EQ(describe(one), db);
  for (std::size_t s = 0; s < one.size(); ++s) {
    EXPECT_EQ(one[s].frames, b[s].frames);
    EXPECT_EQ(one[s].engine_frames, b[s].engine_frames);
  }
}

}  // namespace

TEST(CellBetween, MotionBoundAtContainsEveryVertexMotion) {
  Expected<Cell> cell = arm3_cell(fs::temp_directory_path() / "interfere_robot_between3");
  ASSERT_TRUE(cell) << cell.error().message();
  std::mt19937_64 rng(283);
  std::uniform_real_distribution<double> u(-60, 60);
  JointPath one{{{0, 0, 0}}, {1}};
  const CellScene cs = cell_scene(*cell, one);
  double ratio_sum = 0;
  int ratios = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const std::vector<double> q{u(rng), u(rng), u(rng)}, dq{u(rng) / 4, u(rng) / 4, u(rng) / 4};
    const std::vector<double> at = motion_bounds_at(*cell, cs, q, dq);
    const std::vector<double> reach = motion_bounds(*cell, cs, dq);
    const std::vector<M4> f0 = oracle_frames(q);
    std::vector<double> moved(cs.scene.bodies.size(), 0.0);
    for (int s = -16; s <= 16; ++s) {  // q + t dq, t in [-1, 1]
      const double t = s / 16.0;
      const std::vector<M4> f1 = oracle_frames({q[0] + t * dq[0], q[1] + t * dq[1], q[2] + t * dq[2]});
      for (std::size_t b = 0; b < cs.scene.bodies.size(); ++b) {
        const scene::Body& body = cs.scene.bodies[b];
        const int link = oracle_link(body.id);
        if (link < 0) {
          EXPECT_EQ(at[b], 0.0) << body.id;
          continue;
        }
        for (const Vec3& p : body.mesh->positions)
          moved[b] = std::max(moved[b], norm(apply_m4(f1[link], p) - apply_m4(f0[link], p)));
      }
    }
    for (std::size_t b = 0; b < cs.scene.bodies.size(); ++b) {
      EXPECT_LE(moved[b], at[b] + 1e-9) << cs.scene.bodies[b].id << " trial " << trial;
      EXPECT_LE(at[b], reach[b]) << cs.scene.bodies[b].id;
      if (moved[b] > 1) ratio_sum += at[b] / reach[b], ++ratios;
    }
  }
  ASSERT_GT(ratios, 0);
  RecordProperty("mean_bound_ratio_at_over_reach", std::to_string(ratio_sum / ratios));
  EXPECT_LT(ratio_sum / ratios, 1.0);  // tighter than the reach bound on average
}

TEST(CellBetween, AdvancementEqualsSubdivisionOnRandomPaths) {
  Expected<Cell> cell = arm3_cell(fs::temp_directory_path() / "interfere_robot_between4");
  ASSERT_TRUE(cell) << cell.error().message();
  std::size_t only_advancement = 0, collides = 0, clear = 0;
  for (const auto& [seed, size] : {std::pair{401, 6.0}, std::pair{402, 12.0}, std::pair{403, 20.0}}) {
    JointPath path;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> step(-size, size);
    std::vector<double> q{0, 35, 70};
    for (int i = 0; i < 14; ++i) {
      path.q.push_back(q);
      path.lines.push_back(i + 2);
      for (double& v : q) v += step(rng);
    }
    expect_same_as_subdivision(*cell, path, 10, &only_advancement);
    const CellScene cs = cell_scene(*cell, path);
    const std::vector<SegmentResult> segs = check_between_points(*cell, cs, path);
    const std::vector<bool> dense = dense_meets(*cell, path, 255);
    for (std::size_t s = 0; s < segs.size(); ++s) {
      if (segs[s].state == SegmentState::clear) {
        EXPECT_FALSE(dense[s]) << "seed " << seed << " segment " << s << " proven clear, a sample meets";
        ++clear;
      }
      collides += segs[s].state == SegmentState::collides;
    }
  }
  EXPECT_GT(collides, 3u);
  EXPECT_GT(clear, 3u);
  RecordProperty("segments_collide", static_cast<int>(collides));
  RecordProperty("segments_clear", static_cast<int>(clear));
  RecordProperty("resolved_only_by_advancement", static_cast<int>(only_advancement));
}

TEST(CellBetween, AdvancementEqualsSubdivisionOnTheExample) {
  const fs::path ex = fs::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";
  Expected<Cell> cell = read_cell_json(ex / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  Expected<JointPath> full = read_joint_csv(ex / "path.csv", cell->robot);
  ASSERT_TRUE(full) << full.error().message();
  expect_same_as_subdivision(*cell, *full, 12);
}

TEST(CellBetween, GrazingBetweenTwoClearPoints) {
  // The arm turns about its vertical axis (yaw 0 -> 45 degrees) with the probe tip low, at radius
  // ~490 mm and height ~80 mm: it sweeps through the post at (450, 180) (top at z = 120) between
  // two clear points. A shoulder offset c lifts both ends until the segment just grazes the post
  // (c* by bisection on the dense check, 1,023 samples). At c* and around it (meeting inside /
  // clear by a sliver) both methods agree wherever the subdivision decides, the meeting side is
  // never called clear, and the dense check (4,095 samples) finds nothing inside a segment proven
  // clear. Two segments: constant height, and height changing along the segment.
  Expected<Cell> cell = arm3_cell(fs::temp_directory_path() / "interfere_robot_between5");
  ASSERT_TRUE(cell) << cell.error().message();
  const std::vector<std::pair<std::vector<double>, std::vector<double>>> segments = {
      {{0, -40, 103.4}, {45, -40, 103.4}}, {{0, -38, 103.4}, {45, -44, 108}}};
  int grazes = 0;
  std::size_t meeting_found = 0;
  std::string states;
  for (const auto& [qa, qb] : segments) {
    const auto segment = [&](double c) {
      JointPath p{{qa, qb}, {2, 3}};
      for (auto& v : p.q) v[1] += c;
      return p;
    };
    ASSERT_TRUE(points_clear(*cell, segment(0)));
    ASSERT_TRUE(dense_meets(*cell, segment(0), 255)[0]);
    double clear_c = 0;
    for (double c : {-2.0, -4.0, -8.0, -16.0}) {
      const JointPath p = segment(c);
      if (points_clear(*cell, p) && !dense_meets(*cell, p, 1023)[0]) {
        clear_c = c;
        break;
      }
    }
    ASSERT_NE(clear_c, 0.0);
    double lo = 0, hi = clear_c;  // lo: meets inside, hi: clear
    for (int it = 0; it < 40; ++it) {
      const double m = 0.5 * (lo + hi);
      const JointPath p = segment(m);
      ASSERT_TRUE(points_clear(*cell, p));
      (dense_meets(*cell, p, 1023)[0] ? lo : hi) = m;
    }
    ++grazes;
    for (const double c : {0.0, lo, lo + 1e-3 * (hi - lo), hi, hi - 1e-3 * (hi - lo), 0.5 * clear_c}) {
      const JointPath p = segment(c);
      SCOPED_TRACE("offset " + std::to_string(c));
      expect_same_as_subdivision(*cell, p, 12);
      const CellScene cs = cell_scene(*cell, p);
      const std::vector<SegmentResult> r = check_between_points(*cell, cs, p);
      states += std::string(segment_state_name(r[0].state)) + " (" + std::to_string(r[0].frames) + " middles) ";
      if (dense_meets(*cell, p, 1023)[0]) {
        EXPECT_NE(r[0].state, SegmentState::clear);
        meeting_found += r[0].state == SegmentState::collides;
      }
      if (r[0].state == SegmentState::clear) EXPECT_FALSE(dense_meets(*cell, p, 4095)[0]);
    }
  }
  RecordProperty("states", states);
  EXPECT_EQ(grazes, 2);
  EXPECT_GE(meeting_found, 2u);
}



TEST(CellIkBranch, FirstPointCollisionFree) {
  // The example's pose path: without a start the solver's first converging seed ("home") puts the
  // elbow through the plate at the first point. collision_free_start solves the first pose from
  // every seed, checks the distinct solutions in order and returns the first clear one: the tool
  // is at the pose, the joints within their limits, the frame clear (a separate engine run), and
  // the path solved from it starts there.
  const fs::path ex = fs::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";
  Expected<Cell> cell = read_cell_json(ex / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  Expected<probe::ProbePath> poses = probe::read_path_csv(ex / "paper_path.csv", nullptr);
  ASSERT_TRUE(poses) << poses.error().message();
  const IkTool tool = cell_ik_tool(*cell);
  auto first_clear = [&](const std::vector<double>& q) { return points_clear(*cell, JointPath{{q}, {0}}); };
  Expected<PoseIkPath> plain = pose_path_to_joints(cell->robot, cell->base, tool, *poses, "paper_path.csv");
  ASSERT_TRUE(plain) << plain.error().message();
  EXPECT_FALSE(first_clear(plain->path.q[0]));  // the problem
  Expected<StartChoice> c = collision_free_start(*cell, poses->poses[0]);
  ASSERT_TRUE(c) << c.error().message();
  EXPECT_TRUE(c->collision_free);
  EXPECT_GE(c->candidates, 2u);
  EXPECT_GE(c->colliding, 1u);
  EXPECT_TRUE(check_limits(cell->robot, c->q));
  const probe::ProbePose at = tool_pose(cell->robot, cell->base, tool, c->q);
  EXPECT_LT(norm(at.tip - poses->poses[0].tip), 1e-9);
  EXPECT_LT(norm(at.axis - poses->poses[0].axis), 1e-9);
  EXPECT_TRUE(first_clear(c->q));
  IkOptions o;
  o.start = c->q;
  Expected<PoseIkPath> chosen = pose_path_to_joints(cell->robot, cell->base, tool, *poses, "paper_path.csv", o);
  ASSERT_TRUE(chosen) << chosen.error().message();
  EXPECT_EQ(chosen->seed[0], "start");
  for (std::size_t m = 0; m < c->q.size(); ++m) EXPECT_NEAR(chosen->path.q[0][m], c->q[m], 1e-6);
  RecordProperty("seed", c->seed);
  RecordProperty("candidates", static_cast<int>(c->candidates));
  RecordProperty("colliding", static_cast<int>(c->colliding));
}

#endif
