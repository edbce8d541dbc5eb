// The scarred solver against an intact frustum B (issue #27, scars on tapered rollers; scarred.h):
// one computation of a scarred tapered roller of 64 x 64 side vertices (radii 8 .. 9.5, length 30,
// a generated scar over 120 degrees between z 2 and 28, depth 0.04) against (a) a tapered bearing's
// cone raceway (a frustum of radii 40 .. 46 over 30 mm, the roller along its generator, pressed by
// -0.01 .. 0.05 mm, tilted up to 0.05 degrees, the scar facing the cone) and (b) an intact tapered
// neighbour side by side (axes parallel, gap -0.05 .. 0.05 at the large ends), on a cycle of 256
// poses; a fresh solver per computation hinted by the intact frustum pair's witness, as the
// assembly's rows (assembly_tapered_scars.cpp). For comparison: the same roller against a cylinder
// B of the cone's mean radius (the cylinder code path).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "interfere/bearing/raceway.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Setup {
  Roller roller;
  RollerQuadtree tree;
  Cylinder b;
  std::vector<Transform> poses;
};

Setup make_setup(int partner) {  // 0 cone, 1 neighbour, 2 cylinder
  Setup s;
  s.roller = *make_roller({.radius = 8, .top_radius = 9.5, .height = 30, .radial_segments = 64, .height_segments = 63});
  (void)apply_scar(s.roller, {.angle_center_deg = 180, .angle_width_deg = 120, .z_min = 2, .z_max = 28,
                              .depth = 0.04, .roughness = 0.6, .border = 2, .seed = 5});
  s.tree = build_quadtree(s.roller);
  s.b.base = {0, 0, -15}, s.b.axis = {0, 0, 1}, s.b.height = 30;
  if (partner == 1) s.b.radius = 8, s.b.top_radius = 9.5, s.b.base = {0, 0, 0};
  else if (partner == 2) s.b.radius = 43;
  else s.b.radius = 40, s.b.top_radius = 46;
  std::mt19937_64 gen(27);
  std::uniform_real_distribution<double> U(0, 1);
  const double k = partner == 0 ? 6.0 / 30 : 0.0, beta = std::atan(1.5 / 30);
  for (int i = 0; i < 256; ++i) {
    const double press = 0.06 * U(gen) - 0.01, tilt = 0.05 * kDeg * (2 * U(gen) - 1), spin = 0.2 * (U(gen) - 0.5);
    if (partner == 1) {  // beside the neighbour at +x, the scar (angle 180) facing it
      s.poses.push_back(roller_pose({19 - press, 0, 0}, tilt, 0.5 * std::numbers::pi, spin));
      continue;
    }
    // along the partner's generator on its +x side: lean = atan(k) - beta puts the roller's inner
    // generator parallel to the cone's
    const double lean = std::atan(k) - beta + tilt, r0 = partner == 0 ? 40 : 43;
    s.poses.push_back(roller_pose({r0 + 8 / std::cos(lean) - press, 0, -15}, lean, 0, spin));
  }
  return s;
}

void run(benchmark::State& state, int partner, bool hinted = true) {
  const Setup s = make_setup(partner);
  std::size_t i = 0;
  double evaluated = 0, count = 0, nodes = 0, fallbacks = 0, overlapping = 0;
  for (auto _ : state) {
    const Transform& pose = s.poses[i++ & 255];
    ScarredSolver solver(&s.roller, &s.tree);
    const MeshPairResult r =
        hinted ? solver.solve(pose, s.b, cone_pair_distance(posed_cylinder(8, 9.5, 30, pose), s.b).point_a)
               : solver.solve(pose, s.b);
    benchmark::DoNotOptimize(r);
    evaluated += r.evaluated, nodes += r.nodes_visited, fallbacks += r.fallbacks, count += 1;
    overlapping += r.distance < 0;
  }
  state.counters["triangles_evaluated"] = evaluated / std::max(count, 1.0);
  state.counters["nodes_visited"] = nodes / std::max(count, 1.0);
  state.counters["fallbacks"] = fallbacks / std::max(count, 1.0);
  state.counters["overlapping"] = overlapping / std::max(count, 1.0);
}

/// The hint alone (the intact frustum pair, cone_pair_distance): part of each computation above.
void hint_only(benchmark::State& state, int partner) {
  const Setup s = make_setup(partner);
  std::size_t i = 0;
  for (auto _ : state) {
    const Transform& pose = s.poses[i++ & 255];
    benchmark::DoNotOptimize(cone_pair_distance(posed_cylinder(8, 9.5, 30, pose), s.b));
  }
}

void BM_ScarredTaperedRoller_Cone(benchmark::State& st) { run(st, 0); }
void BM_IntactHint_Cone(benchmark::State& st) { hint_only(st, 0); }
void BM_ScarredTaperedRoller_ConeNoHint(benchmark::State& st) { run(st, 0, false); }
void BM_ScarredTaperedRoller_TaperedNeighbourNoHint(benchmark::State& st) { run(st, 1, false); }
void BM_IntactHint_TaperedNeighbour(benchmark::State& st) { hint_only(st, 1); }
void BM_ScarredTaperedRoller_TaperedNeighbour(benchmark::State& st) { run(st, 1); }
void BM_ScarredTaperedRoller_Cylinder(benchmark::State& st) { run(st, 2); }

}  // namespace

BENCHMARK(BM_ScarredTaperedRoller_Cone)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredTaperedRoller_TaperedNeighbour)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredTaperedRoller_Cylinder)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredTaperedRoller_ConeNoHint)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredTaperedRoller_TaperedNeighbourNoHint)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntactHint_Cone)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntactHint_TaperedNeighbour)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
