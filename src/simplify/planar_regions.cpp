// Convex planar regions of the mesh a distance bound measures to (issue #23, item 12): the
// convexity bound of distance_bound.cpp with one triangle fails on a sliver of `from` that crosses
// many triangles of `to` (a fan-triangulated planar cap measured against a differently fanned
// one: every spoke crosses hundreds), and refining it costs a piece per crossing (the overlay:
// quadratic). The distance to a convex set is convex (Boyd & Vandenberghe, "Convex Optimization",
// 2004, §3.2.5 / example 3.16), so over a region of `to` whose union is a convex planar polygon Q
// one bound covers the whole sliver: its largest distance to Q is at a corner, and a corner's
// distance to Q is at most its distance to any triangle of the region (see region_bound).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "distance_internal.h"
#include "interfere/core/predicates.h"

namespace interfere::detail {
namespace {

// Dents filled at most (summed, in the plane coordinates) per region, relative to the mesh's
// extent: a planar face whose border vertices the simplification moved off their line by rounding
// or by a little more still counts (the bound grows by the dents); a notch (an L) does not.
constexpr double kMaxDent = 1e-4;

struct EdgeUse {
  std::uint64_t key;   // (smaller vertex << 32) | larger vertex
  std::uint32_t slot;  // 3 * triangle + edge (edge k runs from corner k to corner k + 1)
  bool operator<(const EdgeUse& o) const { return key != o.key ? key < o.key : slot < o.slot; }
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

// Whether the union of the region's triangles (in the plane coordinates u, v of each vertex: two of
// its 3-D coordinates, an affine bijection of the region's plane when the third axis is the
// normal's largest) is one convex polygon, by exact predicates: all triangles turn the same way
// (sign s), the boundary chain of their sum (the directed edges without a reverse twin in the
// region) is one simple cycle, it never turns against s, and its edge directions go round once.
// Then the degree of the sum at any point of the plane is the cycle's winding number, 1 inside
// the polygon and 0 outside, and with all signs alike every point of the polygon is covered (and
// none outside): the union is that convex polygon.
bool is_convex_polygon(const TriMesh& m, const std::vector<std::uint32_t>& tris, int axis,
                       double max_dent, double& dent) {
  const int iu = (axis + 1) % 3, iv = (axis + 2) % 3;
  const auto uv = [&](std::uint32_t v) {
    return std::pair{m.positions[v][iu], m.positions[v][iv]};
  };
  int s = 0;
  for (std::uint32_t t : tris) {
    const Tri& f = m.triangles[t];
    const auto [ax, ay] = uv(f[0]);
    const auto [bx, by] = uv(f[1]);
    const auto [cx, cy] = uv(f[2]);
    const int o = orient2d(ax, ay, bx, by, cx, cy);
    if (o == 0 || (s != 0 && o != s)) return false;
    s = o;
  }
  // Boundary chain: each directed edge counts +1, its reverse -1.
  std::vector<EdgeUse> uses;
  uses.reserve(3 * tris.size());
  for (std::uint32_t t : tris)
    for (std::uint32_t k = 0; k < 3; ++k)
      uses.push_back({edge_key(m.triangles[t][k], m.triangles[t][(k + 1) % 3]), 3 * t + k});
  std::sort(uses.begin(), uses.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>>
      boundary;  // (from, to), sorted by from below
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int net = 0;
    for (; j < uses.size() && uses[j].key == uses[i].key; ++j) {
      const Tri& f = m.triangles[uses[j].slot / 3];
      net += f[uses[j].slot % 3] < f[(uses[j].slot % 3 + 1) % 3] ? 1 : -1;
    }
    const auto lo = static_cast<std::uint32_t>(uses[i].key >> 32),
               hi = static_cast<std::uint32_t>(uses[i].key);
    if (net == 1)
      boundary.push_back({lo, hi});
    else if (net == -1)
      boundary.push_back({hi, lo});
    else if (net != 0)
      return false;
    i = j;
  }
  if (boundary.size() < 3) return false;
  std::sort(boundary.begin(), boundary.end());
  for (std::size_t i = 1; i < boundary.size(); ++i)
    if (boundary[i].first == boundary[i - 1].first)
      return false;  // a vertex with two outgoing edges
  const auto next = [&](std::uint32_t v) {
    const auto it =
        std::lower_bound(boundary.begin(), boundary.end(), std::pair{v, std::uint32_t{0}});
    return it != boundary.end() && it->first == v ? it->second : kNoSeed;
  };
  // The cycle, walked from the first edge: it must close after every boundary edge.
  std::vector<std::uint32_t> loop{boundary[0].first};
  for (std::uint32_t v = boundary[0].second; v != boundary[0].first; v = next(v)) {
    if (v == kNoSeed || loop.size() >= boundary.size()) return false;
    loop.push_back(v);
  }
  if (loop.size() != boundary.size()) return false;
  // Dents filled: a vertex turning against s (strictly) is dropped, its neighbours joined, and
  // its distance from their line added to `dent` (the filled triangle's points lie within it of
  // the two edges it replaced). The loop's winding number at a point then falls by the number of
  // filled triangles holding it (each is a clockwise detour of the old loop): the union of the
  // triangles is the convex polygon of the final loop less the filled triangles, every point of
  // which lies within the sum of the dents of the union. Repeated until no vertex turns back
  // (a doubly linked ring; a dropped vertex's neighbours are checked again).
  const std::size_t n = loop.size();
  std::vector<std::size_t> prev(n), nxt(n);
  for (std::size_t i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, nxt[i] = (i + 1) % n;
  std::vector<std::uint8_t> gone(n, 0);
  std::vector<std::size_t> work(n);
  for (std::size_t i = 0; i < n; ++i) work[i] = n - 1 - i;
  std::size_t left = n;
  double dents = 0;
  while (!work.empty() && left >= 3) {
    const std::size_t c = work.back();
    work.pop_back();
    if (gone[c]) continue;
    const auto [px, py] = uv(loop[prev[c]]);
    const auto [cx, cy] = uv(loop[c]);
    const auto [qx, qy] = uv(loop[nxt[c]]);
    if (orient2d(px, py, cx, cy, qx, qy) * s >= 0) continue;
    const double len = std::hypot(qx - px, qy - py);
    if (!(len > 0)) return false;
    dents += std::abs(orient2d_value(px, py, cx, cy, qx, qy)) / len * (1 + 1e-12);
    gone[c] = 1, --left;
    nxt[prev[c]] = nxt[c], prev[nxt[c]] = prev[c];
    work.push_back(nxt[c]);
    work.push_back(prev[c]);
  }
  if (left < 3 || !(dents <= max_dent)) return false;
  // The final loop: convex (straight on where collinear, never back) and going round once.
  const auto half = [&](double dx, double dy) {  // 0: direction angle in [0, pi), 1: in [pi, 2 pi)
    dy *= s;
    return dy > 0 || (dy == 0 && dx > 0) ? 0 : 1;
  };
  std::size_t first = 0;
  while (gone[first]) ++first;
  int wraps = 0;
  std::size_t c = first;
  do {
    const auto [px, py] = uv(loop[prev[c]]);
    const auto [cx, cy] = uv(loop[c]);
    const auto [qx, qy] = uv(loop[nxt[c]]);
    if ((px == cx && py == cy) || (qx == cx && qy == cy)) return false;  // a zero-length edge
    const int o = orient2d(px, py, cx, cy, qx, qy) * s;
    if (o < 0) return false;
    if (o == 0 && ((cx - px > 0) != (qx - cx > 0) || (cx - px < 0) != (qx - cx < 0) ||
                   (cy - py > 0) != (qy - cy > 0) || (cy - py < 0) != (qy - cy < 0)))
      return false;
    wraps += half(cx - px, cy - py) == 1 && half(qx - cx, qy - cy) == 0;
    c = nxt[c];
  } while (c != first);
  if (wraps != 1) return false;
  dent = dents;
  return true;
}

}  // namespace

// Regions grown breadth-first from each unassigned triangle (in index order: deterministic) across
// manifold, consistently oriented edges to neighbours whose corners lie within 1e-6 of the
// extent of the seed's plane (a heuristic: a simplified flat cap's vertices stray by 1e-9 of it, its
// slivers tilt by 2e-8; the bound uses the deviation measured afterwards), then kept when their
// union is a convex polygon up to small dents (is_convex_polygon, in the coordinates that drop the
// normal's largest axis). The bound of a corner through the polygon lifted back to the plane (along
// that axis) is off by at most the largest vertex deviation along the axis, once for the lift and
// once for the corner's triangle, plus the dents (lengths in the plane coordinates grow by at most
// 1 / |n_axis| when lifted): slack = (2 deviation + dents) / |n_axis|.
ConvexRegions convex_planar_regions(const TriMesh& m) {
  ConvexRegions r;
  const std::size_t nt = m.num_triangles();
  r.of.assign(nt, ConvexRegions::kNone);
  r.neighbour.assign(3 * nt, kNoSeed);
  if (nt == 0) return r;
  std::vector<EdgeUse> uses(3 * nt);
  for (std::uint32_t t = 0; t < nt; ++t)
    for (std::uint32_t k = 0; k < 3; ++k)
      uses[3 * t + k] = {edge_key(m.triangles[t][k], m.triangles[t][(k + 1) % 3]), 3 * t + k};
  std::sort(uses.begin(), uses.end());
  for (std::size_t i = 0; i + 1 < uses.size(); ++i) {
    if (uses[i].key != uses[i + 1].key || (i + 2 < uses.size() && uses[i + 2].key == uses[i].key) ||
        (i > 0 && uses[i - 1].key == uses[i].key))
      continue;  // not exactly two uses
    const std::uint32_t a = uses[i].slot, b = uses[i + 1].slot;
    if (m.triangles[a / 3][a % 3] == m.triangles[b / 3][b % 3])
      continue;  // same direction: inconsistent
    r.neighbour[a] = b / 3, r.neighbour[b] = a / 3;
  }
  const double extent = norm(m.bounds().extent()), tol = 1e-6 * extent;
  std::vector<std::uint32_t> tris;
  std::vector<std::uint8_t> seen(nt, 0);  // in a region, kept or not
  for (std::uint32_t seed = 0; seed < nt; ++seed) {
    if (seen[seed]) continue;
    seen[seed] = 1;
    const auto c = m.corners(seed);
    Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
    const double len = norm(n);
    if (!(len > 0) || !std::isfinite(len)) continue;
    n = n / len;
    const auto id = static_cast<std::uint32_t>(r.slack.size());
    tris.assign(1, seed);
    r.of[seed] = id;
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = r.neighbour[3 * tris[i] + k];
        if (u == kNoSeed || seen[u]) continue;
        const auto q = m.corners(u);
        if (!(dot(cross(q[1] - q[0], q[2] - q[0]), n) > 0)) continue;
        if (std::abs(dot(n, q[0] - c[0])) > tol || std::abs(dot(n, q[1] - c[0])) > tol ||
            std::abs(dot(n, q[2] - c[0])) > tol)
          continue;
        r.of[u] = id;
        seen[u] = 1;
        tris.push_back(u);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    double dent = 0;
    if (tris.size() < 2 || !is_convex_polygon(m, tris, axis, kMaxDent * extent, dent)) {
      for (std::uint32_t t : tris) r.of[t] = ConvexRegions::kNone;
      continue;
    }
    double dev = 0;
    for (std::uint32_t t : tris)
      for (std::uint32_t v : m.triangles[t])
        dev = std::max(dev, std::abs(dot(n, m.positions[v] - c[0])));
    r.slack.push_back((2 * dev + dent) / std::abs(n[axis]));
  }
  return r;
}

}  // namespace interfere::detail
