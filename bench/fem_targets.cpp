// The FE targets of issue #26, item 7, as Google Benchmark rows (interfere_bench_fem_targets;
// bench/fem_targets_tables.py runs them and writes docs/fem-benchmarks.md):
//
//  BM_FrdRead/ascii, BM_FrdRead/binary  (target: <= 2 s) read_fem of a CalculiX .frd of 10^6
//      hex8 elements in two bodies with 10 DISP steps (fem_targets_models.h (a)), written once by
//      the bench-only writer (frd_bench_writer.h) and cached under the build tree; the whole read:
//      file bytes, nodes, elements and every displacement step. An untimed read first puts the
//      file in the page cache.
//  BM_Fem20BodiesStep  (target: <= 200 ms per step) 20 bodies, 10^7 tet4 elements in all, 10
//      steps (model (b)); fem_scene once (one-time: surface extraction and frames, counter
//      extract_s), then per iteration scene::clash_scene over every frame with the default
//      all-pairs test (what `interfere clash model.frd` runs); the reported time is the whole
//      clash_scene / frames (manual time), its tree builds (prepare_s) included.
//  BM_FemSceneSeriesStep  (target: <= 30 ms per step on 2 cores) two 10^6-element tet4 bodies,
//      100 steps (model (c), BM_FemSeriesStep's pair) through fem_scene + clash_scene, the same way.
//  Each scene row as the CLI runs it (/depth_maps: the engine's defaults — depth and its upper
//  bound for every clashing pair, the check of the undeformed model — plus the per-node depth
//  maps), with the defaults alone (/clash_depth), and for comparison without the bound (/no_bound)
//  and without the depth (/no_depth).
//
// `interfere_bench_fem_targets --write-frd` writes the .frd files (if absent) and prints their
// paths, for the script's whole-process row (`interfere clash big.frd --json out.json`).
//
// Environment (optional):
//   INTERFERE_BENCH_FRD_DIR          where the .frd files are cached (default <build>/bench/fem_targets_data)
//   INTERFERE_BENCH_FRD_ELEMENTS     elements of the .frd model, default 1e6
//   INTERFERE_BENCH_FRD_STEPS        its DISP steps, default 10
//   INTERFERE_BENCH_MODEL20_ELEMENTS elements of the 20-body model, default 1e7
//   INTERFERE_BENCH_MODEL20_STEPS    its steps, default 10
//   INTERFERE_BENCH_SERIES_ELEMENTS  elements per body of the series, default 1e6
//   INTERFERE_BENCH_SERIES_STEPS     its steps, default 100
//   INTERFERE_BENCH_THREADS          threads of the scene rows, default 2 (the targets' "2 cores")
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "fem_targets_models.h"
#include "frd_bench_writer.h"
#include "interfere/fem/bodies.h"
#include "interfere/fem/io.h"
#include "interfere/scene/engine.h"

#ifndef INTERFERE_BENCH_DATA_DIR
#define INTERFERE_BENCH_DATA_DIR "fem_targets_data"
#endif

namespace interfere::bench_fem_targets {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const double d = std::strtod(v, &end);
  if (end == v || *end || !(d >= 1)) {
    std::fprintf(stderr, "%s=%s: not a positive number\n", name, v);
    std::exit(2);
  }
  return static_cast<std::size_t>(d);
}

int threads() { return static_cast<int>(env_size("INTERFERE_BENCH_THREADS", 2)); }

// ---------------------------------------------------------------- (a) the .frd files

struct FrdFiles {
  fs::path ascii, binary;
  std::size_t elements = 0, nodes = 0, steps = 0;
};

const FrdFiles& frd_files() {
  static const FrdFiles files = [] {
    const std::size_t elements = env_size("INTERFERE_BENCH_FRD_ELEMENTS", 1000000);
    const int steps = static_cast<int>(env_size("INTERFERE_BENCH_FRD_STEPS", 10));
    const char* d = std::getenv("INTERFERE_BENCH_FRD_DIR");
    const fs::path dir = d && *d ? fs::path(d) : fs::path(INTERFERE_BENCH_DATA_DIR);
    fs::create_directories(dir);
    // v1: the layout of frd_bench_writer.cpp and model (a) of fem_targets_models.h; bump when either changes.
    const std::string stem = "two_hex_boxes_" + std::to_string(elements) + "e_" + std::to_string(steps) + "steps_v1";
    FrdFiles f{.ascii = dir / (stem + ".frd"), .binary = dir / (stem + "_bin.frd")};
    std::unique_ptr<FemMesh> m;
    for (const bool bin : {false, true}) {
      const fs::path& p = bin ? f.binary : f.ascii;
      if (fs::exists(p)) continue;
      if (!m) m = std::make_unique<FemMesh>(frd_read_model(elements, steps));
      std::fprintf(stderr, "[fem_targets] writing %s\n", p.c_str());
      if (Status s = bench_frd::write_frd(*m, &m->fields[0], p, {.binary = bin}); !s) {
        std::fprintf(stderr, "%s\n", s.error().message().c_str());
        std::exit(2);
      }
    }
    return f;
  }();
  return files;
}

void BM_FrdRead(benchmark::State& state) {
  const bool bin = state.range(0) == 1;
  const FrdFiles& f = frd_files();
  const fs::path& p = bin ? f.binary : f.ascii;
  static std::map<int, bool> warm;
  if (!warm[bin]) {  // untimed: the page cache
    if (!read_fem(p)) state.SkipWithError("read failed");
    warm[bin] = true;
  }
  std::size_t elements = 0, nodes = 0, steps = 0;
  for (auto _ : state) {
    Expected<FemMesh> m = read_fem(p);
    if (!m) {
      state.SkipWithError(m.error().message().c_str());
      return;
    }
    elements = m->num_elements();
    nodes = m->num_nodes();
    steps = m->fields.empty() ? 0 : m->fields[0].num_steps();
    benchmark::DoNotOptimize(m);
  }
  const double bytes = static_cast<double>(fs::file_size(p));
  state.SetLabel(p.filename().string());
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["file_MB"] = bytes / 1e6;
  state.counters["MB_per_s"] = benchmark::Counter(bytes / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

// ---------------------------------------------------------------- (b), (c) scenes

struct SceneCase {
  scene::Scene scene;
  std::size_t elements = 0, nodes = 0, triangles = 0;
  double generate_s = 0, extract_s = 0;
};

std::unique_ptr<SceneCase> make_case(FemMesh mesh, const std::string& name) {
  auto c = std::make_unique<SceneCase>();
  c->elements = mesh.num_elements();
  c->nodes = mesh.num_nodes();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads()));
  const auto t0 = Clock::now();
  Expected<scene::Scene> s = fem_scene(mesh, name);
  c->extract_s = seconds_since(t0);
  if (!s) {
    std::fprintf(stderr, "fem_scene: %s\n", s.error().message().c_str());
    std::exit(2);
  }
  c->scene = std::move(*s);
  for (const scene::Body& b : c->scene.bodies) c->triangles += b.mesh->num_triangles();
  return c;
}

const SceneCase& twenty_bodies() {
  static const std::unique_ptr<SceneCase> c = [] {
    const auto t0 = Clock::now();
    FemMesh m = twenty_body_model(env_size("INTERFERE_BENCH_MODEL20_ELEMENTS", 10000000),
                                  static_cast<int>(env_size("INTERFERE_BENCH_MODEL20_STEPS", 10)));
    const double gen = seconds_since(t0);
    auto r = make_case(std::move(m), "twenty_bodies.frd");
    r->generate_s = gen;
    return r;
  }();
  return *c;
}

const SceneCase& series() {
  static const std::unique_ptr<SceneCase> c = [] {
    const auto t0 = Clock::now();
    FemMesh m = two_body_series_model(env_size("INTERFERE_BENCH_SERIES_ELEMENTS", 1000000),
                                      static_cast<int>(env_size("INTERFERE_BENCH_SERIES_STEPS", 100)));
    const double gen = seconds_since(t0);
    auto r = make_case(std::move(m), "series.frd");
    r->generate_s = gen;
    return r;
  }();
  return *c;
}

/// clash_scene over every frame per iteration; manual time = its wall time / frames.
void run_scene(benchmark::State& state, const SceneCase& c, const scene::SceneClashOptions& options) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads()));
  const std::vector<scene::ClashTest> tests{scene::ClashTest{}};
  const std::size_t frames = std::max<std::size_t>(1, c.scene.frames.size());
  scene::SceneClashResult last;
  double total = 0;
  std::size_t iterations = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    scene::SceneClashResult r = scene::clash_scene(c.scene, tests, options);
    const double s = seconds_since(t0);
    state.SetIterationTime(s / static_cast<double>(frames));
    total += s;
    ++iterations;
    last = std::move(r);
  }
  std::size_t clashing_frames = 0;
  for (const scene::FrameRow& f : last.frames) clashing_frames += f.clashes > 0;
  state.counters["bodies"] = static_cast<double>(c.scene.bodies.size());
  state.counters["elements"] = static_cast<double>(c.elements);
  state.counters["nodes"] = static_cast<double>(c.nodes);
  state.counters["triangles"] = static_cast<double>(c.triangles);
  state.counters["frames"] = static_cast<double>(c.scene.frames.size());
  state.counters["threads"] = threads();
  state.counters["clash_scene_s"] = total / static_cast<double>(std::max<std::size_t>(iterations, 1));
  state.counters["prepare_s"] = last.prepare_seconds;
  state.counters["broad_s"] = last.broad_seconds;
  state.counters["narrow_s"] = last.narrow_seconds;
  state.counters["extract_s"] = c.extract_s;
  state.counters["generate_s"] = c.generate_s;
  state.counters["candidate_pairs"] = static_cast<double>(last.candidate_pairs);
  state.counters["clashes"] = static_cast<double>(last.clash_count);
  state.counters["clash_pairs"] = static_cast<double>(last.pairs.size());
  state.counters["clashing_frames"] = static_cast<double>(clashing_frames);
  std::size_t inside = 0;
  for (const scene::PairDepthMap& d : last.depth_maps) inside += d.a_in_b.vertices.size() + d.b_in_a.vertices.size();
  state.counters["depth_maps"] = static_cast<double>(last.depth_maps.size());
  state.counters["depth_map_vertices"] = static_cast<double>(inside);
}

/// The engine's options of a row: 2 as `interfere clash model.frd` sets them (the defaults —
/// depth and its upper bound on every clashing pair, the check of the undeformed model — and the
/// penetration depth maps), 0 the defaults, 3 the depth without its bound, 1 without the depth (to
/// show what each costs).
scene::SceneClashOptions scene_options(std::int64_t mode) {
  scene::SceneClashOptions o;
  if (mode == 1) o.depth = false;
  if (mode == 2) o.depth_maps = true;
  if (mode == 3) o.depth_bound_splits = 0;
  return o;
}

void BM_Fem20BodiesStep(benchmark::State& state) { run_scene(state, twenty_bodies(), scene_options(state.range(0))); }
void BM_FemSceneSeriesStep(benchmark::State& state) { run_scene(state, series(), scene_options(state.range(0))); }

void register_all() {
  benchmark::RegisterBenchmark("BM_FrdRead/ascii", BM_FrdRead)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
  benchmark::RegisterBenchmark("BM_FrdRead/binary", BM_FrdRead)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
  for (const auto& [name, mode] : {std::pair{"depth_maps", 2}, std::pair{"clash_depth", 0}, std::pair{"no_bound", 3},
                                   std::pair{"no_depth", 1}}) {
    benchmark::RegisterBenchmark((std::string("BM_Fem20BodiesStep/") + name).c_str(), BM_Fem20BodiesStep)
        ->Arg(mode)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1);
    benchmark::RegisterBenchmark((std::string("BM_FemSceneSeriesStep/") + name).c_str(), BM_FemSceneSeriesStep)
        ->Arg(mode)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1);
  }
}

}  // namespace
}  // namespace interfere::bench_fem_targets

int main(int argc, char** argv) {
  using namespace interfere::bench_fem_targets;
  if (argc == 2 && std::strcmp(argv[1], "--write-frd") == 0) {
    const FrdFiles& f = frd_files();
    std::printf("%s\n%s\n", f.ascii.c_str(), f.binary.c_str());
    return 0;
  }
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
