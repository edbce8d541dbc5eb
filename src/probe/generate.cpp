// Generated curved panels and raster probe paths (issue #5, item 6), standing in for the paper's
// three workpieces and paths (Li, Zhou & Zheng 2008, §4). Deterministic.
#include <array>
#include <cmath>

#include "interfere/probe/generate.h"

namespace interfere::probe {

const char* panel_name(PanelKind k) {
  switch (k) {
    case PanelKind::sheet: return "doubly curved sheet";
    case PanelKind::shell: return "cylindrical shell section";
    case PanelKind::saddle: return "saddle";
  }
  return "?";
}

void panel_point(PanelKind kind, double u, double v, Vec3& p, Vec3& n) {
  switch (kind) {
    case PanelKind::sheet: {
      const double x = 300 * (u - 0.5), y = 200 * (v - 0.5);
      p = {x, y, -(x * x / 1200 + y * y / 800)};
      n = {x / 600, y / 400, 1};
      break;
    }
    case PanelKind::shell: {
      const double phi = (u - 0.5) * (100.0 * M_PI / 180.0), y = 300 * (v - 0.5), r = 250;
      p = {r * std::sin(phi), y, r * std::cos(phi) - r};
      n = {std::sin(phi), 0, std::cos(phi)};
      break;
    }
    case PanelKind::saddle: {
      const double x = 300 * (u - 0.5), y = 300 * (v - 0.5);
      p = {x, y, (x * x - y * y) / 1000};
      n = {-x / 500, y / 500, 1};
      break;
    }
  }
  n = n / norm(n);
}

TriMesh make_panel(PanelKind kind, int nu, int nv) {
  TriMesh m;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      Vec3 p, n;
      panel_point(kind, double(i) / nu, double(j) / nv, p, n);
      m.positions.push_back(p);
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      // (u, v) -> surface is orientation-preserving for all three (normal = dS/du x dS/dv side).
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

ProbePath make_panel_path(PanelKind kind, const PanelPathOptions& o) {
  const Robot robot = pivot_machine(o.pivot_to_tip);
  ProbePath path;
  path.joint_space = true;
  for (const DhJoint& j : robot.joints) path.columns.push_back(j.name);
  std::int64_t index = 0;
  double prev_a = 0;
  for (int l = 0; l < o.lines; ++l) {
    const double v = 0.08 + 0.84 * (o.lines > 1 ? double(l) / (o.lines - 1) : 0.5);
    for (int k = 0; k < o.points_per_line; ++k) {
      const int kk = (l % 2 == 0) ? k : o.points_per_line - 1 - k;
      const double u = 0.06 + 0.88 * (o.points_per_line > 1 ? double(kk) / (o.points_per_line - 1) : 0.5);
      Vec3 p, n;
      panel_point(kind, u, v, p, n);
      const bool collide = o.collide_every > 0 && index % o.collide_every == o.collide_every / 2;
      const double s = collide ? -o.collide_depth : o.standoff;
      ProbePose pose{p + n * s, -n};
      std::array<double, 5> q = pivot_inverse(pose, o.pivot_to_tip);
      while (q[3] - prev_a > 180) q[3] -= 360;  // keep A4 continuous along the path
      while (q[3] - prev_a < -180) q[3] += 360;
      prev_a = q[3];
      path.joints.push_back({q[0], q[1], q[2], q[3], q[4]});
      path.lines.push_back(index + 2);  // as if written with a header row
      ++index;
    }
  }
  resolve_poses(path, robot);
  return path;
}

std::vector<PanelCase> paper_cases() {
  return {
      {"sheet", PanelKind::sheet, 24, 12, {.lines = 8, .points_per_line = 109}},
      {"shell", PanelKind::shell, 24, 24, {.lines = 10, .points_per_line = 143}},
      {"saddle", PanelKind::saddle, 58, 24, {.lines = 14, .points_per_line = 169}},
  };
}

}  // namespace interfere::probe
