// `interfere cell`: the whole inspection cell along a joint path (issue #28, deliverable 3): a URDF
// robot with the probe and holder on its tool link, the workpiece and the fixtures, as bodies of
// the scene engine (robot/cell.h, scene::clash_scene), one frame per path point (plus optional
// sampled frames between points). Reports per path point and per body pair (JSON, CSV). Exit
// status by verdict_exit_status: 0 clear, 1 clash (or what --fail-on names), 2 input error, 3
// undecided.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <map>

#include "cell_pose_path.h"
#include "cell_report.h"
#include "commands.h"
#include "common.h"
#include "interfere/robot/cell.h"
#include "interfere/view/scene_document.h"
#include "report_envelope.h"
#include "view_output.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

using namespace interfere::robot;

struct CellOptions {
  std::string cell, path, json, csv, fail_on;
  std::size_t between = 0;
  bool poses = false;
  bool continuous = false;  ///< --continuous: the conservative check between points
  bool depth = false;       ///< --depth: how deep clashing bodies reach (depth, depth_bound)
  int max_depth = 12;
  int threads = 0;
  ViewOutputs views;  ///< --html, --glb, --pvd: the cell along the path (one step per frame)
  CellPoseInput pose;  ///< --pose-path, --ik-start, --write-joints (inverse kinematics)
};

int run_cell(const CellOptions& o) {
  set_threads(o.threads);
  const FailOn failing = fail_on(o.fail_on);
  Expected<Cell> cell = read_cell_json(o.cell);
  if (!cell) throw InputError(cell.error());
  const bool poses = !o.pose.file.empty();
  const std::string path_file = poses ? o.pose.file : o.path.empty() ? cell->path : o.path;
  if (path_file.empty())
    throw InputError("--path: no joint path given (and the cell file names none)");
  std::vector<NamedPath> outputs{
      {"--json", o.json}, {"--csv", o.csv}, {"--write-joints", o.pose.write_joints}};
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"CELL", o.cell}, {poses ? "--pose-path" : "--path", path_file}}, outputs);
  nlohmann::json ik_report;  // --pose-path: the inverse kinematics per point
  Expected<JointPath> path = poses ? Expected<JointPath>(cell_pose_joint_path(*cell, o.pose, ik_report))
                                   : read_joint_csv(path_file, cell->robot);
  if (!path) throw InputError(path.error());
  if (poses && !o.pose.write_joints.empty())
    write_or_throw(write_output(o.pose.write_joints, cell_joints_csv(*cell, *path, o.pose)));

  const CellScene cs = cell_scene(*cell, *path, o.between);
  scene::SceneClashOptions opt;
  opt.curves = o.views.any();  // the viewer draws the intersection curves
  opt.reference = false;
  opt.depth = o.depth;  // off by default: the points' check is ~4x faster without the depth bounds
  // The frames (the path's points and in-between poses) and, with --continuous, the conservative
  // check between points in one pass with certified distances carried across points
  // (robot/cell.h, check_cell_path: the same verdicts as the engine at every frame).
  PathCheckResult checked;
  try {
    ProgressBar bar("frames", std::max<std::size_t>(cs.scene.frames.size(), 1), "frames");
    PathCheckOptions po;
    po.engine = opt;
    po.engine.progress = bar.callback();
    po.between = o.continuous;
    po.between_options.max_depth = o.max_depth;
    checked = check_cell_path(*cell, cs, *path, po);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.cell + ": " + e.what());
  }
  const scene::SceneClashResult& r = checked.frames;
  std::vector<SegmentResult> between;  // (robot/cell.h, check_between_points)
  if (o.continuous) between = std::move(checked.segments);
  const std::size_t n = path->size();
  // The report (cell_report.h: shared with `interfere-mpi cell`).
  const CellRun run{*cell, cs, *path, r, between};
  CellReportOptions ro;
  ro.cell_file = o.cell;
  ro.path_file = path_file;
  ro.ik = poses;
  if (poses) ro.ik_report = std::move(ik_report);
  ro.between = o.between;
  ro.continuous = o.continuous;
  ro.max_depth = o.max_depth;
  ro.link_poses = o.poses;
  ro.fail_on = failing;
  const CellTotals totals = cell_totals(run, ro);
  const std::size_t colliding_points = totals.colliding_points;
  if (!o.json.empty()) write_or_throw(write_output(o.json, report_text(cell_report_json(run, ro, totals), 1)));
  if (!o.csv.empty()) write_or_throw(write_output(o.csv, cell_report_csv(run)));
  if (o.views.any()) {
    view::SceneDocumentOptions vo;
    vo.title = "interfere cell: " + cell->robot.name + ", " + std::to_string(n) + " path points, " +
               std::to_string(colliding_points) + " colliding";
    vo.command = "cell";
    vo.tool_version = INTERFERE_VERSION;
    vo.flag_instances = true;
    view::Document doc = view::scene_document(cs.scene, cs.tests, r, vo);
    doc.units = "mm";
    write_views(o.views, std::move(doc));
  }
  if (!is_standard_output(o.json) && !is_standard_output(o.csv)) print_cell_summary(stdout, run, ro, totals);
  return totals.status;
}

}  // namespace

void add_cell_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CellOptions>();
  CLI::App* c = app.add_subcommand("cell",
                                   "Inspection cell along a joint path: URDF robot links, probe, "
                                   "holder, workpiece and fixtures as "
                                   "scene bodies, every pair that can meet checked at every path "
                                   "point (docs/probe.md, \"The cell\")");
  c->add_option("CELL", o->cell, "cell file (JSON: robot URDF, tool, workpiece, fixtures)")
      ->required()
      ->check(CLI::ExistingFile);
  CLI::Option* path_opt = c->add_option("--path", o->path,
                "joint path CSV, header = the robot's movable joint names (degrees, mm); default: "
                "the cell's \"path\"")
      ->check(CLI::ExistingFile);
  c->add_option("--pose-path", o->pose.file,
                "probe pose path CSV (px,py,pz,ax,ay,az[,rx,ry,rz], as interfere sweep's) turned "
                "into joints by numerical inverse kinematics, each point from the previous one's "
                "solution; an unreachable point or one outside the joint limits is an error "
                "naming its line")
      ->check(CLI::ExistingFile)
      ->excludes(path_opt);
  c->add_option("--ik-start", o->pose.start,
                "--pose-path: joint values (comma-separated, the robot's movable joints in chain "
                "order) tried first for the first point: picks the branch; or 'collision-free': the "
                "first point solved from every seed and the first solution clear of everything used");
  c->add_option("--write-joints", o->pose.write_joints,
                "--pose-path: write the solved joint path (CSV, header = joint names)");
  c->add_option(
      "--between", o->between,
      "also check N evenly spaced frames inside each segment (joint interpolation; samples, not a "
      "conservative sweep; default 0)");
  c->add_option("--json", o->json, "JSON report (per point, per body pair)");
  c->add_option("--csv", o->csv,
                "CSV table: one row per finding (point, test, body pair), or per clear point");
  c->add_flag("--poses", o->poses,
              "JSON: every link's pose (world <- link, 12 numbers) at every point");
  c->add_flag(
      "--continuous", o->continuous,
      "also prove each segment clear or find where it collides: conservative per-body motion "
      "bounds, intervals halved until decided; undecided segments are 'unresolved' (exit 3)");
  c->add_option("--max-depth", o->max_depth, "--continuous: halvings of a segment (default 12)");
  c->add_flag("--depth", o->depth,
              "also measure how deep clashing bodies reach into each other at the points (pairs' depth, "
              "depth_bound; slower)");
  add_fail_on_option(*c, o->fail_on);
  add_view_options(*c, o->views);
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  c->callback([o, &exit_code] {
    check_output(o->json, {}, "--json");
    check_output(o->csv, {}, "--csv");
    check_output(o->pose.write_joints, {".csv"}, "--write-joints");
    check_view_outputs(o->views);
    exit_code = run_cell(*o);
  });
}

}  // namespace interfere::cli
