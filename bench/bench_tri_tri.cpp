// Triangle–triangle microbenchmarks on realistic inputs: every box-overlapping pair harvested from
// the 1e5 sphere pair (the candidates the narrow phase really sees; most lie near the intersection
// curve). Target (issue #2): the exact yes/no test costs <= 1.5x the double Guigue–Devillers test.
#include <benchmark/benchmark.h>

#include <array>
#include <vector>

#include "common.h"
#include "interfere/bvh/traverse.h"
#include "interfere/np/tri_tri.h"

namespace interfere::bench {
namespace {

struct Candidates {
  std::vector<std::array<Vec3, 3>> a, b;
};

const Candidates& candidates() {
  static const Candidates c = [] {
    const std::size_t n = env_size("INTERFERE_BENCH_TRITRI_SIZE", 100000);
    const ModelPair& m = model_pair(n, BvhBuilder::binned_sah);
    Candidates out;
    for_each_overlap(m.a.bvh, m.b.bvh, 0.0f, [&](std::uint32_t ia, std::uint32_t ib) {
      out.a.push_back(m.a.mesh.corners(ia));
      out.b.push_back(m.b.mesh.corners(ib));
    });
    return out;
  }();
  return c;
}

template <class Test>
void run_test(benchmark::State& state, Test test) {
  const Candidates& c = candidates();
  const std::size_t n = c.a.size();
  std::size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (std::size_t i = 0; i < n; ++i) hits += test(c.a[i], c.b[i]) ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["pairs"] = static_cast<double>(n);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["ns_per_pair"] =
      benchmark::Counter(static_cast<double>(state.iterations() * n),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_TriTri_exact_intersects(benchmark::State& state) {
  run_test(state, [](const auto& a, const auto& b) { return tri_tri_exact_intersects(a, b); });
}
void BM_TriTri_exact_classify(benchmark::State& state) {
  run_test(state, [](const auto& a, const auto& b) {
    return tri_tri_exact(a, b).kind != ContactKind::none;
  });
}
void BM_TriTri_guigue_devillers(benchmark::State& state) {
  run_test(state, [](const auto& a, const auto& b) { return tri_tri_guigue_devillers(a, b); });
}
void BM_TriTri_moller(benchmark::State& state) {
  run_test(state, [](const auto& a, const auto& b) { return tri_tri_moller(a, b); });
}

[[maybe_unused]] const bool registered = [] {
  for (auto [name, fn] : {std::pair{"BM_TriTri_exact_intersects", &BM_TriTri_exact_intersects},
                          std::pair{"BM_TriTri_exact_classify", &BM_TriTri_exact_classify},
                          std::pair{"BM_TriTri_guigue_devillers", &BM_TriTri_guigue_devillers},
                          std::pair{"BM_TriTri_moller", &BM_TriTri_moller}}) {
    benchmark::RegisterBenchmark(name, fn)
        ->Unit(benchmark::kMicrosecond)
        ->Repetitions(target_repetitions());
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
