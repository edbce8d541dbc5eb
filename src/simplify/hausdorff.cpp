// Sampled Hausdorff distance between two meshes (issue #6, item 5) with the engine's BVH
// (bvh/bvh.h) and the closest point on a triangle of np/distance.h (Ericson 2005, §5.1.5):
// every sample runs a depth-first nearest-triangle search, nearer child first, pruning nodes whose
// box lies farther than the best distance found. Self-intersections are counted with the engine's
// exact clash query (query/clash.h) of a mesh against itself.
#include "interfere/simplify/hausdorff.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/np/distance.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere {
namespace {

double point_box_d2(const Vec3& p, const AabbF& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max({0.0, static_cast<double>(b.lo[k]) - p[k], p[k] - static_cast<double>(b.hi[k])});
    d2 += g * g;
  }
  return d2;
}

double nearest_d2(const TriMesh& mesh, const Bvh& bvh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  std::vector<std::uint32_t> spill;
  while (top > 0 || !spill.empty()) {
    const std::uint32_t ni = top > 0 ? stack[--top] : spill.back();
    if (top == 0 && !spill.empty() && ni == spill.back()) spill.pop_back();
    const BvhNode& n = bvh.nodes[ni];
    if (point_box_d2(p, n.box) >= best) continue;
    if (n.is_leaf()) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const std::uint32_t t = bvh.prims[i];
        const Vec3 q = closest_point_on_triangle(p, mesh.corners(t));
        best = std::min(best, squared_norm(q - p));
      }
      continue;
    }
    const std::uint32_t c0 = n.first, c1 = n.first + 1;
    const double d0 = point_box_d2(p, bvh.nodes[c0].box), d1 = point_box_d2(p, bvh.nodes[c1].box);
    const std::uint32_t near = d0 <= d1 ? c0 : c1, far = d0 <= d1 ? c1 : c0;
    for (std::uint32_t c : {far, near}) {  // near is popped first
      if (top < 128) stack[top++] = c;
      else spill.push_back(c);
    }
  }
  return best;
}

}  // namespace

double one_sided_distance(const TriMesh& from, const TriMesh& to, std::size_t* samples) {
  const std::size_t nv = from.num_vertices(), nt = from.num_triangles();
  const std::size_t n = nv + 4 * nt;  // vertices, then per triangle 3 edge midpoints + centroid
  if (samples) *samples = n;
  if (n == 0) return 0;
  if (to.num_triangles() == 0) return std::numeric_limits<double>::infinity();
  const Bvh bvh = build_bvh(to);
  const double d2 = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 1024), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double m) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          Vec3 p;
          if (i < nv) {
            p = from.positions[i];
          } else {
            const std::size_t t = (i - nv) / 4, k = (i - nv) % 4;
            const auto c = from.corners(t);
            p = k == 3 ? (c[0] + c[1] + c[2]) / 3.0 : (c[k] + c[(k + 1) % 3]) * 0.5;
          }
          m = std::max(m, nearest_d2(to, bvh, p));
        }
        return m;
      },
      [](double x, double y) { return std::max(x, y); });
  return std::sqrt(d2);
}

HausdorffResult hausdorff(const TriMesh& a, const TriMesh& b) {
  HausdorffResult r;
  std::size_t sa = 0, sb = 0;
  r.a_to_b = one_sided_distance(a, b, &sa);
  r.b_to_a = one_sided_distance(b, a, &sb);
  r.samples = sa + sb;
  return r;
}

std::size_t count_self_intersections(const TriMesh& mesh) {
  if (mesh.num_triangles() == 0) return 0;
  const Model m = make_model(mesh, {}, false);
  ClashRequest req;
  req.regions = false;
  req.containment = false;
  const ClashResult r = clash(m, m, req);
  std::size_t count = 0;
  for (const TrianglePair& p : r.pairs) {
    if (p.a >= p.b) continue;
    const auto ca = mesh.corners(p.a), cb = mesh.corners(p.b);
    bool share = false;
    for (const Vec3& x : ca)
      for (const Vec3& y : cb) share = share || x == y;
    if (!share) ++count;
  }
  return count;
}

}  // namespace interfere
