// A probe sweep as a viewer document (view/probe_document.h).
#include "interfere/view/probe_document.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "interfere/probe/export.h"
#include "interfere/probe/kinematics.h"
#include "interfere/query/verdict.h"

namespace interfere::view {
namespace {

// The probe's local frame: tip at the origin, pointing along +z, reference direction +x.
Transform probe_frame(const probe::ProbePose& pose) {
  const Vec3 z = pose.axis / norm(pose.axis);
  Vec3 x = probe::perpendicular_reference(pose.ref, z);
  if (x == Vec3{}) {  // no reference: any unit vector perpendicular to the axis
    const Vec3 helper = std::abs(z.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    x = cross(helper, z);
    x = x / norm(x);
  }
  const Vec3 y = cross(z, x);
  Transform t;
  t.r = {{{x.x, y.x, z.x}, {x.y, y.y, z.y}, {x.z, y.z, z.z}}};
  t.t = pose.tip;
  return t;
}

void append(TriMesh& to, const TriMesh& from) {
  const auto base = static_cast<std::uint32_t>(to.positions.size());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  for (const auto& t : from.triangles) to.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

Vec3 lo_of(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 hi_of(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

}  // namespace

Expected<Document> probe_document(const TriMesh& workpiece, const probe::ProbeShape& shape, const probe::ProbePath& path,
                                  const probe::SweepResult& result) {
  const std::size_t n = path.poses.size();
  if (n == 0 || result.points.size() != n)
    return Error{.reason = "probe view: the path has no resolved poses, or the sweep result does not match it"};
  Document doc;
  doc.title = "interfere sweep: " + std::to_string(n) + " path points";
  doc.verdict = verdict_name(result.verdict);

  ViewMesh wm;
  wm.mesh = workpiece;
  wm.source_triangles = workpiece.num_triangles();
  wm.clash_flags.assign(workpiece.num_triangles(), 0);
  for (const probe::PointResult& p : result.points)
    for (std::uint32_t t : p.hits) wm.clash_flags[t] = 1;
  for (const probe::SegmentResult& s : result.segments)
    for (std::uint32_t t : s.triangles) wm.clash_flags[t] = 1;
  doc.meshes.push_back(std::move(wm));
  ViewBody w;
  w.id = "workpiece", w.name = "workpiece", w.path = "/workpiece", w.role = "workpiece", w.mesh = 0;
  doc.bodies.push_back(w);

  // The probe (and holder) in its local frame.
  probe::ProbePose local{.tip = {0, 0, 0}, .axis = {0, 0, 1}, .ref = {1, 0, 0}};
  TriMesh probe_mesh;
  for (const probe::Cylinder& c : probe::probe_cylinders(shape, local)) append(probe_mesh, probe::cylinder_mesh(c, 32));
  if (shape.has_holder_box()) append(probe_mesh, probe::box_mesh(probe::probe_holder_box(shape, local)));
  ViewMesh pm;
  pm.source_triangles = probe_mesh.num_triangles();
  pm.mesh = std::move(probe_mesh);
  doc.meshes.push_back(std::move(pm));
  ViewBody pb;
  pb.id = "probe", pb.name = shape.has_holder() || shape.has_holder_box() ? "probe + holder" : "probe";
  pb.path = "/probe", pb.role = "probe", pb.mesh = 1, pb.color = {0.25f, 0.55f, 0.85f};
  pb.frame_poses.reserve(n);
  for (const probe::ProbePose& pose : path.poses) pb.frame_poses.push_back(probe_frame(pose));
  pb.pose = pb.frame_poses.front();
  doc.bodies.push_back(std::move(pb));

  // Frames: one per path point, marked by its verdict (and a colliding segment leaving it).
  std::vector<Verdict> v(n, Verdict::clear);
  for (std::size_t i = 0; i < n; ++i) v[i] = result.points[i].verdict;
  for (const probe::SegmentResult& s : result.segments)  // a collision only between two clear points
    if (s.between_samples) v[s.from] = worst(v[s.from], s.verdict);
  doc.frames.labels.resize(n);
  doc.frames.verdicts.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    doc.frames.labels[i] = "point " + std::to_string(i) +
                           (i < path.lines.size() ? " (line " + std::to_string(path.lines[i]) + ")" : std::string());
    doc.frames.verdicts[i] = verdict_name(v[i]);
  }

  // A row per run of consecutive path points with the same non-clear verdict: the workpiece
  // triangles they hit as its region (world = workpiece coordinates).
  const auto region_of = [&](const std::vector<std::uint32_t>& tris) -> std::int64_t {
    if (tris.empty()) return -1;
    ViewMesh rm;
    rm.mesh = submesh(workpiece, tris);
    rm.source_triangles = rm.mesh.num_triangles();
    doc.meshes.push_back(std::move(rm));
    return static_cast<std::int64_t>(doc.meshes.size() - 1);
  };
  const auto box_of = [&](ViewClash& c, const std::vector<std::uint32_t>& tris, const Vec3& extra) {
    c.box_min = c.box_max = extra;
    for (std::uint32_t t : tris)
      for (std::uint32_t vtx : workpiece.triangles[t])
        c.box_min = lo_of(c.box_min, workpiece.positions[vtx]), c.box_max = hi_of(c.box_max, workpiece.positions[vtx]);
  };
  std::size_t i = 0;
  while (i < n) {
    const probe::PointResult& first = result.points[i];
    if (first.verdict == Verdict::clear) {
      ++i;
      continue;
    }
    ViewClash c;
    c.verdict = verdict_name(first.verdict);
    c.kind = first.inside ? "inside" : first.holder ? "holder" : "probe";
    c.body_a = 1, c.body_b = 0;
    std::vector<std::uint32_t> tris;
    double smallest = first.clearance;
    std::size_t j = i;
    for (; j < n && result.points[j].verdict == first.verdict; ++j) {
      c.frames.push_back(static_cast<std::uint32_t>(j));
      tris.insert(tris.end(), result.points[j].hits.begin(), result.points[j].hits.end());
      smallest = std::min(smallest, result.points[j].clearance);
    }
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
    c.point = path.poses[i].tip;
    if (first.verdict == Verdict::clearance) {
      c.distance = smallest;
      c.has_witness = true;
      c.witness_a = first.point_probe, c.witness_b = first.point_workpiece;
    }
    box_of(c, tris, c.point);
    c.region_mesh = region_of(tris);
    c.id = "S" + std::to_string(i);
    c.note = (j - i == 1 ? "path point " + std::to_string(i) : "path points " + std::to_string(i) + "-" + std::to_string(j - 1)) +
             (i < path.lines.size() ? " (line " + std::to_string(path.lines[i]) + ")" : std::string()) + ", " +
             std::to_string(tris.size()) + " workpiece triangles hit";
    doc.clashes.push_back(std::move(c));
    i = j;
  }
  // Segments that collide (or stay undecided) between two path points that are both clear.
  for (const probe::SegmentResult& s : result.segments) {
    if (!s.between_samples) continue;
    ViewClash c;
    c.verdict = verdict_name(s.verdict);
    c.kind = "between path points";
    c.body_a = 1, c.body_b = 0;
    const std::size_t to = std::min<std::size_t>(s.from + 1, n - 1);
    c.point = (path.poses[s.from].tip + path.poses[to].tip) * 0.5;
    box_of(c, s.triangles, c.point);
    c.region_mesh = region_of(s.triangles);
    c.frames = {s.from, static_cast<std::uint32_t>(to)};
    c.id = "B" + std::to_string(s.from);
    std::string where;
    for (const auto& iv : s.intervals) where += " [" + std::to_string(iv[0]) + ", " + std::to_string(iv[1]) + "]";
    c.note = "between path points " + std::to_string(s.from) + " and " + std::to_string(to) +
             (where.empty() ? std::string() : ", colliding for t in" + where);
    doc.clashes.push_back(std::move(c));
  }
  return doc;
}

}  // namespace interfere::view
