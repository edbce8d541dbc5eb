// The paper's strategy machinery (Deng et al. 2018, §2.1, Table 2; issue #2 source, §4), shared by
// bench_strategies.cpp (sphere pairs) and bench_fem_strategies.cpp (gmsh FE parts, issue #26 item
// 6): a row is one ClashRequest (triangle test, broad phase, parallel) on trees of one builder; the
// timed loops of a strategy query (trees prebuilt) and of a tree build (both parts, meshes copied
// untimed), and the counters every row reports.
#pragma once
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>

#include "interfere/bvh/bvh.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere::bench {

/// One row of the strategy table.
struct StrategyRow {
  const char* name;
  TriTest test;
  Broadphase broadphase;
  BvhBuilder builder;
  bool parallel;
};

/// The O(n²) rows are left out above their caps (triangles per part).
inline bool strategy_capped(const StrategyRow& row, std::size_t n, std::size_t brute_max,
                            std::size_t pretest_max) {
  return (row.broadphase == Broadphase::brute_force && n > brute_max) ||
         (row.broadphase == Broadphase::box_pretest && n > pretest_max);
}

inline void set_pair_counters(benchmark::State& state, const ClashResult& r, std::size_t na,
                              std::size_t nb) {
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
  state.counters["cross"] = static_cast<double>(r.cross_pairs);
  state.counters["touch"] = static_cast<double>(r.touch_pairs);
  state.counters["candidates"] = static_cast<double>(r.candidate_pairs);
  state.counters["tris_a"] = static_cast<double>(na);
  state.counters["tris_b"] = static_cast<double>(nb);
}

/// Times clash(a, b, request) on prebuilt trees with `threads` worker threads at most; returns the
/// last result.
inline ClashResult run_clash_query(benchmark::State& state, const Model& a, const Model& b,
                            const ClashRequest& request, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  ClashResult r;
  for (auto _ : state) {
    r = clash(a, b, request);
    benchmark::DoNotOptimize(r.pairs.data());
  }
  const std::size_t na = a.mesh.num_triangles(), nb = b.mesh.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (na + nb)));
  set_pair_counters(state, r, na, nb);
  state.counters["regions"] = static_cast<double>(r.regions.size());
  state.counters["threads"] = static_cast<double>(threads);
  return r;
}

/// The row's request: the pair list only (no regions, no containment), as in the paper's table.
inline ClashRequest strategy_request(const StrategyRow& row) {
  return ClashRequest{.test = row.test,
                      .broadphase = row.broadphase,
                      .parallel = row.parallel,
                      .regions = false,
                      .containment = false};
}

/// Times building both trees with `builder` (make_model, no statistics), one after the other; the
/// meshes are copied outside the timing.
inline void run_tree_build(benchmark::State& state, const TriMesh& a, const TriMesh& b,
                           BvhBuilder builder, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const BvhBuildOptions options{.builder = builder};
  std::optional<Model> ma, mb;
  for (auto _ : state) {
    state.PauseTiming();
    ma.reset(), mb.reset();
    TriMesh ca = a, cb = b;
    state.ResumeTiming();
    ma.emplace(make_model(std::move(ca), options, false));
    mb.emplace(make_model(std::move(cb), options, false));
    benchmark::DoNotOptimize(ma->bvh.nodes.data());
    benchmark::DoNotOptimize(mb->bvh.nodes.data());
  }
  const std::size_t nodes = ma ? ma->bvh.nodes.size() + mb->bvh.nodes.size() : 0;
  const std::size_t tris = a.num_triangles() + b.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tris));
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["threads"] = static_cast<double>(threads);
}

}  // namespace interfere::bench
