// Frames in blocks per rank (series.h; issue #31, item 3; docs/mpi.md, "Time series").
//
// Rank k of K takes frames [k F / K, (k + 1) F / K) and runs scene::clash_scene — the engine call of
// `interfere clash --scene` (apps/cli/cmd_clash_scene.cpp), every body, every test — on a scene
// whose frames are that block, its first frame carrying the state (poses, deformed shapes) every
// earlier frame left (the engine keeps a body's pose and shape until a frame changes it). Inside
// the block the engine refits its trees from frame to frame, as one process does.
//
// What crosses a block border: a clash's id. The engine carries a clash of a pair and kind from
// the previous frame (engine.h, SceneClash::id: matched by id, then by nearest location), so rank
// k > 0 starts its run early, at frame `start` < lo (first lo - 1, the previous rank's last), to
// have the previous frames' clashes, and drops those frames' findings. Its run started there
// without history, so its ids at `start` are the clashes' own ids; if they equal the ids the owner
// of frame `start` reported (per test and body pair, as sets), the engine's state there is the one
// process's and so are the ids from there on. Rank 0 checks the borders in rank order; a rank
// whose ids differ (a clash that kept an earlier id across the border) runs again from twice as
// far back, down to frame 0 (one process's chain itself), so the report is always one process's.
// The early frames' counts (candidates, suppressed, core runs) are taken off, from one more engine
// call on frames [start, lo) alone. Not caught by the set check: two clashes of one pair whose
// carried ids are each other's own ids at `start` (docs/mpi.md).
#include "series.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include <nlohmann/json.hpp>

#include "clash_outputs.h"
#include "driver.h"
#include "merge.h"
#include "usage.h"
#include "wire.h"
#include "interfere/query/verdict.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/report.h"

namespace interfere::mpi {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The scene of frames [first, last) of `s`: frame `first` carries every pose and shape frames
// 0..first set (the engine's state there), the later ones as they are.
scene::Scene block_scene(const scene::Scene& s, std::size_t first, std::size_t last) {
  scene::Scene b;
  b.units = s.units;
  b.bodies = s.bodies;
  std::map<std::uint32_t, Transform> pose;
  std::map<std::uint32_t, std::shared_ptr<const std::vector<Vec3>>> shape;
  for (std::size_t f = 0; f <= first; ++f) {
    for (const scene::Frame::Pose& p : s.frames[f].poses) pose[p.body] = p.pose;
    for (const scene::Frame::Shape& sh : s.frames[f].shapes) shape[sh.body] = sh.positions;
  }
  scene::Frame head;
  head.label = s.frames[first].label, head.time = s.frames[first].time;
  for (const auto& [i, t] : pose) head.poses.push_back({i, t});
  for (const auto& [i, p] : shape) head.shapes.push_back({i, p});
  b.frames.push_back(std::move(head));
  for (std::size_t f = first + 1; f < last; ++f) b.frames.push_back(s.frames[f]);
  return b;
}

// The engine's rule for a clash's deepest point over frames (src/scene/engine_frames.cpp,
// keep_deeper): the deepest, ties to the smallest (frame, body, vertex). A total order, so the
// ranks' parts merge in any order to the same point.
void keep_deeper(bool& has, scene::DeepestPoint& kept, const scene::DeepestPoint& c) {
  if (!has || c.depth > kept.depth ||
      (c.depth == kept.depth && std::tie(c.frame, c.body, c.vertex) < std::tie(kept.frame, kept.body, kept.vertex))) {
    kept = c;
    has = true;
  }
}

struct Block {
  std::size_t lo = 0, hi = 0;  // the frames this rank reports
  std::size_t start = 0;       // the first frame of its engine run (lo - 1 for k > 0)
};

Block block_of(std::size_t rank, std::size_t ranks, std::size_t frames) {
  Block b;
  b.lo = rank * frames / ranks, b.hi = (rank + 1) * frames / ranks;
  b.start = b.lo > 0 && b.hi > b.lo ? b.lo - 1 : b.lo;
  return b;
}

}  // namespace

std::optional<int> run_frames(const World& w, const Options& o, const SeriesInputs& in) {
  const bool talk = w.rank == 0 && !o.quiet;
  // The whole scene on every rank, as one process reads it (scene_load: meshes, glTF, STEP, FE
  // models with their steps); the same error everywhere, so rank 0 says it.
  const auto t_read = Clock::now();
  const double cpu_read = cpu_seconds();
  auto loaded = scene::load_scene(in.spec.bodies, in.load);
  if (!loaded) throw UsageError(loaded.error().message());
  scene::LoadedScene ls = std::move(*loaded);
  std::vector<std::string> input_warnings = std::move(ls.scene.warnings);
  ls.scene.warnings.clear();
  if (!in.motion.empty()) {
    if (!ls.scene.frames.empty()) throw UsageError("--motion: the inputs already carry steps (an FE model's); give one motion");
    if (const Status s = scene::read_motion(in.motion, ls.scene); !s) throw UsageError(s.error().message());
    ls.files.push_back(in.motion);
  }
  const double read_s = since(t_read), read_cpu = cpu_seconds() - cpu_read;
  const scene::Scene& sc = ls.scene;
  const std::size_t nf = sc.frames.size(), k = static_cast<std::size_t>(w.size), r = static_cast<std::size_t>(w.rank);
  if (nf == 0) {
    if (talk) std::fprintf(stderr, "[interfere-mpi] warning: --distribute frames: the scene has no frames: distributed by body pairs\n");
    return std::nullopt;
  }
  if (talk && k > nf) std::fprintf(stderr, "[interfere-mpi] warning: %d ranks for %zu frames: %zu ranks idle\n", w.size, nf, k - nf);

  // This rank's block [lo, hi), run from frame `start` <= lo (the frames before lo are earlier
  // ranks'; they give the engine the previous frames' clashes: their ids carry over).
  const Block blk0 = block_of(r, k, nf);
  scene::SceneClashOptions eo;
  eo.group_by = scene::GroupBy::none;  // (rank 0 groups the merged result)
  eo.nominal_fit = ls.nominal_fit;
  eo.zero_clearance_fits = ls.zero_clearance_fits;
  eo.reference = o.reference;
  eo.depth_maps = true;  // (as `interfere clash`: the deepest node per clash and step)
  double engine_s = 0, engine_cpu = 0;
  const auto run_block = [&](std::size_t start) {
    Block blk = blk0;
    blk.start = start;
    const auto t_engine = Clock::now();
    const double cpu_engine = cpu_seconds();
    RankResult mine;
    std::size_t candidates = 0, suppressed = 0, calls = 0;
    if (blk.hi > blk.lo) {
      scene::SceneClashResult res;
      try {
        res = scene::clash_scene(block_scene(sc, blk.start, blk.hi), in.tests, eo);
        ++calls;
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      candidates = res.candidate_pairs, suppressed = res.suppressed, mine.core_runs = res.core_runs;
      if (blk.start < blk.lo) {
        // The earlier ranks' frames [start, lo) are theirs to count: their candidates, suppressed
        // pairs and core runs, from one more engine call on them alone (no reference pass, no
        // depth: the counts do not depend on them), are taken off.
        scene::SceneClashOptions early_options = eo;
        early_options.reference = false, early_options.depth = false, early_options.depth_maps = false;
        early_options.curves = false, early_options.triangles = false;
        const scene::SceneClashResult early = scene::clash_scene(block_scene(sc, blk.start, blk.lo), in.tests, early_options);
        ++calls;
        candidates -= early.candidate_pairs, suppressed -= early.suppressed, mine.core_runs -= early.core_runs;
      }
      const auto global = [&](std::uint32_t f) { return static_cast<std::uint32_t>(blk.start + f); };
      for (scene::SceneClash& c : res.clashes) {
        for (std::uint32_t& f : c.frames) f = global(f);
        if (c.has_deepest) c.deepest.frame = global(c.deepest.frame);
        mine.clashes.push_back(std::move(c));  // (those of frames before lo too: the border check)
      }
      for (scene::FramePairRow& p : res.frame_pairs) {
        p.frame = global(p.frame);
        if (p.has_deepest) p.deepest.frame = global(p.deepest.frame);
        if (p.frame >= blk.lo) mine.frame_pairs.push_back(p);
      }
      for (scene::FrameRow& row : res.frames) {
        row.frame = global(row.frame);
        if (row.frame >= blk.lo) mine.frames.push_back(row);
      }
      mine.reference_pairs = std::move(res.reference_pairs);
      mine.reference_checked = res.reference_checked;
      mine.warnings = std::move(res.warnings);
      mine.prepare_seconds = res.prepare_seconds, mine.broad_seconds = res.broad_seconds, mine.narrow_seconds = res.narrow_seconds;
    }
    engine_s += since(t_engine), engine_cpu += cpu_seconds() - cpu_engine;
    mine.calls = calls;
    mine.bodies_loaded = mine.bodies_used = sc.bodies.size();
    for (const scene::Body& b : sc.bodies) mine.triangles_loaded += b.mesh->num_triangles();
    mine.body_triangles = mine.triangles_loaded;
    mine.load_seconds = read_s, mine.load_cpu_seconds = read_cpu;
    mine.engine_seconds = engine_s, mine.engine_cpu_seconds = engine_cpu;
    mine.peak_rss_mb = peak_rss_mb();
    mine.cpu_seconds = cpu_seconds();
    // To rank 0: the block and its counts (CBOR), then the findings (wire.h).
    const std::vector<std::uint8_t> head = nlohmann::json::to_cbor(nlohmann::json{
        {"lo", blk.lo}, {"hi", blk.hi}, {"start", blk.start}, {"candidates", candidates}, {"suppressed", suppressed}});
    std::string bytes(sizeof(std::uint64_t), '\0');
    const std::uint64_t head_size = head.size();
    std::memcpy(bytes.data(), &head_size, sizeof head_size);
    bytes.append(reinterpret_cast<const char*>(head.data()), head.size());
    return bytes + encode(mine);
  };

  // Rounds: every rank runs its block from one frame before it; rank 0 checks each border in rank
  // order (the owner of frame `start` checked already: rank 0's block starts at frame 0, with no
  // history, as one process); a rank whose ids at `start` differ from the owner's runs again from
  // twice as far back (down to frame 0, where the run is one process's), until every border holds.
  std::vector<std::uint64_t> starts(k);
  for (std::size_t q = 0; q < k; ++q) starts[q] = block_of(q, k, nf).start;
  std::vector<char> verified(k, 0), rerun(k, 1);
  std::vector<nlohmann::json> heads(k);
  std::vector<RankResult> ranks(k);
  std::size_t rounds = 0, reruns = 0;
  const auto frame_owner = [&](std::size_t f) {
    for (std::size_t q = 0; q < k; ++q)
      if (const Block b = block_of(q, k, nf); b.lo <= f && f < b.hi) return q;
    throw std::logic_error("no rank holds frame " + std::to_string(f));
  };
  using Key = std::tuple<std::string, std::uint32_t, std::uint32_t>;
  const auto ids_at = [&](std::size_t q, std::uint32_t f) {  // the ids present at frame f per (test, a, b)
    std::map<Key, std::set<std::string>> ids;
    for (const scene::SceneClash& c : ranks[q].clashes)
      if (std::binary_search(c.frames.begin(), c.frames.end(), f)) ids[{c.test, c.a, c.b}].insert(c.id);
    return ids;
  };
  for (;;) {
    ++rounds;
    const std::string bytes = rerun[r] ? run_block(starts[r]) : std::string();
    const std::vector<std::string> all = gather(bytes);
    if (w.rank == 0) {
      for (std::size_t q = 0; q < k; ++q) {
        if (!rerun[q]) continue;
        std::uint64_t n = 0;
        std::memcpy(&n, all[q].data(), sizeof n);
        heads[q] = nlohmann::json::from_cbor(all[q].substr(sizeof n, n));
        ranks[q] = decode_result(all[q].substr(sizeof n + n));
      }
      std::fill(rerun.begin(), rerun.end(), 0);
      for (std::size_t q = 0; q < k; ++q) {
        if (verified[q]) continue;
        const Block b = block_of(q, k, nf);
        if (starts[q] == b.lo || starts[q] == 0) {  // (no history to carry: an idle rank, or from frame 0)
          verified[q] = 1;
          continue;
        }
        const std::size_t owner = frame_owner(starts[q]);
        if (!verified[owner]) continue;  // (checked in a later round)
        const std::uint32_t f = static_cast<std::uint32_t>(starts[q]);
        if (ids_at(q, f) == ids_at(owner, f)) {
          verified[q] = 1;
          continue;
        }
        const std::size_t back = 2 * (b.lo - starts[q]);
        starts[q] = b.lo > back ? b.lo - back : 0;
        rerun[q] = 1, ++reruns;
        if (talk)
          std::fprintf(stderr, "[interfere-mpi] rank %zu: a clash keeps an earlier id across frame %u: its block [%zu, %zu) runs "
                               "again from frame %llu\n", q, f, b.lo, b.hi, static_cast<unsigned long long>(starts[q]));
      }
    }
    MPI_Bcast(starts.data(), static_cast<int>(k), MPI_UINT64_T, 0, MPI_COMM_WORLD);
    MPI_Bcast(rerun.data(), static_cast<int>(k), MPI_CHAR, 0, MPI_COMM_WORLD);
    MPI_Bcast(verified.data(), static_cast<int>(k), MPI_CHAR, 0, MPI_COMM_WORLD);
    if (std::all_of(verified.begin(), verified.end(), [](char v) { return v != 0; })) break;
  }
  const auto t_merge = Clock::now();
  const double cpu_merge = cpu_seconds();

  int status = 0;
  if (w.rank == 0) {
    scene::SceneClashResult result;
    result.bodies = sc.bodies.size();
    for (const scene::Body& b : sc.bodies) result.triangles += b.mesh->num_triangles();
    scene::BroadPhase broad(sc.bodies, in.tests);  // (the selection warnings: every rank's alike)
    result.warnings = broad.warnings();
    std::set<std::string> open;
    std::map<std::string, std::size_t> by_id;
    // Clashes by id, as the engine merges one clash's frames (engine.cpp): the first frame's data,
    // the worst verdict, the largest depth and bound, the deepest point; in frame order (a rank's
    // early frame is its previous rank's, whose data are the same).
    std::vector<std::pair<std::uint32_t, scene::SceneClash*>> order;
    for (RankResult& rr : ranks)
      for (scene::SceneClash& c : rr.clashes) order.emplace_back(c.frames.front(), &c);
    std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto& [first, cp] : order) {
      scene::SceneClash& c = *cp;
      const auto it = by_id.find(c.id);
      if (it == by_id.end()) {
        by_id.emplace(c.id, result.clashes.size());
        result.clashes.push_back(std::move(c));
        continue;
      }
      scene::SceneClash& into = result.clashes[it->second];
      std::vector<std::uint32_t> frames;
      std::set_union(into.frames.begin(), into.frames.end(), c.frames.begin(), c.frames.end(), std::back_inserter(frames));
      into.frames = std::move(frames);
      into.verdict = worst(into.verdict, c.verdict);
      if (c.has_deepest) keep_deeper(into.has_deepest, into.deepest, c.deepest);
      into.depth = std::max(into.depth, c.depth), into.depth_bound = std::max(into.depth_bound, c.depth_bound);
    }
    bool reference_taken = false;
    for (std::size_t q = 0; q < ranks.size(); ++q) {
      RankResult& rr = ranks[q];
      result.candidate_pairs += heads[q]["candidates"].get<std::size_t>();
      result.suppressed += heads[q]["suppressed"].get<std::size_t>();
      result.core_runs += rr.core_runs;
      result.prepare_seconds += rr.prepare_seconds, result.broad_seconds += rr.broad_seconds, result.narrow_seconds += rr.narrow_seconds;
      result.frames.insert(result.frames.end(), rr.frames.begin(), rr.frames.end());
      result.frame_pairs.insert(result.frame_pairs.end(), rr.frame_pairs.begin(), rr.frame_pairs.end());
      if (rr.reference_checked && !reference_taken) {  // (every rank's reference pass is the same)
        result.reference_pairs = rr.reference_pairs;
        result.reference_checked = reference_taken = true;
      }
      for (const std::string& x : rr.warnings)
        if (x.starts_with("body '")) open.insert(x);
    }
    if (result.frames.size() != nf) throw std::logic_error("merged " + std::to_string(result.frames.size()) + " frame rows, expected " + std::to_string(nf));
    for (std::size_t f = 0; f < nf; ++f)
      if (result.frames[f].frame != f) throw std::logic_error("frame rows out of order at " + std::to_string(f));
    scene::SceneClashOptions go;
    go.group_by = o.group_by == "pair" ? scene::GroupBy::pair : o.group_by == "location" ? scene::GroupBy::location : scene::GroupBy::none;
    go.group_distance = o.group_distance;
    scene::finish_result(sc, in.tests, go, result);
    // The engine's open-body warnings after finish_result, in body order.
    for (const scene::Body& b : sc.bodies)
      for (const std::string& x : open)
        if (x.starts_with("body '" + b.id + "' is not closed")) result.warnings.push_back(x);
    if (!o.baseline.empty())
      if (const Status s = scene::apply_baseline(result, in.baseline_text, o.baseline); !s) throw UsageError(s.error().message());
    status = verdict_exit_status(result.verdict, o.fail_on.empty() ? FailOn{} : *parse_fail_on(o.fail_on));
    const int nthreads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    scene::ReportContext ctx{.command = "clash", .tool_version = INTERFERE_VERSION, .inputs = ls.files, .threads = nthreads,
                             .total_seconds = since(in.start), .exit_status = status, .warnings = input_warnings};
    if (!o.json.empty()) {
      nlohmann::json j = nlohmann::json::parse(scene::report_json(sc, in.tests, result, ctx));
      nlohmann::json per = nlohmann::json::array();
      for (std::size_t q = 0; q < ranks.size(); ++q)
        per.push_back({{"rank", q},
                       {"frames", {heads[q]["lo"], heads[q]["hi"]}},
                       {"from_frame", heads[q]["start"]},
                       {"engine_calls", ranks[q].calls},
                       {"core_runs", ranks[q].core_runs},
                       {"bodies_read", ranks[q].bodies_loaded},
                       {"triangles_read", ranks[q].triangles_loaded},
                       {"load_s", ranks[q].load_seconds},
                       {"load_cpu_s", ranks[q].load_cpu_seconds},
                       {"engine_s", ranks[q].engine_seconds},
                       {"engine_cpu_s", ranks[q].engine_cpu_seconds},
                       {"cpu_s", ranks[q].cpu_seconds},
                       {"peak_rss_mb", ranks[q].peak_rss_mb}});
      j["mpi"] = {{"ranks", w.size},
                  {"distribute", "frames"},
                  {"rounds", rounds},
                  {"reruns", reruns},
                  {"per_rank", per},
                  {"merge", {{"wall_s", since(t_merge)}, {"cpu_s", cpu_seconds() - cpu_merge}}}};
      j["seconds"] = since(in.start);
      write_file(o.json, j.dump(2) + "\n");
    }
    write_clash_tables(o, sc, in.tests, result);
    if (!o.quiet) {
      for (const std::string& x : result.warnings) std::fprintf(stderr, "[interfere-mpi] warning: %s\n", x.c_str());
      for (std::size_t q = 0; q < ranks.size(); ++q)
        std::fprintf(stderr, "[interfere-mpi] rank %zu: frames [%zu, %zu) in %zu engine calls, engine %.3f s, peak %.0f MB\n", q,
                     heads[q]["lo"].get<std::size_t>(), heads[q]["hi"].get<std::size_t>(), ranks[q].calls,
                     ranks[q].engine_seconds, ranks[q].peak_rss_mb);
    }
    std::FILE* out = summary_stream(o);
    const std::string verdict = summary_verdict(result.verdict);
    std::fprintf(out, "%s: %zu bodies, %zu candidate pairs: %zu clashes, %zu contacts, %zu clearance, %zu undecided; %zu frames (%d ranks, by frames)\n",
                 verdict.c_str(), result.bodies, result.candidate_pairs, result.clash_count, result.contact_count,
                 result.clearance_count, result.undecided_count, nf, w.size);
  }
  return broadcast(status);
}

}  // namespace interfere::mpi
