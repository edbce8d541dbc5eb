// FEM benchmarks (issue #3, item 7): boundary surface extraction throughput by element type and
// size (elements/s), and the per-step refit + clash of a 100-step series of two ~10^6-element
// parts. Meshes are generated (fem/generate.h), never read inside a timed region.
//
// Environment (optional):
//   INTERFERE_BENCH_FEM_SIZES   elements per mesh for the extraction rows, default "1e5,1e6"
//   INTERFERE_BENCH_FEM_BIG=1   adds 1e7-element tet4 extraction rows (about 2 GB of mesh)
//   INTERFERE_BENCH_FEM_STEP_ELEMENTS  elements per part of the series rows, default 1e6
//   INTERFERE_BENCH_THREADS     thread counts, default "1,2"
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "common.h"
#include "interfere/fem/deform.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"

namespace interfere::bench {
namespace {

// Cells per axis for about `elements` elements of this type in a cube.
int cells_for(ElemType t, std::size_t elements) {
  const FemBoxOptions o{.type = t};
  const double per_cell = fem_elements_per_cell(o);
  return std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(elements) / per_cell))));
}

const FemMesh& cached_box(ElemType t, std::size_t elements) {
  static std::map<std::pair<int, std::size_t>, std::unique_ptr<FemMesh>> cache;
  auto& slot = cache[{static_cast<int>(t), elements}];
  if (!slot) {
    const int n = cells_for(t, elements);
    slot = std::make_unique<FemMesh>(make_fem_box({.type = t, .nx = n, .ny = n, .nz = n}).mesh);
  }
  return *slot;
}

void BM_FemExtract(benchmark::State& state) {
  const auto type = static_cast<ElemType>(state.range(0));
  const auto elements = static_cast<std::size_t>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  const FemMesh& mesh = cached_box(type, elements);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::size_t tris = 0;
  for (auto _ : state) {
    auto r = extract_surface(mesh);
    tris = r->parts[0].mesh.num_triangles();
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::string(elem_info(type).name));
  state.counters["elements"] = static_cast<double>(mesh.num_elements());
  state.counters["threads"] = threads;
  state.counters["surface_triangles"] = static_cast<double>(tris);
  state.counters["elements_per_s"] =
      benchmark::Counter(static_cast<double>(mesh.num_elements()), benchmark::Counter::kIsIterationInvariantRate);
}

// Two parts: A a tet4 cube [0,1]^3, B a tet4 ball of radius 0.5 starting at x = 1.6 and moving
// toward A by 0.01 per step over 100 steps (it touches A at step 10 and is 0.9 deep at step 99).
struct Series {
  FemMesh a, b;
  SurfaceResult sa, sb;
  NodalSeries u;
  std::unique_ptr<std::pair<Model, Model>> models;
};

Series& cached_series(std::size_t elements) {
  static std::map<std::size_t, std::unique_ptr<Series>> cache;
  auto& slot = cache[elements];
  if (!slot) {
    slot = std::make_unique<Series>();
    Series& s = *slot;
    const int n = cells_for(ElemType::tet4, elements);
    s.a = make_fem_box({.type = ElemType::tet4, .nx = n, .ny = n, .nz = n}).mesh;
    s.b = make_fem_sphere({.type = ElemType::tet4, .nx = n, .ny = n, .nz = n}, 0.5, {1.6, 0.5, 0.5}).mesh;
    s.sa = std::move(*extract_surface(s.a));
    s.sb = std::move(*extract_surface(s.b));
    s.u.name = "u";
    for (int k = 0; k < 100; ++k) {
      s.u.times.push_back(k);
      s.u.values.emplace_back(s.b.num_nodes(), Vec3{-0.01 * k, 0, 0});
    }
    s.models = std::make_unique<std::pair<Model, Model>>(make_models(s.sa.parts[0].mesh, s.sb.parts[0].mesh));
  }
  return *slot;
}

void BM_FemSeriesStep(benchmark::State& state) {
  const auto elements = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Series& s = cached_series(elements);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::size_t step = 0, pairs = 0, clashing = 0, steps = 0;
  std::vector<Vec3> pa, pb;
  for (auto _ : state) {
    // One step as clash_series does it: gather the deformed positions, refit both trees, clash.
    deformed_positions(s.sa.parts[0], s.a, nullptr, step, 1.0, pa);
    deformed_positions(s.sb.parts[0], s.b, &s.u, step, 1.0, pb);
    refit(s.models->first, std::move(pa));
    refit(s.models->second, std::move(pb));
    const ClashResult r = clash(s.models->first, s.models->second);
    pairs += r.pairs.size();
    clashing += r.interference();
    ++steps;
    step = (step + 1) % 100;
    pa = {};
    pb = {};
  }
  state.counters["elements_a"] = static_cast<double>(s.a.num_elements());
  state.counters["elements_b"] = static_cast<double>(s.b.num_elements());
  state.counters["triangles_a"] = static_cast<double>(s.sa.parts[0].mesh.num_triangles());
  state.counters["triangles_b"] = static_cast<double>(s.sb.parts[0].mesh.num_triangles());
  state.counters["threads"] = threads;
  state.counters["mean_pairs"] = static_cast<double>(pairs) / static_cast<double>(std::max<std::size_t>(steps, 1));
  state.counters["clashing_fraction"] =
      static_cast<double>(clashing) / static_cast<double>(std::max<std::size_t>(steps, 1));
  state.SetLabel("refit + clash per step, 100-step series cycled");
}

void register_fem() {
  const std::vector<std::size_t> threads = env_sizes("INTERFERE_BENCH_THREADS", {1, 2});
  std::vector<std::size_t> sizes = env_sizes("INTERFERE_BENCH_FEM_SIZES", {100000, 1000000});
  const char* big = std::getenv("INTERFERE_BENCH_FEM_BIG");
  for (ElemType t : {ElemType::tet4, ElemType::tet10, ElemType::hex8, ElemType::hex20, ElemType::wedge6,
                     ElemType::pyr5}) {
    std::vector<std::size_t> s = sizes;
    if (big && std::string(big) == "1" && t == ElemType::tet4) s.push_back(10000000);
    for (std::size_t n : s) {
      for (std::size_t th : threads) {
        benchmark::RegisterBenchmark(("BM_FemExtract/" + std::string(elem_info(t).name)).c_str(), BM_FemExtract)
            ->Args({static_cast<long>(t), static_cast<long>(n), static_cast<long>(th)})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(0.5);
      }
    }
  }
  const std::size_t step_elements = env_size("INTERFERE_BENCH_FEM_STEP_ELEMENTS", 1000000);
  for (std::size_t th : threads) {
    benchmark::RegisterBenchmark("BM_FemSeriesStep", BM_FemSeriesStep)
        ->Args({static_cast<long>(step_elements), static_cast<long>(th)})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(100);
  }
}

const int kRegistered = (register_fem(), 0);

}  // namespace
}  // namespace interfere::bench
