// Depth of crossing surfaces (include/interfere/query/depth.h): sampled lower bound and proven upper
// bound, first written for assembly-clash (cad/assembly_clash.h, InstancePairResult::depth).
#include <algorithm>
#include <cmath>
#include <array>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

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

// The box of y's BVH root (float, rounded outwards: it holds every triangle of y): a point outside
// it lies outside the solid y.
bool in_root_box(const Bvh& bvh, const Vec3& p) {
  const auto& b = bvh.nodes[0].box;
  return p.x >= b.lo[0] && p.x <= b.hi[0] && p.y >= b.lo[1] && p.y <= b.hi[1] && p.z >= b.lo[2] && p.z <= b.hi[2];
}

}  // namespace

// The triangles of x that touch nothing of y (paired[t] == 0) lie wholly inside or wholly outside
// the solid y, and so does each connected set of them (sharing a vertex): one point decides a set.
// Sets are found by union-find over x's vertices (the smallest index is a set's root), through the
// untouched triangles with a vertex in y's box only: a triangle wholly outside the box is outside,
// and so is every set holding a vertex outside the box (no ray cast for either). One point_in_solid
// (of the root) per remaining set.
std::vector<signed char> untouched_sides(const Model& x, const Model& y, const std::vector<char>& paired) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  const auto nv = static_cast<std::uint32_t>(m.num_vertices());
  std::vector<signed char> side(nt, 0);
  if (y.bvh.empty() || nt == 0) return side;
  std::vector<char> in(nv);
  for (std::uint32_t v = 0; v < nv; ++v) in[v] = in_root_box(y.bvh, m.positions[v]);
  std::vector<std::uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  const auto unite = [&](std::uint32_t u, std::uint32_t v) {
    u = find(u), v = find(v);
    parent[std::max(u, v)] = std::min(u, v);
  };
  const auto counts = [&](std::uint32_t t) {  // untouched, with a vertex in y's box
    const auto& c = m.triangles[t];
    return !paired[t] && (in[c[0]] || in[c[1]] || in[c[2]]);
  };
  std::vector<std::uint32_t> out_of_box;  // vertices of such triangles outside y's box
  for (std::uint32_t t = 0; t < nt; ++t)
    if (counts(t)) {
      const auto& c = m.triangles[t];
      unite(c[0], c[1]), unite(c[0], c[2]);
      for (std::uint32_t v : c)
        if (!in[v]) out_of_box.push_back(v);
    }
  // Per root: 2 unknown, 0 outside (a vertex out of the box), else its point_in_solid.
  std::vector<signed char> set_side(nv, 2);
  for (const std::uint32_t v : out_of_box) set_side[find(v)] = 0;
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (!counts(t)) continue;
    const std::uint32_t root = find(m.triangles[t][0]);
    if (set_side[root] == 2) set_side[root] = static_cast<signed char>(point_in_solid(y, m.positions[root]));
    side[t] = set_side[root];
  }
  return side;
}

DepthMap depth_map(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  const auto nv = static_cast<std::uint32_t>(m.num_vertices());
  DepthMap map;
  map.depth.assign(nv, 0.0);
  map.side.assign(nv, 0);
  if (y.bvh.empty()) return map;
  // The vertices of untouched triangles take their set's side (they lie off y's surface); the
  // others, vertices of triangles that cross or touch y only, are tested one by one (in parallel).
  std::vector<char> known(nv, 0);
  for (std::uint32_t t = 0; t < nt; ++t)
    if (!paired[t])
      for (std::uint32_t v : m.triangles[t]) map.side[v] = side[t], known[v] = 1;
  std::vector<std::uint32_t> own;
  for (std::uint32_t t = 0; t < nt; ++t)
    if (paired[t])
      for (std::uint32_t v : m.triangles[t])
        if (!known[v]) {
          known[v] = 1;
          if (in_root_box(y.bvh, m.positions[v])) own.push_back(v);
        }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, own.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i)
      map.side[own[i]] = static_cast<signed char>(point_in_solid(y, m.positions[own[i]]));
  });
  // The inside vertices' distances to y's surface, in runs of consecutive vertices (neighbours, in
  // most meshes): each query seeded with the previous one's nearest triangle (the same exact
  // nearest triangle, found sooner). A vertex at distance 0 lies on y's surface: outside (0).
  std::vector<std::uint32_t> inside;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (map.side[v] == 1) inside.push_back(v);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, inside.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
    std::uint32_t last = kNoTriangle;
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const std::uint32_t v = inside[i];
      map.depth[v] = std::sqrt(nearest_triangle_d2(y.mesh, y.bvh, m.positions[v], &last, -1, last));
    }
  });
  for (const std::uint32_t v : inside) {
    if (!(map.depth[v] > 0)) {
      map.depth[v] = 0, map.side[v] = 0;
      continue;
    }
    ++map.inside;
    if (map.depth[v] > map.max_depth) map.max_depth = map.depth[v], map.max_vertex = v;
  }
  for (std::uint32_t v = 0; v < nv; ++v) map.undecided += map.side[v] < 0;
  return map;
}

// How deep the surface of x reaches into the solid y, sampled: the largest distance to y's surface
// of x's points inside y (exact ray parity) among: the vertices of x inside y (the depth map: the
// vertices of the triangles that cross or touch y, `paired`, and those of the connected sets of its
// other triangles that lie inside y), and the middles of the stretches of the crossing triangles'
// edges between their crossings of y's surface (a long edge may pass through y with both ends
// outside).
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired, const DepthMap& map) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  double depth = map.max_depth;
  // The distance to y's surface, the previous query's nearest triangle tried first (samples come
  // in runs of neighbours; the nearest distance is the same, found sooner).
  std::uint32_t last = kNoTriangle;
  const auto distance_seeded = [&](const Vec3& p) { return std::sqrt(nearest_triangle_d2(y.mesh, y.bvh, p, &last, -1, last)); };
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
  return depth;
}

double depth_into(const Model& x, const Model& y, const std::vector<char>& paired,
                  const std::vector<signed char>& side) {
  return depth_into(x, y, paired, depth_map(x, y, paired, side));
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
                   const std::vector<signed char>& side, double lower, std::size_t max_splits, const DepthMap* map) {
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
  // A piece of x that may lie inside y, with its bound; dropped when it lies outside. `meets`: known
  // to meet y (x's triangles in the clash's pairs), no test needed.
  const auto add = [&](const std::array<Corner, 3>& c, bool inside, bool meets = false) {
    const std::array<Vec3, 3> p{c[0].p, c[1].p, c[2].p};
    if (!inside && !meets && !meets_y(p)) {
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
  const bool use_map = map && map->depth.size() == m.num_vertices() && map->side.size() == m.num_vertices();
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (!paired[t] && side[t] == 0) continue;  // (undecided: kept)
    if (use_map) {
      // The Lipschitz bound from the map's distances (inside vertices; the others are searched as
      // below): a triangle whose bound stays within `lower` can neither raise the result nor be
      // split (only pieces above 1.1 lower are), so it is left out before any search of its own.
      double far = 0;
      bool known = true;
      for (const std::uint32_t v : m.triangles[t]) {
        if (map->side[v] == 1) far = std::max(far, map->depth[v]);
        else if (vd[v] >= 0) far = std::max(far, vd[v]);
        else known = false;
      }
      if (known) {
        const auto p = m.corners(t);
        const double edge = std::max({norm(p[1] - p[0]), norm(p[2] - p[1]), norm(p[0] - p[2])});
        if (far + edge / std::sqrt(3.0) <= lower) continue;
      }
    }
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
    add(c, !paired[t], paired[t] != 0);
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
namespace {

// The triangles of the clash's part a (which == 0) or b that meet the other part.
std::vector<char> paired_of(const Model& m, const ClashResult& r, int which) {
  std::vector<char> p(m.mesh.num_triangles(), 0);
  for (const TrianglePair& q : r.pairs) p[which == 0 ? q.a : q.b] = 1;
  return p;
}

bool boxes_meet(const Bvh& x, const Bvh& y) {
  if (x.empty() || y.empty()) return false;
  const auto &a = x.nodes[0].box, &b = y.nodes[0].box;
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// x's map into the solid y (closed or not), x being the clash's part `which`.
DepthMap map_into(const Model& x, const Model& y, const ClashResult& r, int which, bool y_closed) {
  const auto nv = x.mesh.num_vertices();
  if (!boxes_meet(x.bvh, y.bvh)) {  // every vertex outside y's box
    DepthMap map;
    map.depth.assign(nv, 0.0);
    map.side.assign(nv, 0);
    return map;
  }
  if (!y_closed) {  // no inside: undecided in y's box, outside beyond it
    DepthMap map;
    map.depth.assign(nv, 0.0);
    map.side.assign(nv, 0);
    for (std::size_t v = 0; v < nv; ++v)
      if (detail::in_root_box(y.bvh, x.mesh.positions[v])) map.side[v] = -1, ++map.undecided;
    return map;
  }
  const std::vector<char> paired = paired_of(x, r, which);
  return detail::depth_map(x, y, paired, detail::untouched_sides(x, y, paired));
}

}  // namespace

DepthMap depth_map(const Model& a, const Model& b, const ClashResult& r, DepthOf of, const DepthMapRequest& request) {
  const int which = of == DepthOf::a_in_b ? 0 : 1;
  const Model& y = which == 0 ? b : a;
  const bool closed = request.stats ? request.stats(1 - which).closed() : y.stats.closed();
  return map_into(which == 0 ? a : b, y, r, which, closed);
}

DepthMaps depth_maps(const Model& a, const Model& b, const ClashResult& r, const DepthMapRequest& request) {
  DepthMaps m;  // (the two directions side by side: their serial passes overlap)
  tbb::parallel_invoke([&] { m.a = depth_map(a, b, r, DepthOf::a_in_b, request); },
                       [&] { m.b = depth_map(a, b, r, DepthOf::b_in_a, request); });
  return m;
}

PenetrationDepth penetration_depth(const Model& a, const Model& b, const ClashResult& r, std::size_t max_splits,
                                   DepthMaps* maps) {
  PenetrationDepth out;
  if (r.pairs.empty()) {  // (crossing, or touching surfaces of overlapping solids)
    if (maps) *maps = {map_into(a, b, r, 0, true), map_into(b, a, r, 1, true)};
    return out;
  }
  const std::vector<char> pa = paired_of(a, r, 0), pb = paired_of(b, r, 1);
  const std::vector<signed char> sa = detail::untouched_sides(a, b, pa), sb = detail::untouched_sides(b, a, pb);
  DepthMap ma, mb;
  tbb::parallel_invoke([&] { ma = detail::depth_map(a, b, pa, sa); }, [&] { mb = detail::depth_map(b, a, pb, sb); });
  out.depth = std::max(detail::depth_into(a, b, pa, ma), detail::depth_into(b, a, pb, mb));
  out.depth_bound = out.depth;
  if (max_splits > 0) {
    out.bounded = true;
    double ba = 0, bb = 0;  // (the two directions side by side)
    tbb::parallel_invoke([&] { ba = detail::depth_bound(a, b, pa, sa, out.depth, max_splits, &ma); },
                         [&] { bb = detail::depth_bound(b, a, pb, sb, out.depth, max_splits, &mb); });
    out.depth_bound = std::max({out.depth, ba, bb});
  }
  if (maps) *maps = {std::move(ma), std::move(mb)};
  return out;
}

}  // namespace interfere
