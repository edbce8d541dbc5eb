// Depth of crossing surfaces (include/interfere/query/depth.h): sampled lower bound and proven upper
// bound, first written for assembly-clash (cad/assembly_clash.h, InstancePairResult::depth).
#include <algorithm>
#include <cmath>
#include <array>
#include <queue>

#include "interfere/query/depth.h"
#include "interfere/bvh/traverse.h"
#include "interfere/mesh/validate.h"
#include "interfere/np/tri_tri.h"
#include "interfere/query/distance.h"

namespace interfere::detail {
namespace {

// Where the segment pq meets the surface of m: parameters in (0, 1), sorted (floating point: a
// sampling aid, each interval between them is classified exactly afterwards).
std::vector<double> surface_crossings(const Model& m, const Vec3& p, const Vec3& q) {
  std::vector<double> ts;
  const Vec3 d = q - p;
  for_each_on_segment(m.bvh, p, d, 0.0, [&](std::uint32_t t) {
    const auto c = m.mesh.corners(t);
    const Vec3 nrm = cross(c[1] - c[0], c[2] - c[0]);
    const double sp = dot(nrm, p - c[0]), sq = dot(nrm, q - c[0]);
    if ((sp > 0) == (sq > 0) || sp == sq) return true;
    const double s = sp / (sp - sq);
    const Vec3 x = p + d * s;
    const double e0 = dot(cross(c[1] - c[0], x - c[0]), nrm), e1 = dot(cross(c[2] - c[1], x - c[1]), nrm),
                 e2 = dot(cross(c[0] - c[2], x - c[2]), nrm);
    if (e0 >= 0 && e1 >= 0 && e2 >= 0 && s > 0 && s < 1) ts.push_back(s);
    return true;
  });
  std::sort(ts.begin(), ts.end());
  return ts;
}

}  // namespace

std::vector<signed char> untouched_sides(const Model& x, const Model& y, const std::vector<char>& paired) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  std::vector<char> free_of(nt);  // the triangles that touch nothing of y
  for (std::uint32_t t = 0; t < nt; ++t) free_of[t] = !paired[t];
  const std::vector<std::uint32_t> set = connected_sets(m, free_of);
  std::vector<signed char> side(nt, 0);
  for (std::uint32_t t = 0; t < nt; ++t)  // a set's root comes first in it (connected_sets)
    if (!paired[t])
      side[t] = set[t] == t ? static_cast<signed char>(point_in_solid(y, m.positions[m.triangles[t][0]])) : side[set[t]];
  return side;
}

// How deep the surface of x reaches into the solid y, sampled: the largest distance to y's surface
// of x's points inside y (exact ray parity) among: the middles of the stretches of the crossing
// triangles' edges between their crossings of y's surface, the vertices of the triangles that cross
// or touch y (`paired`), and the vertices of the connected sets of its other triangles that lie
// inside y (such a set lies wholly inside or outside; one vertex, exactly off y's surface,
// decides).
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired,
                  const std::vector<signed char>& side) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  std::vector<char> state(m.num_vertices(), 0);  // 0 unknown, 1 inside, 2 not
  double depth = 0;
  // Along the edges of the crossing triangles: the middle of each stretch between two crossings of
  // y's surface that lies inside y (a long edge may pass through y with both ends outside).
  std::vector<std::array<std::uint32_t, 2>> crossing_edges;
  for (std::uint32_t t = 0; t < nt; ++t)
    if (paired[t])
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = m.triangles[t][k], v = m.triangles[t][(k + 1) % 3];
        crossing_edges.push_back({std::min(u, v), std::max(u, v)});
      }
  std::sort(crossing_edges.begin(), crossing_edges.end());
  crossing_edges.erase(std::unique(crossing_edges.begin(), crossing_edges.end()),
                       crossing_edges.end());
  for (const auto& [u, v] : crossing_edges) {
    const Vec3 p = m.positions[u], q = m.positions[v];
    std::vector<double> ts = surface_crossings(y, p, q);
    ts.insert(ts.begin(), 0.0);
    ts.push_back(1.0);
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
      if (!(ts[i + 1] > ts[i])) continue;
      const Vec3 mid = p + (q - p) * (0.5 * (ts[i] + ts[i + 1]));
      if (point_in_solid(y, mid) == 1) depth = std::max(depth, surface_distance(y, mid));
    }
  }
  for (std::uint32_t t = 0; t < nt; ++t) {
    const bool whole = !paired[t] && side[t] == 1;  // (undecided: not sampled)
    if (!paired[t] && !whole) continue;
    for (std::uint32_t v : m.triangles[t]) {
      if (state[v] == 0) state[v] = whole || point_in_solid(y, m.positions[v]) == 1 ? 1 : 2;
      if (state[v] == 1) {
        depth = std::max(depth, surface_distance(y, m.positions[v]));
        state[v] = 3;  // (measured)
      }
    }
  }
  return depth;
}

// An upper bound of depth_into: the same reach over every point of x's surface that may lie
// inside y, not samples, by branch and bound on the 1-Lipschitz distance to y's surface: a piece
// (a triangle of x, or a part of one) is bounded by its corners' largest distance plus its longest
// edge / sqrt 3 (every point of a triangle lies within that of a corner: the circumradius of an
// acute triangle, half the longest edge of an obtuse one). Pieces that meet no triangle of y (exact
// tests, np/tri_tri.h) lie wholly inside or outside it: outside ones are dropped (exact ray parity
// of a corner; undecided counts as inside), and x's triangles that touch nothing of y count by
// their connected set, as in depth_into. The piece with the largest bound is split at its edge
// midpoints until that bound is within 10 % of `lower` (the sampled depth, a lower bound) or
// `max_splits` splits were made; the largest bound left is the result.
double depth_bound(const Model& x, const Model& y, const std::vector<char>& paired,
                   const std::vector<signed char>& side, double lower, std::size_t max_splits) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  const auto meets_y = [&](const std::array<Vec3, 3>& c) {
    Aabb box;
    for (const Vec3& v : c) box.expand(v);
    bool meets = false;
    for_each_in_box(y.bvh, to_float_outward(box), [&](std::uint32_t t) {
      meets = meets || tri_tri_exact_intersects(c, y.mesh.corners(t));
    });
    return meets;
  };
  struct Piece {
    double bound;
    std::array<Vec3, 3> c;
    bool inside;  // known to meet nothing of y and to lie inside it (its parts too)
    bool operator<(const Piece& o) const { return bound < o.bound; }
  };
  std::priority_queue<Piece> pieces;
  // A piece of x that may lie inside y, with its bound; dropped when it lies outside.
  const auto add = [&](const std::array<Vec3, 3>& c, bool inside) {
    if (!inside && !meets_y(c)) {
      if (point_in_solid(y, c[0]) == 0) return;  // (1 inside, -1 undecided: kept)
      inside = true;
    }
    const double edge = std::max({norm(c[1] - c[0]), norm(c[2] - c[1]), norm(c[0] - c[2])});
    const double corner = std::max({surface_distance(y, c[0]), surface_distance(y, c[1]), surface_distance(y, c[2])});
    pieces.push({corner + edge / std::sqrt(3.0), c, inside});
  };
  for (std::uint32_t t = 0; t < nt; ++t)
    if (paired[t] || side[t] != 0) add(m.corners(t), !paired[t]);  // (undecided: kept)
  for (std::size_t split = 0; split < max_splits && !pieces.empty() && pieces.top().bound > 1.1 * lower; ++split) {
    const Piece p = pieces.top();
    pieces.pop();
    const auto& c = p.c;
    const Vec3 a = (c[0] + c[1]) * 0.5, b = (c[1] + c[2]) * 0.5, d = (c[2] + c[0]) * 0.5;
    add({c[0], a, d}, p.inside);
    add({a, c[1], b}, p.inside);
    add({d, b, c[2]}, p.inside);
    add({a, b, d}, p.inside);
  }
  // (the rounded midpoints stand for the exact ones: a relative 1e-15, far below any bound here)
  return pieces.empty() ? lower : std::max(lower, pieces.top().bound);
}

}  // namespace interfere::detail

namespace interfere {

PenetrationDepth penetration_depth(const Model& a, const Model& b, const ClashResult& r, std::size_t max_splits) {
  PenetrationDepth out;
  if (r.pairs.empty()) return out;  // (crossing, or touching surfaces of overlapping solids)
  std::vector<char> pa(a.mesh.num_triangles(), 0), pb(b.mesh.num_triangles(), 0);
  for (const TrianglePair& q : r.pairs) pa[q.a] = 1, pb[q.b] = 1;
  const std::vector<signed char> sa = detail::untouched_sides(a, b, pa), sb = detail::untouched_sides(b, a, pb);
  out.depth = std::max(detail::depth_into(a, b, pa, sa), detail::depth_into(b, a, pb, sb));
  out.depth_bound = out.depth;
  if (max_splits > 0) {
    out.bounded = true;
    out.depth_bound = std::max({out.depth, detail::depth_bound(a, b, pa, sa, out.depth, max_splits),
                                detail::depth_bound(b, a, pb, sb, out.depth, max_splits)});
  }
  return out;
}

}  // namespace interfere
