// The paper's three-level hierarchy at one path point (Li, Zhou & Zheng 2008, Fig. 1, §3.2-3.4),
// evaluated beside the exact test so that the paper's errors show per point (issue #28,
// deliverable 3; docs/probe.md "The paper's three levels, as written").
#include <algorithm>

#include "interfere/probe/paper_tests.h"

namespace interfere::probe {

PaperPointCheck paper_point_check(const Workpiece& w, const ProbeShape& shape, const ProbePose& pose, int edge) {
  PaperPointCheck out;
  const Cylinder c = cylinder_from_tip(pose.tip, pose.axis, shape.length, shape.radius);
  const Aabb probe_box = paper_cylinder_box(c);
  // Level 1 (§3.2): patch boxes.
  for (std::size_t p = 0; p < w.patches.size(); ++p) {
    const Aabb& pb = w.patches.boxes[p];
    if (!(paper_box_test(probe_box, pb) || paper_box_test(pb, probe_box))) continue;
    ++out.patches_passed;
    // Level 2 (§3.3) and level 3 (§3.4) for the patch's triangles.
    for (std::uint32_t t : w.patches.tris[p]) {
      const auto tri = w.mesh.corners(t);
      if (!paper_triangle_box_test(tri, probe_box)) continue;
      ++out.triangles_passed;
      if (!three_projection_test(c, tri, edge)) continue;
      ++out.projections_passed;
      out.hits.push_back(t);
    }
  }
  std::sort(out.hits.begin(), out.hits.end());
  out.collides = !out.hits.empty();
  // The exact test on every triangle near the probe (a box that contains the cylinder first).
  const Aabb near = cylinder_box(c);
  for (std::uint32_t t = 0; t < w.mesh.num_triangles() && !out.exact; ++t) {
    if (!w.mesh.triangle_box(t).overlaps(near)) continue;
    out.exact = cylinder_triangle_intersect(c, w.mesh.corners(t));
  }
  return out;
}

}  // namespace interfere::probe
