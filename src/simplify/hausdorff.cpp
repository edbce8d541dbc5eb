// Sampled Hausdorff distance between two meshes (issue #6, item 5) with the engine's BVH
// (bvh/bvh.h) and the closest point on a triangle of np/distance.h (Ericson 2005, §5.1.5):
// every sample runs a depth-first nearest-triangle search, nearer child first, pruning nodes whose
// box lies farther than the best distance found. Self-intersections are counted with the engine's
// exact clash query (query/clash.h) of a mesh against itself.
#include "interfere/simplify/hausdorff.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"

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

/// Squared distance from p to the nearest triangle of `mesh`, and that triangle (in `tri`).
double nearest_d2(const TriMesh& mesh, const Bvh& bvh, const Vec3& p, std::uint32_t* tri = nullptr) {
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
        const double d2 = squared_norm(q - p);
        if (d2 < best) {
          best = d2;
          if (tri) *tri = t;
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

// A distance at a point and the triangle of `to` nearest to it.
struct Near {
  double d = 0;  ///< distance (not squared)
  std::uint32_t tri = 0;
};

Near nearest(const TriMesh& to, const Bvh& bvh, const Vec3& p) {
  Near n;
  n.d = std::sqrt(nearest_d2(to, bvh, p, &n.tri));
  return n;
}

// One triangle c of `from` with its samples: distances at the corners, edge midpoints (m[k] on
// edge k, k+1) and centroid, each with its nearest triangle of `to`.
struct Sampled {
  std::array<Vec3, 3> c, m;
  std::array<Near, 3> at, mid;
  Near centre;
  double max_sample() const {
    return std::max({at[0].d, at[1].d, at[2].d, mid[0].d, mid[1].d, mid[2].d, centre.d});
  }
};

Sampled sample(const TriMesh& to, const Bvh& bvh, const std::array<Vec3, 3>& c, const std::array<Near, 3>& at) {
  Sampled s{c, {}, at, {}, {}};
  for (int k = 0; k < 3; ++k) {
    s.m[k] = (c[k] + c[(k + 1) % 3]) * 0.5;
    s.mid[k] = nearest(to, bvh, s.m[k]);
  }
  s.centre = nearest(to, bvh, (c[0] + c[1] + c[2]) / 3.0);
  return s;
}

// A convex polygon (a triangle of `from` cut by planes).
struct Poly {
  std::array<Vec3, 10> v;
  int n = 0;
};

// The polygon's part on the positive side of the plane n.(x - o) >= 0 (Sutherland-Hodgman).
Poly clip(const Poly& p, const Vec3& n, const Vec3& o) {
  Poly out;
  for (int i = 0; i < p.n; ++i) {
    const Vec3& a = p.v[i];
    const Vec3& b = p.v[(i + 1) % p.n];
    const double da = dot(n, a - o), db = dot(n, b - o);
    if (da >= 0 && out.n < 10) out.v[out.n++] = a;
    if (((da < 0) != (db < 0)) && out.n < 10) out.v[out.n++] = a + (b - a) * (da / (da - db));
  }
  return out;
}

// A plane between triangles t1 and t2 of `to` (normal towards t1) with the point x on t2's side,
// cutting across the surface they approximate (N: their mean normal): through their shared edge,
// halving the angle between them; through their shared vertex, between their centroids; else
// between x's closest points on t1 and t2 (x is nearer to t2's); each only if it leaves x on t2's
// side (the cut must make progress).
bool separating_plane(const std::array<Vec3, 3>& t1, const std::array<Vec3, 3>& t2, const Vec3& x, Vec3& n,
                      Vec3& o) {
  const auto accept = [&](const Vec3& nn, const Vec3& oo) {
    if (!(squared_norm(nn) > 0) || !(dot(nn, x - oo) < 0)) return false;
    n = nn, o = oo;
    return true;
  };
  int shared = 0, i1[2], i2[2];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (t1[a] == t2[b] && shared < 2) i1[shared] = a, i2[shared] = b, ++shared;
  if (shared == 2) {
    const Vec3 u = t1[i1[0]], e = t1[i1[1]] - u;
    const double ee = dot(e, e);
    const Vec3 w1 = t1[3 - i1[0] - i1[1]] - u, w2 = t2[3 - i2[0] - i2[1]] - u;
    const Vec3 a1 = w1 - e * (dot(w1, e) / ee), a2 = w2 - e * (dot(w2, e) / ee);
    const double l1 = norm(a1), l2 = norm(a2);
    if (ee > 0 && l1 > 0 && l2 > 0 && accept(a1 / l1 - a2 / l2, u)) return true;
  }
  Vec3 mean = cross(t1[1] - t1[0], t1[2] - t1[0]), m2 = cross(t2[1] - t2[0], t2[2] - t2[0]);
  const double ml1 = norm(mean), ml2 = norm(m2);
  mean = ml1 > 0 && ml2 > 0 ? mean / ml1 + m2 / ml2 : Vec3{};
  const double ml = norm(mean);
  const auto across = [&](const Vec3& v) { return ml > 0 ? v - mean * (dot(v, mean) / (ml * ml)) : v; };
  if (shared == 1) {
    const Vec3 c1 = (t1[0] + t1[1] + t1[2]) / 3.0, c2 = (t2[0] + t2[1] + t2[2]) / 3.0;
    if (accept(across(c1 - c2), t1[i1[0]])) return true;
  }
  const Vec3 q1 = closest_point_on_triangle(x, t1), q2 = closest_point_on_triangle(x, t2);
  return accept(across(q1 - q2), (q1 + q2) * 0.5) || accept(q1 - q2, (q1 + q2) * 0.5);
}

// Upper bound of the distance from the points of polygon p to `to`: the distance to one triangle
// t of `to` is convex, so on p it is largest at a vertex, and the distance to `to` is at most
// that, for each candidate t. Where the best candidate leaves the bound above `floor`, p is cut by
// a plane between that candidate and the one nearest to its worst vertex and each part bounded
// with its own best candidate (any partition gives a bound; this one follows the output's
// triangles: a triangle of the input straddling an edge of the output).
double convex_bound(const TriMesh& to, const Poly& p, const std::uint32_t* cand, int nc, double floor, int depth) {
  if (p.n == 0) return 0;
  double best = std::numeric_limits<double>::infinity();
  int bi = -1, worst_v = 0;
  for (int i = 0; i < nc; ++i) {
    const auto t = to.corners(cand[i]);
    double w = 0;
    int wv = 0;
    for (int k = 0; k < p.n && w < best; ++k) {
      const double d = norm(closest_point_on_triangle(p.v[k], t) - p.v[k]);
      if (d > w) w = d, wv = k;
    }
    if (w < best) best = w, bi = i, worst_v = wv;
  }
  if (best <= floor || depth == 0 || nc < 2) return best;
  const Vec3& x = p.v[worst_v];
  int bj = -1;
  double dj = norm(closest_point_on_triangle(x, to.corners(cand[bi])) - x);
  for (int i = 0; i < nc; ++i) {
    if (i == bi) continue;
    const double d = norm(closest_point_on_triangle(x, to.corners(cand[i])) - x);
    if (d < dj) dj = d, bj = i;
  }
  Vec3 n, o;
  if (bj < 0 || !separating_plane(to.corners(cand[bi]), to.corners(cand[bj]), x, n, o)) return best;
  const Poly p1 = clip(p, n, o), p2 = clip(p, n * -1.0, o);
  if (p1.n == 0 || p2.n == 0) return best;
  const double b1 = convex_bound(to, p1, cand, nc, floor, depth - 1);
  if (b1 >= best) return best;
  return std::min(best, std::max(b1, convex_bound(to, p2, cand, nc, floor, depth - 1)));
}

// Upper bound of the distance from the points of triangle s.c to `to`, the smaller of two bounds,
// computed lazily down to `floor`:
// - convexity (convex_bound) with the nearest triangles of the samples as candidates (the
//   centroid's first: 0 for a triangle the output kept);
// - Lipschitz: the distance is 1-Lipschitz, and every point of a triangle with longest edge l lies
//   within l / sqrt(3) of a corner (at most the circumradius of an acute triangle, whose largest
//   angle is >= 60 degrees, or half the longest edge of an obtuse one); split at the edge
//   midpoints, the four halves have longest edges <= l/2: max over corners and midpoints + l / (2
//   sqrt 3).
double local_bound(const TriMesh& to, const Sampled& s, double floor) {
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(s.c[(k + 1) % 3] - s.c[k]));
  const double lips = std::max({s.at[0].d, s.at[1].d, s.at[2].d, s.mid[0].d, s.mid[1].d, s.mid[2].d}) +
                      longest / (2.0 * std::sqrt(3.0));
  if (lips <= floor) return lips;
  std::array<std::uint32_t, 7> cand{s.centre.tri, s.at[0].tri, s.at[1].tri, s.at[2].tri,
                                    s.mid[0].tri, s.mid[1].tri, s.mid[2].tri};
  int nc = 0;
  for (std::size_t i = 0; i < cand.size(); ++i)
    if (std::find(cand.begin(), cand.begin() + nc, cand[i]) == cand.begin() + nc) cand[nc++] = cand[i];
  Poly p;
  p.n = 3;
  std::copy(s.c.begin(), s.c.end(), p.v.begin());
  return std::min(lips, convex_bound(to, p, cand.data(), nc, std::max(floor, 0.0), 4));
}

// The triangles of a mesh around each vertex (compressed rows).
struct Fans {
  std::vector<std::uint32_t> start, tris;
};

Fans fans_of(const TriMesh& m) {
  Fans f;
  f.start.assign(m.num_vertices() + 1, 0);
  for (const Tri& t : m.triangles)
    for (std::uint32_t v : t) ++f.start[v + 1];
  for (std::size_t v = 0; v < m.num_vertices(); ++v) f.start[v + 1] += f.start[v];
  f.tris.resize(f.start.back());
  std::vector<std::uint32_t> fill(f.start.begin(), f.start.end() - 1);
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t)
    for (std::uint32_t v : m.triangles[t]) f.tris[fill[v]++] = t;
  return f;
}

// convex_bound with more candidates: the samples' nearest triangles and every triangle sharing a
// vertex with one of them (an input triangle over a vertex of the output where several meet).
double ring_bound(const TriMesh& to, const Fans& fans, const Sampled& s, double floor) {
  constexpr int kMax = 64;
  std::array<std::uint32_t, kMax> cand;
  int nc = 0;
  const auto add = [&](std::uint32_t t) {
    if (nc < kMax && std::find(cand.begin(), cand.begin() + nc, t) == cand.begin() + nc) cand[nc++] = t;
  };
  for (const Near* n : {&s.centre, &s.at[0], &s.at[1], &s.at[2], &s.mid[0], &s.mid[1], &s.mid[2]}) add(n->tri);
  const int seeds = nc;
  for (int i = 0; i < seeds; ++i)
    for (std::uint32_t v : to.triangles[cand[i]])
      for (std::uint32_t k = fans.start[v]; k < fans.start[v + 1]; ++k) add(fans.tris[k]);
  Poly p;
  p.n = 3;
  std::copy(s.c.begin(), s.c.end(), p.v.begin());
  return convex_bound(to, p, cand.data(), nc, floor, 6);
}

// local_bound refined by midpoint subdivision (depth levels) where it exceeds `floor`.
double refined_bound(const TriMesh& to, const Bvh& bvh, const Sampled& s, double floor, int depth) {
  const double b = local_bound(to, s, floor);
  if (b <= floor || depth == 0) return b;
  const std::array<std::array<Vec3, 3>, 4> sub{{{s.c[0], s.m[0], s.m[2]}, {s.m[0], s.c[1], s.m[1]},
                                                 {s.m[2], s.m[1], s.c[2]}, {s.m[0], s.m[1], s.m[2]}}};
  const std::array<std::array<Near, 3>, 4> sub_at{{{s.at[0], s.mid[0], s.mid[2]}, {s.mid[0], s.at[1], s.mid[1]},
                                                    {s.mid[2], s.mid[1], s.at[2]}, {s.mid[0], s.mid[1], s.mid[2]}}};
  double r = 0;
  for (int k = 0; k < 4 && r < b; ++k) r = std::max(r, refined_bound(to, bvh, sample(to, bvh, sub[k], sub_at[k]), floor, depth - 1));
  return std::min(b, r);
}

}  // namespace

// Samples: every vertex (used by a triangle or not), then per triangle its 3 edge midpoints and
// its centroid. The bound: per triangle local_bound, computed in the sampling pass down to 1.25x
// the vertices' largest distance (usually the largest of all: QEM errs most at vertices); the
// triangles still above 1.25x the largest sampled distance are refined by subdivision (4 levels).
OneSidedDistance one_sided(const TriMesh& from, const TriMesh& to, bool with_bound) {
  OneSidedDistance out;
  const std::size_t nv = from.num_vertices(), nt = from.num_triangles();
  out.samples = nv + 4 * nt;
  if (out.samples == 0) return out;
  if (to.num_triangles() == 0) {
    out.sampled = out.bound = std::numeric_limits<double>::infinity();
    return out;
  }
  constexpr double kSlack = 1.25;
  const Bvh bvh = build_bvh(to);
  std::vector<Near> vn(nv);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v < r.end(); ++v) vn[v] = nearest(to, bvh, from.positions[v]);
  });
  double vertex_max = 0;
  for (const Near& n : vn) vertex_max = std::max(vertex_max, n.d);  // unused vertices are samples too
  const auto corners_of = [&](std::size_t t) {
    const Tri& tr = from.triangles[t];
    return std::array<Near, 3>{vn[tr[0]], vn[tr[1]], vn[tr[2]]};
  };
  std::vector<double> local(nt);
  struct Max {
    double sampled = 0, local = 0;
  };
  const Max m = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nt, 256), Max{},
      [&](const tbb::blocked_range<std::size_t>& r, Max m) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          const Sampled s = sample(to, bvh, from.corners(t), corners_of(t));
          local[t] = with_bound ? local_bound(to, s, kSlack * vertex_max) : 0.0;
          m.sampled = std::max(m.sampled, s.max_sample());
          m.local = std::max(m.local, local[t]);
        }
        return m;
      },
      [](Max x, Max y) { return Max{std::max(x.sampled, y.sampled), std::max(x.local, y.local)}; });
  out.sampled = std::max(vertex_max, m.sampled);
  const double floor = kSlack * out.sampled;
  double bound = m.local;
  if (with_bound && bound > floor) {
    const Fans fans = fans_of(to);
    bound = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, nt, 64), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double b) {
          for (std::size_t t = r.begin(); t < r.end(); ++t) {
            double x = local[t];
            if (x > floor) {
              const Sampled s = sample(to, bvh, from.corners(t), corners_of(t));
              x = std::min(x, ring_bound(to, fans, s, floor));
              if (x > floor) x = std::min(x, refined_bound(to, bvh, s, floor, 2));
            }
            b = std::max(b, x);
          }
          return b;
        },
        [](double x, double y) { return std::max(x, y); });
  }
  // Rounding of the closest-point computations (relative 1e-11 seen on CAD slivers): a margin of
  // 1e-9 of the two meshes' joint extent.
  Aabb box = from.bounds();
  box.expand(to.bounds());
  out.bound = with_bound ? std::max(bound, out.sampled) + 1e-9 * norm(box.extent())
                         : std::numeric_limits<double>::infinity();
  return out;
}

double one_sided_distance(const TriMesh& from, const TriMesh& to, std::size_t* samples) {
  const OneSidedDistance d = one_sided(from, to, false);
  if (samples) *samples = d.samples;
  return d.sampled;
}

HausdorffResult hausdorff(const TriMesh& a, const TriMesh& b) {
  HausdorffResult r;
  const OneSidedDistance ab = one_sided(a, b), ba = one_sided(b, a, false);
  r.a_to_b = ab.sampled, r.b_to_a = ba.sampled;
  r.a_to_b_bound = ab.bound;
  r.samples = ab.samples + ba.samples;
  return r;
}

// Self-intersections with the engine's BVH (bvh/bvh.h) traversed against itself, each unordered
// node pair once, and the exact triangle-triangle test of np/tri_tri.h (the decision the engine's
// clash query makes for a pair). Pairs sharing a vertex position are excluded before the exact test
// (they touch by construction), which is what made clash(m, m) slow on a freshly simplified mesh:
// every adjacent pair went through the exact (degenerate, touching) path, twice.
// With skip flags, a node whose triangles are all skipped is "quiet": a pair of quiet nodes holds
// only skipped pairs and is not descended (the kept feature faces of a simplified part). The node
// pairs are expanded serially to a frontier of at least kFrontier, then each frontier pair is
// traversed and its leaf pairs tested in parallel; the pairs found are sorted (a fixed result for
// any thread count). Simplified casing, 5,200 triangles: 1.33 -> 1.15 ms on 2 cores (the serial
// traversal was a third of the time).
std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs(const TriMesh& mesh,
                                                                     const std::vector<std::uint8_t>* skip) {
  using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  using NodePair = std::pair<std::uint32_t, std::uint32_t>;
  const std::size_t nt = mesh.num_triangles();
  if (nt < 2) return {};
  // Leaves of 8: fewer leaf pairs; the box tests inside a leaf pair are cheap (1.2x faster than 4
  // from 5e3 to 1e6 triangles).
  const Bvh bvh = build_bvh(mesh, {.max_leaf_size = 8});
  // Triangles (and skip flags) in leaf order: the leaf tests read them sequentially.
  std::vector<Tri> tri(bvh.prims.size());
  std::vector<std::uint8_t> quiet_prim(bvh.prims.size(), 0);
  for (std::size_t k = 0; k < bvh.prims.size(); ++k) {
    tri[k] = mesh.triangles[bvh.prims[k]];
    if (skip) quiet_prim[k] = (*skip)[bvh.prims[k]];
  }
  std::vector<std::uint8_t> quiet(bvh.nodes.size(), 0);
  if (skip) {
    for (std::size_t i = bvh.nodes.size(); i-- > 0;) {  // children after their parent
      const BvhNode& n = bvh.nodes[i];
      if (n.is_leaf()) {
        std::uint8_t q = 1;
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k) q &= quiet_prim[k];
        quiet[i] = q;
      } else {
        quiet[i] = quiet[n.first] & quiet[n.first + 1];
      }
    }
  }
  // One step of the descent: a pair's child pairs, or false for a leaf pair.
  const auto expand = [&](NodePair p, auto&& push) {
    const auto [i, j] = p;
    const BvhNode& a = bvh.nodes[i];
    const BvhNode& b = bvh.nodes[j];
    if (a.is_leaf() && b.is_leaf()) return false;
    const auto visit = [&](std::uint32_t x, std::uint32_t y) {
      if (quiet[x] && quiet[y]) return;
      if (x != y && !bvh.nodes[x].box.overlaps(bvh.nodes[y].box)) return;
      push(NodePair{x, y});
    };
    if (i == j) {
      visit(a.first, a.first);
      visit(a.first + 1, a.first + 1);
      visit(a.first, a.first + 1);
    } else if (!a.is_leaf()) {
      visit(a.first, j);
      visit(a.first + 1, j);
    } else {
      visit(i, b.first);
      visit(i, b.first + 1);
    }
    return true;
  };
  const auto leaf_pair = [&](NodePair p, Pairs& found) {
    const BvhNode& na = bvh.nodes[p.first];
    const BvhNode& nb = bvh.nodes[p.second];
    const bool same = p.first == p.second;
    for (std::uint32_t x = na.first; x < na.first + na.count; ++x) {
      // A triangle away from the other leaf's box meets none of its triangles.
      if (!same && !bvh.prim_boxes[x].overlaps(nb.box)) continue;
      const AabbF& bx = bvh.prim_boxes[x];
      const Tri& ta = tri[x];
      for (std::uint32_t y = same ? x + 1 : nb.first; y < nb.first + nb.count; ++y) {
        if (!bx.overlaps(bvh.prim_boxes[y])) continue;
        if (quiet_prim[x] && quiet_prim[y]) continue;
        // Adjacent by index (a welded mesh) first, else by position (a soup).
        const Tri& tb = tri[y];
        bool share = false;
        for (std::uint32_t i : ta) share = share || i == tb[0] || i == tb[1] || i == tb[2];
        if (share) continue;
        const std::array<Vec3, 3> ca{mesh.positions[ta[0]], mesh.positions[ta[1]], mesh.positions[ta[2]]};
        const std::array<Vec3, 3> cb{mesh.positions[tb[0]], mesh.positions[tb[1]], mesh.positions[tb[2]]};
        for (const Vec3& u : ca)
          for (const Vec3& v : cb) share = share || u == v;
        if (!share && tri_tri_exact_intersects(ca, cb))
          found.emplace_back(std::min(bvh.prims[x], bvh.prims[y]), std::max(bvh.prims[x], bvh.prims[y]));
      }
    }
  };
  constexpr std::size_t kFrontier = 256;
  std::vector<NodePair> frontier, next;
  if (!quiet[0]) frontier.push_back({0u, 0u});
  Pairs pairs;
  while (!frontier.empty() && frontier.size() < kFrontier) {
    next.clear();
    bool grew = false;
    for (const NodePair& p : frontier) {
      if (expand(p, [&](NodePair c) { next.push_back(c); })) grew = true;
      else leaf_pair(p, pairs);
    }
    frontier.swap(next);
    if (!grew) break;
  }
  Pairs deep = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, frontier.size(), 4), Pairs{},  // the identity of the join
      [&](const tbb::blocked_range<std::size_t>& r, Pairs found) {
        std::vector<NodePair> stack;
        for (std::size_t k = r.begin(); k < r.end(); ++k) {
          stack.assign(1, frontier[k]);
          while (!stack.empty()) {
            const NodePair p = stack.back();
            stack.pop_back();
            if (!expand(p, [&](NodePair c) { stack.push_back(c); })) leaf_pair(p, found);
          }
        }
        return found;
      },
      [](Pairs x, const Pairs& y) {
        x.insert(x.end(), y.begin(), y.end());
        return x;
      });
  pairs.insert(pairs.end(), deep.begin(), deep.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::size_t count_self_intersections(const TriMesh& mesh) { return self_intersecting_pairs(mesh).size(); }

}  // namespace interfere
