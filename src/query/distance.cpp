// Minimum distance between two parts (issue #2, item 5): best-first branch and bound over node pairs
// ordered by box distance; leaf pairs whose boxes touch are first tested for intersection exactly.
#include "interfere/query/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"

namespace interfere {
namespace {

double box_distance_squared(const AabbF& x, const AabbF& y) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, static_cast<double>(x.lo[k]) - y.hi[k],
                                 static_cast<double>(y.lo[k]) - x.hi[k]});
    d2 += gap * gap;
  }
  return d2;
}

struct NodePair {
  double d2;
  std::uint32_t na, nb;
  bool operator>(const NodePair& o) const {
    return d2 != o.d2 ? d2 > o.d2 : (na != o.na ? na > o.na : nb > o.nb);
  }
};

}  // namespace

DistanceResult distance(const Model& a, const Model& b, const DistanceRequest& request) {
  DistanceResult best;
  best.distance = std::numeric_limits<double>::infinity();
  if (a.bvh.empty() || b.bvh.empty()) return best;
  double bound = request.upper_bound > 0 ? request.upper_bound : std::numeric_limits<double>::infinity();
  std::priority_queue<NodePair, std::vector<NodePair>, std::greater<>> queue;
  queue.push({box_distance_squared(a.bvh.nodes[0].box, b.bvh.nodes[0].box), 0, 0});
  while (!queue.empty()) {
    const NodePair np = queue.top();
    queue.pop();
    if (std::sqrt(np.d2) > std::min(bound, best.distance)) break;  // nothing closer remains
    const BvhNode& x = a.bvh.nodes[np.na];
    const BvhNode& y = b.bvh.nodes[np.nb];
    if (x.is_leaf() && y.is_leaf()) {
      for (std::uint32_t i = 0; i < x.count; ++i) {
        const std::uint32_t ta = a.bvh.prims[x.first + i];
        for (std::uint32_t j = 0; j < y.count; ++j) {
          const std::uint32_t tb = b.bvh.prims[y.first + j];
          const auto ca = a.mesh.corners(ta), cb = b.mesh.corners(tb);
          if (np.d2 == 0 && tri_tri_exact_intersects(ca, cb)) {
            const TriTriResult r = tri_tri_exact(ca, cb);
            best.intersecting = true;
            best.distance = 0;
            best.triangle_a = ta, best.triangle_b = tb;
            // A point of the intersection: the crossing segment's start, or the closest corner pair.
            const Vec3 w = r.kind == ContactKind::cross ? r.segment[0] : triangle_triangle_closest(ca, cb).p;
            best.point_a = best.point_b = w;
            return best;
          }
          const ClosestPoints cp = triangle_triangle_closest(ca, cb);
          if (cp.distance < best.distance) {
            best.distance = cp.distance;
            best.point_a = cp.p, best.point_b = cp.q;
            best.triangle_a = ta, best.triangle_b = tb;
          }
        }
      }
      continue;
    }
    // Descend the inner node with the larger box (or the only inner one).
    const bool split_a = !x.is_leaf() && (y.is_leaf() || x.box.surface_area() >= y.box.surface_area());
    for (int c = 0; c < 2; ++c) {
      const std::uint32_t na = split_a ? x.first + c : np.na;
      const std::uint32_t nb = split_a ? np.nb : y.first + c;
      const double d2 = box_distance_squared(a.bvh.nodes[na].box, b.bvh.nodes[nb].box);
      if (std::sqrt(d2) <= std::min(bound, best.distance)) queue.push({d2, na, nb});
    }
  }
  if (best.distance > bound) best.distance = std::numeric_limits<double>::infinity();
  return best;
}

// Nearest triangle by the BVH, nearer child first, boxes farther than the best pruned.
namespace {

double point_box_d2(const Vec3& p, const AabbF& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max({0.0, static_cast<double>(b.lo[k]) - p[k], p[k] - static_cast<double>(b.hi[k])});
    d2 += g * g;
  }
  return d2;
}

}  // namespace

// Depth-first, nearer child first, pruning nodes (and, in a leaf, triangles) whose box lies
// farther than the best distance found (Ericson 2005, §6.2 "closest point queries" on a BVH; the
// closest point on a triangle of np/distance.h, §5.1.5).
double nearest_triangle_d2(const TriMesh& mesh, const Bvh& bvh, const Vec3& p, std::uint32_t* tri, double stop_d2,
                           std::uint32_t seed, const std::uint32_t* owner) {
  double best = std::numeric_limits<double>::infinity();
  if (bvh.nodes.empty() || mesh.triangles.empty()) return best;
  if (seed != kNoTriangle) {
    best = squared_norm(closest_point_on_triangle(p, mesh.corners(seed)) - p);
    if (tri) *tri = seed;
    if (best <= stop_d2) return best;
  }
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
        if (point_box_d2(p, bvh.prim_boxes[i]) >= best) continue;  // cheaper than the closest point
        const std::uint32_t t = owner ? owner[bvh.prims[i]] : bvh.prims[i];
        const Vec3 q = closest_point_on_triangle(p, mesh.corners(t));
        const double d2 = squared_norm(q - p);
        if (d2 < best) {
          best = d2;
          if (tri) *tri = t;
          if (best <= stop_d2) return best;
        }
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

double surface_distance(const Model& m, const Vec3& p) {
  return std::sqrt(nearest_triangle_d2(m.mesh, m.bvh, p));
}

}  // namespace interfere
