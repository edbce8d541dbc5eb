// Scene benchmarks (issue #24, item 9), executable interfere_bench_scene; bench/scene_tables.py
// runs it and regenerates docs/scene-benchmarks.md. The FCL peer of the assembly rows is in
// peer_fcl_scene.cpp (absent when FCL is not found).
//   Scene/assembly/interfere/hard/threads:<t>
//   Scene/assembly/interfere/hard+clearance/threads:<t>
//       clash_scene on the generated assembly (scene/generate.h: 10,000 bodies, ~10^7 triangles),
//       from the meshes in memory: the time includes every body's world model (pose applied, tree
//       built), the broad phase, the exact core on every candidate pair and the result's sorting
//       and grouping. Tests: all pairs hard, plus all pairs clearance 0.1 mm. Counters: the
//       result's counts and phase times, and its body pairs against the generator's construction
//       (gt_clash_missing/extra: clashing pairs; gt_contact_missing/extra; gt_gap_missing/extra for
//       the clearance test).
//   Scene/moving/interfere/hard/threads:<t>
//       1,000 moving bodies (generate_moving_scene, MovingLayout::cell): the assembly's parts
//       standing apart on a grid with clearances, 2 % of them in near pairs that touch or clash in
//       some frames, every body given a fresh random small rigid motion in every frame;
//       clash_scene over all frames (100 by default); frames_per_second, clashes and contacts per
//       frame, near_pairs (by construction the only pairs that can meet).
//   Scene/moving_assembly/interfere/hard/threads:<t>
//       the first version of the moving benchmark (MovingLayout::assembly): 1,000 bodies of the
//       bolted assembly all moving, so that its designed face contacts become shallow clashes in
//       every frame (one frame by default: about 35 s; docs/scene-benchmarks.md).
// Peak memory of the 10^7-triangle scene is measured in its own process (bench/scene_run.cpp).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <string>
#include <unordered_map>

#include "common.h"
#include "scene_bench.h"

namespace interfere::bench {

const AssemblyFixture& assembly_fixture() {
  static const AssemblyFixture fx = [] {
    AssemblyFixture f;
    f.options.bodies = env_size("INTERFERE_BENCH_SCENE_BODIES", 10000);
    f.options.segments = static_cast<int>(env_size("INTERFERE_BENCH_SCENE_SEGMENTS", 48));
    f.scene = scene::generate_assembly(f.options, &f.info);
    return f;
  }();
  return fx;
}

std::vector<scene::ClashTest> assembly_tests(bool with_clearance) {
  scene::ClashTest hard;
  hard.name = "hard";
  std::vector<scene::ClashTest> tests{hard};
  if (with_clearance) {
    scene::ClashTest c;
    c.name = "clearance";
    c.mode = scene::ClashMode::clearance;
    c.clearance = static_cast<double>(env_size("INTERFERE_BENCH_SCENE_CLEARANCE", 100)) * 1e-3;
    tests.push_back(c);
  }
  return tests;
}

namespace {

std::pair<std::uint32_t, std::uint32_t> ordered(std::uint32_t a, std::uint32_t b) {
  return a < b ? std::pair{a, b} : std::pair{b, a};
}

/// The pairs of `test` with `verdict` in a result.
BodyPairs pairs_with(const scene::SceneClashResult& r, const std::string& test, Verdict verdict) {
  BodyPairs out;
  for (const scene::PairSummary& p : r.pairs)
    if (p.test == test && p.verdict == verdict) out.insert(ordered(p.a, p.b));
  return out;
}

BodyPairs ground_truth(const std::vector<std::pair<std::string, std::string>>& ids) {
  const auto& fx = assembly_fixture();
  static const std::unordered_map<std::string, std::uint32_t> index = [&] {
    std::unordered_map<std::string, std::uint32_t> m;
    for (std::size_t i = 0; i < fx.scene.bodies.size(); ++i)
      m[fx.scene.bodies[i].id] = static_cast<std::uint32_t>(i);
    return m;
  }();
  BodyPairs out;
  for (const auto& [a, b] : ids) out.insert(ordered(index.at(a), index.at(b)));
  return out;
}

/// |found \ expected| and |expected \ found| as counters <name>_extra and <name>_missing.
void diff_counters(benchmark::State& state, const std::string& name, const BodyPairs& found,
                   const BodyPairs& expected) {
  std::size_t extra = 0, missing = 0;
  for (const auto& p : found) extra += !expected.contains(p);
  for (const auto& p : expected) missing += !found.contains(p);
  state.counters[name + "_extra"] = static_cast<double>(extra);
  state.counters[name + "_missing"] = static_cast<double>(missing);
}

void result_counters(benchmark::State& state, const scene::SceneClashResult& r) {
  state.counters["bodies"] = static_cast<double>(r.bodies);
  state.counters["triangles"] = static_cast<double>(r.triangles);
  state.counters["candidate_pairs"] = static_cast<double>(r.candidate_pairs);
  state.counters["core_runs"] = static_cast<double>(r.core_runs);
  state.counters["clashes"] = static_cast<double>(r.clash_count);
  state.counters["contacts"] = static_cast<double>(r.contact_count);
  state.counters["clearances"] = static_cast<double>(r.clearance_count);
  state.counters["undecided"] = static_cast<double>(r.undecided_count);
  state.counters["prepare_s"] = r.prepare_seconds;
  state.counters["broad_s"] = r.broad_seconds;
  state.counters["narrow_s"] = r.narrow_seconds;
}

/// Sums of the exact core's per-pair counts (SceneClashOptions::on_pair): triangle pairs whose
/// boxes overlap, and those that cross or touch, over every candidate body pair of every test.
struct TriangleCounts {
  std::atomic<std::size_t> candidates{0}, cross{0}, touch{0};
  void attach(scene::SceneClashOptions& o) {
    o.on_pair = [this](std::size_t, std::uint32_t, std::uint32_t, const ClashResult& r) {
      candidates += r.candidate_pairs, cross += r.cross_pairs, touch += r.touch_pairs;
    };
  }
  void report(benchmark::State& state) const {
    state.counters["tri_candidates"] = static_cast<double>(candidates.load());
    state.counters["tri_cross"] = static_cast<double>(cross.load());
    state.counters["tri_touch"] = static_cast<double>(touch.load());
  }
};

void bm_assembly(benchmark::State& state, bool with_clearance, int threads) {
  const AssemblyFixture& fx = assembly_fixture();
  const std::vector<scene::ClashTest> tests = assembly_tests(with_clearance);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  scene::SceneClashResult r;
  const scene::SceneClashOptions options;
  for (auto _ : state) {
    state.PauseTiming();
    r = {};
    state.ResumeTiming();
    r = scene::clash_scene(fx.scene, tests, options);
    benchmark::DoNotOptimize(r.clashes.data());
  }
  // Triangle counts come from on_pair, which makes the engine decide every body pair on its own,
  // once per test, in the world frame (the caller sees each pair's own core result): one more run,
  // untimed, on the hard row only; the timed runs are the path users get.
  TriangleCounts counts;
  if (!with_clearance) {
    scene::SceneClashOptions counting;
    counts.attach(counting);
    scene::clash_scene(fx.scene, tests, counting);
  }
  result_counters(state, r);
  if (!with_clearance) counts.report(state);
  state.counters["threads"] = threads;
  state.counters["clash_pairs"] = static_cast<double>(pairs_with(r, "hard", Verdict::clash).size());
  state.counters["contact_pairs"] =
      static_cast<double>(pairs_with(r, "hard", Verdict::contact).size());
  diff_counters(state, "gt_clash", pairs_with(r, "hard", Verdict::clash),
                ground_truth(fx.info.clash_pairs));
  diff_counters(state, "gt_contact", pairs_with(r, "hard", Verdict::contact),
                ground_truth(fx.info.contact_pairs));
  if (with_clearance)
    diff_counters(state, "gt_gap", pairs_with(r, "clearance", Verdict::clearance),
                  ground_truth(fx.info.gap_pairs));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * fx.scene.bodies.size()));
}

struct MovingFixture {
  scene::Scene scene;
  std::vector<std::pair<std::string, std::string>> near_pairs;
};

const MovingFixture& moving_scene(scene::MovingLayout layout) {
  static const MovingFixture cell = [] {
    scene::MovingSceneGenOptions o;
    o.bodies = env_size("INTERFERE_BENCH_MOVING_BODIES", 1000);
    o.frames = env_size("INTERFERE_BENCH_MOVING_FRAMES", 100);
    o.segments = static_cast<int>(env_size("INTERFERE_BENCH_SCENE_SEGMENTS", 48));
    // (analysis: INTERFERE_BENCH_MOVING_NEAR_GAP=1 keeps every stack apart: no clash at all)
    o.near_gap = std::stod(env_string("INTERFERE_BENCH_MOVING_NEAR_GAP", "0.06"));
    MovingFixture f;
    f.scene = scene::generate_moving_scene(o, &f.near_pairs);
    return f;
  }();
  if (layout == scene::MovingLayout::cell) return cell;
  static const MovingFixture assembly = [] {
    scene::MovingSceneGenOptions o;
    o.layout = scene::MovingLayout::assembly;
    o.bodies = env_size("INTERFERE_BENCH_MOVING_BODIES", 1000);
    o.frames = env_size("INTERFERE_BENCH_MOVING_ASSEMBLY_FRAMES", 1);
    o.segments = static_cast<int>(env_size("INTERFERE_BENCH_SCENE_SEGMENTS", 48));
    MovingFixture f;
    f.scene = scene::generate_moving_scene(o);
    return f;
  }();
  return assembly;
}

void bm_moving(benchmark::State& state, int threads, scene::MovingLayout layout) {
  const MovingFixture& fx = moving_scene(layout);
  const scene::Scene& s = fx.scene;
  const std::vector<scene::ClashTest> tests = assembly_tests(false);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  scene::SceneClashResult r;
  TriangleCounts counts;
  scene::SceneClashOptions options;
  counts.attach(options);
  double seconds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    r = {};
    counts.candidates = counts.cross = counts.touch = 0;
    state.ResumeTiming();
    const auto t0 = std::chrono::steady_clock::now();
    r = scene::clash_scene(s, tests, options);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(r.clashes.data());
  }
  result_counters(state, r);
  counts.report(state);
  state.counters["threads"] = threads;
  state.counters["frames"] = static_cast<double>(r.frames.size());
  state.counters["frames_per_second"] =
      seconds > 0 ? static_cast<double>(r.frames.size() * state.iterations()) / seconds : 0;
  std::size_t clashes = 0, contacts = 0;
  for (const scene::FrameRow& f : r.frames) clashes += f.clashes, contacts += f.contacts;
  state.counters["clashes_per_frame"] =
      r.frames.empty() ? 0 : static_cast<double>(clashes) / r.frames.size();
  state.counters["contacts_per_frame"] =
      r.frames.empty() ? 0 : static_cast<double>(contacts) / r.frames.size();
  state.counters["near_pairs"] = static_cast<double>(fx.near_pairs.size());
  std::size_t frames_with_clash = 0;
  for (const scene::FrameRow& f : r.frames) frames_with_clash += f.clashes > 0;
  state.counters["frames_with_clash"] = static_cast<double>(frames_with_clash);
  state.counters["candidates_per_frame"] =
      r.frames.empty() ? 0 : static_cast<double>(r.candidate_pairs) / r.frames.size();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * r.frames.size()));
}

[[maybe_unused]] const bool registered = [] {
  for (std::size_t t : env_sizes("INTERFERE_BENCH_SCENE_THREADS", {2})) {
    const int th = static_cast<int>(t);
    const std::string ts = "/threads:" + std::to_string(th);
    for (bool c : {false, true}) {
      benchmark::RegisterBenchmark(
          ("Scene/assembly/interfere/" + std::string(c ? "hard+clearance" : "hard") + ts).c_str(),
          [c, th](benchmark::State& s) { bm_assembly(s, c, th); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(1);
    }
    for (const auto& [name, layout] : {std::pair{"Scene/moving/interfere/hard", scene::MovingLayout::cell},
                                       std::pair{"Scene/moving_assembly/interfere/hard", scene::MovingLayout::assembly}}) {
      benchmark::RegisterBenchmark((name + ts).c_str(),
                                   [th, layout](benchmark::State& s) { bm_moving(s, th, layout); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(1);
    }
  }
  return true;
}();

}  // namespace

const ExactPairs& exact_assembly_pairs() {
  static const ExactPairs e = [] {
    scene::SceneClashOptions o;
    o.curves = false;
    const scene::SceneClashResult r =
        scene::clash_scene(assembly_fixture().scene, assembly_tests(false), o);
    return ExactPairs{pairs_with(r, "hard", Verdict::clash),
                      pairs_with(r, "hard", Verdict::contact),
                      pairs_with(r, "hard", Verdict::undecided)};
  }();
  return e;
}

}  // namespace interfere::bench
