// Workpiece patches (Li, Zhou & Zheng 2008, §3.2): the surface is cut into patches whose bounding
// boxes are about 30-35 times the probe volume, so that a probe box meets few patch boxes. Here:
// recursive median split (centroids, longest box axis) until the box volume (extents floored at
// min_extent) is below the target and the normals spread less than max_normal_angle (curvature).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "interfere/probe/sweep.h"

namespace interfere::probe {
namespace {

double floored_volume(const Aabb& b, double floor) {
  const Vec3 e = b.extent();
  return std::max(e.x, floor) * std::max(e.y, floor) * std::max(e.z, floor);
}

}  // namespace

Patches make_patches(const TriMesh& mesh, const PatchOptions& options) {
  Patches out;
  const std::size_t n = mesh.num_triangles();
  out.patch_of.assign(n, kNone);
  if (n == 0) return out;
  std::vector<Vec3> centroid(n), normal(n);
  std::vector<Aabb> tbox(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto c = mesh.corners(t);
    tbox[t] = mesh.triangle_box(t);
    centroid[t] = (c[0] + c[1] + c[2]) / 3.0;
    const Vec3 nn = cross(c[1] - c[0], c[2] - c[0]);
    const double l = norm(nn);
    normal[t] = l > 0 ? nn / l : Vec3{};
  }
  const double cos_max = std::cos(options.max_normal_angle * M_PI / 180.0);
  std::vector<std::uint32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  struct Range {
    std::size_t lo, hi;
  };
  std::vector<Range> stack{{0, n}};
  std::vector<Range> leaves;
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    Aabb box, cbox;
    Vec3 mean{};
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      box.expand(tbox[ids[i]]);
      cbox.expand(centroid[ids[i]]);
      mean += normal[ids[i]];
    }
    bool flat = true;
    const double ml = norm(mean);
    for (std::size_t i = r.lo; i < r.hi && flat; ++i) {
      flat = ml > 0 && dot(normal[ids[i]], mean / ml) >= cos_max;
    }
    const bool small = floored_volume(box, options.min_extent) <= options.target_volume;
    if (r.hi - r.lo <= 1 || (small && flat)) {
      leaves.push_back(r);
      continue;
    }
    const Vec3 e = cbox.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    const std::size_t mid = (r.lo + r.hi) / 2;
    std::nth_element(ids.begin() + r.lo, ids.begin() + mid, ids.begin() + r.hi, [&](std::uint32_t a, std::uint32_t b) {
      const double ca = centroid[a][axis], cb = centroid[b][axis];
      return ca != cb ? ca < cb : a < b;
    });
    stack.push_back({mid, r.hi});
    stack.push_back({r.lo, mid});
  }
  // Deterministic numbering: by smallest triangle index.
  std::vector<std::vector<std::uint32_t>> tris;
  for (const Range& r : leaves) {
    std::vector<std::uint32_t> t(ids.begin() + r.lo, ids.begin() + r.hi);
    std::sort(t.begin(), t.end());
    tris.push_back(std::move(t));
  }
  std::sort(tris.begin(), tris.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  out.tris = std::move(tris);
  for (std::size_t p = 0; p < out.tris.size(); ++p) {
    Aabb b;
    for (std::uint32_t t : out.tris[p]) {
      b.expand(tbox[t]);
      out.patch_of[t] = static_cast<std::uint32_t>(p);
    }
    out.boxes.push_back(b);
  }
  return out;
}

}  // namespace interfere::probe
