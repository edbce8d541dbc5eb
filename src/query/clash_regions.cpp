// Clash regions and intersection curves (issue #2, item 5).
// A region is a connected set of intersecting triangles: nodes are the clashing triangles of A and B,
// joined by every intersecting pair and by sharing a vertex within a part. Curves chain the crossing
// pairs' segments (as CATIA draws its intersection curves): endpoints are keyed by the exact features
// (vertex / edge / face of each part) they lie on, so neighbouring pairs agree without tolerances.
#include <algorithm>
#include <numeric>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

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

/// One segment endpoint: the key of the point (feature on A, feature on B) and where it came from.
struct EndRecord {
  FeatureKey on_a, on_b;
  std::uint32_t segment;
  std::uint8_t end;
  auto tie() const { return std::tie(on_a, on_b, segment, end); }
  bool operator<(const EndRecord& o) const { return tie() < o.tie(); }
  bool same_point(const EndRecord& o) const { return on_a == o.on_a && on_b == o.on_b; }
};

/// Chains segments (pairs of point ids) into polylines; deterministic for sorted input. Each
/// polyline comes with one of its segments (to find its region).
std::vector<std::pair<Polyline, std::uint32_t>> chain(
    const std::vector<Vec3>& points, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& segs) {
  std::vector<std::vector<std::uint32_t>> incident(points.size());
  for (std::uint32_t s = 0; s < segs.size(); ++s) {
    incident[segs[s].first].push_back(s);
    incident[segs[s].second].push_back(s);
  }
  std::vector<bool> used(segs.size(), false);
  std::vector<std::pair<Polyline, std::uint32_t>> out;
  auto walk = [&](std::uint32_t start) {
    Polyline pl;
    std::uint32_t first_seg = UINT32_MAX;
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
      first_seg = std::min(first_seg, next_seg);
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
    if (pl.points.size() >= 2 || pl.closed) out.emplace_back(std::move(pl), first_seg);
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

std::vector<ClashRegion> build_regions(const TriMesh& a, const TriMesh& b, const std::vector<TrianglePair>& hits,
                                       const std::vector<Segment>& segments) {
  if (hits.empty()) return {};
  // Node ids: clashing triangles of A first, then of B (both sorted).
  std::vector<std::uint32_t> ta, tb;
  for (const TrianglePair& h : hits) ta.push_back(h.a), tb.push_back(h.b);
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
  for (const TrianglePair& h : hits) uf.unite(node_a(h.a), node_b(h.b));
  // (the union-find's roots are the sets' smallest nodes whatever the order of the unions, so a
  // sorted list of (vertex, node) joins the same sets as a map of each vertex's first node)
  auto join_by_vertex = [&](const TriMesh& m, const std::vector<std::uint32_t>& tris, std::uint32_t base) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> at_vertex;  // (vertex, node)
    at_vertex.reserve(3 * tris.size());
    for (std::uint32_t n = 0; n < tris.size(); ++n)
      for (std::uint32_t v : m.triangles[tris[n]]) at_vertex.emplace_back(v, base + n);
    std::sort(at_vertex.begin(), at_vertex.end());
    for (std::size_t i = 1; i < at_vertex.size(); ++i)
      if (at_vertex[i].first == at_vertex[i - 1].first) uf.unite(at_vertex[i - 1].second, at_vertex[i].second);
  };
  join_by_vertex(a, ta, 0);
  join_by_vertex(b, tb, static_cast<std::uint32_t>(ta.size()));

  // Regions numbered by their smallest node (A's triangles come first), hence deterministic.
  std::vector<std::uint32_t> region_of_root(ta.size() + tb.size(), UINT32_MAX);
  std::vector<ClashRegion> regions;
  auto region = [&](std::uint32_t node) -> ClashRegion& {
    std::uint32_t& r = region_of_root[uf.find(node)];
    if (r == UINT32_MAX) r = static_cast<std::uint32_t>(regions.size()), regions.emplace_back();
    return regions[r];
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

  for (const TrianglePair& h : hits) {
    ClashRegion& r = region(node_a(h.a));
    (h.kind == ContactKind::cross ? r.cross_pairs : r.touch_pairs)++;
  }

  // Curves: endpoints keyed by the exact features they lie on; equal keys are one point. Sorting the
  // records (not a map) keeps this O(n log n) with small constants for 10^5+ segments.
  std::vector<EndRecord> ends(2 * segments.size());
  tbb::parallel_for(std::size_t{0}, segments.size(), [&](std::size_t i) {
    const Segment& g = segments[i];
    for (std::uint8_t k = 0; k < 2; ++k) {
      ends[2 * i + k] = {feature_key(a, g.a, g.feature_a[k]), feature_key(b, g.b, g.feature_b[k]),
                         static_cast<std::uint32_t>(i), k};
    }
  });
  tbb::parallel_sort(ends.begin(), ends.end());
  std::vector<Vec3> points;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> segs(segments.size());
  for (std::size_t i = 0; i < ends.size(); ++i) {
    if (i == 0 || !ends[i].same_point(ends[i - 1])) points.push_back(segments[ends[i].segment].points[ends[i].end]);
    const auto id = static_cast<std::uint32_t>(points.size() - 1);
    (ends[i].end == 0 ? segs[ends[i].segment].first : segs[ends[i].segment].second) = id;
  }
  // A crossing segment has positive length, so its two ends never share a key.
  for (auto& [polyline, seg] : chain(points, segs)) {
    ClashRegion& r = region(node_a(segments[seg].a));
    r.curve_length += polyline.length;
    r.curves.push_back(std::move(polyline));
  }
  return regions;
}

}  // namespace interfere::detail
