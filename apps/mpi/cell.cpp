// interfere-mpi cell (issue #31, item 3; docs/mpi.md, "Time series"). The verdicts of `interfere
// cell` at a frame (a path point or a --between sample) are the engine's at that frame whatever
// came before (robot/cell.h, check_cell_path: certificates only skip pairs proven apart, the
// frames x pairs rows, verdicts and candidate counts are the plain run's), and the cell report
// shows no clash ids, so the path splits exactly in blocks: rank k of K takes points
// [k n / K, (k + 1) n / K) and checks its sub-path with the same calls as `interfere cell`
// (cell_scene, check_cell_path). With --between the segment from a block's last point to the next
// block's first is the earlier rank's: its sub-path runs to that border point, whose own frame is
// dropped (its rows are the next rank's) and whose broad-phase counts are taken off (one engine
// call on that frame alone, deciding no pair). Rank 0 renumbers the frames (cell_scene's order:
// point-major, point i's frame at i (between + 1)), merges the clashes by id as check_cell_path
// merges its chunks, derives the pair summaries and verdict (scene::finish_result) and writes the
// report through the CLI's writer (apps/cli/cell_report.h).
//
// --pose-path (with --ik-start, --write-joints): each point's inverse kinematics is seeded with the
// previous point's solution, so every rank solves the whole path first (cell_pose_joint_path, the
// CLI's call) and then takes its block; rank 0 writes --write-joints.
//
// Not offered (usage error, exit 2): --continuous (its certified distances are carried across
// path points and its blocks of points and look-ahead are counted from point 0, so a block's
// segments could be left `unresolved`, with other `frames` counts, where one process proves them
// clear) and the views (--html, --glb, --pvd).
#include "cell.h"

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "args.h"
#include "block_outputs.h"
#include "driver.h"
#include "cell_pose_path.h"
#include "cell_report.h"
#include "common.h"  // (cli::InputError, which cell_pose_joint_path throws; nothing of common.cpp)
#include "interfere/robot/cell.h"
#include "interfere/scene/engine.h"
#include "report_envelope.h"
#include "usage.h"
#include "wire.h"

namespace interfere::mpi {
namespace {

using namespace interfere::robot;
using Clock = std::chrono::steady_clock;

const char* const kCellUsage =
    "usage: mpirun -n K interfere-mpi cell CELL [--path FILE | --pose-path FILE [--ik-start Q|collision-free]\n"
    "         [--write-joints OUT.csv]] [--between N] [--json OUT] [--csv OUT] [--poses] [--depth] [--fail-on LIST]\n"
    "         [--threads N] [--quiet]\n"
    "The path's points split in blocks per rank; the outputs are those of `interfere cell` (docs/probe.md)\n"
    "plus \"mpi\" in the JSON (a pose path is solved whole on every rank first). Not offered: --continuous,\n"
    "--html, --glb, --pvd (docs/mpi.md, \"Time series\").\n";

struct CellArgs {
  std::string cell, path, json, csv, fail_on;
  std::size_t between = 0;
  bool poses = false, depth = false, quiet = false;
  int max_depth = 12, threads = 0;
  cli::CellPoseInput pose;  ///< --pose-path, --ik-start, --write-joints
};

CellArgs parse_cell(int argc, char** argv) {
  CellArgs o;
  CLI::App app("interfere-mpi cell");
  app.set_help_flag();
  bool help = false, version = false, continuous = false;
  std::string html, glb, pvd, budget;
  app.add_flag("-h,--help", help);
  app.add_flag("--version", version);
  app.add_option("CELL", o.cell);
  app.add_option("--path", o.path);
  app.add_option("--between", o.between);
  app.add_option("--json", o.json);
  app.add_option("--csv", o.csv);
  app.add_flag("--poses", o.poses);
  app.add_flag("--depth", o.depth);
  app.add_option("--max-depth", o.max_depth);
  app.add_option("--fail-on", o.fail_on);
  app.add_option("--threads", o.threads);
  app.add_flag("-q,--quiet", o.quiet);
  app.add_flag("--continuous", continuous);
  app.add_option("--pose-path", o.pose.file);
  app.add_option("--ik-start", o.pose.start);
  app.add_option("--write-joints", o.pose.write_joints);
  app.add_option("--html", html);
  app.add_option("--glb", glb);
  app.add_option("--pvd", pvd);
  app.add_option("--view-budget", budget);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    throw UsageError(std::string(e.what()) + "\n" + kCellUsage);
  }
  if (help) throw InfoRequest{kCellUsage};
  if (version) throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
  if (continuous)
    throw UsageError(
        "--continuous: not offered by interfere-mpi cell: the conservative check between points carries certified "
        "distances across path points (from point 0), so a block of points could leave segments 'unresolved' that one "
        "process proves clear: run `interfere cell --continuous` (docs/mpi.md, \"Time series\")");
  if (app.count("--pose-path") && app.count("--path")) throw UsageError("--pose-path excludes --path");
  if (!o.pose.write_joints.empty() &&
      (o.pose.write_joints.size() < 4 || o.pose.write_joints.substr(o.pose.write_joints.size() - 4) != ".csv"))
    throw UsageError("--write-joints: " + o.pose.write_joints + ": unsupported extension (give a .csv file)");
  for (const char* flag : {"--html", "--glb", "--pvd", "--view-budget"})
    if (app.count(flag))
      throw UsageError(std::string(flag) +
                       ": not offered by interfere-mpi cell: views are drawn from one process's result: run `interfere "
                       "cell` with --html/--glb/--pvd (docs/mpi.md, \"Options\")");
  if (o.cell.empty()) throw UsageError(std::string("CELL: the cell file is required\n") + kCellUsage);
  if (!o.fail_on.empty() && !parse_fail_on(o.fail_on))
    throw UsageError("--fail-on: '" + o.fail_on + "' is not a list of contact, clearance, undecided (comma-separated)");
  if (o.threads < 0) throw UsageError("--threads must be >= 0");
  return o;
}

// What a rank sends besides its RankResult (frame rows, frames x pairs rows, clashes; global frames).
struct CellHeader {
  std::uint64_t lo = 0, hi = 0, frames = 0, candidate_pairs = 0, suppressed = 0;
  double seconds = 0, cpu_seconds = 0;
};

int run_checked(const World& w, const CellArgs& o) {
  const auto t_total = Clock::now();
  // The inputs: every rank reads them and the ranks agree on any error before the work.
  std::optional<Cell> cell;
  JointPath path;
  std::string path_file, error;
  bool poses = false;
  nlohmann::json ik_report;  // --pose-path: the inverse kinematics per point
  try {
    Expected<Cell> read = read_cell_json(o.cell);
    if (!read) throw InputError(read.error().message());
    cell = std::move(*read);
    poses = !o.pose.file.empty();
    path_file = poses ? o.pose.file : o.path.empty() ? cell->path : o.path;
    if (path_file.empty()) throw InputError("--path: no joint path given (and the cell file names none)");
    if (poses) {
      path = cli::cell_pose_joint_path(*cell, o.pose, ik_report);  // (the whole path, on every rank)
    } else {
      Expected<JointPath> p = read_joint_csv(path_file, cell->robot);
      if (!p) throw InputError(p.error().message());
      path = std::move(*p);
    }
    // Outputs: their folders must exist, no output may be an input, --json and --csv differ.
    for (const auto& [flag, out] : {std::pair<const char*, const std::string*>{"--json", &o.json},
                                    {"--csv", &o.csv},
                                    {"--write-joints", &o.pose.write_joints}}) {
      if (out->empty() || *out == "-") continue;
      const std::filesystem::path abs = std::filesystem::absolute(*out);
      if (!std::filesystem::is_directory(abs.parent_path()))
        throw InputError(std::string(flag) + " " + *out + ": no folder " + abs.parent_path().string());
      for (const std::string* input : {&o.cell, static_cast<const std::string*>(&path_file)})
        if (std::filesystem::absolute(*input) == abs) throw InputError(std::string(flag) + " " + *out + ": is an input file");
    }
    if (!o.json.empty() && o.json != "-" && !o.csv.empty() &&
        std::filesystem::absolute(o.json) == std::filesystem::absolute(o.csv))
      throw InputError("--json and --csv name the same file " + o.json);
    if (!o.pose.write_joints.empty())
      for (const std::string* out : {&o.json, &o.csv})
        if (!out->empty() && *out != "-" &&
            std::filesystem::absolute(*out) == std::filesystem::absolute(o.pose.write_joints))
          throw InputError("--write-joints and another output name the same file " + *out);
  } catch (const InputError& e) {
    error = e.what();
  } catch (const cli::InputError& e) {  // (cell_pose_joint_path: the pose path, --ik-start)
    error = e.what();
  }
  for (const std::string& e : allgather(error))
    if (!e.empty()) throw InputError(e);
  const FailOn fail = o.fail_on.empty() ? FailOn{} : *parse_fail_on(o.fail_on);
  std::unique_ptr<tbb::global_control> threads;
  if (o.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);

  // This rank's block of points, and with --between the segment to the next block's first point.
  const std::size_t n = path.size(), k = static_cast<std::size_t>(w.size), rank = static_cast<std::size_t>(w.rank);
  const std::size_t lo = rank * n / k, hi = (rank + 1) * n / k, per = o.between + 1;
  if (w.rank == 0 && k > n && !o.quiet)
    std::fprintf(stderr, "[interfere-mpi] warning: %d ranks for %zu path points: %zu ranks idle\n", w.size, n, k - n);
  const bool border = o.between > 0 && lo < hi && hi < n;
  const auto t_run = Clock::now();
  scene::SceneClashOptions engine;
  engine.reference = false;
  engine.depth = o.depth;
  RankResult mine;
  CellHeader head;
  head.lo = lo, head.hi = hi;
  if (lo < hi) {
    JointPath sub;
    for (std::size_t i = lo; i < hi + (border ? 1 : 0); ++i) sub.q.push_back(path.q[i]), sub.lines.push_back(path.lines[i]);
    const CellScene cs = cell_scene(*cell, sub, o.between);
    PathCheckOptions po;
    po.engine = engine;
    PathCheckResult checked = check_cell_path(*cell, cs, sub, po);
    scene::SceneClashResult& r = checked.frames;
    const std::size_t keep = border ? cs.scene.frames.size() - 1 : cs.scene.frames.size();
    const auto offset = static_cast<std::uint32_t>(lo * per);
    for (scene::FrameRow& row : r.frames)
      if (row.frame < keep) row.frame += offset, mine.frames.push_back(std::move(row));
    for (scene::FramePairRow& row : r.frame_pairs)
      if (row.frame < keep) row.frame += offset, mine.frame_pairs.push_back(row);
    for (scene::SceneClash& c : r.clashes) {
      std::vector<std::uint32_t> frames;
      for (std::uint32_t f : c.frames)
        if (f < keep) frames.push_back(f + offset);
      if (frames.empty()) continue;
      c.frames = std::move(frames);
      mine.clashes.push_back(std::move(c));
    }
    head.frames = keep;
    head.candidate_pairs = r.candidate_pairs, head.suppressed = r.suppressed;
    if (border) {
      // The border point's frame belongs to the next rank: its broad-phase counts are taken off
      // (the engine on that frame alone, no pair decided: the same boxes, the same candidates).
      scene::Scene one = cs.scene;
      one.frames = {cs.scene.frames.back()};
      scene::SceneClashOptions count = engine;
      count.decide_in_frame = [](std::size_t, std::uint32_t, std::uint32_t) { return false; };
      const scene::SceneClashResult extra = scene::clash_scene(one, cs.tests, count);
      head.candidate_pairs -= extra.candidate_pairs, head.suppressed -= extra.suppressed;
    }
  }
  head.seconds = std::chrono::duration<double>(Clock::now() - t_run).count();
  head.cpu_seconds = cpu_seconds();
  const std::vector<std::string> all = gather_blocks(head, encode(mine));

  int status = 0;
  if (w.rank == 0) {
    if (poses && !o.pose.write_joints.empty()) write_file(o.pose.write_joints, cli::cell_joints_csv(*cell, path, o.pose));
    const CellScene cs = cell_scene(*cell, path, o.between);  // (the whole path: the report's frames)
    scene::SceneClashResult r;
    std::unordered_map<std::string, std::size_t> by_id;
    nlohmann::json ranks = nlohmann::json::array();
    for (std::size_t q = 0; q < all.size(); ++q) {
      CellHeader h;
      RankResult part = decode_result(block_rows(all[q], h));
      for (scene::FrameRow& row : part.frames) r.frames.push_back(std::move(row));
      for (scene::FramePairRow& row : part.frame_pairs) r.frame_pairs.push_back(row);
      // (ranks in frame order: a clash's first entry is kept, later ranks' frames added, as
      // check_cell_path merges its chunks)
      for (scene::SceneClash& c : part.clashes) {
        const auto it = by_id.find(c.id);
        if (it == by_id.end()) {
          by_id.emplace(c.id, r.clashes.size());
          r.clashes.push_back(std::move(c));
          continue;
        }
        scene::SceneClash& prev = r.clashes[it->second];
        prev.frames.insert(prev.frames.end(), c.frames.begin(), c.frames.end());
        prev.verdict = worst(prev.verdict, c.verdict);
        prev.depth = std::max(prev.depth, c.depth), prev.depth_bound = std::max(prev.depth_bound, c.depth_bound);
      }
      r.candidate_pairs += h.candidate_pairs, r.suppressed += h.suppressed;
      ranks.push_back({{"rank", q},
                       {"points", {h.lo, h.hi}},
                       {"frames", h.frames},
                       {"seconds", h.seconds},
                       {"cpu_seconds", h.cpu_seconds}});
    }
    if (r.frames.size() != cs.scene.frames.size())
      throw std::logic_error("gathered " + std::to_string(r.frames.size()) + " frame rows, expected " +
                             std::to_string(cs.scene.frames.size()));
    for (std::size_t f = 0; f < r.frames.size(); ++f)
      if (r.frames[f].frame != f) throw std::logic_error("frame rows out of order at " + std::to_string(f));
    r.bodies = cs.scene.bodies.size();
    scene::finish_result(cs.scene, cs.tests, engine, r);
    const std::vector<SegmentResult> none;
    const cli::CellRun run{*cell, cs, path, r, none};
    cli::CellReportOptions ro;
    ro.cell_file = o.cell;
    ro.path_file = path_file;
    ro.ik = poses;
    if (poses) ro.ik_report = std::move(ik_report);
    ro.between = o.between;
    ro.max_depth = o.max_depth;
    ro.link_poses = o.poses;
    ro.fail_on = fail;
    const cli::CellTotals totals = cli::cell_totals(run, ro);
    status = totals.status;
    const BlockOutputs outputs{.json = o.json, .csv = o.csv, .quiet = o.quiet, .start = t_total};
    write_block_reports(w, outputs, std::move(ranks), [&] { return cli::cell_report_json(run, ro, totals); },
                        [&] { return cli::cell_report_csv(run); });
    print_block_summary(w, outputs, [&] { cli::print_cell_summary(stdout, run, ro, totals); });
  }
  return broadcast(status);
}

}  // namespace

int run_cell(const World& w, int argc, char** argv) {
  return run_guarded(w, [&] { return run_checked(w, parse_cell(argc, argv)); });
}

}  // namespace interfere::mpi
