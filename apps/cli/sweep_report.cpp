// The report of `interfere sweep`, moved out of cmd_sweep.cpp (issue #31, item 3) so that
// `interfere-mpi sweep` writes the same files (sweep_report.h).
#include "sweep_report.h"

#include <cmath>

#include "interfere/query/verdict.h"

namespace interfere::cli {
namespace {

using namespace interfere::probe;

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string csv_number(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "" : "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

void sweep_min_clearance(const SweepResult& r, double& min_clear, long& min_point) {
  min_clear = std::numeric_limits<double>::infinity();
  min_point = -1;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const double c = r.points[i].collides ? 0.0 : r.points[i].clearance;
    if (c < min_clear) min_clear = c, min_point = static_cast<long>(i);
  }
}

nlohmann::json sweep_report_json(const SweepRun& run) {
  const SweepOptions& o = run.o;
  const Workpiece& w = run.w;
  const ProbePath& path = run.path;
  const bool pose_input = run.pose_input;
  const Robot* robot = run.robot;
  const ProbeShape& shape = run.shape;
  const Hierarchy hierarchy = run.hierarchy;
  const bool joint_motion = run.joint_motion;
  const SweepResult& r = run.r;
  const std::vector<PaperPointCheck>& paper = run.paper;
  const std::size_t paper_colliding = run.paper_colliding, paper_fp = run.paper_fp, paper_fn = run.paper_fn;
  const double workpiece_scale = run.workpiece_scale, read_seconds = run.read_seconds;
  const bool replanning = run.replanning;
  const ReplanRequest& replan_request = run.replan_request;
  const ReplanResult& replanned = run.replanned;
  const SweepResult& after = run.after;
  const int status = run.status;
  double min_clear = 0;
  long min_point = -1;
  sweep_min_clearance(r, min_clear, min_point);
  nlohmann::json j;
  j["version"] = INTERFERE_VERSION;
  j["command"] = "sweep";
  j["verdict"] = verdict_name(r.verdict);
  j["warnings"] = w.warnings;
  j["units"] = o.units;
  j["inputs"] = {{"workpiece", {{"file", o.workpiece}, {"format", run.format}, {"units", run.unit},
                                {"units_source", run.unit_source}, {"scale_to_working_unit", workpiece_scale},
                                {"triangles", w.mesh.num_triangles()}, {"vertices", w.mesh.num_vertices()}}},
                 {"path", {{"file", o.path}, {"points", path.size()}, {"kind", pose_input ? "poses" : "joints"},
                           {"columns", path.columns},
                           {"inverse_kinematics", pose_input && path.joint_space}}}};
  if (run.format == "step") j["inputs"]["workpiece"]["linear_deflection"] = run.linear_deflection;
  if (robot) {
    j["inputs"]["robot"] = {{"file", o.robot}, {"name", robot->name}, {"joints", robot->joints.size()}};
  }
  j["probe"] = {{"radius", shape.radius},
                {"length", shape.length},
                {"holder_kind", shape.has_holder_box() ? "box" : shape.has_holder() ? "cylinder" : "none"},
                {"holder_radius", shape.holder_radius},
                {"holder_length", shape.holder_length},
                {"holder_box_width", shape.holder_box_width},
                {"holder_box_depth", shape.holder_box_depth},
                {"holder_box_length", shape.holder_box_length}};
  j["options"] = {{"hierarchy", hierarchy_name(hierarchy)},
                  {"interpolate", joint_motion ? "joint" : "pose"},
                  {"patch_rule", o.patch_rule},
                  {"patch_size", o.patch_size},
                  {"continuous", !o.no_continuous},
                  {"clearance", !o.no_clearance},
                  {"max_clearance", number_or_null(o.max_clearance > 0 ? o.max_clearance : INFINITY)},
                  {"depth", o.depth},
                  {"max_poses", o.max_poses},
                  {"clearance_requested", o.clearance},
                  {"fail_on", o.fail_on.empty() ? std::string("clash") : o.fail_on},
                  {"threads", run.threads}};
  j["workpiece"] = {{"triangles", w.mesh.num_triangles()}, {"patches", w.patches.size()},
                    {"solids", w.solids.size()}, {"open_components", w.open_components}};
  j["summary"] = {{"points", path.size()},
                  {"colliding_points", r.colliding_points},
                  {"verdict", verdict_name(r.verdict)},
                  {"inside_points", r.inside_points},
                  {"undecided_points", r.undecided_points},
                  {"colliding_segments", r.colliding_segments},
                  {"unresolved_segments", r.unresolved_segments},
                  {"segments_checked", o.no_continuous || path.size() < 2 ? 0 : path.size() - 1},
                  {"clear_segments", o.no_continuous || path.size() < 2 ? 0 : path.size() - 1 - r.segments.size()},
                  {"between_samples_segments", r.between_samples_segments},
                  {"min_clearance", number_or_null(min_clear)},
                  {"min_clearance_point", min_point},
                  {"candidate_tests", r.candidate_tests},
                  {"collision", r.any_collision()}};
  if (o.paper_levels) {
    j["summary"]["paper_levels"] = {{"colliding_points", paper_colliding},
                                    {"false_positives", paper_fp},
                                    {"false_negatives", paper_fn}};
  }
  nlohmann::json pts = nlohmann::json::array();
  nlohmann::json colliding = nlohmann::json::array();
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const PointResult& p = r.points[i];
    nlohmann::json e{{"index", i},
                     {"line", path.lines[i]},
                     {"verdict", verdict_name(p.verdict)},
                     {"collides", p.collides},
                     {"inside", p.inside},
                     {"holder", p.holder},
                     {"clearance", number_or_null(p.clearance)},
                     {"triangle", p.triangle == kNone ? nlohmann::json(nullptr) : nlohmann::json(p.triangle)},
                     {"patch", p.patch == kNone ? nlohmann::json(nullptr) : nlohmann::json(p.patch)},
                     {"hits", p.hits},
                     {"tip", vec_json(path.poses[i].tip)},
                     {"axis", vec_json(path.poses[i].axis)}};
    if (path.joint_space && i < path.joints.size()) e["joints"] = path.joints[i];
    if (o.paper_levels) {
      const PaperPointCheck& pc = paper[i];
      e["paper"] = {{"collides", pc.collides},
                    {"exact_probe_contact", pc.exact},
                    {"false_positive", pc.false_positive()},
                    {"false_negative", pc.false_negative()},
                    {"patches_passed", pc.patches_passed},
                    {"triangles_passed", pc.triangles_passed},
                    {"projections_passed", pc.projections_passed},
                    {"hits", pc.hits}};
    }
    if (!p.collides && p.triangle != kNone) {
      e["point_probe"] = vec_json(p.point_probe);
      e["point_workpiece"] = vec_json(p.point_workpiece);
    }
    if (p.collides) colliding.push_back(i);
    pts.push_back(std::move(e));
  }
  j["points"] = std::move(pts);
  j["colliding_points"] = std::move(colliding);
  // Every segment whose verdict is not clear; "colliding_segments" keeps those that collide.
  auto intervals = [](const std::vector<std::array<double, 2>>& v) {
    nlohmann::json iv = nlohmann::json::array();
    for (const auto& x : v) iv.push_back({x[0], x[1]});
    return iv;
  };
  nlohmann::json segs = nlohmann::json::array(), colliding_segs = nlohmann::json::array();
  for (const SegmentResult& s : r.segments) {
    nlohmann::json e{{"from", s.from},
                     {"to", s.from + 1},
                     {"verdict", verdict_name(s.verdict)},
                     {"state", segment_state_name(s.state)},
                     {"intervals", intervals(s.intervals)},
                     {"unresolved", intervals(s.unresolved)},
                     {"between_samples", s.between_samples},
                     {"triangles", s.triangles},
                     {"poses_tested", s.poses_tested}};
    if (s.state == SegmentState::unresolved) {
      e["smallest_gap"] = number_or_null(s.smallest_gap);
      e["unresolved_motion"] = s.unresolved_motion;
    }
    if (o.clearance > 0 && s.state == SegmentState::clear) {
      e["clearance_state"] = segment_state_name(s.clearance_state);
      e["clearance_intervals"] = intervals(s.clearance_intervals);
      e["clearance_unresolved"] = intervals(s.clearance_unresolved);
    }
    if (s.state == SegmentState::collides) colliding_segs.push_back(e);
    segs.push_back(std::move(e));
  }
  j["segments"] = std::move(segs);
  j["colliding_segments"] = std::move(colliding_segs);
  j["timings"] = {{"read", read_seconds}, {"build", w.build_seconds}, {"discrete", r.discrete_seconds},
                  {"clearance", r.clearance_seconds}, {"continuous", r.continuous_seconds},
                  {"total", run.total_seconds}};
  if (replanning) {
    nlohmann::json rp = nlohmann::json::array();
    for (const ReplannedPoint& q : replanned.points) {
      nlohmann::json e{{"index", q.point}, {"line", q.line}, {"found", q.found}, {"poses_tested", q.poses_tested},
                       {"target", {q.target.x, q.target.y, q.target.z}}};
      if (q.found) {
        e["tilt_deg"] = q.tilt_deg;
        e["standoff_change"] = q.standoff_change;
        e["tip"] = {q.pose.tip.x, q.pose.tip.y, q.pose.tip.z};
        e["axis"] = {q.pose.axis.x, q.pose.axis.y, q.pose.axis.z};
        e["joints"] = q.joints;
      }
      if (!q.reason.empty()) e["reason"] = q.reason;
      rp.push_back(std::move(e));
    }
    j["replan"] = {{"max_tilt_deg", replan_request.max_tilt_deg},
                   {"standoff_range", {replan_request.standoff_min, replan_request.standoff_max}},
                   {"points", std::move(rp)},
                   {"found", replanned.found},
                   {"seconds", replanned.seconds},
                   {"replanned_path", o.replanned_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.replanned_path)},
                   {"after", {{"colliding_points", after.colliding_points},
                              {"colliding_segments", after.colliding_segments},
                              {"unresolved_segments", after.unresolved_segments},
                              {"verdict", verdict_name(after.verdict)}}}};
  }
  j["exit_status"] = status;
  return j;
}

std::string sweep_report_csv(const ProbePath& path, const SweepResult& r) {
  std::string out =
      "index,line,collides,holder,clearance,triangle,patch,hits,tip_x,tip_y,tip_z,axis_x,axis_y,axis_z,inside,verdict\n";
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const PointResult& p = r.points[i];
    std::string hits;
    for (std::uint32_t t : p.hits) hits += (hits.empty() ? "" : ";") + std::to_string(t);
    const ProbePose& q = path.poses[i];
    out += std::to_string(i) + "," + std::to_string(path.lines[i]) + "," + (p.collides ? "1" : "0") + "," +
           (p.holder ? "1" : "0") + "," + csv_number(p.clearance) + "," +
           (p.triangle == kNone ? "" : std::to_string(p.triangle)) + "," +
           (p.patch == kNone ? "" : std::to_string(p.patch)) + "," + hits + "," + csv_number(q.tip.x) + "," +
           csv_number(q.tip.y) + "," + csv_number(q.tip.z) + "," + csv_number(q.axis.x) + "," +
           csv_number(q.axis.y) + "," + csv_number(q.axis.z) + "," + (p.inside ? "1" : "0") + "," +
           verdict_name(p.verdict) + "\n";
  }
  return out;
}

void print_sweep_summary(const SweepRun& run) {
  const SweepOptions& o = run.o;
  const SweepResult& r = run.r;
  const ProbePath& path = run.path;
  double min_clear = 0;
  long min_point = -1;
  sweep_min_clearance(r, min_clear, min_point);
  const bool replanning = run.replanning;
  const ReplanRequest& replan_request = run.replan_request;
  const ReplanResult& replanned = run.replanned;
  const SweepResult& after = run.after;
  const std::size_t paper_colliding = run.paper_colliding, paper_fp = run.paper_fp, paper_fn = run.paper_fn;
  const char* head = r.verdict == Verdict::clash       ? "COLLISION"
                     : r.verdict == Verdict::undecided ? "UNDECIDED"
                                                       : verdict_name(r.verdict);
  std::printf("%s: %zu of %zu points collide (%zu inside the workpiece), %zu colliding segments (%zu only between "
              "samples), %zu unresolved; min clearance %s %s\n",
              head, r.colliding_points, path.size(), r.inside_points, r.colliding_segments, r.between_samples_segments,
              r.unresolved_segments, csv_number(min_clear).c_str(), o.units.c_str());
  if (replanning)
    std::printf("re-planned %zu of %zu colliding points (tilt <= %s deg); the re-planned path: %zu colliding points, %zu "
                "colliding segments, %zu unresolved\n",
                replanned.found, replanned.points.size(), csv_number(replan_request.max_tilt_deg).c_str(),
                after.colliding_points, after.colliding_segments, after.unresolved_segments);
  if (o.paper_levels) {
    std::printf("paper's three levels (§3.2-3.4, probe only): %zu points collide, %zu false positives, %zu false "
                "negatives against the exact test\n",
                paper_colliding, paper_fp, paper_fn);
  }
}

}  // namespace interfere::cli
