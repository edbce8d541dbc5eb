// The paper's strategy table on FE parts (issue #26, item 6; Deng et al. 2018, §2.1, Table 2):
// the same strategies as bench_strategies.cpp (sphere pairs), on the surfaces of a gmsh-generated
// FE assembly resembling the paper's CFETR parts (fem_strategy_parts.h: a vacuum-vessel sector of hex8 and
// a port duct of tet4 crossing its wall), loaded by read_fem + extract_surface. Part A is the
// vessel, part B the port. Each row changes one thing against the row it builds on:
//   1   brute force, Möller                        (paper 1)
//   2   1 with Guigue–Devillers                    (paper 2)
//   3   2 with per-triangle box pre-test           (paper 3, the paper's test kept)
//   3x  3 with the exact test                      (side row: the test alone)
//   4   3 with an insertion-built tree             (paper 4)
//   5   4 with the median-split tree               (paper 5, "optimised" tree)
//   5x  5 with the binned-SAH tree                 (side row: the builder alone)
//   6   5 traversed in parallel                    (paper 6; the paper ran 4 threads)
//   7   6 with the exact test
//   8   7 on the engine's default tree (lbvh)
//   9   8 with the engine's default request (regions, curves, containment): the engine default
// Rows 1–5x run serially (one thread); 6–9 at each INTERFERE_BENCH_THREADS count. Rows 1–8 time
// clash() with regions and containment off (the pair list); trees are prebuilt, their builds are
// the Build/ rows; Load/ is read_fem + extract_surface of the cached .msh.
//
// Environment: INTERFERE_BENCH_FEM_SIZES (surface triangles per part, default "1e4,1e5,3e5"; add
// 1e6 for the largest scale: gmsh writes it in about half a minute, cached afterwards),
// INTERFERE_BENCH_BRUTE_MAX (default 1e4) and INTERFERE_BENCH_PRETEST_MAX (default 1e5): the O(n²)
// rows above them are left out; INTERFERE_BENCH_THREADS; INTERFERE_BENCH_FEM_CACHE (fem_strategy_parts.h).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common.h"
#include "fem_strategy_parts.h"
#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"
#include "strategy_bench.h"

namespace interfere::bench {
namespace {

/// Trees of the assembly built with `builder` (no statistics), once per process.
const ModelPair& fem_models(std::size_t n, BvhBuilder builder) {
  static std::mutex mutex;
  static std::map<std::pair<std::size_t, int>, std::unique_ptr<ModelPair>> cache;
  const FemAssembly& fa = fem_assembly(n);
  std::lock_guard lock(mutex);
  auto& slot = cache[{n, static_cast<int>(builder)}];
  if (!slot) {
    const BvhBuildOptions options{.builder = builder};
    slot = std::make_unique<ModelPair>(
        ModelPair{make_model(fa.vessel, options, false), make_model(fa.port, options, false)});
  }
  return *slot;
}

/// The exact pair list of the assembly (binned-SAH trees, exact test), once per process.
const PairList& fem_reference(std::size_t n) {
  static std::mutex mutex;
  static std::map<std::size_t, PairList> cache;
  const FemAssembly& fa = fem_assembly(n);
  std::lock_guard lock(mutex);
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, exact_pairs(fa.vessel, fa.port)).first;
  return it->second;
}

void bm_strategy(benchmark::State& state, std::size_t n, const StrategyRow& row,
                 ClashRequest request, std::size_t threads) {
  const ModelPair& m = fem_models(n, row.builder);
  // The trees are built without statistics; the surfaces' own (computed at load) stand in where
  // the request needs closedness (containment, touching overlap), as the scene engine's lazy ones.
  const FemAssembly& fa = fem_assembly(n);
  request.stats = [&fa](int side) -> const MeshStats& {
    return side == 0 ? fa.vessel_stats : fa.port_stats;
  };
  const ClashResult r = run_clash_query(state, m.a, m.b, request, threads);
  state.counters["warnings"] = static_cast<double>(r.warnings.size());
  state.counters["clash_verdict"] = r.verdict == Verdict::clash ? 1 : 0;
  // The row's pair list against the exact one (the double tests may differ on touching pairs).
  PairList pairs;
  pairs.reserve(r.pairs.size());
  for (const TrianglePair& tp : r.pairs) pairs.emplace_back(tp.a, tp.b);
  std::sort(pairs.begin(), pairs.end());
  const PairDiff d = diff_pairs(pairs, fem_reference(n));
  state.counters["extra"] = static_cast<double>(d.extra);
  state.counters["missing"] = static_cast<double>(d.missing);
}

void bm_build(benchmark::State& state, std::size_t n, BvhBuilder builder, std::size_t threads) {
  const FemAssembly& fa = fem_assembly(n);
  run_tree_build(state, fa.vessel, fa.port, builder, threads);
}

/// read_fem + extract_surface + the part checks of the cached file (the user's path to the
/// surfaces).
void bm_load(benchmark::State& state, std::size_t n) {
  const FemAssembly& fa = fem_assembly(n);  // generates the file if needed, untimed
  std::size_t tris = 0;
  for (auto _ : state) {
    const FemAssembly loaded = load_fem_assembly(fa.file);
    tris = loaded.vessel.num_triangles() + loaded.port.num_triangles();
    benchmark::DoNotOptimize(tris);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tris));
  state.counters["tris_a"] = static_cast<double>(fa.vessel.num_triangles());
  state.counters["tris_b"] = static_cast<double>(fa.port.num_triangles());
  state.counters["hex8"] = static_cast<double>(fa.hex_elements);
  state.counters["tet4"] = static_cast<double>(fa.tet_elements);
  state.counters["nodes"] = static_cast<double>(fa.nodes);
  state.counters["volume_a"] = fa.vessel_volume;
  state.counters["volume_a_analytic"] = fa.vessel_volume_analytic;
  state.counters["volume_b"] = fa.port_volume;
  state.counters["volume_b_analytic"] = fa.port_volume_analytic;
  state.counters["gmsh_seconds"] = fa.generate_seconds;
}

void add(const std::string& name, std::function<void(benchmark::State&)> fn, int repetitions) {
  benchmark::RegisterBenchmark(name.c_str(), std::move(fn))
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Repetitions(repetitions);
}

[[maybe_unused]] const bool registered = [] {
  const std::size_t brute_max = env_size("INTERFERE_BENCH_BRUTE_MAX", 10000);
  const std::size_t pretest_max = env_size("INTERFERE_BENCH_PRETEST_MAX", 100000);
  const std::vector<std::size_t> sizes =
      env_sizes("INTERFERE_BENCH_FEM_SIZES", {10000, 100000, 300000});
  const std::vector<std::size_t> threads = thread_counts();
  const int reps = target_repetitions();
  constexpr BvhBuilder kMedian = BvhBuilder::median_split;
  const BvhBuilder kDefault = BvhBuildOptions{}.builder;

  // Rows 1–3x never touch a tree; the median-split trees they are handed go unused.
  const StrategyRow serial_rows[] = {
      {"1_brute_force_moller", TriTest::moller, Broadphase::brute_force, kMedian, false},
      {"2_brute_force_guigue_devillers", TriTest::guigue_devillers, Broadphase::brute_force,
       kMedian, false},
      {"3_box_pretest_guigue_devillers", TriTest::guigue_devillers, Broadphase::box_pretest,
       kMedian, false},
      {"3x_box_pretest_exact", TriTest::exact, Broadphase::box_pretest, kMedian, false},
      {"4_insertion_tree", TriTest::guigue_devillers, Broadphase::bvh, BvhBuilder::insertion,
       false},
      {"5_median_split_tree", TriTest::guigue_devillers, Broadphase::bvh, kMedian, false},
      {"5x_sah_tree", TriTest::guigue_devillers, Broadphase::bvh, BvhBuilder::binned_sah, false},
  };
  const StrategyRow parallel_rows[] = {
      {"6_median_split_tree_parallel", TriTest::guigue_devillers, Broadphase::bvh, kMedian, true},
      {"7_exact_test", TriTest::exact, Broadphase::bvh, kMedian, true},
      {"8_default_tree", TriTest::exact, Broadphase::bvh, kDefault, true},
  };
  const StrategyRow engine_default{"9_engine_default", TriTest::exact, Broadphase::bvh, kDefault,
                                   true};

  for (std::size_t n : sizes) {
    const std::string sn = size_label(n);
    add("Load/read_fem_extract_surface/" + sn, [n](benchmark::State& s) { bm_load(s, n); }, reps);
    for (const BvhBuilder b : {BvhBuilder::insertion, kMedian, BvhBuilder::binned_sah, kDefault}) {
      for (std::size_t t : threads) {
        // The paper's builders (insertion, median) are serial.
        if ((b == BvhBuilder::insertion || b == kMedian) && t != 1) continue;
        add("Build/" + std::string(bvh_builder_name(b)) + "/" + sn + "/threads:" +
                std::to_string(t),
            [n, b, t](benchmark::State& s) { bm_build(s, n, b, t); }, reps);
      }
    }
    for (const StrategyRow& row : serial_rows) {
      if (strategy_capped(row, n, brute_max, pretest_max)) continue;
      add("Strategy/" + std::string(row.name) + "/" + sn,
          [n, row](benchmark::State& s) { bm_strategy(s, n, row, strategy_request(row), 1); },
          reps);
    }
    for (std::size_t t : threads) {
      for (const StrategyRow& row : parallel_rows) {
        add("Strategy/" + std::string(row.name) + "/" + sn + "/threads:" + std::to_string(t),
            [n, row, t](benchmark::State& s) { bm_strategy(s, n, row, strategy_request(row), t); },
            reps);
      }
      add("Strategy/" + std::string(engine_default.name) + "/" + sn + "/threads:" +
              std::to_string(t),
          [n, row = engine_default, t](benchmark::State& s) {
            bm_strategy(s, n, row, ClashRequest{}, t);
          },
          reps);
    }
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
