// Self-intersections of a mesh (issue #6, item 6: simplification introduces none) with the
// engine's BVH traversed against itself and the exact triangle test of np/tri_tri.h.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/np/tri_tri.h"
#include "interfere/simplify/hausdorff.h"

namespace interfere {

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
// traversal was a third of the time), 0.95 ms with the leaf tests below.
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
  // The triangles' boxes per coordinate in leaf order (8 spare zero entries at the end, read past a
  // leaf's last triangle and masked out): one triangle's box is tested against four of the other
  // leaf's at a time without branches, and only the overlapping ones are visited (the branchy
  // per-pair test, its outcome a coin toss, was about half of the check's time).
  const std::size_t np = bvh.prims.size(), stride = np + 8;
  std::vector<float> soa(6 * stride, 0.0f);
  const float* lo[3] = {soa.data(), soa.data() + stride, soa.data() + 2 * stride};
  const float* hi[3] = {soa.data() + 3 * stride, soa.data() + 4 * stride, soa.data() + 5 * stride};
  for (std::size_t k = 0; k < np; ++k)
    for (int c = 0; c < 3; ++c)
      soa[c * stride + k] = bvh.prim_boxes[k].lo[c], soa[(3 + c) * stride + k] = bvh.prim_boxes[k].hi[c];
  // Bit j set: the box of x overlaps that of y0 + j (j < 4).
  const auto overlaps4 = [&](const AabbF& bx, std::uint32_t y0) {
#if defined(__SSE2__)
    __m128 m = _mm_castsi128_ps(_mm_set1_epi32(-1));
    for (int c = 0; c < 3; ++c) {
      m = _mm_and_ps(m, _mm_cmple_ps(_mm_set1_ps(bx.lo[c]), _mm_loadu_ps(hi[c] + y0)));
      m = _mm_and_ps(m, _mm_cmple_ps(_mm_loadu_ps(lo[c] + y0), _mm_set1_ps(bx.hi[c])));
    }
    return static_cast<unsigned>(_mm_movemask_ps(m));
#else
    unsigned bits = 0;
    for (unsigned j = 0; j < 4; ++j) {
      bool o = true;
      for (int c = 0; c < 3; ++c) o = o && bx.lo[c] <= hi[c][y0 + j] && lo[c][y0 + j] <= bx.hi[c];
      bits |= static_cast<unsigned>(o) << j;
    }
    return bits;
#endif
  };
  const auto leaf_pair = [&](NodePair p, Pairs& found) {
    const BvhNode& na = bvh.nodes[p.first];
    const BvhNode& nb = bvh.nodes[p.second];
    const bool same = p.first == p.second;
    const std::uint32_t y_end = nb.first + nb.count;
    for (std::uint32_t x = na.first; x < na.first + na.count; ++x) {
      // A triangle away from the other leaf's box meets none of its triangles.
      const AabbF& bx = bvh.prim_boxes[x];
      if (!same && !bx.overlaps(nb.box)) continue;
      const Tri& ta = tri[x];
      for (std::uint32_t y0 = same ? x + 1 : nb.first; y0 < y_end; y0 += 4) {
        unsigned mask = overlaps4(bx, y0);
        if (y_end - y0 < 4) mask &= (1u << (y_end - y0)) - 1u;
        for (; mask != 0; mask &= mask - 1) {
          const std::uint32_t y = y0 + static_cast<std::uint32_t>(__builtin_ctz(mask));
          if (quiet_prim[x] && quiet_prim[y]) continue;
          // Adjacent by index (a welded mesh) first, else by position (a soup).
          // (Bitwise, without branches: four in five of the overlapping pairs are adjacent.)
          const Tri& tb = tri[y];
          bool share = false;
          for (std::uint32_t i : ta) share = share | (i == tb[0]) | (i == tb[1]) | (i == tb[2]);
          if (share) continue;
          const std::array<Vec3, 3> ca{mesh.positions[ta[0]], mesh.positions[ta[1]], mesh.positions[ta[2]]};
          const std::array<Vec3, 3> cb{mesh.positions[tb[0]], mesh.positions[tb[1]], mesh.positions[tb[2]]};
          for (const Vec3& u : ca)
            for (const Vec3& v : cb) share = share || u == v;
          if (!share && tri_tri_exact_intersects(ca, cb))
            found.emplace_back(std::min(bvh.prims[x], bvh.prims[y]), std::max(bvh.prims[x], bvh.prims[y]));
        }
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
