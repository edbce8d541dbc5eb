// Generated workpieces and probe paths for issue #5 (items 6 and 7), shared by the tests, the
// benchmarks (bench/bench_probe.cpp) and the docs script (bench/probe_tables.py via
// `interfere_bench_probe --write-cases`): three curved panels like the paper's (Li, Zhou & Zheng
// 2008, §4: 576, 1,152 and 2,784 triangles) and raster paths at a stand-off with some colliding
// points (872, 1,430 and 2,366 points).
#pragma once
#include <string>
#include <vector>

#include "interfere/mesh/tri_mesh.h"
#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"

namespace interfere::probe {

enum class PanelKind {
  sheet,   ///< doubly curved sheet 300 x 200 mm, z = -(x^2/1200 + y^2/800)
  shell,   ///< cylindrical shell section: radius 250 mm, +-50 degrees, 300 mm long (axis y)
  saddle,  ///< saddle 300 x 300 mm, z = (x^2 - y^2)/1000
};
const char* panel_name(PanelKind k);

/// Open panel of nu x nv quads, 2 nu nv triangles, normals (counter-clockwise) facing the probe side
/// (+z for the sheet and saddle, outward for the shell).
TriMesh make_panel(PanelKind kind, int nu, int nv);

/// The analytic surface point and unit normal at (u, v) in [0, 1]^2.
void panel_point(PanelKind kind, double u, double v, Vec3& point, Vec3& normal);

struct PanelPathOptions {
  int lines = 8;               ///< raster lines (along v)
  int points_per_line = 109;   ///< points per line (along u), zigzag
  double standoff = 10.0;      ///< tip distance from the surface along its normal
  int collide_every = 97;      ///< every collide_every-th point (from index collide_every/2) ...
  double collide_depth = 1.0;  ///< ... has its tip this far below the surface (colliding)
  double pivot_to_tip = 150;   ///< the pivot machine's pivot-to-tip distance
};

/// Joint path (x, y, z, a, b) of the pivot machine (pivot_machine(options.pivot_to_tip)) following
/// the panel at the stand-off, probe along the inward normal; poses resolved.
ProbePath make_panel_path(PanelKind kind, const PanelPathOptions& options);

/// The paper's three cases: 0 = sheet 576 tri / 872 pts, 1 = shell 1152 / 1430, 2 = saddle 2784 / 2366.
struct PanelCase {
  std::string name;
  PanelKind kind;
  int nu, nv;
  PanelPathOptions path;
};
std::vector<PanelCase> paper_cases();

}  // namespace interfere::probe
