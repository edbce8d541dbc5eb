// The distribution plan (plan.h; issue #31, items 2 and 6).
#include "plan.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

#include "interfere/scene/engine.h"

namespace interfere::mpi {

AabbF broad_box(const Aabb& local, const Transform& t) {
  return scene::broad_box(local, t);  // the engine's own: the plan finds the engine's candidates
}

BroadResult broad_phase(const std::vector<scene::Body>& bodies, const std::vector<scene::ClashTest>& tests,
                        const std::vector<std::vector<AabbF>>& boxes, std::size_t uncounted) {
  BroadResult r;
  scene::BroadPhase broad(bodies, tests);
  r.warnings = broad.warnings();
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> found;  // (a, b, frame)
  for (std::size_t f = 0; f < boxes.size(); ++f) {
    std::size_t counted = 0, suppressed = 0;
    for (const scene::CandidatePair& c : broad.candidates(boxes[f], counted, suppressed))
      found.emplace_back(c.a, c.b, static_cast<std::uint32_t>(f));
    if (f >= uncounted) r.candidate_pairs += counted, r.suppressed += suppressed;
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  for (const auto& [a, b, f] : found) {
    if (r.units.empty() || r.units.back().a != a || r.units.back().b != b)
      r.units.push_back({.a = a, .b = b, .item = static_cast<std::uint32_t>(r.units.size())});
    ++r.units.back().frames;
  }
  return r;
}

namespace {

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

std::uint64_t spread(std::uint64_t v) {  // 21 bits -> every third bit
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// Morton codes of the box centres in the boxes' bounds.
std::vector<std::uint64_t> morton(const std::vector<AabbF>& boxes) {
  Aabb all;
  for (const AabbF& b : boxes) all.expand(Vec3{b.lo[0], b.lo[1], b.lo[2]}), all.expand(Vec3{b.hi[0], b.hi[1], b.hi[2]});
  std::vector<std::uint64_t> code(boxes.size(), 0);
  const Vec3 ext = all.extent();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    std::uint64_t q[3];
    const double c[3] = {0.5 * (double(boxes[i].lo[0]) + boxes[i].hi[0]), 0.5 * (double(boxes[i].lo[1]) + boxes[i].hi[1]),
                         0.5 * (double(boxes[i].lo[2]) + boxes[i].hi[2])};
    const double lo[3] = {all.lo.x, all.lo.y, all.lo.z}, e[3] = {ext.x, ext.y, ext.z};
    for (int k = 0; k < 3; ++k) q[k] = e[k] > 0 ? static_cast<std::uint64_t>(std::clamp((c[k] - lo[k]) / e[k], 0.0, 1.0) * 2097151.0) : 0;
    code[i] = spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2;
  }
  return code;
}

struct Piece {
  std::vector<std::uint32_t> items;
  std::vector<std::uint32_t> bodies;  // sorted
  double cost = 0;                    // its items' (the bodies' are counted where they are placed)
};

}  // namespace

void join_classes(BroadResult& broad, const std::vector<std::uint64_t>& mesh_key,
                  const std::vector<std::vector<Transform>>& poses) {
  Dsu dsu(broad.units.size());
  // Only units whose two mesh keys another unit shares can join (most products: few). A hash of
  // the two keys: a collision only lets a unit through to the exact comparison below.
  const auto pair_hash = [&](const Unit& u) { return mesh_key[u.a] * 0x9e3779b97f4a7c15ULL ^ (mesh_key[u.b] + 0x632be59bd9b4e019ULL); };
  std::unordered_map<std::uint64_t, std::uint32_t> mesh_pairs;
  mesh_pairs.reserve(broad.units.size());
  for (const Unit& u : broad.units) ++mesh_pairs[pair_hash(u)];
  std::vector<std::uint32_t> shared;
  for (std::uint32_t k = 0; k < broad.units.size(); ++k)
    if (mesh_pairs.at(pair_hash(broad.units[k])) > 1) shared.push_back(k);
  for (const std::vector<Transform>& pose : poses) {
    std::map<std::tuple<std::uint64_t, std::uint64_t, std::array<double, 12>>, std::uint32_t> first;
    for (const std::uint32_t k : shared) {
      const Unit& u = broad.units[k];
      const auto key = std::tuple{mesh_key[u.a], mesh_key[u.b], scene::relative_pose_key(pose[u.a], pose[u.b])};
      const auto [it, added] = first.emplace(key, k);
      if (!added) dsu.join(it->second, k);
    }
  }
  std::vector<std::uint32_t> number(broad.units.size(), UINT32_MAX);
  std::uint32_t items = 0;
  for (std::uint32_t k = 0; k < broad.units.size(); ++k) {
    const std::uint32_t root = dsu.find(k);
    if (number[root] == UINT32_MAX) number[root] = items++;
    broad.units[k].item = number[root];
  }
}

double pair_cost(std::uint64_t na, std::uint64_t nb) { return CostModel{}.pair(na, nb); }

Partition partition(const BroadResult& broad, const std::vector<AabbF>& boxes, const std::vector<std::uint64_t>& triangles,
                    const CostModel& model, std::size_t ranks, const std::vector<std::uint32_t>& reader) {
  Partition out;
  const std::size_t n = boxes.size();
  ranks = std::max<std::size_t>(ranks, 1);
  // Items: their units and cost. The units of a class share one core run: the costliest member's
  // cost, and 2 % of each other member's (its clashes mapped to its bodies).
  std::uint32_t item_count = 0;
  for (const Unit& u : broad.units) item_count = std::max(item_count, u.item + 1);
  std::vector<std::vector<std::uint32_t>> item_units(item_count);
  for (std::uint32_t k = 0; k < broad.units.size(); ++k) item_units[broad.units[k].item].push_back(k);
  std::vector<double> item_cost(item_count, 0);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    double sum = 0, most = 0;
    for (const std::uint32_t k : item_units[i]) sum += broad.units[k].cost, most = std::max(most, broad.units[k].cost);
    item_cost[i] = most + 0.02 * (sum - most);
  }
  // Components of the candidate graph (a class joins its pairs' bodies too).
  Dsu dsu(n);
  for (const std::vector<std::uint32_t>& units : item_units)
    for (const std::uint32_t k : units) dsu.join(broad.units[k].a, broad.units[k].b), dsu.join(broad.units[k].a, broad.units[units[0]].a);
  std::vector<std::uint32_t> comp_of(n, UINT32_MAX);
  std::vector<std::vector<std::uint32_t>> comp_items;  // in order of their first item
  for (std::uint32_t i = 0; i < item_count; ++i) {
    const std::uint32_t root = dsu.find(broad.units[item_units[i][0]].a);
    if (comp_of[root] == UINT32_MAX) comp_of[root] = static_cast<std::uint32_t>(comp_items.size()), comp_items.emplace_back();
    comp_items[comp_of[root]].push_back(i);
  }
  const auto bodies_of = [&](const std::vector<std::uint32_t>& items) {
    std::vector<std::uint32_t> b;
    for (const std::uint32_t i : items)
      for (const std::uint32_t k : item_units[i]) b.push_back(broad.units[k].a), b.push_back(broad.units[k].b);
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    return b;
  };
  std::vector<double> body_cost(n);
  std::vector<double> read_cost(n);
  for (std::size_t i = 0; i < n; ++i) {
    body_cost[i] = model.body(i < triangles.size() ? triangles[i] : 0);
    read_cost[i] = reader.empty() ? 0.0 : model.read(i < triangles.size() ? triangles[i] : 0);
  }
  double total = 0;
  std::vector<double> comp_cost(comp_items.size(), 0);
  std::vector<std::vector<std::uint32_t>> comp_bodies(comp_items.size());
  for (std::size_t c = 0; c < comp_items.size(); ++c) {
    comp_bodies[c] = bodies_of(comp_items[c]);
    for (const std::uint32_t i : comp_items[c]) comp_cost[c] += item_cost[i];
    for (const std::uint32_t b : comp_bodies[c]) comp_cost[c] += body_cost[b];
    total += comp_cost[c];
  }
  const double limit = ranks > 1 ? total / static_cast<double>(4 * ranks) : total + 1;
  const std::vector<std::uint64_t> code = morton(boxes);
  std::vector<Piece> pieces;
  for (std::size_t c = 0; c < comp_items.size(); ++c) {
    if (comp_cost[c] <= limit || comp_items[c].size() == 1) {
      Piece p;
      p.items = comp_items[c], p.bodies = comp_bodies[c];
      for (const std::uint32_t i : p.items) p.cost += item_cost[i];
      pieces.push_back(std::move(p));
      continue;
    }
    // Cut: the bodies in Morton order, each item owned by its first body there; runs of bodies
    // holding about `limit` (their owned items and their own cost) are pieces.
    std::vector<std::uint32_t> order = comp_bodies[c];
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return std::tie(code[x], x) < std::tie(code[y], y); });
    std::vector<std::uint32_t> rank_in(n, 0);
    for (std::uint32_t k = 0; k < order.size(); ++k) rank_in[order[k]] = k;
    std::vector<std::vector<std::uint32_t>> owned(order.size());
    for (const std::uint32_t i : comp_items[c]) {
      std::uint32_t owner = UINT32_MAX;
      for (const std::uint32_t k : item_units[i])
        owner = std::min({owner, rank_in[broad.units[k].a], rank_in[broad.units[k].b]});
      owned[owner].push_back(i);
    }
    Piece p;
    double acc = 0;
    for (std::uint32_t k = 0; k < order.size(); ++k) {
      for (const std::uint32_t i : owned[k]) p.items.push_back(i), p.cost += item_cost[i], acc += item_cost[i];
      acc += body_cost[order[k]];
      if (acc >= limit && !p.items.empty()) {
        p.bodies = bodies_of(p.items);
        pieces.push_back(std::move(p));
        p = {}, acc = 0;
      }
    }
    if (!p.items.empty()) p.bodies = bodies_of(p.items), pieces.push_back(std::move(p));
  }
  out.pieces = pieces.size();
  // Placement: costliest first, each to the rank where it ends earliest (its cost plus the body
  // cost of the bodies that rank does not hold yet), among the least loaded rank and the ranks
  // holding one of its bodies.
  std::vector<std::uint32_t> order(pieces.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    double cx = pieces[x].cost, cy = pieces[y].cost;
    for (const std::uint32_t b : pieces[x].bodies) cx += body_cost[b];
    for (const std::uint32_t b : pieces[y].bodies) cy += body_cost[b];
    return cx > cy;
  });
  out.rank_cost.assign(ranks, 0);
  std::set<std::pair<double, std::uint32_t>> by_load;
  for (std::uint32_t r = 0; r < ranks; ++r) by_load.emplace(0.0, r);
  std::vector<std::vector<std::uint32_t>> holders(n);  // ranks holding a body
  std::vector<std::uint32_t> rank_of_piece(pieces.size(), 0);
  for (const std::uint32_t pi : order) {
    const Piece& p = pieces[pi];
    std::vector<std::uint32_t> cand{by_load.begin()->second};
    for (const std::uint32_t b : p.bodies) {
      cand.insert(cand.end(), holders[b].begin(), holders[b].end());
      if (b < reader.size() && reader[b] < ranks) cand.push_back(reader[b]);
    }
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    std::uint32_t best = cand[0];
    double best_end = 0;
    for (std::size_t k = 0; k < cand.size(); ++k) {
      const std::uint32_t r = cand[k];
      double end = out.rank_cost[r] + p.cost;
      for (const std::uint32_t b : p.bodies)
        if (std::find(holders[b].begin(), holders[b].end(), r) == holders[b].end())
          end += body_cost[b] + (b < reader.size() && reader[b] == r ? 0.0 : read_cost[b]);
      if (k == 0 || end < best_end) best = r, best_end = end;
    }
    by_load.erase({out.rank_cost[best], best});
    out.rank_cost[best] = best_end;
    by_load.emplace(best_end, best);
    for (const std::uint32_t b : p.bodies)
      if (std::find(holders[b].begin(), holders[b].end(), best) == holders[b].end()) holders[b].push_back(best);
    rank_of_piece[pi] = best;
  }
  out.rank_units.assign(ranks, {});
  out.rank_bodies.assign(ranks, {});
  for (std::uint32_t pi = 0; pi < pieces.size(); ++pi) {
    const std::uint32_t r = rank_of_piece[pi];
    for (const std::uint32_t i : pieces[pi].items) out.rank_units[r].insert(out.rank_units[r].end(), item_units[i].begin(), item_units[i].end());
  }
  for (std::uint32_t b = 0; b < n; ++b)
    for (const std::uint32_t r : holders[b]) out.rank_bodies[r].push_back(b);
  for (std::vector<std::uint32_t>& u : out.rank_units) std::sort(u.begin(), u.end());
  return out;
}

std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes) {
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

}  // namespace interfere::mpi
