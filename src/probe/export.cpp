// OBJ / VTK output of the colliding probe poses and hit triangles (issue #5, item 5).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "interfere/core/atomic_file.h"
#include "interfere/probe/export.h"

namespace interfere::probe {
namespace {

std::string num(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void append(CollisionGeometry& g, const TriMesh& m, int kind, long point) {
  const auto base = static_cast<std::uint32_t>(g.mesh.positions.size());
  g.mesh.positions.insert(g.mesh.positions.end(), m.positions.begin(), m.positions.end());
  for (const Tri& t : m.triangles) {
    g.mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    g.kind.push_back(kind);
    g.point.push_back(point);
  }
}

}  // namespace

TriMesh cylinder_mesh(const Cylinder& c, int sides) {
  TriMesh m;
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const Vec3 u = len > 0 ? d / len : Vec3{0, 0, 1};
  Vec3 e1 = cross(u, std::fabs(u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
  e1 = e1 / norm(e1);
  const Vec3 e2 = cross(u, e1);
  for (int end = 0; end < 2; ++end) {
    const Vec3 ctr = end == 0 ? c.c0 : c.c1;
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * k / sides;
      m.positions.push_back(ctr + e1 * (c.radius * std::cos(a)) + e2 * (c.radius * std::sin(a)));
    }
  }
  m.positions.push_back(c.c0);
  m.positions.push_back(c.c1);
  const auto n = static_cast<std::uint32_t>(sides);
  const std::uint32_t k0 = 2 * n, k1 = 2 * n + 1;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t a = k, b = (k + 1) % n;
    // sides outward: (e1, e2, u) is right-handed, so a -> b -> n + b turns about +radial
    m.triangles.push_back({a, b, n + b});
    m.triangles.push_back({a, n + b, n + a});
    m.triangles.push_back({k0, b, a});
    m.triangles.push_back({k1, n + a, n + b});
  }
  return m;
}

TriMesh box_mesh(const OrientedBox& b) {
  TriMesh m;
  m.positions.assign(b.corners.begin(), b.corners.end());
  for (const auto& f : b.faces) m.triangles.push_back({f[0], f[1], f[2]});
  return m;
}

CollisionGeometry collision_geometry(const Workpiece& w, const ProbePath& path, const Robot* robot,
                                     const ProbeShape& probe, const SweepResult& result, int sides) {
  CollisionGeometry g;
  std::vector<std::uint32_t> hits;
  for (const PointResult& p : result.points) hits.insert(hits.end(), p.hits.begin(), p.hits.end());
  for (const SegmentResult& s : result.segments) hits.insert(hits.end(), s.triangles.begin(), s.triangles.end());
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
  g.hit_triangles = hits.size();
  if (!hits.empty()) append(g, submesh(w.mesh, hits), 0, -1);
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    if (!result.points[i].collides) continue;
    for (const Cylinder& c : probe_cylinders(probe, path.poses[i])) append(g, cylinder_mesh(c, sides), 1, static_cast<long>(i));
    if (probe.has_holder_box()) append(g, box_mesh(probe_holder_box(probe, path.poses[i])), 1, static_cast<long>(i));
    ++g.probe_poses;
  }
  for (const SegmentResult& s : result.segments) {
    if (!s.between_samples) continue;
    for (const auto& iv : s.intervals) {
      const ProbePose pose = pose_at(path, robot, s.from, 0.5 * (iv[0] + iv[1]));
      for (const Cylinder& c : probe_cylinders(probe, pose)) append(g, cylinder_mesh(c, sides), 2, s.from);
      if (probe.has_holder_box()) append(g, box_mesh(probe_holder_box(probe, pose)), 2, s.from);
      ++g.probe_poses;
    }
  }
  return g;
}

Status write_collision_geometry(const std::filesystem::path& file, const CollisionGeometry& g) {
  std::string ext = file.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  std::string out;
  const TriMesh& m = g.mesh;
  if (ext == ".obj") {
    out += "# interfere sweep: hit triangles (group hits) and probe poses (probe_<point>, segment_<from>)\n";
    for (const Vec3& p : m.positions) out += "v " + num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
    std::string group;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const std::string name = g.kind[t] == 0 ? "hits"
                               : (g.kind[t] == 1 ? "probe_" : "segment_") + std::to_string(g.point[t]);
      if (name != group) out += "g " + name + "\n", group = name;
      out += "f " + std::to_string(m.triangles[t][0] + 1) + " " + std::to_string(m.triangles[t][1] + 1) + " " +
             std::to_string(m.triangles[t][2] + 1) + "\n";
    }
  } else if (ext == ".vtk") {
    out += "# vtk DataFile Version 3.0\ninterfere sweep: kind 0 = hit triangle, 1 = probe at a colliding point, 2 = "
           "probe inside a colliding segment\nASCII\nDATASET POLYDATA\n";
    out += "POINTS " + std::to_string(m.positions.size()) + " double\n";
    for (const Vec3& p : m.positions) out += num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
    out += "POLYGONS " + std::to_string(m.triangles.size()) + " " + std::to_string(4 * m.triangles.size()) + "\n";
    for (const Tri& t : m.triangles) {
      out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
    }
    out += "CELL_DATA " + std::to_string(m.triangles.size()) + "\nSCALARS kind int 1\nLOOKUP_TABLE default\n";
    for (int k : g.kind) out += std::to_string(k) + "\n";
    out += "SCALARS point int 1\nLOOKUP_TABLE default\n";
    for (long p : g.point) out += std::to_string(p) + "\n";
  } else {
    return Error{.file = file.string(), .reason = "unsupported extension '" + ext + "' (.obj or .vtk)"};
  }
  return write_file_atomic(file, out);
}

}  // namespace interfere::probe
