// The partitioner on a synthetic product (simulate.h; issue #31, item 6).
#include "simulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "plan.h"

namespace interfere::mpi {

int simulate(int argc, char** argv) {
  // Parameters (docs/scaling.md): the product and the fitted cost model.
  const CostModel defaults;
  double bodies = 1e5, triangles = 1e9, pair_s = defaults.pair_s, pair_tri_s = defaults.pair_tri_s,
         body_tri_s = defaults.body_tri_s, read_tri_s = 1e-7, body_bytes = 200,
         tri_bytes = 200, bandwidth = 5e9, sigma = 1.0, base_mb = 60;
  std::vector<double> ranks{8, 16, 32, 64, 128, 256, 512, 1024};
  for (int i = 0; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    const double v = std::stod(argv[i + 1]);
    if (k == "--bodies") bodies = v;
    else if (k == "--triangles") triangles = v;
    else if (k == "--pair-s") pair_s = v;
    else if (k == "--pair-tri-s") pair_tri_s = v;
    else if (k == "--body-tri-s") body_tri_s = v;
    else if (k == "--read-tri-s") read_tri_s = v;
    else if (k == "--tri-bytes") tri_bytes = v;
    else if (k == "--base-mb") base_mb = v;
    else if (k == "--bandwidth") bandwidth = v;
    else if (k == "--sigma") sigma = v;
    else if (k == "--ranks") ranks = {v};
    else {
      std::fprintf(stderr, "interfere: error: simulate: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const auto n = static_cast<std::uint32_t>(bodies);
  // Triangles per body: log-normal (sigma), scaled to the total; bodies on a cubic grid of pitch 1,
  // each a box of half-size 0.45..0.6 (so about half the grid neighbours overlap: ~3 pairs a body).
  std::mt19937_64 rng(31);
  std::lognormal_distribution<double> size(0.0, sigma);
  std::uniform_real_distribution<double> half(0.45, 0.6);
  std::vector<double> tri(n);
  double sum = 0;
  for (double& t : tri) sum += t = size(rng);
  std::vector<std::uint64_t> tris(n);
  for (std::uint32_t i = 0; i < n; ++i) tris[i] = std::max<std::uint64_t>(12, static_cast<std::uint64_t>(tri[i] / sum * triangles));
  const auto side = static_cast<std::uint32_t>(std::ceil(std::cbrt(static_cast<double>(n))));
  std::vector<scene::Body> meta(n);
  std::vector<AabbF> boxes(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    meta[i].id = "b" + std::to_string(1000000 + i);
    const Vec3 c{static_cast<double>(i % side), static_cast<double>((i / side) % side), static_cast<double>(i / side / side)};
    const double h = half(rng);
    Aabb b;
    b.lo = c - Vec3{h, h, h}, b.hi = c + Vec3{h, h, h};
    boxes[i] = to_float_outward(b);
  }
  const auto t0 = std::chrono::steady_clock::now();
  BroadResult broad = broad_phase(meta, {scene::ClashTest{}}, {boxes});
  const double broad_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The partition balances the fitted model (plan.h CostModel: per pair, per triangle of a pair,
  // per triangle of a body a rank holds), as a run given --cost-model does; a rank's modelled time
  // is its pairs' and bodies' cost.
  const CostModel model{.pair_s = pair_s, .pair_tri_s = pair_tri_s, .body_tri_s = body_tri_s};
  double total = 0;
  for (Unit& u : broad.units) total += u.cost = model.pair(tris[u.a], tris[u.b]);
  for (std::uint32_t i = 0; i < n; ++i) total += model.body(tris[i]);
  nlohmann::json out{{"bodies", n}, {"triangles", triangles}, {"candidate_pairs", broad.units.size()},
                     {"serial_pair_s", total}, {"broad_phase_s", broad_s},
                     {"model", {{"pair_s", pair_s}, {"pair_tri_s", pair_tri_s}, {"body_tri_s", body_tri_s}, {"read_tri_s", read_tri_s},
                                {"tri_bytes", tri_bytes}, {"body_bytes", body_bytes}, {"bandwidth", bandwidth}, {"base_mb", base_mb}}},
                     {"ranks", nlohmann::json::array()}};
  for (const double kd : ranks) {
    const auto k = static_cast<std::size_t>(kd);
    const auto t1 = std::chrono::steady_clock::now();
    const Partition p = partition(broad, boxes, tris, model, k);
    const double partition_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    const double mean_cost = total / static_cast<double>(k);
    const double max_cost = *std::max_element(p.rank_cost.begin(), p.rank_cost.end());
    double sum_cost = 0;  // (bodies held by two ranks counted twice: the halo's extra work)
    for (const double c : p.rank_cost) sum_cost += c;
    // Bodies and triangles each rank reads: its share in step 1 (n / k by size) and its pairs'.
    std::uint64_t max_tri = 0, max_bodies = 0, sum_bodies = 0;
    for (std::size_t r = 0; r < k; ++r) {
      std::uint64_t t = 0;
      for (const std::uint32_t i : p.rank_bodies[r]) t += tris[i];
      max_tri = std::max(max_tri, t), max_bodies = std::max<std::uint64_t>(max_bodies, p.rank_bodies[r].size());
      sum_bodies += p.rank_bodies[r].size();
    }
    const double share_tri = triangles / static_cast<double>(k);
    const double allgather_bytes = body_bytes * n;  // every rank receives every body's metadata
    const double time = (share_tri + static_cast<double>(max_tri)) * read_tri_s + broad_s + partition_s +
                        allgather_bytes / bandwidth * std::log2(static_cast<double>(k)) + max_cost;
    out["ranks"].push_back({{"ranks", k},
                            {"pieces", p.pieces},
                            {"max_rank_pair_s", max_cost},
                            {"mean_rank_pair_s", mean_cost},
                            {"imbalance", sum_cost > 0 ? max_cost / (sum_cost / static_cast<double>(k)) - 1 : 0},
                            {"over_ideal", mean_cost > 0 ? max_cost / mean_cost - 1 : 0},
                            {"halo_work", total > 0 ? sum_cost / total - 1 : 0},
                            {"max_bodies_read", max_bodies},
                            {"bodies_read_over_n", static_cast<double>(sum_bodies) / n},
                            {"max_triangles_read", max_tri},
                            {"allgather_bytes_per_rank", allgather_bytes},
                            {"memory_per_rank_gb", (base_mb * 1e6 + static_cast<double>(max_tri) * tri_bytes + allgather_bytes * 4) / 1e9},
                            {"partition_s", partition_s},
                            {"predicted_s", time}});
  }
  std::printf("%s\n", out.dump(1).c_str());
  return 0;
}

}  // namespace interfere::mpi
