// Sweep with a box-shaped holder (issue #5, item 2): a pose only the box hits (an inscribed holder
// cylinder would miss, and the same box turned by 90 degrees misses), identical decisions for every
// hierarchy against a filter-free brute force, the clearance agrees with a dense-sampling oracle (sampled_clearance.h), the
// continuous check finds a box contact that happens only between samples (pose paths twisting about
// the axis and tilting it, a joint path turning the a axis), forward kinematics fills the reference direction
// (hand-computed), and missing reference directions are rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "interfere/probe/export.h"
#include "interfere/probe/generate.h"
#include "interfere/probe/sweep.h"
#include "sampled_clearance.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

/// A vertical wall x = x0 (|y| <= 100, z in [-100, 300]).
TriMesh wall(double x0) {
  TriMesh m;
  m.positions = {{x0, -100, -100}, {x0, 100, -100}, {x0, 100, 300}, {x0, -100, 300}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// A small triangle around (15 cos 45, 15 sin 45, z) (vertical, 0.02 wide).
TriMesh post(double z0, double z1) {
  const double c = 15 * std::sqrt(0.5);
  TriMesh m;
  m.positions = {{c, c, z0}, {c, c, z1}, {c + 0.01, c - 0.01, 0.5 * (z0 + z1)}};
  m.triangles = {{0, 1, 2}};
  return m;
}

ProbePath pose_path(std::vector<ProbePose> poses) {
  ProbePath p;
  p.joint_space = false;
  p.columns = {"px", "py", "pz", "ax", "ay", "az", "rx", "ry", "rz"};
  p.poses = std::move(poses);
  for (std::size_t i = 0; i < p.poses.size(); ++i) p.lines.push_back(static_cast<std::int64_t>(i) + 2);
  return p;
}

void expect_vec(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

/// Brute force without any box filter: every triangle against every body.
std::vector<std::uint32_t> brute_hits(const TriMesh& mesh, const ProbeShape& probe, const ProbePose& pose) {
  std::vector<std::uint32_t> hits;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    bool hit = probe.has_holder_box() && box_triangle_intersect(probe_holder_box(probe, pose), mesh.corners(t));
    for (const Cylinder& c : probe_cylinders(probe, pose)) hit = hit || cylinder_triangle_intersect(c, mesh.corners(t));
    if (hit) hits.push_back(t);
  }
  return hits;
}

}  // namespace

TEST(ProbeSweepBox, OnlyTheBoxHits) {
  // Probe down from tip z = 100, length 40: the box (40 wide along ref, 20 deep, 30 long) spans
  // z in [140, 170] and reaches x = 20 with ref = x. The wall at x = 18 is hit by the box only: the
  // probe (radius 5) and a holder cylinder inscribed in the box (radius 10) miss it, and so does
  // the box turned by 90 degrees (ref = y).
  const ProbeShape probe{
      .radius = 5, .length = 40, .holder_box_width = 40, .holder_box_depth = 20, .holder_box_length = 30};
  const ProbePath path = pose_path({{{0, 0, 100}, {0, 0, -1}, {1, 0, 0}}, {{0, 0, 100}, {0, 0, -1}, {0, 1, 0}}});
  const Workpiece w = prepare_workpiece(wall(18), probe);
  const SweepResult r = sweep(w, path, nullptr, {.probe = probe, .continuous = false});
  EXPECT_TRUE(r.points[0].collides);
  EXPECT_TRUE(r.points[0].holder);
  EXPECT_EQ(r.points[0].hits, std::vector<std::uint32_t>{1});  // the box lies above the wall's diagonal
  EXPECT_FALSE(r.points[1].collides);
  EXPECT_NEAR(r.points[1].clearance, 8.0, 1e-9);  // box face at x = 10
  EXPECT_NEAR(r.points[1].point_probe.x, 10.0, 1e-9);
  EXPECT_NEAR(r.points[1].point_workpiece.x, 18.0, 1e-9);
  const ProbeShape cylinder{.radius = 5, .length = 40, .holder_radius = 10, .holder_length = 30};
  EXPECT_FALSE(sweep(w, path, nullptr, {.probe = cylinder, .continuous = false}).points[0].collides);
  // The OBJ/VTK geometry carries the box mesh (8 corners, 12 triangles) at the colliding pose.
  const CollisionGeometry g = collision_geometry(w, path, nullptr, probe, r);
  EXPECT_EQ(g.probe_poses, 1u);
  EXPECT_EQ(g.mesh.num_triangles(), 1u + 4u * 24u + 12u);
}

TEST(ProbeSweepBox, HierarchiesAgreeWithBruteForce) {
  // Random tilted poses over a saddle, tips from 2 below to 30 above the surface, random reference
  // directions; a large box holder makes many points collide through the box only.
  const ProbeShape probe{
      .radius = 5, .length = 15, .holder_box_width = 140, .holder_box_depth = 40, .holder_box_length = 20};
  const TriMesh mesh = make_panel(PanelKind::saddle, 20, 14);
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ProbePose> poses;
  for (int i = 0; i < 120; ++i) {
    Vec3 p, n;
    panel_point(PanelKind::saddle, 0.1 + 0.8 * u(g), 0.1 + 0.8 * u(g), p, n);
    Vec3 axis = -n + Vec3{0.8 * u(g) - 0.4, 0.8 * u(g) - 0.4, 0};
    axis = axis / norm(axis);
    const double phi = 2 * M_PI * u(g);
    poses.push_back(
        {p + n * (-2 + 32 * u(g)), axis, perpendicular_reference({std::cos(phi), std::sin(phi), 0.3}, axis)});
  }
  const ProbePath path = pose_path(poses);
  std::vector<SweepResult> results;
  for (Hierarchy h :
       {Hierarchy::brute_force, Hierarchy::bvh, Hierarchy::patches, Hierarchy::grid, Hierarchy::distance_field}) {
    const Workpiece w = prepare_workpiece(mesh, probe, {.hierarchy = h, .field_spacing = 10});
    results.push_back(sweep(w, path, nullptr, {.probe = probe, .clearance = false, .max_depth = 4}));
  }
  for (std::size_t k = 1; k < results.size(); ++k) {  // the continuous check's grown boxes too
    ASSERT_EQ(results[k].segments.size(), results[0].segments.size()) << k;
    for (std::size_t s = 0; s < results[0].segments.size(); ++s) {
      EXPECT_EQ(results[k].segments[s].intervals, results[0].segments[s].intervals) << k << " " << s;
      EXPECT_EQ(results[k].segments[s].triangles, results[0].segments[s].triangles) << k << " " << s;
    }
  }
  std::size_t box_only = 0;
  const ProbeShape bare{.radius = probe.radius, .length = probe.length};
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::vector<std::uint32_t> hits = brute_hits(mesh, probe, path.poses[i]);
    for (std::size_t k = 0; k < results.size(); ++k) {
      EXPECT_EQ(results[k].points[i].hits, hits) << k << " " << i;
      EXPECT_EQ(results[k].points[i].collides, !hits.empty()) << k << " " << i;
    }
    box_only += !hits.empty() && brute_hits(mesh, bare, path.poses[i]).empty();
  }
  EXPECT_GT(box_only, 10u);
  EXPECT_GT(results[0].colliding_points, box_only);  // and some through the probe
  EXPECT_LT(results[0].colliding_points, path.size());
}

TEST(ProbeSweepBox, ClearanceMatchesSampledOracle) {
  const ProbeShape probe{
      .radius = 4, .length = 10, .holder_box_width = 100, .holder_box_depth = 30, .holder_box_length = 20};
  const TriMesh mesh = make_panel(PanelKind::saddle, 16, 16);
  std::vector<ProbePose> poses;
  for (int i = 0; i < 12; ++i) {
    Vec3 p, n;
    panel_point(PanelKind::saddle, 0.1 + 0.07 * i, 0.3 + 0.03 * i, p, n);
    const Vec3 axis = (-n + Vec3{0.3, 0, 0}) / norm(-n + Vec3{0.3, 0, 0});
    poses.push_back({p + n * 30, axis, perpendicular_reference({1, 0.2 * i, 0}, axis)});
  }
  const ProbePath path = pose_path(poses);
  const Workpiece w = prepare_workpiece(mesh, probe);
  const SweepResult r = sweep(w, path, nullptr, {.probe = probe, .continuous = false});
  int box_nearest = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    ASSERT_FALSE(r.points[i].collides) << i;
    // Independent oracle (issue #23, item 14): dense samples of the probe's and the box's surfaces
    // against the nearby triangles by reference::point_triangle_distance; true <= sampled <= true + h.
    const double reach = r.points[i].clearance + 2;
    const oracle::Sampled sc = oracle::sample_cylinder(probe_cylinders(probe, path.poses[i])[0], 0.25);
    const oracle::Sampled sb = oracle::sample_box(probe_holder_box(probe, path.poses[i]), 0.5);
    const double cyl = oracle::sampled_distance(sc, mesh, reach), box = oracle::sampled_distance(sb, mesh, reach);
    const double sampled = std::min(cyl, box), h = std::max(sc.h, sb.h);
    EXPECT_LE(r.points[i].clearance, sampled + 1e-9) << i;
    EXPECT_GE(r.points[i].clearance, sampled - h - 1e-9) << i;
    box_nearest += box < cyl - sc.h;  // the box is provably the nearer body
  }
  EXPECT_GT(box_nearest, 0);
}

TEST(ProbeSweepBox, TwistBetweenSamplesPosePath) {
  // The probe stays put (tip z = 100, pointing down) while its reference turns from x to y: the box
  // (40 wide, 10 deep, z in [140, 170]) sweeps about the axis. A post at radius 15, azimuth 45
  // degrees, is clear at both ends and hit for twists psi with 15 |sin(45 - psi)| <= 5, i.e.
  // t = psi / 90 in [0.5 -+ asin(1/3) / (pi/2)] (the post's 0.01 width moves that by < 1e-3).
  const ProbeShape probe{
      .radius = 5, .length = 40, .holder_box_width = 40, .holder_box_depth = 10, .holder_box_length = 30};
  const ProbePath path = pose_path({{{0, 0, 100}, {0, 0, -1}, {1, 0, 0}}, {{0, 0, 100}, {0, 0, -1}, {0, 1, 0}}});
  const Workpiece w = prepare_workpiece(post(150, 160), probe);
  const SweepResult r = sweep(w, path, nullptr, {.probe = probe, .max_depth = 14});
  EXPECT_FALSE(r.points[0].collides);
  EXPECT_FALSE(r.points[1].collides);
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_TRUE(r.segments[0].between_samples);
  ASSERT_EQ(r.segments[0].intervals.size(), 1u);
  const auto iv = r.segments[0].intervals[0];
  const double half = std::asin(1.0 / 3) / (M_PI / 2);
  EXPECT_LE(iv[0], 0.5 - half + 1e-9);  // conservative: the post's edge at azimuth 45 is hit there
  EXPECT_GE(iv[1], 0.5 + half - 1e-9);
  EXPECT_GE(iv[0], 0.5 - half - 2e-3);
  EXPECT_LE(iv[1], 0.5 + half + 2e-3);
  // The interpolated reference direction at the middle is at 45 degrees.
  expect_vec(pose_at(path, nullptr, 0, 0.5).ref, {std::sqrt(0.5), std::sqrt(0.5), 0}, 1e-12);
}

TEST(ProbeSweepBox, TiltBetweenSamplesPosePath) {
  // The probe tilts about the x axis through its tip (at the origin) by phi = 0 .. 120 degrees:
  // axis (0, sin phi, -cos phi), ref x. The box (60 wide, 10 deep) behind the probe (40 long) spans
  // 40..70 from the tip; a small post at distance 65 from the tip, 10 degrees off the start
  // direction, is inside it for |sin(10 deg - phi)| <= 5/65, only between the samples. The motion
  // bound must use the box's reach (76 from the tip), not the probe's (40): with the latter the
  // grown box at the midpoint misses the post and the collision is lost.
  const double a = 10 * M_PI / 180, rho = 65;
  TriMesh post;
  post.positions = {{-1, -rho * std::sin(a), rho * std::cos(a)},
                    {1, -rho * std::sin(a), rho * std::cos(a)},
                    {0, -rho * std::sin(a) - 0.01, rho * std::cos(a)}};
  post.triangles = {{0, 1, 2}};
  const double end = 120 * M_PI / 180;
  const ProbePath path =
      pose_path({{{0, 0, 0}, {0, 0, -1}, {1, 0, 0}}, {{0, 0, 0}, {0, std::sin(end), -std::cos(end)}, {1, 0, 0}}});
  const ProbeShape probe{
      .radius = 5, .length = 40, .holder_box_width = 60, .holder_box_depth = 10, .holder_box_length = 30};
  const Workpiece w = prepare_workpiece(post, probe);
  const SweepResult r = sweep(w, path, nullptr, {.probe = probe, .max_depth = 14});
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_TRUE(r.segments[0].between_samples);
  const auto iv = r.segments[0].intervals[0];
  const double half = std::asin(5 / rho);
  const double t_enter = (a - half) / end, t_exit = (a + half) / end;
  EXPECT_LE(iv[0], t_enter + 1e-9);
  EXPECT_GE(iv[1], t_exit - 1e-9);
  EXPECT_GE(iv[0], t_enter - 1e-3);
  EXPECT_LE(iv[1], t_exit + 1e-3);
}

TEST(ProbeSweepBox, TurningJointBetweenSamples) {
  // The paper machine turns a from 0 to 90 degrees with b = 0 (probe down, tip at z = 50): the
  // tool's x axis, the box's width direction, turns with it (ref = (cos a, sin a, 0)); the box spans
  // z in [90, 120]. The same post as above, between z = 100 and 110: hit for a in 45 -+ 19.47.
  const Robot robot = pivot_machine(150);
  ProbePath path;
  path.columns = {"x", "y", "z", "a", "b"};
  path.joints = {{0, 0, 200, 0, 0}, {0, 0, 200, 90, 0}};
  path.lines = {2, 3};
  resolve_poses(path, robot);
  const ProbeShape probe{
      .radius = 5, .length = 40, .holder_box_width = 40, .holder_box_depth = 10, .holder_box_length = 30};
  const Workpiece w = prepare_workpiece(post(100, 110), probe);
  const SweepResult r = sweep(w, path, &robot, {.probe = probe, .max_depth = 14});
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_TRUE(r.segments[0].between_samples);
  const auto iv = r.segments[0].intervals[0];
  const double half = std::asin(1.0 / 3) / (M_PI / 2);
  EXPECT_LE(iv[0], 0.5 - half + 1e-9);  // conservative: the post's edge at azimuth 45 is hit there
  EXPECT_GE(iv[1], 0.5 + half - 1e-9);
  EXPECT_GE(iv[0], 0.5 - half - 2e-3);
  EXPECT_LE(iv[1], 0.5 + half + 2e-3);
  // Without the continuous check the path looks clear.
  EXPECT_FALSE(sweep(w, path, &robot, {.probe = probe, .continuous = false}).any_collision());
}

TEST(ProbeSweepBox, ForwardKinematicsReferenceHandComputed) {
  // Paper machine, frame 5: x5 = (cos b cos a, cos b sin a, -sin b), y5 = (sin a, -cos a, 0),
  // z5 = (-sin b cos a, -sin b sin a, -cos b) (the probe axis).
  const Robot r = pivot_machine(150);
  const ProbePose p = forward_kinematics(r, {1, 2, 3, 90, 30});
  expect_vec(p.axis, {0, -0.5, -std::sqrt(0.75)}, 1e-15);
  expect_vec(p.ref, {0, std::sqrt(0.75), -0.5}, 1e-15);
  const ProbePose q = forward_kinematics(r, {0, 0, 0, 0, 0});
  expect_vec(q.ref, {1, 0, 0}, 0);
  // tool.ref = y of the last frame.
  Robot ry = r;
  ry.tool_ref = {0, 1, 0};
  expect_vec(forward_kinematics(ry, {0, 0, 0, 90, 30}).ref, {1, 0, 0}, 1e-15);
  // A reference not perpendicular to the tool axis: its perpendicular part.
  ry.tool_ref = {1, 0, 5};
  expect_vec(forward_kinematics(ry, {0, 0, 0, 0, 0}).ref, {1, 0, 0}, 1e-15);
  // The holder box at q (ref = x, axis = -z; back centre 40 above the tip at z = -150).
  const ProbeShape probe{
      .radius = 5, .length = 40, .holder_box_width = 40, .holder_box_depth = 20, .holder_box_length = 30};
  const Aabb a = box_aabb(probe_holder_box(probe, q));
  expect_vec(a.lo, {-20, -10, -110}, 1e-9);
  expect_vec(a.hi, {20, 10, -80}, 1e-9);
  // The bundled file and its JSON round trip keep the reference direction.
  auto again = parse_robot_json(robot_to_json(ry), "mem");
  ASSERT_TRUE(again) << again.error().message();
  expect_vec(again->tool_ref, ry.tool_ref, 0);
}

TEST(ProbeSweepBox, RobotToolReference) {
  auto robot = [](const char* tool) {
    return parse_robot_json(std::string(R"({"joints": [{"type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}],
 "tool": )") + tool + "}",
                            "robot.json");
  };
  auto r = robot(R"({"tip": [0,0,0], "axis": [0,0,1], "ref": [0,2,0]})");
  ASSERT_TRUE(r) << r.error().message();
  expect_vec(forward_kinematics(*r, {90}).ref, {-1, 0, 0}, 1e-15);
  r = robot(R"({"tip": [0,0,0], "axis": [1,0,0]})");  // default x is parallel: y
  ASSERT_TRUE(r);
  expect_vec(forward_kinematics(*r, {0}).ref, {0, 1, 0}, 0);
  r = robot(R"({"tip": [0,0,0],
 "axis": [0,0,1], "ref": [0,0,-3]})");
  ASSERT_FALSE(r);
  const std::string m = r.error().message();
  EXPECT_NE(m.find("robot.json:3"), std::string::npos) << m;
  EXPECT_NE(m.find("tool.ref"), std::string::npos) << m;
  EXPECT_NE(m.find("parallel"), std::string::npos) << m;
}

TEST(ProbeSweepBox, PosePathReferenceColumns) {
  auto p = parse_path_csv("px,py,pz,ax,ay,az,rx,ry,rz\n0,0,1,0,0,-2,3,0,4\n", "p.csv", nullptr);
  ASSERT_TRUE(p) << p.error().message();
  EXPECT_FALSE(p->joint_space);
  expect_vec(p->poses[0].ref, {1, 0, 0}, 0);  // the part perpendicular to the axis, normalised
  EXPECT_TRUE(check_reference_frames(*p, "p.csv"));
  auto again = parse_path_csv(path_to_csv(*p), "again.csv", nullptr);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->poses[0].ref, p->poses[0].ref);
  auto err = [](const char* text) {
    auto q = parse_path_csv(text, "p.csv", nullptr);
    return q ? std::string() : q.error().message();
  };
  std::string m = err("px,py,pz,ax,ay,az,rx,ry,rz\n0,0,1,0,0,-1,1,0,0\n0,0,1,0,0,-1,0,0,2\n");
  EXPECT_NE(m.find("p.csv:3"), std::string::npos) << m;
  EXPECT_NE(m.find("field 'rx,ry,rz'"), std::string::npos) << m;
  EXPECT_NE(m.find("parallel"), std::string::npos) << m;
  m = err("px,py,pz,ax,ay,az,rx,ry,rz\n0,0,1,0,0,-1,0,0,0\n");
  EXPECT_NE(m.find("zero reference"), std::string::npos) << m;
  // Without the columns: no reference; a box holder is refused with file, line and field.
  auto bare = parse_path_csv("# poses\npx,py,pz,ax,ay,az\n0,0,1,0,0,-1\n", "bare.csv", nullptr);
  ASSERT_TRUE(bare);
  EXPECT_FALSE(bare->poses[0].has_ref());
  const Status s = check_reference_frames(*bare, "bare.csv");
  ASSERT_FALSE(s);
  m = s.error().message();
  EXPECT_NE(m.find("bare.csv:3"), std::string::npos) << m;
  EXPECT_NE(m.find("field 'rx,ry,rz'"), std::string::npos) << m;
  const ProbeShape probe{.holder_box_width = 1, .holder_box_depth = 1, .holder_box_length = 1};
  const Workpiece w = prepare_workpiece(wall(18), probe);
  EXPECT_THROW(sweep(w, *bare, nullptr, {.probe = probe}), std::invalid_argument);
}
