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

}  // namespace

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
  return r;
}

}  // namespace interfere::detail
