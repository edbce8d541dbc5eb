// The search tree of the distance measurements (issue #23, item 12): the engine's BVH (bvh/bvh.h)
// built over pieces of the sliver triangles instead of the triangles. A sliver's box is as large
// as its length in two directions (a spoke of a fan: a point anywhere near the fan lies inside the
// boxes of a third of the spokes), so a nearest-triangle search (Ericson 2005, §6.2) that cannot
// prune by boxes visits O(n) leaves; cut into strips across its length, each strip's box is
// about as wide as long. The search measures whole triangles (nearest_triangle_d2's owner map):
// distances are the same bits as with the plain tree.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "distance_internal.h"
#include "interfere/np/distance.h"

namespace interfere::detail {
namespace {

// A sliver is cut into k strips when its longest edge exceeds kAspect times its shortest; at most
// kMaxStrips per triangle and `max_pieces` pieces in all (halving the strips until they fit; below
// kMinStrips the pieces gain less than the larger tree costs, and the plain tree is built): memory
// and build time stay O(n + max_pieces).
constexpr double kAspect = 4;
constexpr int kMaxStrips = 16, kMinStrips = 8;

int strips(const std::array<Vec3, 3>& c, int most, int& apex) {
  double shortest = std::numeric_limits<double>::infinity(), longest = 0;
  for (int k = 0; k < 3; ++k) {
    const double l = norm(c[(k + 2) % 3] - c[(k + 1) % 3]);  // the edge opposite corner k
    if (l < shortest) shortest = l, apex = k;
    longest = std::max(longest, l);
  }
  if (!(longest > kAspect * shortest)) return 1;  // also NaN: one piece
  const double k = longest / (kAspect * shortest);
  return k >= most ? most : std::max(1, static_cast<int>(std::ceil(k)));
}

// The n pieces of triangle t cut from corner `apex` (see piece_bvh), written from piece `at` on.
void cut(const TriMesh& m, std::size_t t, int n, int apex, std::size_t at, TriMesh& pieces,
         std::vector<std::uint32_t>& owner, std::vector<double>& pad) {
  const auto c = m.corners(t);
  const Vec3 c0 = c[apex], c1 = c[(apex + 1) % 3], c2 = c[(apex + 2) % 3];
  double big = 0;
  for (const Vec3& v : c) big = std::max({big, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  const double p =
      8 * std::numeric_limits<double>::epsilon() * big + std::numeric_limits<double>::denorm_min();
  const auto add = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
    const auto base = static_cast<std::uint32_t>(3 * at);
    pieces.positions[base] = a, pieces.positions[base + 1] = b, pieces.positions[base + 2] = d;
    pieces.triangles[at] = {base, base + 1, base + 2};
    owner[at] = static_cast<std::uint32_t>(t);
    pad[at] = p;
    ++at;
  };
  const auto on = [&](const Vec3& end, int i) {
    return i == n ? end : c0 + (end - c0) * (double(i) / n);
  };
  if (n == 1) {
    add(c[0], c[1], c[2]);
    return;
  }
  add(c0, on(c1, 1), on(c2, 1));
  for (int i = 1; i < n; ++i) {
    const Vec3 x0 = on(c1, i), x1 = on(c1, i + 1), y0 = on(c2, i), y1 = on(c2, i + 1);
    add(x0, x1, y1);
    add(x0, y1, y0);
  }
}

// The leaf entries of r's tree (distance_internal.h, LeafTri), filled in parallel.
void attach_leaves(const TriMesh& m, PieceBvh& r) {
  const Bvh& b = r.bvh;
  r.leaf.resize(b.prims.size());
  const std::uint32_t* own = r.owners();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.prims.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        LeafTri& e = r.leaf[i];
                        e.tri = own ? own[b.prims[i]] : b.prims[i];
                        e.c = m.corners(e.tri);
                        e.box = b.prim_boxes[i];
                        e.sliver = sliver_test(e.c);
                      }
                    });
}

// As query/distance.cpp's.
double point_box_d2(const Vec3& p, const AabbF& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max(
        {0.0, static_cast<double>(b.lo[k]) - p[k], p[k] - static_cast<double>(b.hi[k])});
    d2 += g * g;
  }
  return d2;
}

}  // namespace

bool sliver_test(const std::array<Vec3, 3>& c) {
  const Vec3 ab = c[1] - c[0], ac = c[2] - c[0];
  const double l2 = std::max({squared_norm(ab), squared_norm(ac), squared_norm(c[2] - c[1])});
  return squared_norm(cross(ab, ac)) <= 1e-8 * l2 * l2;
}

// np/distance.cpp's closest_point_on_triangle (Ericson 2005, §5.1.5) with its sliver test given;
// a sliver, and the cases where it falls back to its sliver routine, go to it whole.
Vec3 closest_point(const Vec3& p, const std::array<Vec3, 3>& t, bool sliver) {
  if (sliver) return closest_point_on_triangle(p, t);
  const Vec3& a = t[0];
  const Vec3& b = t[1];
  const Vec3& c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double sum = va + vb + vc;
  if (!(sum > 0)) return closest_point_on_triangle(p, t);
  const Vec3 q = a + ab * (vb / sum) + ac * (vc / sum);
  return is_finite(q) ? q : closest_point_on_triangle(p, t);
}

// query/distance.cpp's nearest_triangle_d2, step for step (depth-first, nearer child first, the
// same stack and overflow), on the leaf entries.
double nearest_d2(const TriMesh& to, const PieceBvh& tree, const Vec3& p, std::uint32_t* tri,
                  double stop_d2, std::uint32_t seed) {
  const Bvh& bvh = tree.bvh;
  double best = std::numeric_limits<double>::infinity();
  if (bvh.nodes.empty() || to.triangles.empty()) return best;
  if (seed != kNoTriangle) {
    best = squared_norm(closest_point_on_triangle(p, to.corners(seed)) - p);
    if (tri) *tri = seed;
    if (best <= stop_d2) return best;
  }
  struct Entry {
    std::uint32_t node;
    double d2;  // point_box_d2 of the node's box
  };
  Entry stack[128];
  int top = 0;
  stack[top++] = {0, point_box_d2(p, bvh.nodes[0].box)};
  std::vector<Entry> spill;
  const LeafTri* leaf = tree.leaf.data();
  while (top > 0 || !spill.empty()) {
    const Entry e = top > 0 ? stack[--top] : spill.back();
    if (top == 0 && !spill.empty() && e.node == spill.back().node) spill.pop_back();
    if (e.d2 >= best) continue;
    const BvhNode& n = bvh.nodes[e.node];
    if (n.is_leaf()) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const LeafTri& l = leaf[i];
        if (point_box_d2(p, l.box) >= best) continue;
        const double d2 = squared_norm(closest_point(p, l) - p);
        if (d2 < best) {
          best = d2;
          if (tri) *tri = l.tri;
          if (best <= stop_d2) return best;
        }
      }
      continue;
    }
    const std::uint32_t c0 = n.first, c1 = n.first + 1;
    const double d0 = point_box_d2(p, bvh.nodes[c0].box), d1 = point_box_d2(p, bvh.nodes[c1].box);
    const Entry near = d0 <= d1 ? Entry{c0, d0} : Entry{c1, d1};
    const Entry far = d0 <= d1 ? Entry{c1, d1} : Entry{c0, d0};
    for (const Entry& c : {far, near}) {  // near is taken first
      if (top < 128)
        stack[top++] = c;
      else
        spill.push_back(c);
    }
  }
  return best;
}

// Strip i of a triangle cut from its apex c0 (the corner opposite the shortest edge): between the
// cuts at s_i = i / k along both edges from c0 (the first strip a triangle, the others quads as two
// triangles). The cut points are rounded; each piece's box is padded by 8 units in the last place
// of the triangle's largest coordinate (more than the rounding of c0 + e * s), so the boxes cover
// the pieces as cut at the rounded s_i exactly, which tile the triangle. Box layout as the builder
// guarantees it: leaves' boxes from their pieces, then parents from children (reverse sweep).
PieceBvh piece_bvh(const TriMesh& m, std::size_t max_pieces) {
  PieceBvh r;
  const std::size_t nt = m.num_triangles();
  std::vector<int> k(nt), apex(nt, 0);
  int most = kMaxStrips;
  for (;;) {
    std::size_t pieces = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      k[t] = strips(m.corners(t), most, apex[t]);
      pieces += 2 * k[t] - 1;
    }
    if (pieces == nt || most < kMinStrips) {
      r.bvh = build_bvh(m);
      attach_leaves(m, r);
      return r;
    }
    if (pieces <= max_pieces) break;
    most /= 2;
  }
  // Each triangle's pieces at a fixed offset (prefix sums), filled in parallel: the same arrays
  // for any thread count; the boxes too (80,000-triangle 20,000-gon prism to its tenth: 185,000
  // pieces, the tree 0.16 -> 0.10 s, 2 threads).
  std::vector<std::size_t> first(nt + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) first[t + 1] = first[t] + (2 * k[t] - 1);
  TriMesh pieces;
  pieces.positions.resize(3 * first[nt]);
  pieces.triangles.resize(first[nt]);
  r.owner.resize(first[nt]);
  std::vector<double> pad(first[nt]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t < range.end(); ++t)
                        cut(m, t, k[t], apex[t], first[t], pieces, r.owner, pad);
                    });
  r.bvh = build_bvh(pieces);
  Bvh& b = r.bvh;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.prims.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        Aabb box = pieces.triangle_box(b.prims[i]);
                        const double p = pad[b.prims[i]];
                        box.lo = box.lo - Vec3{p, p, p}, box.hi = box.hi + Vec3{p, p, p};
                        b.prim_boxes[i] = to_float_outward(box);
                      }
                    });
  for (std::size_t i = b.nodes.size(); i-- > 0;) {
    BvhNode& n = b.nodes[i];
    if (n.is_leaf()) {
      n.box = b.prim_boxes[n.first];
      for (std::uint32_t j = 1; j < n.count; ++j) n.box.expand(b.prim_boxes[n.first + j]);
    } else {
      n.box = b.nodes[n.first].box;
      n.box.expand(b.nodes[n.first + 1].box);
    }
  }
  attach_leaves(m, r);
  return r;
}

}  // namespace interfere::detail
