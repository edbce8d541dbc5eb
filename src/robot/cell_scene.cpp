// The inspection cell as a scene (issue #28, deliverable 3; robot/cell.h): bodies, tests with the
// adjacent pairs suppressed, and one frame per path point (plus optional between-point frames).
#include <tbb/parallel_for.h>

#include <stdexcept>

#include "interfere/probe/cylinder.h"
#include "interfere/probe/export.h"
#include "interfere/query/model.h"
#include "interfere/robot/cell.h"

namespace interfere::robot {
namespace {

scene::Selector by_id(const std::string& id) {
  return {scene::Selector::Kind::id, id};
}
scene::Selector by_tag(const std::string& tag) {
  return {scene::Selector::Kind::tag, tag};
}

scene::Body body(const std::string& id, const std::string& name,
                 std::shared_ptr<const TriMesh> mesh, const Transform& pose, const std::string& tag,
                 scene::SourceKind kind, const std::string& file, const std::string& detail) {
  scene::Body b;
  b.id = id;
  b.name = name;
  b.path = name;
  b.mesh = std::move(mesh);
  b.pose = pose;
  b.tags = {tag};
  b.source = {kind, file, detail};
  return b;
}

std::string number(double v) {
  return short_number(v);
}

}  // namespace

ToolCylinders tool_cylinders(const CellTool& tool, const Transform& f) {
  ToolCylinders c;
  c.tip = f.apply(tool.tip);
  c.back = f.apply(tool.tip - tool.axis * tool.probe_length);
  c.holder_back = f.apply(tool.tip - tool.axis * (tool.probe_length + tool.holder_length));
  c.probe_radius = tool.probe_radius;
  c.holder_radius = tool.holder_radius;
  return c;
}

CellScene cell_scene(const Cell& cell, const JointPath& path, std::size_t between) {
  CellScene out;
  scene::Scene& s = out.scene;
  s.units = "mm";
  const Chain& chain = cell.robot;
  const std::vector<Transform> f0 = link_frames(
      chain, path.size() ? path.q[0] : std::vector<double>(chain.dof(), 0.0), cell.base);
  // links
  out.link_body.assign(chain.links.size(), -1);
  for (std::size_t i = 0; i < chain.links.size(); ++i) {
    const ChainLink& l = chain.links[i];
    if (!l.mesh) continue;
    out.link_body[i] = static_cast<std::int64_t>(s.bodies.size());
    s.bodies.push_back(
        body(scene::make_body_id("link:" + l.name), l.name, l.mesh, f0[i], "link",
             l.mesh_files.empty() ? scene::SourceKind::primitive : scene::SourceKind::mesh_file,
             l.mesh_files.empty() ? cell.robot_file : l.mesh_files.front(),
             (cell.robot_format == "dh" ? "DH link " : "URDF link ") + l.name));
  }
  // tool (in the tool link's frame)
  const CellTool& t = cell.tool;
  const Vec3 back = t.tip - t.axis * t.probe_length;
  out.probe_body = static_cast<std::int64_t>(s.bodies.size());
  s.bodies.push_back(
      body("probe", "probe",
           std::make_shared<TriMesh>(probe::cylinder_mesh({t.tip, back, t.probe_radius}, t.sides)),
           f0[cell.tool_link], "tool", scene::SourceKind::primitive, cell.file,
           "cylinder r " + number(t.probe_radius) + " l " + number(t.probe_length)));
  if (t.holder_radius > 0 && t.holder_length > 0) {
    out.holder_body = static_cast<std::int64_t>(s.bodies.size());
    s.bodies.push_back(
        body("holder", "holder",
             std::make_shared<TriMesh>(probe::cylinder_mesh(
                 {back, back - t.axis * t.holder_length, t.holder_radius}, t.sides)),
             f0[cell.tool_link], "tool", scene::SourceKind::primitive, cell.file,
             "cylinder r " + number(t.holder_radius) + " l " + number(t.holder_length)));
  }
  // workpiece and fixtures: static, so their world models (BVH) are built once here and shared by
  // every engine run on this scene (the check at the points and each halving level of
  // check_between_points), instead of once per run (issue #28: a 10^6-triangle workpiece).
  auto with_model = [](scene::Body b) {
    b.world_model = std::make_shared<const Model>(
        make_model(b.pose.is_identity() ? *b.mesh : transformed(*b.mesh, b.pose), {}, false));
    return b;
  };
  s.bodies.push_back(with_model(body("workpiece", "workpiece", cell.workpiece.mesh,
                                     cell.workpiece.pose, "workpiece", scene::SourceKind::mesh_file,
                                     cell.workpiece.file, "")));
  for (const CellObject& o : cell.fixtures) {
    s.bodies.push_back(with_model(body(scene::make_body_id("fixture:" + o.id), o.id, o.mesh, o.pose,
                                       "fixture", scene::SourceKind::mesh_file, o.file, "")));
  }
  // tests
  const scene::ClashMode mode =
      cell.clearance > 0 ? scene::ClashMode::clearance : scene::ClashMode::hard;
  auto test = [&](const std::string& name, scene::Selection a, scene::Selection b) {
    scene::ClashTest ct;
    ct.name = name;
    ct.a = std::move(a);
    ct.b = std::move(b);
    ct.mode = mode;
    ct.clearance = cell.clearance;
    return ct;
  };
  out.tests.push_back(test("tool", {by_tag("tool")}, {by_tag("workpiece"), by_tag("fixture")}));
  bool any_link = false;
  for (std::int64_t b : out.link_body) any_link = any_link || b >= 0;
  if (any_link)
    out.tests.push_back(test("arm", {by_tag("link")}, {by_tag("workpiece"), by_tag("fixture")}));
  scene::ClashTest self = test("self", {by_tag("link"), by_tag("tool")}, {});
  auto suppress = [&](std::int64_t a, std::int64_t b, const std::string& why) {
    self.suppressions.push_back({{by_id(s.bodies[a].id)}, {by_id(s.bodies[b].id)}, why});
  };
  std::int64_t previous = -1, tool_neighbour = -1;
  for (std::size_t i = 0; i < chain.links.size(); ++i) {
    const std::int64_t b = out.link_body[i];
    if (b >= 0) {
      if (previous >= 0)
        suppress(previous, b, "adjacent links (joint '" + chain.joints[i - 1].name + "')");
      previous = b;
    }
    if (i == cell.tool_link) tool_neighbour = previous;
  }
  if (tool_neighbour >= 0) {
    suppress(tool_neighbour, out.probe_body, "probe mounted on this link");
    if (out.holder_body >= 0)
      suppress(tool_neighbour, out.holder_body, "holder mounted on this link");
  }
  if (out.holder_body >= 0) suppress(out.probe_body, out.holder_body, "probe held by the holder");
  out.tests.push_back(std::move(self));
  // frames
  std::vector<std::uint32_t> moving;
  std::vector<std::size_t> moving_link;
  for (std::size_t i = 0; i < chain.links.size(); ++i) {
    if (out.link_body[i] >= 0)
      moving.push_back(static_cast<std::uint32_t>(out.link_body[i])), moving_link.push_back(i);
  }
  moving.push_back(static_cast<std::uint32_t>(out.probe_body)),
      moving_link.push_back(cell.tool_link);
  if (out.holder_body >= 0)
    moving.push_back(static_cast<std::uint32_t>(out.holder_body)),
        moving_link.push_back(cell.tool_link);
  // One frame per point and per sample between points, built in parallel (forward kinematics per
  // frame: 10^5 points, issue #28's full cell).
  const std::size_t per = between + 1;
  const std::size_t count = path.size() ? (path.size() - 1) * per + 1 : 0;
  s.frames.resize(count);
  out.frame_point.resize(count);
  out.frame_t.resize(count);
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
    const std::size_t point = k / per, step = k % per;
    const double u = step == 0 ? 0.0 : static_cast<double>(step) / static_cast<double>(between + 1);
    std::vector<double> q = path.q[point];
    if (step != 0) {
      for (std::size_t j = 0; j < q.size(); ++j)
        q[j] = path.q[point][j] + u * (path.q[point + 1][j] - path.q[point][j]);
    }
    const std::vector<Transform> f = link_frames(chain, q, cell.base);
    scene::Frame& fr = s.frames[k];
    fr.label = u == 0 ? "point " + std::to_string(point)
                      : "point " + std::to_string(point) + " + " + number(u);
    fr.time = static_cast<double>(point) + u;
    fr.poses.reserve(moving.size());
    for (std::size_t m = 0; m < moving.size(); ++m) fr.poses.push_back({moving[m], f[moving_link[m]]});
    out.frame_point[k] = point;
    out.frame_t[k] = u;
  });
  return out;
}

}  // namespace interfere::robot
