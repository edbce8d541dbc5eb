// The issue #27 target: "one maximum-interference computation of a scarred roller against a scarred
// raceway at 64^2 vertices, scar in range: <= 20 us" (raceway_scar_solver.h). A roller of 64 x 64
// side vertices (radius 10, length 38, a generated scar over the whole circumference between
// z 2 and 36) against a raceway whose scar is 64 x 64 vertices (45 degrees of a 512-column grid,
// the whole 50 mm width), on a cycle of 256 poses with the roller over the scar (angles within
// +-15 degrees of its centre), pressed by -0.01 .. 0.05 mm and tilted up to 0.05 degrees in its
// tangential plane. Variants: the inner raceway (convex) and the outer bore (concave), inward or
// raised raceway scars, and an intact roller. Each computation is a fresh solve (no state kept
// between poses: the per-frame rows of an assembly are pure functions of the poses).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "interfere/bearing/raceway_scar.h"
#include "interfere/bearing/raceway_scar_solver.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Setup {
  RacewayScar scar;
  Roller roller;
  RollerQuadtree tree;
  std::vector<Transform> poses;
  double radius = 0;
  int side = 1;
};

Setup make_setup(bool concave, bool raised) {
  Setup s;
  s.radius = concave ? 100.1 : 80;
  s.side = concave ? -1 : 1;
  const RacewayGeometry g{.surface = concave ? RacewaySurface::outer : RacewaySurface::inner, .z0 = -25,
                          .width = 50, .radius = s.radius, .top_radius = s.radius};
  // 45 degrees of 512 columns, centred half a column off a vertex: 64 columns; 63 quads across the
  // width: 64 rings
  const ScarParams w{.angle_center_deg = 0.3515625, .angle_width_deg = 45, .z_min = 0, .z_max = 50, .depth = 0.05,
                     .roughness = 0.6, .border = 2, .seed = 21, .raised = raised};
  s.scar = *make_raceway_scar(g, {.radial_segments = 512, .height_segments = 63}, w);
  s.roller = *make_roller({.radius = 10, .height = 38, .radial_segments = 64, .height_segments = 63});
  const ScarParams rs{.angle_center_deg = 0, .angle_width_deg = 359, .z_min = 2, .z_max = 36, .depth = 0.04,
                      .roughness = 0.6, .border = 2, .seed = 5};
  (void)apply_scar(s.roller, rs);
  s.tree = build_quadtree(s.roller);
  std::mt19937_64 gen(27);
  std::uniform_real_distribution<double> U(0, 1);
  for (int i = 0; i < 256; ++i) {
    const double phi = (30 * U(gen) - 15) * kDeg, press = 0.06 * U(gen) - 0.01;
    const double tilt = 0.05 * kDeg * (2 * U(gen) - 1), spin = 2 * std::numbers::pi * U(gen);
    const Vec3 radial{std::cos(phi), std::sin(phi), 0};
    const Vec3 mid = radial * (s.radius + s.side * (10 - press));
    const double az = phi + 0.5 * std::numbers::pi;
    const Vec3 axis{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
    s.poses.push_back(roller_pose(mid - axis * 19.0, tilt, az, spin));
  }
  return s;
}

void run(benchmark::State& state, bool concave, bool raised, bool scarred_roller) {
  const Setup s = make_setup(concave, raised);
  const RacewayPairRing ring{&s.scar, Transform::identity()};
  std::size_t i = 0;
  double evaluated = 0, count = 0, in_range = 0, nodes = 0, fallbacks = 0;
  for (auto _ : state) {
    const Transform& pose = s.poses[i++ & 255];
    RacewayPairRoller roller{posed_cylinder(10, -1, 38, pose), scarred_roller ? &s.roller : nullptr,
                             scarred_roller ? &s.tree : nullptr, pose};
    const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
    benchmark::DoNotOptimize(r);
    evaluated += r.evaluated, count += 1, nodes += r.nodes_visited, fallbacks += r.fallbacks;
    in_range += raceway_scar_in_range(roller, ring);
  }
  state.counters["triangles_evaluated"] = evaluated / std::max(count, 1.0);
  state.counters["in_range"] = in_range / std::max(count, 1.0);
  state.counters["nodes_visited"] = nodes / std::max(count, 1.0);
  state.counters["fallbacks"] = fallbacks / std::max(count, 1.0);
}

void BM_ScarredRollerScarredRaceway_Inner(benchmark::State& st) { run(st, false, false, true); }
void BM_ScarredRollerScarredRaceway_InnerRaised(benchmark::State& st) { run(st, false, true, true); }
void BM_ScarredRollerScarredRaceway_Outer(benchmark::State& st) { run(st, true, false, true); }
void BM_ScarredRollerScarredRaceway_OuterRaised(benchmark::State& st) { run(st, true, true, true); }
void BM_IntactRollerScarredRaceway_Inner(benchmark::State& st) { run(st, false, false, false); }
void BM_IntactRollerScarredRaceway_Outer(benchmark::State& st) { run(st, true, false, false); }

}  // namespace

BENCHMARK(BM_ScarredRollerScarredRaceway_Inner)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredRollerScarredRaceway_InnerRaised)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredRollerScarredRaceway_Outer)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScarredRollerScarredRaceway_OuterRaised)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntactRollerScarredRaceway_Inner)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntactRollerScarredRaceway_Outer)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
