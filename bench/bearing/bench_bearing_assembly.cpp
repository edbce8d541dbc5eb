// Bearing assemblies (issue #27): wall-clock time per frame of run_assembly (every pair of every
// bearing, in parallel over pairs), for the shipped example (data/examples/bearing_axle.json: two
// cylindrical and two tapered bearings, 316 pairs) and for the issue's target size, 1,024 rollers
// in 32 cylindrical bearings of 32 rollers with a quarter of them scarred. The issue's target
// (1,000 frames/s for 1,024 rollers) is measured here, not asserted anywhere.
#include <benchmark/benchmark.h>

#include <string>

#include "interfere/bearing/assembly.h"

namespace {

using namespace interfere;
using namespace interfere::bearing;

void run_frames(benchmark::State& state, const AssemblySpec& spec, int frames) {
  Expected<Assembly> as = build_assembly(spec);
  if (!as) {
    state.SkipWithError(as.error().message().c_str());
    return;
  }
  const AssemblyMotion motion = generate_motion(*as, frames, spec.seed);
  for (auto _ : state) {
    const AssemblyResult r = run_assembly(*as, motion);
    benchmark::DoNotOptimize(r.worst);
  }
  state.counters["pairs"] = static_cast<double>(as->pairs.size());
  state.counters["frames_per_second"] =
      benchmark::Counter(static_cast<double>(frames) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_AssemblyExample(benchmark::State& state) {
  Expected<AssemblySpec> spec = read_assembly_file(std::string(INTERFERE_SOURCE_DIR) + "/data/examples/bearing_axle.json");
  if (!spec) {
    state.SkipWithError(spec.error().message().c_str());
    return;
  }
  run_frames(state, *spec, 4);
}
BENCHMARK(BM_AssemblyExample)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void BM_Assembly1024Rollers(benchmark::State& state) {
  std::string bearings;
  for (int i = 0; i < 32; ++i) {
    if (i) bearings += ",";
    bearings += R"({"id": "b)" + std::to_string(i) + R"(", "type": "cylindrical", "position": [)" +
                std::to_string(300 * i) + R"(, 0, 0], "axis": [1, 0, 0],
      "inner_ring": {"bore_radius": 95, "raceway_radius": 110, "width": 50, "rib": {"height": 4, "width": 5}},
      "outer_ring": {"raceway_radius": 130.1, "outer_radius": 145, "width": 50},
      "rollers": {"count": 32, "radius": 10, "length": 38, "pitch_radius": 120.05},
      "cage": {"pocket_clearance": 0.3, "web_thickness": 8}})";
  }
  const std::string text = R"({"seed": 3, "clearance": 0.05,
      "motion": {"max_tilt_deg": 0.05, "load": {"displacement": 0.08}, "pocket_play": 1.2, "axial_play": 1.02},
      "scar": {"fraction": 0.25, "angle_width_deg": 350, "seed": 5}, "bearings": [)" + bearings + "]}";
  Expected<AssemblySpec> spec = parse_assembly(text, "1024 rollers");
  if (!spec) {
    state.SkipWithError(spec.error().message().c_str());
    return;
  }
  run_frames(state, *spec, 1);
}
BENCHMARK(BM_Assembly1024Rollers)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
