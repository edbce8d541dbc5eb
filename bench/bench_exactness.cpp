// "Exactness beside the peers" (issue #2: FCL's double triangle test reports false pairs on
// coplanar contact and misses a part lying wholly inside another). The engine's row of each
// exactness scene of common.h; peer_fcl.cpp and peer_cgal.cpp run the same scenes.
//   Exact/<scene>/interfere   meshes in memory -> both default trees with statistics (needed for
//                             containment) -> the default clash() (exact test with cross/touch
//                             classification, regions, containment); all threads of the run
// Counters: pairs, cross, touch, containment (the Containment enumerator: 0 none, 1 a_inside_b,
// 2 b_inside_a, 3 not_checked), interference (ClashResult::interference()), tris_a, tris_b. The
// pair list is checked against exact_scene_reference() (the same exact test on binned-SAH trees);
// a difference is reported as an error, since both are the engine's exact answer.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <optional>
#include <string>

#include "common.h"
#include "interfere/query/clash.h"

namespace interfere::bench {
namespace {

void bm_exact_interfere(benchmark::State& state, const std::string& scene, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const ExactScene& sc = exact_scene(scene);
  std::optional<Model> ma, mb;
  ClashResult r;
  for (auto _ : state) {
    state.PauseTiming();
    ma.reset(), mb.reset(), r = ClashResult{};
    TriMesh a = sc.a, b = sc.b;
    state.ResumeTiming();
    ma.emplace(make_model(std::move(a), BvhBuildOptions{}, true));
    mb.emplace(make_model(std::move(b), BvhBuildOptions{}, true));
    r = clash(*ma, *mb, ClashRequest{});
    benchmark::DoNotOptimize(r.pairs.data());
  }
  PairList pairs;
  pairs.reserve(r.pairs.size());
  for (const TrianglePair& tp : r.pairs) pairs.emplace_back(tp.a, tp.b);
  const PairDiff d = diff_pairs(pairs, exact_scene_reference(scene));
  if (d.extra || d.missing) {
    state.SkipWithError("default tree and binned-SAH tree disagree on the exact pair list");
  }
  const std::size_t na = sc.a.num_triangles(), nb = sc.b.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (na + nb)));
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
  state.counters["cross"] = static_cast<double>(r.cross_pairs);
  state.counters["touch"] = static_cast<double>(r.touch_pairs);
  state.counters["candidates"] = static_cast<double>(r.candidate_pairs);
  state.counters["regions"] = static_cast<double>(r.regions.size());
  state.counters["containment"] = static_cast<double>(static_cast<int>(r.containment));
  state.counters["interference"] = r.interference() ? 1 : 0;
  state.counters["warnings"] = static_cast<double>(r.warnings.size());
  state.counters["tris_a"] = static_cast<double>(na);
  state.counters["tris_b"] = static_cast<double>(nb);
  state.counters["threads"] = static_cast<double>(threads);
}

[[maybe_unused]] const bool registered = [] {
  std::size_t max_threads = 1;
  for (std::size_t t : thread_counts()) max_threads = std::max(max_threads, t);
  for (const std::string& scene : exact_scene_names()) {
    benchmark::RegisterBenchmark(
        ("Exact/" + scene + "/interfere").c_str(),
        [scene, max_threads](benchmark::State& s) { bm_exact_interfere(s, scene, max_threads); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
