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

// Lists of indices, one per item, stored flat: list i is flat[start[i] .. start[i + 1]).
struct Lists {
  std::vector<std::uint32_t> start, flat;
  struct Range {
    const std::uint32_t *b, *e;
    const std::uint32_t* begin() const { return b; }
    const std::uint32_t* end() const { return e; }
    std::uint32_t operator[](std::size_t k) const { return b[k]; }
  };
  Range operator[](std::size_t i) const { return {flat.data() + start[i], flat.data() + start[i + 1]}; }
};

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


}  // namespace

void join_classes(BroadResult& broad, const std::vector<std::uint64_t>& mesh_key,
                  const std::vector<std::vector<Transform>>& poses) {
  Dsu dsu(broad.units.size());
  // Only units whose two mesh keys another unit shares can join (most products: few). Two units
  // with the same two keys are either the same two bodies (a unit is one pair: no) or have a body
  // whose mesh key another body has too: units of two bodies with mesh keys of their own are left
  // out first (a product of distinct parts: every unit, without hashing the units at all). A hash
  // of the two keys: a collision only lets a unit through to the exact comparison below.
  std::vector<char> repeated(mesh_key.size(), 0);
  {
    std::vector<std::uint32_t> by_key(mesh_key.size());
    std::iota(by_key.begin(), by_key.end(), 0u);
    std::sort(by_key.begin(), by_key.end(), [&](std::uint32_t x, std::uint32_t y) { return mesh_key[x] < mesh_key[y]; });
    for (std::size_t i = 1; i < by_key.size(); ++i)
      if (mesh_key[by_key[i]] == mesh_key[by_key[i - 1]]) repeated[by_key[i]] = repeated[by_key[i - 1]] = 1;
  }
  const auto pair_hash = [&](const Unit& u) { return mesh_key[u.a] * 0x9e3779b97f4a7c15ULL ^ (mesh_key[u.b] + 0x632be59bd9b4e019ULL); };
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t k = 0; k < broad.units.size(); ++k)
    if (repeated[broad.units[k].a] || repeated[broad.units[k].b]) candidates.push_back(k);
  std::unordered_map<std::uint64_t, std::uint32_t> mesh_pairs;
  mesh_pairs.reserve(candidates.size());
  for (const std::uint32_t k : candidates) ++mesh_pairs[pair_hash(broad.units[k])];
  std::vector<std::uint32_t> shared;
  for (const std::uint32_t k : candidates)
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
                    const CostModel& model, std::size_t ranks, const std::vector<std::uint32_t>& reader, double first_extra) {
  Partition out;
  const std::size_t n = boxes.size();
  ranks = std::max<std::size_t>(ranks, 1);
  // Items: their units and cost. The units of a class share one core run: the costliest member's
  // cost, and 2 % of each other member's (its clashes mapped to its bodies).
  // (items' units and bodies as flat lists with offsets: a product has ~10^6 items, most a single
  // pair, whose lists one allocation each would cost more than the partition itself)
  std::uint32_t item_count = 0;
  for (const Unit& u : broad.units) item_count = std::max(item_count, u.item + 1);
  const Lists item_units = [&] {
    Lists l;
    l.start.assign(item_count + 1, 0);
    for (const Unit& u : broad.units) ++l.start[u.item + 1];
    for (std::uint32_t i = 0; i < item_count; ++i) l.start[i + 1] += l.start[i];
    l.flat.resize(broad.units.size());
    std::vector<std::uint32_t> next(l.start.begin(), l.start.end() - 1);
    for (std::uint32_t k = 0; k < broad.units.size(); ++k) l.flat[next[broad.units[k].item]++] = k;
    return l;
  }();
  std::vector<double> item_cost(item_count, 0);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    double sum = 0, most = 0;
    for (const std::uint32_t k : item_units[i]) sum += broad.units[k].cost, most = std::max(most, broad.units[k].cost);
    item_cost[i] = most + 0.02 * (sum - most);
  }
  // Components of the candidate graph (a class joins its pairs' bodies too).
  Dsu dsu(n);
  for (std::uint32_t i = 0; i < item_count; ++i)
    for (const std::uint32_t k : item_units[i])
      dsu.join(broad.units[k].a, broad.units[k].b), dsu.join(broad.units[k].a, broad.units[item_units[i][0]].a);
  std::vector<double> body_cost(n), read_cost(n);
  for (std::size_t i = 0; i < n; ++i) {
    body_cost[i] = model.body(i < triangles.size() ? triangles[i] : 0);
    read_cost[i] = reader.empty() ? 0.0 : model.read(i < triangles.size() ? triangles[i] : 0);
  }
  // Item weights: its cost and a share of its bodies' (each body's cost split among its items).
  std::vector<std::uint32_t> degree(n, 0);
  Lists item_bodies;
  item_bodies.start.reserve(item_count + 1);
  item_bodies.flat.reserve(2 * broad.units.size());
  item_bodies.start.push_back(0);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    const auto first = static_cast<std::ptrdiff_t>(item_bodies.flat.size());
    for (const std::uint32_t k : item_units[i]) item_bodies.flat.push_back(broad.units[k].a), item_bodies.flat.push_back(broad.units[k].b);
    std::sort(item_bodies.flat.begin() + first, item_bodies.flat.end());
    item_bodies.flat.erase(std::unique(item_bodies.flat.begin() + first, item_bodies.flat.end()), item_bodies.flat.end());
    item_bodies.start.push_back(static_cast<std::uint32_t>(item_bodies.flat.size()));
    for (const std::uint32_t x : item_bodies[i]) ++degree[x];
  }
  std::vector<double> weight(item_count);
  double total = 0;
  for (std::uint32_t i = 0; i < item_count; ++i) {
    weight[i] = item_cost[i];
    for (const std::uint32_t x : item_bodies[i]) weight[i] += body_cost[x] / degree[x];
    total += weight[i];
  }
  // Position of an item on the space-filling curve: its component's first body in Morton order
  // for a component costing at most total / (4 ranks) (kept together), else its own first body;
  // grouped first by the rank that read that body (step 2), so that chunks follow the readers.
  const std::vector<std::uint64_t> code = morton(boxes);
  const auto before = [&](std::uint32_t x, std::uint32_t y) {
    const std::uint32_t rx = reader.empty() ? 0 : reader[x], ry = reader.empty() ? 0 : reader[y];
    return std::tie(rx, code[x], x) < std::tie(ry, code[y], y);
  };
  std::vector<std::uint32_t> comp_first(n, UINT32_MAX);
  std::vector<double> comp_weight(n, 0);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    const std::uint32_t root = dsu.find(item_bodies[i][0]);
    comp_weight[root] += weight[i];
    for (const std::uint32_t x : item_bodies[i])
      if (comp_first[root] == UINT32_MAX || before(x, comp_first[root])) comp_first[root] = x;
  }
  const double small = ranks > 1 ? total / static_cast<double>(4 * ranks) : total + 1;
  std::vector<std::uint32_t> position(item_count);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    const std::uint32_t root = dsu.find(item_bodies[i][0]);
    std::uint32_t first = item_bodies[i][0];
    for (const std::uint32_t x : item_bodies[i])
      if (before(x, first)) first = x;
    position[i] = comp_weight[root] <= small ? comp_first[root] : first;
  }
  std::vector<std::uint32_t> order(item_count);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    if (position[x] != position[y]) return before(position[x], position[y]);
    return x < y;
  });
  // Giants first: an item heavier than the mean of what is left gets a rank of its own (the last
  // ranks); the rest of the curve is cut into runs over the other ranks below.
  std::vector<std::uint32_t> rank_of(item_count, UINT32_MAX);
  // (no item heavier than the mean, as in most products: no sort needed)
  const bool giants = ranks > 1 && std::any_of(weight.begin(), weight.end(), [&](double x) { return x > total / static_cast<double>(ranks); });
  std::vector<std::uint32_t> by_weight(giants ? item_count : 0);
  std::iota(by_weight.begin(), by_weight.end(), 0u);
  std::stable_sort(by_weight.begin(), by_weight.end(), [&](std::uint32_t x, std::uint32_t y) { return weight[x] > weight[y]; });
  double left = total;
  std::size_t free_ranks = ranks;
  for (const std::uint32_t i : by_weight) {
    if (free_ranks <= 1 || weight[i] <= left / static_cast<double>(free_ranks)) break;
    rank_of[i] = static_cast<std::uint32_t>(--free_ranks);
    left -= weight[i];
  }
  // The cut: runs of the curve over the other ranks minimising the busiest rank's true cost (its
  // items, every body it holds at full cost, reads of bodies another rank read first) - not the
  // weights above, in which a body at a run's border counts once though two ranks build it. The
  // cost of a run only grows as it takes items, so filling each run up to a bound C in curve
  // order gives the fewest runs for C (the linear-partition bottleneck problem); C is found by
  // bisection above the mean of the weights. Deterministic.
  std::vector<std::uint32_t> curve;
  for (const std::uint32_t i : order)
    if (rank_of[i] == UINT32_MAX) curve.push_back(i);
  std::vector<std::uint32_t> stamp(n, UINT32_MAX);  // the last run that holds a body
  // Rank 0 merges every rank's findings after its engine call (first_extra seconds): its run
  // starts that much full, so that it ends with the others (only when it takes part in the cut).
  const double extra = free_ranks > 1 ? first_extra : 0.0;
  const auto fill = [&](double bound, bool assign) {
    std::fill(stamp.begin(), stamp.end(), UINT32_MAX);
    std::uint32_t q = 0;
    double acc = extra;  // (rank 0's run starts with its work after the engine)
    std::size_t runs = curve.empty() ? 0 : 1;
    const auto added = [&](std::uint32_t i, std::uint32_t run) {
      double c = item_cost[i];
      for (const std::uint32_t x : item_bodies[i])
        if (stamp[x] != run) c += body_cost[x] + (!reader.empty() && reader[x] != run ? read_cost[x] : 0.0);
      return c;
    };
    for (const std::uint32_t i : curve) {
      double c = added(i, q);
      if (acc > 0 && acc + c > bound) {
        ++q, ++runs, acc = 0;
        if (q >= free_ranks && !assign) return runs;
        c = added(i, q);
      }
      for (const std::uint32_t x : item_bodies[i]) stamp[x] = q;
      acc += c;
      if (assign) rank_of[i] = std::min<std::uint32_t>(q, static_cast<std::uint32_t>(free_ranks - 1));
    }
    return runs;
  };
  double lo = extra, whole = extra;
  for (const std::uint32_t i : curve) {
    lo += weight[i];
    double c = item_cost[i];
    for (const std::uint32_t x : item_bodies[i]) c += body_cost[x] + read_cost[x];
    whole += c;
  }
  lo /= static_cast<double>(std::max<std::size_t>(free_ranks, 1));
  // (widened from 3 % above the mean weight by 25 % steps until feasible, then bisected to 0.1 %:
  // few fills where the border bodies are few, as for 2 ranks)
  double hi = std::min(whole, 1.03 * lo);
  while (hi < whole && fill(hi, false) > free_ranks) lo = hi, hi = std::min(whole, 1.25 * hi);
  for (int step = 0; step < 40 && hi > lo * (1 + 1e-3); ++step) {
    const double mid = 0.5 * (lo + hi);
    (fill(mid, false) <= free_ranks ? hi : lo) = mid;
  }
  const std::size_t runs = fill(hi, true);
  out.pieces = runs + (ranks - free_ranks);
  out.rank_units.assign(ranks, {});
  out.rank_bodies.assign(ranks, {});
  out.rank_cost.assign(ranks, 0);
  for (std::uint32_t i = 0; i < item_count; ++i) {
    const std::uint32_t q = rank_of[i];
    out.rank_units[q].insert(out.rank_units[q].end(), item_units[i].begin(), item_units[i].end());
    out.rank_cost[q] += item_cost[i];
    out.rank_bodies[q].insert(out.rank_bodies[q].end(), item_bodies[i].begin(), item_bodies[i].end());
  }
  for (std::size_t q = 0; q < ranks; ++q) {
    std::vector<std::uint32_t>& b = out.rank_bodies[q];
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    // (summed in body order, as before: the same rank_cost bit for bit)
    for (const std::uint32_t x : b) out.rank_cost[q] += body_cost[x] + (!reader.empty() && reader[x] != q ? read_cost[x] : 0.0);
  }
  for (std::vector<std::uint32_t>& u : out.rank_units) std::sort(u.begin(), u.end());
  return out;
}

std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes) {
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

}  // namespace interfere::mpi
