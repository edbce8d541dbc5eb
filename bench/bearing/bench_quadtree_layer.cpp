// The quadtree's calculation layer (Jia & Zheng 2019, §2.4; issue #27): the paper's rule (the
// highest nodes whose leaves all lie inside the range, the default) against the project's former
// rule (the deepest nodes still spanning the window), for the paper's quadtree method
// (vertex_quadtree_method) on a scarred roller with the scar in range (every node in the window is
// then searched exhaustively) and on an intact one (greedy descent), 32^2..64^2 vertices, and
// for two windows: the paper's range of Eq. (1) (half-width theta/2) and the former, narrower
// contact_turn_bound. Counters: the layer, vertices evaluated per call, and the largest error
// against the vertex brute force (the minimum over every vertex, which the method approximates).
// Run: build/bench/interfere_bench_quadtree_layer (docs/bearing.md, "Calculation layer").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"
#include "interfere/bearing/window.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kR = 30, kr = 10, kH = 40, kAlpha = 1.0 * kDeg, kGap = -0.05;

Cylinder partner() {
  Cylinder b;
  b.base = {0, 0, 0.5 * kH - 30}, b.axis = {0, 0, 1}, b.height = 60, b.radius = kR;
  return b;
}

// The poses of bench_bearing.cpp's Table 1: the scar (body angle 180 degrees) faces the partner,
// spin swept back and forth over +-32 degrees, slow tilt walk within alpha.
std::vector<Transform> poses() {
  std::vector<Transform> out;
  SplitMix64 g{5};
  double tx = 0.3, ty = 0.2;
  for (int f = 0; f < 256; ++f) {
    tx = std::clamp(tx + 0.05 * g.symmetric(), -0.7, 0.7), ty = std::clamp(ty + 0.05 * g.symmetric(), -0.7, 0.7);
    const double spin = (f < 128 ? f - 64 : 192 - f) * 0.5 * kDeg;
    out.push_back(roller_pose({kR + kr + kGap, 0, 0}, kAlpha * std::hypot(tx, ty), std::atan2(ty, tx), spin));
  }
  return out;
}

void BM_CalculationLayer(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto rule = state.range(1) == 0 ? CalculationLayerRule::paper : CalculationLayerRule::spanning_window;
  const bool paper_window = state.range(2) == 0;
  const bool scar = state.range(3) != 0;
  Roller roller = *make_roller({.radius = kr, .height = kH, .radial_segments = n, .height_segments = n - 1});
  if (scar)
    (void)apply_scar(roller, {.angle_center_deg = 180, .angle_width_deg = 60, .z_min = 0, .z_max = kH, .depth = 0.1,
                            .roughness = 0.6, .border = 2, .seed = 7});
  const RollerQuadtree tree = build_quadtree(roller, {.layer_rule = rule});
  const WindowParams wp{.roller_radius = kr, .partner_radius = kR, .height = kH, .max_tilt = kAlpha};
  const double window = paper_window ? interference_window(wp) : contact_turn_bound(wp);
  const Cylinder b = partner();
  const std::vector<Transform> ps = poses();
  double max_error = 0, evaluated = 0;
  for (const Transform& p : ps) {
    const MeshPairResult q = vertex_quadtree_method(roller, tree, p, b, window);
    max_error = std::max(max_error, std::fabs(q.distance - vertex_brute_force(roller, p, b).distance));
    evaluated += q.evaluated;
  }
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vertex_quadtree_method(roller, tree, ps[k], b, window));
    k = (k + 1) % ps.size();
  }
  state.SetLabel(std::string(rule == CalculationLayerRule::paper ? "paper_rule" : "spanning_rule") +
                 (paper_window ? "/window=theta/2" : "/window=contact_turn") + (scar ? "/scarred" : "/intact"));
  state.counters["layer"] = tree.calculation_layer(window, n);
  state.counters["evaluated"] = evaluated / static_cast<double>(ps.size());
  state.counters["max_error"] = max_error;
}

void Args(benchmark::internal::Benchmark* b) {
  for (const int n : {32, 48, 64})
    for (const int rule : {0, 1})
      for (const int window : {0, 1})
        for (const int scar : {1, 0}) b->Args({n, rule, window, scar});
}
BENCHMARK(BM_CalculationLayer)->Apply(Args)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
