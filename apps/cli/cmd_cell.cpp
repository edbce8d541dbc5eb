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

nlohmann::json vec_json(const Vec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}
nlohmann::json pose_json(const Transform& t) {
  const auto v = t.to_row_major();
  return nlohmann::json(std::vector<double>(v.begin(), v.end()));
}
nlohmann::json number_or_null(double v) {
  return v >= 0 ? nlohmann::json(v) : nlohmann::json(nullptr);
}
std::string csv_number(double v) {
  if (v < 0) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

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
  const auto& bodies = cs.scene.bodies;
  // Per frame: its findings (frame_pairs rows, sorted by frame).
  std::vector<std::vector<const scene::FramePairRow*>> rows(cs.scene.frames.size());
  for (const scene::FramePairRow& row : r.frame_pairs) rows[row.frame].push_back(&row);
  const std::size_t n = path->size();
  std::vector<Verdict> point_verdict(n, Verdict::clear),
      segment_verdict(n ? n - 1 : 0, Verdict::clear);
  for (std::size_t f = 0; f < cs.scene.frames.size(); ++f) {
    const Verdict v = r.frames.size() > f ? r.frames[f].verdict : Verdict::clear;
    Verdict& target =
        cs.frame_t[f] == 0 ? point_verdict[cs.frame_point[f]] : segment_verdict[cs.frame_point[f]];
    target = worst(target, v);
  }
  std::size_t colliding_points = 0, colliding_segments = 0;
  for (Verdict v : point_verdict) colliding_points += v == Verdict::clash;
  for (Verdict v : segment_verdict) colliding_segments += v == Verdict::clash;
  // The conservative check between points (robot/cell.h, check_between_points).
  std::vector<SegmentResult> between;
  std::size_t seg_collide = 0, seg_unresolved = 0;
  Verdict verdict = r.verdict;
  if (o.continuous) {
    between = std::move(checked.segments);
    for (const SegmentResult& sr : between) {
      seg_collide += sr.state == robot::SegmentState::collides;
      seg_unresolved += sr.state == robot::SegmentState::unresolved;
    }
    if (seg_unresolved) verdict = worst(verdict, Verdict::undecided);
    if (seg_collide) verdict = worst(verdict, Verdict::clash);
  }
  const int status = verdict_exit_status(verdict, failing);

  auto pair_json = [&](const scene::FramePairRow& row) {
    nlohmann::json e = {{"test", cs.tests[row.test].name},
                        {"a", bodies[row.a].id},
                        {"b", bodies[row.b].id},
                        {"verdict", verdict_name(row.verdict)},
                        {"min_distance", number_or_null(row.min_distance)}};
    if (row.max_depth_bound > 0) e["depth"] = row.max_depth, e["depth_bound"] = row.max_depth_bound;
    return e;
  };
  if (!o.json.empty()) {
    nlohmann::json j;
    j["command"] = "cell";
    j["cell"] = o.cell;
    j["path"] = path_file;
    if (poses) j["ik"] = std::move(ik_report);
    j["units"] = "mm";
    nlohmann::json joints = nlohmann::json::array();
    for (std::size_t m : cell->robot.movable) {
      const ChainJoint& jt = cell->robot.joints[m];
      joints.push_back({{"name", jt.name},
                        {"type", joint_kind_name(jt.kind)},
                        {"lower", jt.lower},
                        {"upper", jt.upper}});
    }
    j["robot"] = {{"name", cell->robot.name},
                  {"format", cell->robot_format},
                  {"file", cell->robot_file},
                  {"joints", joints},
                  {"tool_link", cell->tool.link},
                  {"base", pose_json(cell->base)}};
    if (cell->robot_format == "urdf") j["robot"]["urdf"] = cell->robot_file;  // as before DH cells
    nlohmann::json jb = nlohmann::json::array();
    for (const scene::Body& b : bodies) {
      jb.push_back({{"id", b.id},
                    {"tags", b.tags},
                    {"triangles", b.mesh->num_triangles()},
                    {"source", b.source.file}});
    }
    j["bodies"] = std::move(jb);
    nlohmann::json jt = nlohmann::json::array();
    for (const scene::ClashTest& t : cs.tests) {
      nlohmann::json sup = nlohmann::json::array();
      for (const scene::Suppression& s : t.suppressions) {
        sup.push_back({{"a", s.a[0].pattern}, {"b", s.b[0].pattern}, {"reason", s.reason}});
      }
      jt.push_back(
          {{"name", t.name}, {"mode", scene::clash_mode_name(t.mode)}, {"suppressed", sup}});
    }
    j["tests"] = std::move(jt);
    nlohmann::json points = nlohmann::json::array(), segments = nlohmann::json::array();
    for (std::size_t f = 0; f < cs.scene.frames.size(); ++f) {
      const std::size_t i = cs.frame_point[f];
      nlohmann::json pairs = nlohmann::json::array();
      for (const scene::FramePairRow* row : rows[f]) pairs.push_back(pair_json(*row));
      if (cs.frame_t[f] != 0) {
        if (!pairs.empty()) {
          segments.push_back({{"from", i},
                              {"to", i + 1},
                              {"t", cs.frame_t[f]},
                              {"verdict", verdict_name(r.frames[f].verdict)},
                              {"pairs", std::move(pairs)}});
        }
        continue;
      }
      nlohmann::json q = nlohmann::json::object();
      for (std::size_t m = 0; m < cell->robot.dof(); ++m)
        q[cell->robot.joints[cell->robot.movable[m]].name] = path->q[i][m];
      const std::vector<Transform> frames = link_frames(cell->robot, path->q[i], cell->base);
      const ToolCylinders tc = tool_cylinders(cell->tool, frames[cell->tool_link]);
      nlohmann::json p = {{"index", i},
                          {"line", path->lines[i]},
                          {"joints", std::move(q)},
                          {"verdict", verdict_name(point_verdict[i])},
                          {"tip", vec_json(tc.tip)},
                          {"axis", vec_json((tc.tip - tc.back) / norm(tc.tip - tc.back))},
                          {"pairs", std::move(pairs)}};
      if (o.poses) {
        nlohmann::json lp = nlohmann::json::object();
        for (std::size_t k = 0; k < frames.size(); ++k)
          lp[cell->robot.links[k].name] = pose_json(frames[k]);
        p["links"] = std::move(lp);
      }
      points.push_back(std::move(p));
    }
    j["points"] = std::move(points);
    j["between"] = o.between;
    j["segments"] = std::move(segments);
    nlohmann::json pairs = nlohmann::json::array();
    for (const scene::PairSummary& s : r.pairs) {
      std::vector<std::size_t> pts;
      for (const scene::FramePairRow& row : r.frame_pairs) {
        if (row.a == s.a && row.b == s.b && cs.tests[row.test].name == s.test &&
            cs.frame_t[row.frame] == 0 &&
            (row.verdict == Verdict::clash || row.verdict == Verdict::contact)) {
          pts.push_back(cs.frame_point[row.frame]);
        }
      }
      pairs.push_back({{"test", s.test},
                       {"a", bodies[s.a].id},
                       {"b", bodies[s.b].id},
                       {"verdict", verdict_name(s.verdict)},
                       {"points", pts}});
    }
    j["pairs"] = std::move(pairs);
    if (o.continuous) {
      nlohmann::json js = nlohmann::json::array();
      for (const SegmentResult& sr : between) {
        nlohmann::json e = {{"from", sr.from},
                            {"to", sr.from + 1},
                            {"state", robot::segment_state_name(sr.state)},
                            {"frames", sr.frames}};
        if (sr.state == robot::SegmentState::collides) {
          nlohmann::json ps = nlohmann::json::array();
          for (const SegmentPair& p : sr.pairs)
            ps.push_back({{"test", p.test}, {"a", p.a}, {"b", p.b}, {"t", p.t}});
          e["t"] = sr.t;
          e["pairs"] = std::move(ps);
        }
        if (sr.state == robot::SegmentState::unresolved)
          e["unresolved_pairs"] = sr.unresolved_pairs;
        js.push_back(std::move(e));
      }
      j["between_points"] = {{"max_depth", o.max_depth}, {"segments", std::move(js)}};
    }
    j["summary"] = {{"points", n},
                    {"colliding_points", colliding_points},
                    {"colliding_segments", colliding_segments},
                    {"frames", cs.scene.frames.size()},
                    {"bodies", bodies.size()},
                    {"candidate_pairs", r.candidate_pairs},
                    {"suppressed", r.suppressed},
                    {"continuous", o.continuous},
                    {"colliding_between", seg_collide},
                    {"unresolved_between", seg_unresolved},
                    {"verdict", verdict_name(verdict)}};
    j["exit_status"] = status;
    write_or_throw(write_output(o.json, report_text(j, 1)));
  }
  if (!o.csv.empty()) {
    std::string out = "point,line,t,verdict,test,a,b,pair_verdict,min_distance\n";
    for (std::size_t f = 0; f < cs.scene.frames.size(); ++f) {
      const std::size_t i = cs.frame_point[f];
      const std::string head = std::to_string(i) + "," + std::to_string(path->lines[i]) + "," +
                               short_number(cs.frame_t[f]) + "," +
                               verdict_name(r.frames[f].verdict) + ",";
      if (rows[f].empty()) {
        if (cs.frame_t[f] == 0) out += head + ",,,,\n";
        continue;
      }
      for (const scene::FramePairRow* row : rows[f]) {
        out += head + cs.tests[row->test].name + "," + bodies[row->a].id + "," + bodies[row->b].id +
               "," + verdict_name(row->verdict) + "," + csv_number(row->min_distance) + "\n";
      }
    }
    write_or_throw(write_output(o.csv, out));
  }
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
  if (!is_standard_output(o.json) && !is_standard_output(o.csv)) {
    std::printf(
        "%s: %zu of %zu path points collide, %zu of %zu segments collide at a sampled "
        "between-point frame (%zu per segment); %zu bodies, %zu candidate body pairs checked "
        "over %zu frames (%zu adjacent pairs left out)\n",
        verdict == Verdict::clash ? "COLLISION" : verdict_name(verdict), colliding_points, n,
        colliding_segments, n ? n - 1 : 0, o.between, bodies.size(), r.candidate_pairs,
        cs.scene.frames.size(), r.suppressed);
    std::map<std::string, std::size_t> by_pair;
    for (const scene::FramePairRow& row : r.frame_pairs) {
      if (cs.frame_t[row.frame] == 0 && row.verdict == Verdict::clash) {
        ++by_pair[bodies[row.a].id + " / " + bodies[row.b].id];
      }
    }
    for (const auto& [k, v] : by_pair) std::printf("  %s: %zu points\n", k.c_str(), v);
    if (o.continuous) {
      std::printf(
          "between points (conservative, depth %d): %zu of %zu segments collide, %zu unresolved\n",
          o.max_depth, seg_collide, between.size(), seg_unresolved);
    }
  }
  return status;
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
