// Penetration depth maps (issue #26, item 3; query/depth.h depth_maps): per surface vertex of each of
// two clashing FE bodies, the depth inside the other. Part of the per-step target of issue #26,
// item 7 (refit + clash + depth map of the clashing region <= 30 ms on 2 cores).
//
// The bodies: a hex8 box [0,1]^3 of n^3 cells and a hex8 ball of radius 0.5 (n^3 cells), its centre
// over the box's top face, sunk s/1000 into it: 12 n^2 surface triangles each (n = 55: 36,300;
// n = 100: 120,000). The default rows keep a few thousand vertices inside: n = 55 sunk 0.17 (about
// 3,000 of the ball's surface vertices inside the box, 1,300 of the box's inside the ball) and
// n = 100 sunk 0.05; n = 100 sunk 0.17 (about 14,600 inside) shows the cost per inside vertex.
//
//   BM_DepthMap/<n>/<s>/<threads>      depth_maps of the clash (the clash computed once, outside)
//   BM_DepthMapStep/<n>/<s>/<threads>  one step: refit both trees (the ball moved to one of 11 sink
//                                      depths, 0.6 s to 1.4 s, cycled), clash, depth_maps
//
// Environment: INTERFERE_BENCH_THREADS (thread counts).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <map>
#include <memory>
#include <string>

#include "common.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"

namespace interfere::bench {
namespace {

struct DepthScene {
  TriMesh box, ball;  // the ball's surface centred at the origin
  std::unique_ptr<std::pair<Model, Model>> models;
};

TriMesh surface_of(const FemMesh& m) { return std::move(extract_surface(m)->parts.at(0).mesh); }

std::vector<Vec3> ball_at(const TriMesh& ball, double sink) {
  std::vector<Vec3> p = ball.positions;
  for (Vec3& v : p) v = v + Vec3{0.5, 0.5, 1.5 - sink};
  return p;
}

DepthScene& cached_scene(int n, double sink) {
  static std::map<std::pair<int, double>, std::unique_ptr<DepthScene>> cache;
  auto& slot = cache[{n, sink}];
  if (!slot) {
    slot = std::make_unique<DepthScene>();
    DepthScene& s = *slot;
    const FemBoxOptions o{.type = ElemType::hex8, .nx = n, .ny = n, .nz = n};
    s.box = surface_of(make_fem_box(o).mesh);
    s.ball = surface_of(make_fem_sphere(o, 0.5).mesh);
    TriMesh placed = s.ball;
    placed.positions = ball_at(s.ball, sink);
    s.models = std::make_unique<std::pair<Model, Model>>(make_models(s.box, std::move(placed)));
  }
  return *slot;
}

void counters(benchmark::State& state, const DepthScene& s, const DepthMaps& m, int threads) {
  state.counters["triangles_box"] = static_cast<double>(s.box.num_triangles());
  state.counters["triangles_ball"] = static_cast<double>(s.ball.num_triangles());
  state.counters["inside_box_vertices"] = static_cast<double>(m.a.inside);
  state.counters["inside_ball_vertices"] = static_cast<double>(m.b.inside);
  state.counters["max_depth"] = std::max(m.a.max_depth, m.b.max_depth);
  state.counters["threads"] = threads;
}

void BM_DepthMap(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), threads = static_cast<int>(state.range(2));
  const double sink = 0.001 * static_cast<double>(state.range(1));
  DepthScene& s = cached_scene(n, sink);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const Model &a = s.models->first, &b = s.models->second;
  const ClashResult r = clash(a, b);
  DepthMaps m;
  for (auto _ : state) {
    m = depth_maps(a, b, r);
    benchmark::DoNotOptimize(m);
  }
  counters(state, s, m, threads);
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
  state.SetLabel("depth_maps of both bodies, clash given");
}

void BM_DepthMapStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), threads = static_cast<int>(state.range(2));
  const double sink = 0.001 * static_cast<double>(state.range(1));
  DepthScene& s = cached_scene(n, sink);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Model &a = s.models->first, &b = s.models->second;
  DepthMaps m;
  int step = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<Vec3> pa = s.box.positions, pb = ball_at(s.ball, sink * (0.6 + 0.08 * step));
    state.ResumeTiming();
    refit(a, std::move(pa));
    refit(b, std::move(pb));
    const ClashResult r = clash(a, b);
    m = depth_maps(a, b, r);
    benchmark::DoNotOptimize(m);
    step = (step + 1) % 11;
  }
  counters(state, s, m, threads);
  state.SetLabel("refit + clash + depth_maps per step");
  refit(b, ball_at(s.ball, sink));  // (as BM_DepthMap expects it)
}

void register_depth_map() {
  for (const auto& [n, sink] : std::vector<std::pair<long, long>>{{55, 170}, {100, 50}, {100, 170}})
    for (std::size_t th : thread_counts()) {
      const std::vector<long> args{n, sink, static_cast<long>(th)};
      benchmark::RegisterBenchmark("BM_DepthMap", BM_DepthMap)->Args(args)->Unit(benchmark::kMillisecond)->UseRealTime();
      benchmark::RegisterBenchmark("BM_DepthMapStep", BM_DepthMapStep)
          ->Args(args)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
}

const int kRegistered = (register_depth_map(), 0);

}  // namespace
}  // namespace interfere::bench
