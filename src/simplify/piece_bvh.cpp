// The search tree of the distance measurements (issue #23, item 12): the engine's BVH (bvh/bvh.h)
// built over pieces of the sliver triangles instead of the triangles. A sliver's box is as large
// as its length in two directions (a spoke of a fan: a point anywhere near the fan lies inside the
// boxes of a third of the spokes), so a nearest-triangle search (Ericson 2005, §6.2) that cannot
// prune by boxes visits O(n) leaves; cut into strips across its length, each strip's box is
// about as wide as long. The search measures whole triangles (nearest_triangle_d2's owner map):
// distances are the same bits as with the plain tree.
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
  TriMesh pieces;
  std::vector<double> pad;
  for (std::uint32_t t = 0; t < nt; ++t) {
    const auto c = m.corners(t);
    const Vec3 c0 = c[apex[t]], c1 = c[(apex[t] + 1) % 3], c2 = c[(apex[t] + 2) % 3];
    double big = 0;
    for (const Vec3& v : c) big = std::max({big, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    const double p = 8 * std::numeric_limits<double>::epsilon() * big +
                     std::numeric_limits<double>::denorm_min();
    const auto add = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
      const auto base = static_cast<std::uint32_t>(pieces.positions.size());
      pieces.positions.insert(pieces.positions.end(), {a, b, d});
      pieces.triangles.push_back({base, base + 1, base + 2});
      r.owner.push_back(t);
      pad.push_back(p);
    };
    const int n = k[t];
    const auto at = [&](const Vec3& end, int i) {
      return i == n ? end : c0 + (end - c0) * (double(i) / n);
    };
    if (n == 1) {
      add(c[0], c[1], c[2]);
      continue;
    }
    add(c0, at(c1, 1), at(c2, 1));
    for (int i = 1; i < n; ++i) {
      const Vec3 x0 = at(c1, i), x1 = at(c1, i + 1), y0 = at(c2, i), y1 = at(c2, i + 1);
      add(x0, x1, y1);
      add(x0, y1, y0);
    }
  }
  r.bvh = build_bvh(pieces);
  Bvh& b = r.bvh;
  for (std::size_t i = 0; i < b.prims.size(); ++i) {
    Aabb box = pieces.triangle_box(b.prims[i]);
    const double p = pad[b.prims[i]];
    box.lo = box.lo - Vec3{p, p, p}, box.hi = box.hi + Vec3{p, p, p};
    b.prim_boxes[i] = to_float_outward(box);
  }
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
