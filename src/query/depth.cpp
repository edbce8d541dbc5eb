// Depth of crossing surfaces (include/interfere/query/depth.h): sampled lower bound and proven upper
// bound, first written for assembly-clash (cad/assembly_clash.h, InstancePairResult::depth).
#include <algorithm>
#include <cmath>
#include <array>

#include "interfere/query/depth.h"
#include "interfere/bvh/traverse.h"
#include "interfere/mesh/validate.h"
#include "interfere/np/distance.h"
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
  // The distance to y's surface, the previous query's nearest triangle tried first (samples come
  // in runs of neighbours; the nearest distance is the same, found sooner).
  std::uint32_t last = kNoTriangle;
  const auto distance_seeded = [&](const Vec3& p) { return std::sqrt(nearest_triangle_d2(y.mesh, y.bvh, p, &last, -1, last)); };
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
      if (point_in_solid(y, mid) == 1) depth = std::max(depth, distance_seeded(mid));
    }
  }
  for (std::uint32_t t = 0; t < nt; ++t) {
    const bool whole = !paired[t] && side[t] == 1;  // (undecided: not sampled)
    if (!paired[t] && !whole) continue;
    for (std::uint32_t v : m.triangles[t]) {
      if (state[v] == 0) state[v] = whole || point_in_solid(y, m.positions[v]) == 1 ? 1 : 2;
      if (state[v] == 1) {
        depth = std::max(depth, distance_seeded(m.positions[v]));
        state[v] = 3;  // (measured)
      }
    }
  }
  return depth;
}

// An upper bound of depth_into: the same reach over every point of x's surface that may lie
// inside y, not samples, by branch and bound on the distance f to y's surface. A piece (a triangle
// of x, or a part of one) is bounded by the smaller of two proven bounds:
//  - Lipschitz: f is 1-Lipschitz, so f <= its corners' largest f plus the longest edge / sqrt 3
//    (every point of a triangle lies within that of a corner: the circumradius of an acute
//    triangle, half the longest edge of an obtuse one);
//  - convexity: f <= the distance to any one triangle T of y, a convex function of the point
//    (distance to a convex set), whose largest value over the piece is at a corner; T ranges over
//    the triangles of y nearest to the piece's corners. Where one face of y is nearest to the whole
//    piece (a shaft inside a bore, a face sunk into a plate) this bound is the exact reach, so the
//    piece needs no splitting at all.
// Pieces that meet no triangle of y (exact tests, np/tri_tri.h) lie wholly inside or outside it:
// outside ones are dropped (exact ray parity of a corner; undecided counts as inside), and x's
// triangles that touch nothing of y count by their connected set, as in depth_into. The piece with
// the largest bound is split at its edge midpoints until that bound is within 10 % of `lower` (the
// sampled depth, a lower bound) or `max_splits` splits were made; the largest bound left is the
// result. Each corner's distance and nearest triangle are computed once (shared by the pieces
// around it; a parent's nearest triangle seeds a midpoint's search, the same exact result).
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
  struct Corner {
    Vec3 p;
    double d;         // distance to y's surface
    std::uint32_t t;  // a nearest triangle of y
  };
  const auto corner = [&](const Vec3& p, std::uint32_t seed) {
    Corner c{p, 0, seed};
    c.d = std::sqrt(nearest_triangle_d2(y.mesh, y.bvh, p, &c.t, -1, seed));
    return c;
  };
  struct Piece {
    double bound;
    std::array<Corner, 3> c;
    bool inside;  // known to meet nothing of y and to lie inside it (its parts too)
  };
  const auto lower_bound_first = [](const Piece& a, const Piece& b) { return a.bound < b.bound; };
  // The heap's storage is kept per thread between calls (a fresh block of megabytes per crossing
  // pair cost more in page faults than the bound itself); taken out while in use, so a nested call
  // would only start with an empty one. Nothing in here runs tasks.
  thread_local std::vector<Piece> spare;
  std::vector<Piece> heap;
  heap.swap(spare);
  heap.clear();
  struct GiveBack {
    std::vector<Piece>& heap;
    ~GiveBack() {
      heap.clear();
      if (heap.capacity() <= (std::size_t{1} << 16)) heap.swap(spare);  // (at most ~9 MB kept per thread)
    }
  } give_back{heap};
  // A piece of x that may lie inside y, with its bound; dropped when it lies outside.
  const auto add = [&](const std::array<Corner, 3>& c, bool inside) {
    const std::array<Vec3, 3> p{c[0].p, c[1].p, c[2].p};
    if (!inside && !meets_y(p)) {
      if (point_in_solid(y, p[0]) == 0) return;  // (1 inside, -1 undecided: kept)
      inside = true;
    }
    const double edge = std::max({norm(p[1] - p[0]), norm(p[2] - p[1]), norm(p[0] - p[2])});
    double bound = std::max({c[0].d, c[1].d, c[2].d}) + edge / std::sqrt(3.0);
    for (int k = 0; k < 3; ++k) {
      if (k > 0 && (c[k].t == c[0].t || (k == 2 && c[2].t == c[1].t))) continue;
      const std::array<Vec3, 3> t = y.mesh.corners(c[k].t);
      double far = 0;
      for (int i = 0; i < 3 && far < bound; ++i)
        far = std::max(far, c[i].t == c[k].t ? c[i].d : norm(closest_point_on_triangle(p[i], t) - p[i]));
      bound = std::min(bound, far);
    }
    heap.push_back({bound, c, inside});
    std::push_heap(heap.begin(), heap.end(), lower_bound_first);
  };
  std::vector<double> vd(m.num_vertices(), -1);  // corners of x's own triangles, once per vertex
  std::vector<std::uint32_t> vt(m.num_vertices(), kNoTriangle);
  std::uint32_t last = kNoTriangle;  // the previous corner's nearest triangle seeds the next search
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (!paired[t] && side[t] == 0) continue;  // (undecided: kept)
    std::array<Corner, 3> c;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m.triangles[t][k];
      if (vd[v] < 0) {
        const Corner q = corner(m.positions[v], last);
        last = q.t;
        vd[v] = q.d, vt[v] = q.t;
      }
      c[k] = {m.positions[v], vd[v], vt[v]};
    }
    add(c, !paired[t]);
  }
  for (std::size_t split = 0; split < max_splits && !heap.empty() && heap.front().bound > 1.1 * lower; ++split) {
    std::pop_heap(heap.begin(), heap.end(), lower_bound_first);
    const Piece q = heap.back();
    heap.pop_back();
    const auto& c = q.c;
    const Corner a = corner((c[0].p + c[1].p) * 0.5, c[0].t), b = corner((c[1].p + c[2].p) * 0.5, c[1].t),
                 d = corner((c[2].p + c[0].p) * 0.5, c[2].t);
    add({c[0], a, d}, q.inside);
    add({a, c[1], b}, q.inside);
    add({d, b, c[2]}, q.inside);
    add({a, b, d}, q.inside);
  }
  // (the rounded midpoints stand for the exact ones: a relative 1e-15, far below any bound here)
  return heap.empty() ? lower : std::max(lower, heap.front().bound);
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
