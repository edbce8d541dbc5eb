// The distribution plan (plan.h; issue #31, item 2).
#include "plan.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "engine_internal.h"
#include "interfere/bvh/traverse.h"

namespace interfere::mpi {

AabbF broad_box(const Aabb& local, const Transform& t) {
  return scene::detail::broad_box(local, t);  // the engine's own: the plan finds the engine's candidates
}

namespace {

bool pair_matches(const scene::Selection& x, const scene::Selection& y, const scene::Body& p, const scene::Body& q) {
  return (scene::selects(x, p) && scene::selects(y, q)) || (scene::selects(x, q) && scene::selects(y, p));
}

double test_margin(const scene::ClashTest& t) {
  double m = t.mode == scene::ClashMode::duplicates ? t.tolerance : 0;
  if (t.mode == scene::ClashMode::clearance) {
    m = t.clearance;
    for (const scene::ClearanceOverride& o : t.clearance_overrides) m = std::max(m, o.clearance);
  }
  return m;
}

// Pairs (x in a, y in other, x != y) with boxes_overlap(box x, box y, margin): the engine's own
// traversal (engine.cpp: a box tree per selection, detail::build_box_tree, and for_each_overlap).
void overlaps(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& other, bool within,
              const std::vector<AabbF>& box, float margin, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) {
  const auto boxes_of = [&](const std::vector<std::uint32_t>& sel) {
    std::vector<AabbF> b(sel.size());
    for (std::size_t i = 0; i < sel.size(); ++i) b[i] = box[sel[i]];
    return b;
  };
  const Bvh tree_a = scene::detail::build_box_tree(boxes_of(a));
  const Bvh tree_b = within ? Bvh{} : scene::detail::build_box_tree(boxes_of(other));
  for_each_overlap(tree_a, within ? tree_a : tree_b, margin, [&](std::uint32_t x, std::uint32_t y) {
    if (a[x] != other[y]) out.emplace_back(a[x], other[y]);
  });
}

}  // namespace

BroadResult broad_phase(const std::vector<scene::Body>& bodies, const std::vector<scene::ClashTest>& tests,
                        const std::vector<std::vector<AabbF>>& boxes, std::size_t uncounted) {
  BroadResult r;
  const auto n = static_cast<std::uint32_t>(bodies.size());
  std::vector<std::vector<std::uint32_t>> sel_a(tests.size()), sel_b(tests.size());
  for (std::size_t k = 0; k < tests.size(); ++k) {
    const scene::ClashTest& t = tests[k];
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scene::selects(t.a, bodies[i])) sel_a[k].push_back(i);
      if (!t.b.empty() && scene::selects(t.b, bodies[i])) sel_b[k].push_back(i);
    }
    if (sel_a[k].empty()) r.warnings.push_back("clash test '" + t.name + "': selection A selects no body");
    if (!t.b.empty() && sel_b[k].empty()) r.warnings.push_back("clash test '" + t.name + "': selection B selects no body");
  }
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> found;  // (a, b, frame)
  for (std::size_t f = 0; f < boxes.size(); ++f) {
    for (std::size_t k = 0; k < tests.size(); ++k) {
      const scene::ClashTest& t = tests[k];
      std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
      overlaps(sel_a[k], t.b.empty() ? sel_a[k] : sel_b[k], t.b.empty(), boxes[f], round_up(test_margin(t)), pairs);
      for (auto& [u, v] : pairs)
        if (bodies[v].id < bodies[u].id) std::swap(u, v);
      std::sort(pairs.begin(), pairs.end());
      pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
      const bool counted = f >= uncounted;
      if (counted) r.candidate_pairs += pairs.size();
      for (const auto& [u, v] : pairs) {
        bool suppressed = false;
        for (const scene::Suppression& s : t.suppressions) suppressed = suppressed || pair_matches(s.a, s.b, bodies[u], bodies[v]);
        if (suppressed) {
          r.suppressed += counted;
          continue;
        }
        found.emplace_back(u, v, static_cast<std::uint32_t>(f));
      }
    }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  for (const auto& [a, b, f] : found) {
    if (r.units.empty() || r.units.back().a != a || r.units.back().b != b) r.units.push_back({.a = a, .b = b});
    ++r.units.back().frames;
  }
  return r;
}

double pair_cost(std::uint64_t na, std::uint64_t nb) {
  // A fixed estimate, linear in the triangles (what balances memory and reading too). Not the
  // fitted model of docs/scaling.md (tools/mpi_scaling.py), whose per-pair term is far larger on
  // its sphere products, where half the candidates clash and carry a depth bound.
  return 2e-5 + 2.5e-7 * static_cast<double>(na + nb);
}

namespace {

std::uint64_t spread(std::uint64_t v) {  // 21 bits -> every third bit
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

struct Dsu {
  std::vector<std::uint32_t> p;
  explicit Dsu(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

namespace {

void finish(Block& b, const BroadResult& broad) {
  for (const std::uint32_t k : b.units) b.bodies.push_back(broad.units[k].a), b.bodies.push_back(broad.units[k].b);
  std::sort(b.bodies.begin(), b.bodies.end());
  b.bodies.erase(std::unique(b.bodies.begin(), b.bodies.end()), b.bodies.end());
  std::sort(b.units.begin(), b.units.end());
}

Block merged(const std::vector<const Block*>& parts) {
  Block m;
  for (const Block* p : parts) {
    m.bodies.insert(m.bodies.end(), p->bodies.begin(), p->bodies.end());
    m.units.insert(m.units.end(), p->units.begin(), p->units.end());
    m.cost += p->cost;
  }
  std::sort(m.bodies.begin(), m.bodies.end());
  m.bodies.erase(std::unique(m.bodies.begin(), m.bodies.end()), m.bodies.end());
  std::sort(m.units.begin(), m.units.end());
  return m;
}

}  // namespace

Partition partition(const BroadResult& broad, const std::vector<AabbF>& boxes, std::size_t ranks) {
  Partition out;
  const std::size_t n = boxes.size();
  ranks = std::max<std::size_t>(ranks, 1);
  Dsu dsu(n);
  double total = 0;
  for (const Unit& u : broad.units) dsu.join(u.a, u.b), total += u.cost;
  const double piece_limit = ranks > 1 ? total / static_cast<double>(4 * ranks) : total + 1;
  // Components in order of their smallest body.
  std::vector<std::vector<std::uint32_t>> comp_units;
  std::vector<std::uint32_t> comp_of(n, UINT32_MAX);
  for (std::uint32_t k = 0; k < broad.units.size(); ++k) {
    const std::uint32_t root = dsu.find(broad.units[k].a);
    if (comp_of[root] == UINT32_MAX) comp_of[root] = static_cast<std::uint32_t>(comp_units.size()), comp_units.emplace_back();
    comp_units[comp_of[root]].push_back(k);
  }
  // Morton codes of the box centres in the scene's bounds.
  Aabb all;
  for (const AabbF& b : boxes) all.expand(Vec3{b.lo[0], b.lo[1], b.lo[2]}), all.expand(Vec3{b.hi[0], b.hi[1], b.hi[2]});
  std::vector<std::uint64_t> code(n, 0);
  const Vec3 ext = all.extent();
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t q[3];
    const double c[3] = {0.5 * (double(boxes[i].lo[0]) + boxes[i].hi[0]), 0.5 * (double(boxes[i].lo[1]) + boxes[i].hi[1]),
                         0.5 * (double(boxes[i].lo[2]) + boxes[i].hi[2])};
    const double lo[3] = {all.lo.x, all.lo.y, all.lo.z}, e[3] = {ext.x, ext.y, ext.z};
    for (int k = 0; k < 3; ++k) q[k] = e[k] > 0 ? static_cast<std::uint64_t>(std::clamp((c[k] - lo[k]) / e[k], 0.0, 1.0) * 2097151.0) : 0;
    code[i] = spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2;
  }
  std::vector<std::uint32_t> comp_of_block;  // component of every block
  std::vector<char> cross;                   // a pair between two groups
  std::vector<std::array<std::uint32_t, 2>> cross_groups;  // its two groups' blocks
  std::vector<char> cut(comp_units.size(), 0);
  for (std::uint32_t ci = 0; ci < comp_units.size(); ++ci) {
    const std::vector<std::uint32_t>& units = comp_units[ci];
    double cost = 0;
    for (const std::uint32_t k : units) cost += broad.units[k].cost;
    if (cost <= piece_limit || units.size() == 1) {
      Block b;
      b.units = units, b.cost = cost;
      finish(b, broad);
      out.blocks.push_back(std::move(b)), comp_of_block.push_back(ci), cross.push_back(0), cross_groups.push_back({0, 0});
      continue;
    }
    cut[ci] = 1;
    // Groups: runs of the Morton order of the component's bodies, each about piece_limit (a body's
    // cost: half of each of its pairs').
    std::vector<std::uint32_t> bodies;
    for (const std::uint32_t k : units) bodies.push_back(broad.units[k].a), bodies.push_back(broad.units[k].b);
    std::sort(bodies.begin(), bodies.end());
    bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
    std::vector<double> body_cost(bodies.size(), 0);
    for (const std::uint32_t k : units) {
      const Unit& u = broad.units[k];
      body_cost[std::lower_bound(bodies.begin(), bodies.end(), u.a) - bodies.begin()] += 0.5 * u.cost;
      body_cost[std::lower_bound(bodies.begin(), bodies.end(), u.b) - bodies.begin()] += 0.5 * u.cost;
    }
    std::vector<std::uint32_t> order(bodies.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
      return std::tie(code[bodies[x]], bodies[x]) < std::tie(code[bodies[y]], bodies[y]);
    });
    std::vector<std::uint32_t> group(n, 0);
    std::uint32_t groups = 0;
    double acc = 0;
    for (const std::uint32_t i : order) {
      group[bodies[i]] = groups;
      acc += body_cost[i];
      if (acc >= piece_limit) ++groups, acc = 0;
    }
    if (acc > 0) ++groups;
    const auto first = static_cast<std::uint32_t>(out.blocks.size());
    for (std::uint32_t g = 0; g < groups; ++g)
      out.blocks.emplace_back(), comp_of_block.push_back(ci), cross.push_back(0), cross_groups.push_back({0, 0});
    for (const std::uint32_t k : units) {
      const Unit& u = broad.units[k];
      if (group[u.a] == group[u.b]) {
        out.blocks[first + group[u.a]].units.push_back(k), out.blocks[first + group[u.a]].cost += u.cost;
      } else {
        Block b;
        b.units = {k}, b.cost = u.cost;
        out.blocks.push_back(std::move(b)), comp_of_block.push_back(ci), cross.push_back(1);
        cross_groups.push_back({first + group[u.a], first + group[u.b]});
      }
    }
  }
  for (Block& b : out.blocks) finish(b, broad);
  // Longest processing time first (groups and whole components), then the pairs between groups.
  std::vector<std::uint32_t> order;
  for (std::uint32_t k = 0; k < out.blocks.size(); ++k)
    if (!cross[k] && !out.blocks[k].units.empty()) order.push_back(k);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return out.blocks[x].cost > out.blocks[y].cost; });
  out.rank_cost.assign(ranks, 0);
  out.rank_of_block.assign(out.blocks.size(), 0);
  for (const std::uint32_t k : order) {
    const std::size_t r = static_cast<std::size_t>(std::min_element(out.rank_cost.begin(), out.rank_cost.end()) - out.rank_cost.begin());
    out.rank_of_block[k] = static_cast<std::uint32_t>(r);
    out.rank_cost[r] += out.blocks[k].cost;
  }
  // Pairs between groups, costliest first: to the less loaded of its groups' ranks unless that
  // rank would pass the mean load by 1 %, else to the least loaded rank.
  std::vector<std::uint32_t> crossing;
  for (std::uint32_t k = 0; k < out.blocks.size(); ++k)
    if (cross[k]) crossing.push_back(k);
  std::stable_sort(crossing.begin(), crossing.end(), [&](std::uint32_t x, std::uint32_t y) { return out.blocks[x].cost > out.blocks[y].cost; });
  const double cap = 1.01 * total / static_cast<double>(ranks);
  for (const std::uint32_t k : crossing) {
    const std::uint32_t r0 = out.rank_of_block[cross_groups[k][0]], r1 = out.rank_of_block[cross_groups[k][1]];
    std::uint32_t r = out.rank_cost[r1] < out.rank_cost[r0] ? r1 : r0;
    if (out.rank_cost[r] + out.blocks[k].cost > cap)
      r = static_cast<std::uint32_t>(std::min_element(out.rank_cost.begin(), out.rank_cost.end()) - out.rank_cost.begin());
    out.rank_of_block[k] = r;
    out.rank_cost[r] += out.blocks[k].cost;
  }
  // Engine calls per rank.
  out.calls.assign(ranks, {});
  std::vector<std::uint32_t> unit_rank(broad.units.size(), 0);
  for (std::uint32_t k = 0; k < out.blocks.size(); ++k)
    for (const std::uint32_t u : out.blocks[k].units) unit_rank[u] = out.rank_of_block[k];
  std::vector<std::vector<std::uint32_t>> adj(n);
  for (std::uint32_t k = 0; k < broad.units.size(); ++k) adj[broad.units[k].a].push_back(k);
  for (std::uint32_t r = 0; r < ranks; ++r) {
    std::vector<const Block*> whole;
    std::vector<std::vector<const Block*>> per_cut(comp_units.size());
    for (std::uint32_t k = 0; k < out.blocks.size(); ++k) {
      if (out.rank_of_block[k] != r || out.blocks[k].units.empty()) continue;
      if (cut[comp_of_block[k]]) per_cut[comp_of_block[k]].push_back(&out.blocks[k]);
      else whole.push_back(&out.blocks[k]);
    }
    if (!whole.empty()) out.calls[r].push_back(merged(whole));
    for (const std::vector<const Block*>& parts : per_cut) {
      if (parts.empty()) continue;
      Block m = merged(parts);
      bool foreign = false;  // a pair of another rank among the union's bodies
      std::vector<char> in(n, 0);
      for (const std::uint32_t i : m.bodies) in[i] = 1;
      for (const std::uint32_t i : m.bodies)
        for (const std::uint32_t k : adj[i]) foreign = foreign || (in[broad.units[k].b] && unit_rank[k] != r);
      if (!foreign) out.calls[r].push_back(std::move(m));
      else
        for (const Block* p : parts) out.calls[r].push_back(*p);
    }
  }
  return out;
}

std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes) {
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

}  // namespace interfere::mpi
