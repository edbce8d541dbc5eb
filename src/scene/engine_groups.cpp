// Grouping of clashes (issue #24, item 4): by body pair, or by location — clashes whose tight
// boxes lie within SceneClashOptions::group_distance of each other join one group (single
// linkage, as Navisworks' and IfcClash's "smart grouping" gather many small clashes at one place).
#include <algorithm>
#include <cstdio>
#include <numeric>

#include "engine_internal.h"

namespace interfere::scene::detail {
namespace {

std::uint32_t find(std::vector<std::uint32_t>& p, std::uint32_t x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

ClashGroup make_group(const SceneClashResult& r, std::vector<std::uint32_t> members) {
  ClashGroup g;
  std::sort(members.begin(), members.end());
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const std::uint32_t i : members) {
    const SceneClash& c = r.clashes[i];
    g.box.expand(c.box);
    g.verdict = worst(g.verdict, c.verdict);
    h = fnv1a(h, c.id);
  }
  char id[24];
  std::snprintf(id, sizeof id, "G%016llx", static_cast<unsigned long long>(h));
  g.id = id;
  g.clashes = std::move(members);
  return g;
}

}  // namespace

void group_clashes(SceneClashResult& result, const SceneClashOptions& options) {
  result.groups.clear();
  if (options.group_by == GroupBy::pair) {
    for (const PairSummary& p : result.pairs) result.groups.push_back(make_group(result, p.clashes));
    return;
  }
  if (options.group_by != GroupBy::location) return;
  const auto n = static_cast<std::uint32_t>(result.clashes.size());
  const double d = std::max(0.0, options.group_distance);
  std::vector<std::uint32_t> parent(n), order(n);
  std::iota(parent.begin(), parent.end(), 0u);
  std::iota(order.begin(), order.end(), 0u);
  const auto& c = result.clashes;
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return c[x].box.lo.x < c[y].box.lo.x || (c[x].box.lo.x == c[y].box.lo.x && x < y);
  });
  for (std::uint32_t k = 0; k < n; ++k) {
    const Aabb& a = c[order[k]].box;
    for (std::uint32_t l = k + 1; l < n && c[order[l]].box.lo.x <= a.hi.x + d; ++l) {
      const Aabb& b = c[order[l]].box;
      if (b.lo.y <= a.hi.y + d && a.lo.y <= b.hi.y + d && b.lo.z <= a.hi.z + d && a.lo.z <= b.hi.z + d)
        parent[find(parent, order[k])] = find(parent, order[l]);
    }
  }
  std::vector<std::vector<std::uint32_t>> sets(n);
  for (std::uint32_t i = 0; i < n; ++i) sets[find(parent, i)].push_back(i);
  for (auto& s : sets)
    if (!s.empty()) result.groups.push_back(make_group(result, std::move(s)));
  std::sort(result.groups.begin(), result.groups.end(),
            [](const ClashGroup& x, const ClashGroup& y) { return x.clashes.front() < y.clashes.front(); });
}

}  // namespace interfere::scene::detail
