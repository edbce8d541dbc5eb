// One pair computation of each raceway solver (raceway.h, issue #27), on a cycle of 256 poses of a
// roller near its ring (tilts up to 3 degrees, clearance to overlap of 0.3): roller in a
// cylindrical bore, roller end against a rib face (partly outside the annulus), tapered roller
// against a cone raceway, tapered roller in a cup. Context: the budget for one maximum
// interference computation is 20 us.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "interfere/bearing/raceway.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

Vec3 tilted(const Vec3& u, double tilt, double az) {
  const Vec3 a = std::fabs(u.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  Vec3 p1 = a - u * dot(a, u);
  p1 = p1 / norm(p1);
  const Vec3 p2 = cross(u, p1);
  return u * std::cos(tilt) + (p1 * std::cos(az) + p2 * std::sin(az)) * std::sin(tilt);
}

Cylinder make(const Vec3& center, const Vec3& d, double r0, double r1, double h) {
  Cylinder c;
  c.axis = d / norm(d), c.base = center - c.axis * (0.5 * h), c.height = h, c.radius = r0;
  c.top_radius = r1 == r0 ? -1 : r1;
  return c;
}

/// Rollers placed on a cone line (R0 at z = 0 to R1 at z = w, about the z axis) from the inside
/// (sign -1: bore, cup) or the outside (+1: cone raceway), at random azimuths, gaps and tilts.
std::vector<Cylinder> poses(double R0, double R1, double w, double sign, double r0, double r1, double h) {
  std::mt19937_64 g(27);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Cylinder> out;
  for (int i = 0; i < 256; ++i) {
    const double az = 2 * std::numbers::pi * U(g);
    const Vec3 radial{std::cos(az), std::sin(az), 0}, u{0, 0, 1};
    const double L = std::hypot(R1 - R0, w);
    const Vec3 gen = (radial * (R1 - R0) + u * w) / L, nout = (radial * w - u * (R1 - R0)) / L;
    const double zc = 0.5 * w + 2 * (U(g) - 0.5);
    const Vec3 on = u * zc + radial * (R0 + (R1 - R0) * zc / w);
    const double gap = 0.6 * U(g) - 0.3;
    out.push_back(make(on + nout * (sign * (0.5 * (r0 + r1) + gap)), tilted(gen, 3 * kDeg * U(g), 7 * U(g)), r0, r1, h));
  }
  return out;
}

void BM_RollerBore(benchmark::State& state) {
  const Bore bore{{0, 0, 0}, {0, 0, 1}, 40, 30};
  const auto rs = poses(40, 40, 30, -1, 5, 5, 20);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(roller_bore_distance(rs[i++ & 255], bore));
}
BENCHMARK(BM_RollerBore);

void BM_RollerCup(benchmark::State& state) {
  const Cup cup{{0, 0, 0}, {0, 0, 1}, 40, 34, 30};
  const auto rs = poses(40, 34, 30, -1, 5.5, 4.5, 20);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(roller_cup_distance(rs[i++ & 255], cup));
}
BENCHMARK(BM_RollerCup);

void BM_ConePair(benchmark::State& state) {
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
  const auto rs = poses(30, 25, 30, +1, 4.5, 3.8, 18);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(cone_pair_distance(rs[i++ & 255], b));
}
BENCHMARK(BM_ConePair);

// the end-face dual: a roller standing on the cone's top face
void BM_ConePairEndFace(benchmark::State& state) {
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
  const Cylinder a = make({5, 3, 38.9}, tilted({0, 0, 1}, 2 * kDeg, 1), 4.5, 3.8, 18);
  for (auto _ : state) benchmark::DoNotOptimize(cone_pair_distance(a, b));
}
BENCHMARK(BM_ConePairEndFace)->Unit(benchmark::kMicrosecond);

// the reverse direction s(cone ring, roller) of the two-sided value, over the same 256 poses as
// BM_ConePair (the end-face dual, else the nested golden-section path)
void BM_ConePairReverse(benchmark::State& state) {
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
  const auto rs = poses(30, 25, 30, +1, 4.5, 3.8, 18);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(cone_pair_distance(b, rs[i++ & 255]));
}
BENCHMARK(BM_ConePairReverse)->Unit(benchmark::kMicrosecond);

void BM_RollerRib(benchmark::State& state) {
  // inner ring rib, annulus 25..36 below rollers of radius 5 at pitch radius 34 (ends partly outside)
  const Rib rib{{0, 0, 0}, {0, 0, 1}, 25, 36, {0, 0, 1}};
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Cylinder> rs;
  for (int i = 0; i < 256; ++i) {
    const double az = 2 * std::numbers::pi * U(g);
    Cylinder c;
    c.base = Vec3{34 * std::cos(az), 34 * std::sin(az), 0.6 * U(g) - 0.3};
    c.axis = tilted({0, 0, 1}, 3 * kDeg * U(g), 7 * U(g)), c.height = 20, c.radius = 5;
    rs.push_back(c);
  }
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(roller_rib_distance(rs[i++ & 255], rib));
}
BENCHMARK(BM_RollerRib);

}  // namespace

BENCHMARK_MAIN();
