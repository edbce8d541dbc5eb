// The two-stage MAAG decomposition of He & Xu (SJTU 2023) §2.2 used for matching (issue #29, item 1):
// split the AAG at inner-loop arcs (SG1), match each subgraph against the library, split the
// unmatched ones at convex arcs (SG2) and match again. Two matchers side by side: exact attributed
// graph isomorphism (backtracking over bijections) and the paper's procedure (steps 1-5: equal node
// and arc counts; Flag(i, j) when node i of one graph and node j of the other have equal attributes
// and equal first-order arcs; isomorphic when every node of each graph has a flagged partner), which
// accepts graphs that are not isomorphic (e.g. two 3-regular graphs on six nodes: the prism and K3,3).
#include <algorithm>
#include <functional>
#include <map>
#include <numeric>
#include <set>

#include "aag_merge.h"
#include "interfere/cad/features.h"

namespace interfere::cad {
namespace {

// A pattern's own graph: its non-shared roles and the arcs among them.
struct Core {
  std::vector<const PatternNode*> nodes;
  std::vector<std::pair<std::size_t, std::size_t>> arcs;  // node indices
  std::vector<const PatternArc*> arc_attr;
};

Core core_of(const FeaturePattern& p) {
  std::set<std::string> shared;
  for (const PatternCheck& ck : p.checks)
    if (ck.kind == "__shared") shared.insert(ck.roles[0]);
  Core c;
  std::map<std::string, std::size_t> index;
  for (const PatternNode& n : p.nodes)
    if (!shared.count(n.role)) index[n.role] = c.nodes.size(), c.nodes.push_back(&n);
  for (const PatternArc& a : p.arcs) {
    auto x = index.find(a.a), y = index.find(a.b);
    if (x == index.end() || y == index.end()) continue;
    c.arcs.push_back({x->second, y->second});
    c.arc_attr.push_back(&a);
  }
  return c;
}

// A subgraph: nodes (merged AAG ids) and its arcs, one per neighbouring pair (the first arc's attributes).
struct Sub {
  std::vector<std::uint32_t> nodes;
  std::map<std::pair<std::size_t, std::size_t>, const AagArc*> arcs;  // local indices, first < second
  std::vector<std::vector<std::size_t>> adj;
};

Sub make_sub(const Aag& g, const std::vector<std::uint32_t>& nodes, const std::vector<char>& arc_on) {
  Sub s;
  s.nodes = nodes;
  std::map<std::uint32_t, std::size_t> local;
  for (std::size_t i = 0; i < nodes.size(); ++i) local[nodes[i]] = i;
  s.adj.resize(nodes.size());
  for (std::size_t k = 0; k < g.arcs.size(); ++k) {
    if (!arc_on[k]) continue;
    const AagArc& a = g.arcs[k];
    auto x = local.find(a.a), y = local.find(a.b);
    if (x == local.end() || y == local.end()) continue;
    const auto key = std::minmax(x->second, y->second);
    if (s.arcs.emplace(std::pair{key.first, key.second}, &a).second) s.adj[x->second].push_back(y->second), s.adj[y->second].push_back(x->second);
  }
  return s;
}

bool node_attr_ok(const AagNode& n, const PatternNode& p) {
  if (std::find(p.types.begin(), p.types.end(), n.type) == p.types.end()) return false;
  return p.hole < 0 || int(n.hole) == p.hole;
}
bool arc_attr_ok(const AagArc& a, const PatternArc& p) {
  if (!p.curves.empty() && std::find(p.curves.begin(), p.curves.end(), a.curve) == p.curves.end()) return false;
  return p.convexity.empty() || std::find(p.convexity.begin(), p.convexity.end(), a.convexity) != p.convexity.end();
}

const AagArc* sub_arc(const Sub& s, std::size_t i, std::size_t j) {
  auto it = s.arcs.find(std::minmax(i, j));
  return it == s.arcs.end() ? nullptr : it->second;
}
const PatternArc* core_arc(const Core& c, std::size_t i, std::size_t j) {
  for (std::size_t k = 0; k < c.arcs.size(); ++k)
    if ((c.arcs[k].first == i && c.arcs[k].second == j) || (c.arcs[k].first == j && c.arcs[k].second == i)) return c.arc_attr[k];
  return nullptr;
}

bool exact_extend(const Aag& g, const Sub& s, const Core& c, std::vector<std::size_t>& map, std::vector<char>& used) {
  const std::size_t k = map.size();
  if (k == c.nodes.size()) return true;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    if (used[i] || !node_attr_ok(g.nodes[s.nodes[i]], *c.nodes[k])) continue;
    bool ok = true;
    for (std::size_t q = 0; q < k && ok; ++q) {
      const AagArc* a = sub_arc(s, i, map[q]);
      const PatternArc* p = core_arc(c, k, q);
      ok = (a == nullptr) == (p == nullptr) && (!a || arc_attr_ok(*a, *p));
    }
    if (!ok) continue;
    used[i] = 1, map.push_back(i);
    if (exact_extend(g, s, c, map, used)) return true;
    used[i] = 0, map.pop_back();
  }
  return false;
}

// First-order arcs of sub node i and core node j equal: as many, and the sub's arcs assignable one to
// one to pattern arcs that accept them (bipartite matching by augmenting paths; a handful of arcs).
bool first_order_equal(const Sub& s, std::size_t i, const Core& c, std::size_t j) {
  std::vector<const PatternArc*> pj;
  for (std::size_t k = 0; k < c.arcs.size(); ++k)
    if (c.arcs[k].first == j || c.arcs[k].second == j) pj.push_back(c.arc_attr[k]);
  std::vector<const AagArc*> si;
  for (std::size_t q : s.adj[i]) si.push_back(sub_arc(s, i, q));
  if (pj.size() != si.size()) return false;
  std::vector<int> owner(pj.size(), -1);
  std::function<bool(std::size_t, std::vector<char>&)> augment = [&](std::size_t a, std::vector<char>& seen) {
    for (std::size_t b = 0; b < pj.size(); ++b) {
      if (seen[b] || !arc_attr_ok(*si[a], *pj[b])) continue;
      seen[b] = 1;
      if (owner[b] < 0 || augment(std::size_t(owner[b]), seen)) return owner[b] = int(a), true;
    }
    return false;
  };
  for (std::size_t a = 0; a < si.size(); ++a) {
    std::vector<char> seen(pj.size(), 0);
    if (!augment(a, seen)) return false;
  }
  return true;
}

bool matches(const Aag& g, const Sub& s, const Core& c, GraphMatch method) {
  // Step 1: node and arc counts.
  if (c.nodes.empty() || s.nodes.size() != c.nodes.size() || s.arcs.size() != c.arcs.size()) return false;
  if (method == GraphMatch::exact) {
    std::vector<std::size_t> map;
    std::vector<char> used(s.nodes.size(), 0);
    return exact_extend(g, s, c, map, used);
  }
  // Steps 2-5.
  std::vector<char> row(s.nodes.size(), 0), col(c.nodes.size(), 0);
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    for (std::size_t j = 0; j < c.nodes.size(); ++j)
      if (node_attr_ok(g.nodes[s.nodes[i]], *c.nodes[j]) && first_order_equal(s, i, c, j)) row[i] = col[j] = 1;
  return std::all_of(row.begin(), row.end(), [](char x) { return x != 0; }) &&
         std::all_of(col.begin(), col.end(), [](char x) { return x != 0; });
}

// Connected components of `nodes` over the arcs switched on.
std::vector<std::vector<std::uint32_t>> components(const Aag& g, const std::vector<std::uint32_t>& nodes,
                                                   const std::vector<char>& arc_on) {
  std::map<std::uint32_t, std::uint32_t> parent;
  for (std::uint32_t n : nodes) parent[n] = n;
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t k = 0; k < g.arcs.size(); ++k) {
    if (!arc_on[k] || !parent.count(g.arcs[k].a) || !parent.count(g.arcs[k].b)) continue;
    const std::uint32_t x = find(g.arcs[k].a), y = find(g.arcs[k].b);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
  }
  std::map<std::uint32_t, std::vector<std::uint32_t>> groups;
  for (std::uint32_t n : nodes) groups[find(n)].push_back(n);
  std::vector<std::vector<std::uint32_t>> out;
  for (auto& [r, v] : groups) out.push_back(std::move(v));
  return out;
}

}  // namespace

std::vector<MaagSubgraph> maag_decomposition(const Aag& input, const FeatureLibrary& library, GraphMatch method,
                                             double tolerance) {
  const detail::MergedAag merged = detail::merge_split_faces(input, tolerance);
  const Aag& g = merged.aag;
  std::vector<Core> cores;
  for (const FeaturePattern& p : library.patterns) cores.push_back(core_of(p));
  auto first_match = [&](const Sub& s) -> std::string {
    for (std::size_t k = 0; k < cores.size(); ++k)
      if (matches(g, s, cores[k], method)) return library.patterns[k].type;
    return {};
  };
  // (1) SG1: every arc but those on inner loops.
  std::vector<char> stage1(g.arcs.size()), stage2(g.arcs.size());
  for (std::size_t k = 0; k < g.arcs.size(); ++k) {
    const AagArc& a = g.arcs[k];
    stage1[k] = !(a.inner_loop_a || a.inner_loop_b);
    stage2[k] = stage1[k] && a.convexity != Convexity::convex;
  }
  std::vector<std::uint32_t> all(g.nodes.size());
  std::iota(all.begin(), all.end(), 0u);
  std::vector<MaagSubgraph> out;
  auto emit = [&](const std::vector<std::uint32_t>& nodes, int stage, std::string type) {
    MaagSubgraph m;
    for (std::uint32_t n : nodes) m.faces.insert(m.faces.end(), merged.members[n].begin(), merged.members[n].end());
    std::sort(m.faces.begin(), m.faces.end());
    m.stage = stage, m.type = std::move(type);
    out.push_back(std::move(m));
  };
  for (const auto& sg1 : components(g, all, stage1)) {
    // (2) match SG1's subgraph as it is.
    std::string type = first_match(make_sub(g, sg1, stage1));
    if (!type.empty()) {
      emit(sg1, 1, type);
      continue;
    }
    // (3) the unmatched: split at convex arcs, match again.
    for (const auto& sg2 : components(g, sg1, stage2)) emit(sg2, 2, first_match(make_sub(g, sg2, stage2)));
  }
  std::sort(out.begin(), out.end(), [](const MaagSubgraph& a, const MaagSubgraph& b) { return a.faces < b.faces; });
  return out;
}

}  // namespace interfere::cad
