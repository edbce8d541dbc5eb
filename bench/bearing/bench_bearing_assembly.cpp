// Bearing assemblies (issue #27): wall-clock time per frame of run_assembly (every pair of every
// bearing, in parallel over pairs), for the shipped example (data/examples/bearing_axle.json: two
// cylindrical and two tapered bearings, 316 pairs) and for the issue's target size, 1,024 rollers
// in 32 cylindrical bearings of 32 rollers with a quarter of them scarred. The issue's target
// (1,000 frames/s for 1,024 rollers) is measured here, not asserted anywhere.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <utility>
#include <ctime>
#include <string>
#include <tbb/global_control.h>
#include <vector>

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
BENCHMARK(BM_AssemblyExample)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(1);

/// The issue's target scene: 32 cylindrical bearings of 32 rollers, a quarter of them scarred with
/// the scar in range every frame (angle_width 350 degrees).
Expected<AssemblySpec> spec_1024() {
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
  return parse_assembly(text, "1024 rollers");
}

/// The 1,024-roller scene built (its description and assembly), or an error already reported to
/// the benchmark (the caller returns).
std::optional<std::pair<AssemblySpec, Assembly>> built_1024(benchmark::State& state) {
  Expected<AssemblySpec> spec = spec_1024();
  if (!spec) {
    state.SkipWithError(spec.error().message().c_str());
    return std::nullopt;
  }
  Expected<Assembly> as = build_assembly(*spec);
  if (!as) {
    state.SkipWithError(as.error().message().c_str());
    return std::nullopt;
  }
  return std::make_pair(std::move(*spec), std::move(*as));
}

void BM_Assembly1024Rollers(benchmark::State& state) {
  Expected<AssemblySpec> spec = spec_1024();
  if (!spec) {
    state.SkipWithError(spec.error().message().c_str());
    return;
  }
  run_frames(state, *spec, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_Assembly1024Rollers)->Arg(4)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(1);

/// run_assembly's schedule (issue #27; src/bearing/assembly_schedule.h) over more frames than
/// BM_Assembly1024Rollers' 4 (a scarred roller's pair over a block of 16 frames at a time), on
/// range(1) threads (tbb::global_control): "ms_frame_cpu" is the process's CPU time per frame (on
/// 1 thread robust to other load on the machine), "frames_per_second" the wall clock's rate.
double process_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void BM_Assembly1024Threads(benchmark::State& state) {
  auto built = built_1024(state);
  if (!built) return;
  const AssemblySpec* spec = &built->first;
  const Assembly* as = &built->second;
  const int frames = static_cast<int>(state.range(0));
  const AssemblyMotion motion = generate_motion(*as, frames, spec->seed);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  double cpu = 0;
  for (auto _ : state) {
    const double t0 = process_seconds();
    const AssemblyResult r = run_assembly(*as, motion);
    cpu += process_seconds() - t0;
    benchmark::DoNotOptimize(r.worst);
  }
  const double runs = static_cast<double>(frames) * static_cast<double>(state.iterations());
  state.counters["ms_frame_cpu"] = 1e3 * cpu / runs;
  state.counters["frames_per_second"] = benchmark::Counter(runs, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Assembly1024Threads)->Args({16, 1})->Args({16, 2})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

/// Where the time goes: the pairs of the 1,024-roller scene solved on this thread, kind by kind
/// (pairs with a scarred part apart), over several frames; the thread's CPU time per batch (robust
/// to other load on the machine) gives "us_<kind>[_scarred]" (microseconds per pair) and
/// "ms_frame_..." (CPU milliseconds per frame); "n_<kind>_<solver>_<path>": pairs per frame that
/// took that solver and path. solve_pair is the function run_assembly calls.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void BM_Assembly1024ByKind(benchmark::State& state) {
  auto built = built_1024(state);
  if (!built) return;
  const AssemblySpec* spec = &built->first;
  const Assembly* as = &built->second;
  const int frames = 4;
  const AssemblyMotion motion = generate_motion(*as, frames, spec->seed);
  std::size_t kinds = 0;  // every kind the pair list has (the enum may grow)
  for (const AssemblyPair& p : as->pairs) kinds = std::max(kinds, static_cast<std::size_t>(p.kind) + 1);
  std::vector<std::vector<std::size_t>> batch(2 * kinds);
  for (std::size_t i = 0; i < as->pairs.size(); ++i) {
    const AssemblyPair& p = as->pairs[i];
    const bool scarred = as->parts[p.a].scarred || as->parts[p.b].scarred;  // either part
    batch[static_cast<std::size_t>(p.kind) + (scarred ? kinds : 0)].push_back(i);
  }
  std::vector<double> seconds(2 * kinds, 0.0);
  std::map<std::string, double> paths;
  for (auto _ : state) {
    for (std::size_t k = 0; k < 2 * kinds; ++k) {
      const double t0 = thread_seconds();
      for (int f = 0; f < frames; ++f)
        for (const std::size_t i : batch[k]) {
          const AssemblyPairResult r = solve_pair(*as, as->pairs[i], motion.poses[static_cast<std::size_t>(f)], spec->clearance);
          benchmark::DoNotOptimize(r.distance);
        }
      seconds[k] += thread_seconds() - t0;
    }
  }
  for (int f = 0; f < frames; ++f)
    for (const AssemblyPair& p : as->pairs) {
      const AssemblyPairResult r = solve_pair(*as, p, motion.poses[static_cast<std::size_t>(f)], spec->clearance);
      paths[std::string("n_") + assembly_pair_kind_name(p.kind) + "_" + assembly_solver_name(r.solver) + "_" +
            analytic_path_name(r.path)] += 1;
    }
  const double runs = static_cast<double>(frames) * static_cast<double>(state.iterations());
  double total = 0;
  for (std::size_t k = 0; k < 2 * kinds; ++k) {
    if (batch[k].empty()) continue;
    const std::string name = std::string(assembly_pair_kind_name(static_cast<AssemblyPairKind>(k % kinds))) +
                             (k >= kinds ? "_scarred" : "");
    state.counters["us_" + name] = 1e6 * seconds[k] / (runs * static_cast<double>(batch[k].size()));
    state.counters["ms_frame_" + name] = 1e3 * seconds[k] / runs;
    total += seconds[k];
  }
  state.counters["ms_frame_total_cpu"] = 1e3 * total / runs;
  for (const auto& [name, n] : paths) state.counters[name] = n / static_cast<double>(frames);
}
BENCHMARK(BM_Assembly1024ByKind)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
