// Clash regions and intersection curves (issue #2, item 5).
// A region is a connected set of intersecting triangles: nodes are the clashing triangles of A and B,
// joined by every intersecting pair and by sharing a vertex within a part. Curves chain the crossing
// pairs' segments (as CATIA draws its intersection curves): endpoints are keyed by the exact features
// (vertex / edge / face of each part) they lie on, so neighbouring pairs agree without tolerances.
#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "clash_internal.h"

namespace interfere::detail {
namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t x, std::uint32_t y) {
    x = find(x), y = find(y);
    if (x != y) parent_[std::max(x, y)] = std::min(x, y);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

/// Global key of a feature of one part: (type, id0, id1) with vertex/edge ids as mesh vertex ids.
using FeatureKey = std::tuple<std::uint8_t, std::uint32_t, std::uint32_t>;

FeatureKey feature_key(const TriMesh& m, std::uint32_t tri, const Feature& f) {
  const Tri& t = m.triangles[tri];
  switch (f.type) {
    case Feature::vertex: return {0, t[f.index], 0};
    case Feature::edge: {
      const std::uint32_t u = t[f.index], v = t[(f.index + 1) % 3];
      return {1, std::min(u, v), std::max(u, v)};
    }
    case Feature::face: break;
  }
  return {2, tri, 0};
}

using PointKey = std::pair<FeatureKey, FeatureKey>;

/// Chains segments (pairs of point ids) into polylines; deterministic for sorted input.
std::vector<Polyline> chain(const std::vector<Vec3>& points,
                            const std::vector<std::pair<std::uint32_t, std::uint32_t>>& segs) {
  std::vector<std::vector<std::uint32_t>> incident(points.size());
  for (std::uint32_t s = 0; s < segs.size(); ++s) {
    incident[segs[s].first].push_back(s);
    incident[segs[s].second].push_back(s);
  }
  std::vector<bool> used(segs.size(), false);
  std::vector<Polyline> out;
  auto walk = [&](std::uint32_t start) {
    Polyline pl;
    pl.points.push_back(points[start]);
    std::uint32_t at = start;
    for (;;) {
      std::uint32_t next_seg = UINT32_MAX;
      for (std::uint32_t s : incident[at]) {
        if (!used[s]) {
          next_seg = s;
          break;
        }
      }
      if (next_seg == UINT32_MAX) break;
      used[next_seg] = true;
      const auto [p, q] = segs[next_seg];
      const std::uint32_t nxt = p == at ? q : p;
      pl.length += distance(points[at], points[nxt]);
      at = nxt;
      if (at == start) {
        pl.closed = true;
        break;
      }
      pl.points.push_back(points[at]);
      if (incident[at].size() != 2) break;  // end or branch point: stop here
    }
    if (pl.points.size() >= 2 || pl.closed) out.push_back(std::move(pl));
  };
  // Open chains start at ends and branch points; what remains are closed loops.
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (incident[p].size() != 2) {
      for (std::size_t k = 0; k < incident[p].size(); ++k) walk(p);
    }
  }
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    bool any = false;
    for (std::uint32_t s : incident[p]) any |= !used[s];
    if (any) walk(p);
  }
  return out;
}

}  // namespace

std::vector<ClashRegion> build_regions(const TriMesh& a, const TriMesh& b, const std::vector<Hit>& hits) {
  if (hits.empty()) return {};
  // Node ids: clashing triangles of A first, then of B (both sorted).
  std::vector<std::uint32_t> ta, tb;
  for (const Hit& h : hits) ta.push_back(h.a), tb.push_back(h.b);
  std::sort(ta.begin(), ta.end());
  ta.erase(std::unique(ta.begin(), ta.end()), ta.end());
  std::sort(tb.begin(), tb.end());
  tb.erase(std::unique(tb.begin(), tb.end()), tb.end());
  auto node_a = [&](std::uint32_t t) {
    return static_cast<std::uint32_t>(std::lower_bound(ta.begin(), ta.end(), t) - ta.begin());
  };
  auto node_b = [&](std::uint32_t t) {
    return static_cast<std::uint32_t>(ta.size() + (std::lower_bound(tb.begin(), tb.end(), t) - tb.begin()));
  };
  UnionFind uf(ta.size() + tb.size());
  for (const Hit& h : hits) uf.unite(node_a(h.a), node_b(h.b));
  auto join_by_vertex = [&](const TriMesh& m, const std::vector<std::uint32_t>& tris, std::uint32_t base) {
    std::unordered_map<std::uint32_t, std::uint32_t> first_at_vertex;
    for (std::uint32_t n = 0; n < tris.size(); ++n) {
      for (std::uint32_t v : m.triangles[tris[n]]) {
        const auto [it, inserted] = first_at_vertex.try_emplace(v, base + n);
        if (!inserted) uf.unite(it->second, base + n);
      }
    }
  };
  join_by_vertex(a, ta, 0);
  join_by_vertex(b, tb, static_cast<std::uint32_t>(ta.size()));

  // Regions numbered by their smallest node (A's triangles come first), hence deterministic.
  std::map<std::uint32_t, std::size_t> region_of_root;
  std::vector<ClashRegion> regions;
  auto region = [&](std::uint32_t node) -> ClashRegion& {
    const auto [it, inserted] = region_of_root.try_emplace(uf.find(node), regions.size());
    if (inserted) regions.emplace_back();
    return regions[it->second];
  };
  for (std::uint32_t n = 0; n < ta.size(); ++n) {
    ClashRegion& r = region(n);
    r.triangles_a.push_back(ta[n]);
    for (std::uint32_t v : a.triangles[ta[n]]) r.box.expand(a.positions[v]);
  }
  for (std::uint32_t n = 0; n < tb.size(); ++n) {
    ClashRegion& r = region(static_cast<std::uint32_t>(ta.size()) + n);
    r.triangles_b.push_back(tb[n]);
    for (std::uint32_t v : b.triangles[tb[n]]) r.box.expand(b.positions[v]);
  }

  // Curves: per region, the crossing segments with their endpoints keyed by exact features.
  std::vector<std::vector<const Hit*>> region_hits(regions.size());
  for (const Hit& h : hits) {
    ClashRegion& r = region(node_a(h.a));
    (h.kind == ContactKind::cross ? r.cross_pairs : r.touch_pairs)++;
    if (h.has_segment) region_hits[&r - regions.data()].push_back(&h);
  }
  for (std::size_t ri = 0; ri < regions.size(); ++ri) {
    std::map<PointKey, std::uint32_t> point_id;
    std::vector<Vec3> points;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> segs;
    for (const Hit* h : region_hits[ri]) {
      std::uint32_t ids[2];
      for (int k = 0; k < 2; ++k) {
        const PointKey key{feature_key(a, h->a, h->feature_a[k]), feature_key(b, h->b, h->feature_b[k])};
        const auto [it, inserted] = point_id.try_emplace(key, static_cast<std::uint32_t>(points.size()));
        if (inserted) points.push_back(h->segment[k]);
        ids[k] = it->second;
      }
      if (ids[0] != ids[1]) segs.emplace_back(ids[0], ids[1]);
    }
    regions[ri].curves = chain(points, segs);
    for (const Polyline& pl : regions[ri].curves) regions[ri].curve_length += pl.length;
  }
  return regions;
}

}  // namespace interfere::detail
