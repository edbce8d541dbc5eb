// The paper's strategy table (issue #2 source, §4) on the same sphere pairs, then the default
// engine end to end. Build and query are timed separately:
//   Build/<builder>/<n>/threads:<t>        both trees one after the other (make_model, no
//                                          statistics), meshes copied untimed
//   Strategy/<k>_<name>/<n>[/threads:<t>]  the clash query only, trees prebuilt
//   Engine/query_default/<n>/threads:<t>   the default clash request alone, trees prebuilt
//   Engine/end_to_end/<n>/threads:<t>      meshes in memory -> both default trees, built
//                                          concurrently (make_models) -> clash with exact
//                                          classification, regions and curves -> sorted pair list
// Strategies 1 and 2 run the published double tests on all |A|·|B| pairs; 3 tests every pair's
// boxes first; 4–6 traverse two trees; 7 is 6 on the engine's default tree (LBVH). Rows 3–6 use the
// engine's exact test (the candidate count, not the triangle test, dominates there;
// bench_tri_tri.cpp compares the tests themselves). The O(n²) rows are capped
// (INTERFERE_BENCH_BRUTE_MAX, default 1e4, and INTERFERE_BENCH_PRETEST_MAX, default 1e5 triangles
// per part): at 1e5 a brute-force row is 1e10 triangle tests, minutes per iteration on one core;
// the box pre-test row does 1e10 box tests there, seconds.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <optional>
#include <string>

#include "common.h"
#include "interfere/query/clash.h"
#include "strategy_bench.h"

namespace interfere::bench {
namespace {

void bm_strategy(benchmark::State& state, std::size_t n, StrategyRow row, std::size_t threads) {
  const ModelPair& m = model_pair(n, row.builder);
  run_clash_query(state, m.a, m.b, strategy_request(row), threads);
}

/// The default request (exact + regions + curves + containment) on prebuilt default trees: the
/// query part of the end-to-end row.
void bm_query_default(benchmark::State& state, std::size_t n, std::size_t threads) {
  const ModelPair& m = model_pair(n, BvhBuildOptions{}.builder);
  run_clash_query(state, m.a, m.b, ClashRequest{}, threads);
}

void bm_build(benchmark::State& state, std::size_t n, BvhBuilder builder, std::size_t threads) {
  const SpherePair& p = sphere_pair(n);
  run_tree_build(state, p.a, p.b, builder, threads);
}

void bm_end_to_end(benchmark::State& state, std::size_t n, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const SpherePair& p = sphere_pair(n);
  std::optional<std::pair<Model, Model>> m;
  ClashResult r;
  for (auto _ : state) {
    state.PauseTiming();
    m.reset(), r = ClashResult{};  // freeing the previous run is not part of the query
    TriMesh a = p.a, b = p.b;
    state.ResumeTiming();
    m.emplace(make_models(std::move(a), std::move(b), BvhBuildOptions{}, false));
    r = clash(m->first, m->second, ClashRequest{});
    benchmark::DoNotOptimize(r.pairs.data());
  }
  const std::size_t na = p.a.num_triangles(), nb = p.b.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (na + nb)));
  set_pair_counters(state, r, na, nb);
  std::size_t curves = 0;
  double length = 0;
  for (const ClashRegion& g : r.regions) curves += g.curves.size(), length += g.curve_length;
  state.counters["regions"] = static_cast<double>(r.regions.size());
  state.counters["curves"] = static_cast<double>(curves);
  state.counters["curve_length"] = length;
  state.counters["threads"] = static_cast<double>(threads);
}

[[maybe_unused]] const bool registered = [] {
  const std::size_t brute_max = env_size("INTERFERE_BENCH_BRUTE_MAX", 10000);
  const std::size_t pretest_max = env_size("INTERFERE_BENCH_PRETEST_MAX", 100000);
  const std::vector<std::size_t> sizes = table_sizes();
  const std::vector<std::size_t> threads = thread_counts();

  const StrategyRow serial_rows[] = {
      {"1_brute_force_moller", TriTest::moller, Broadphase::brute_force, BvhBuilder::binned_sah,
       false},
      {"2_brute_force_guigue_devillers", TriTest::guigue_devillers, Broadphase::brute_force,
       BvhBuilder::binned_sah, false},
      {"3_box_pretest", TriTest::exact, Broadphase::box_pretest, BvhBuilder::binned_sah, false},
      {"4_insertion_tree", TriTest::exact, Broadphase::bvh, BvhBuilder::insertion, false},
      {"5_median_split_tree", TriTest::exact, Broadphase::bvh, BvhBuilder::median_split, false},
  };
  // (6) as in the paper's table: the split-optimised (here SAH) tree, traversed in parallel; then
  // the same query on the engine's default tree, whose build is the cheaper one.
  const StrategyRow parallel_rows[] = {
      {"6_sah_tree_parallel", TriTest::exact, Broadphase::bvh, BvhBuilder::binned_sah, true},
      {"7_default_tree_parallel", TriTest::exact, Broadphase::bvh, BvhBuildOptions{}.builder, true},
  };

  for (std::size_t n : sizes) {
    const std::string sn = size_label(n);
    for (const BvhBuilder b : {BvhBuilder::insertion, BvhBuilder::median_split,
                               BvhBuilder::binned_sah, BvhBuilder::lbvh}) {
      // The paper's builders (insertion, median) are timed on one thread; SAH and LBVH are
      // parallel.
      for (std::size_t t : threads) {
        if ((b == BvhBuilder::insertion || b == BvhBuilder::median_split) && t != 1) continue;
        benchmark::RegisterBenchmark(("Build/" + std::string(bvh_builder_name(b)) + "/" + sn +
                                      "/threads:" + std::to_string(t))
                                         .c_str(),
                                     [n, b, t](benchmark::State& s) { bm_build(s, n, b, t); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
    for (const StrategyRow& row : serial_rows) {
      if (strategy_capped(row, n, brute_max, pretest_max)) continue;
      benchmark::RegisterBenchmark(("Strategy/" + std::string(row.name) + "/" + sn).c_str(),
                                   [n, row](benchmark::State& s) { bm_strategy(s, n, row, 1); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    for (const StrategyRow& row : parallel_rows) {
      for (std::size_t t : threads) {
        benchmark::RegisterBenchmark(
            ("Strategy/" + std::string(row.name) + "/" + sn + "/threads:" + std::to_string(t))
                .c_str(),
            [n, row, t](benchmark::State& s) { bm_strategy(s, n, row, t); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
    for (std::size_t t : threads) {
      benchmark::RegisterBenchmark(
          ("Engine/query_default/" + sn + "/threads:" + std::to_string(t)).c_str(),
          [n, t](benchmark::State& s) { bm_query_default(s, n, t); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    for (std::size_t t : threads) {
      benchmark::RegisterBenchmark(
          ("Engine/end_to_end/" + sn + "/threads:" + std::to_string(t)).c_str(),
          [n, t](benchmark::State& s) { bm_end_to_end(s, n, t); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Repetitions(n >= 1000000 ? target_repetitions() : 1);
    }
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
