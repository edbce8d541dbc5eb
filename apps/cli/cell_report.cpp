// The report of `interfere cell` (cell_report.h; issue #28 deliverable 3, moved out of cmd_cell.cpp
// for `interfere-mpi cell`, issue #31 item 3).
#include "cell_report.h"

#include <cmath>
#include <map>

#include "interfere/core/error.h"

namespace interfere::cli {
namespace {

using namespace interfere::robot;

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

// Per frame: its findings (frame_pairs rows, sorted by frame).
std::vector<std::vector<const scene::FramePairRow*>> rows_by_frame(const CellRun& run) {
  std::vector<std::vector<const scene::FramePairRow*>> rows(run.cs.scene.frames.size());
  for (const scene::FramePairRow& row : run.r.frame_pairs) rows[row.frame].push_back(&row);
  return rows;
}

}  // namespace

CellTotals cell_totals(const CellRun& run, const CellReportOptions& o) {
  const CellScene& cs = run.cs;
  const scene::SceneClashResult& r = run.r;
  CellTotals t;
  const std::size_t n = run.path.size();
  t.point_verdict.assign(n, Verdict::clear);
  t.segment_verdict.assign(n ? n - 1 : 0, Verdict::clear);
  for (std::size_t f = 0; f < cs.scene.frames.size(); ++f) {
    const Verdict v = r.frames.size() > f ? r.frames[f].verdict : Verdict::clear;
    Verdict& target =
        cs.frame_t[f] == 0 ? t.point_verdict[cs.frame_point[f]] : t.segment_verdict[cs.frame_point[f]];
    target = worst(target, v);
  }
  for (Verdict v : t.point_verdict) t.colliding_points += v == Verdict::clash;
  for (Verdict v : t.segment_verdict) t.colliding_segments += v == Verdict::clash;
  t.verdict = r.verdict;
  if (o.continuous) {
    for (const SegmentResult& sr : run.between) {
      t.seg_collide += sr.state == robot::SegmentState::collides;
      t.seg_unresolved += sr.state == robot::SegmentState::unresolved;
    }
    if (t.seg_unresolved) t.verdict = worst(t.verdict, Verdict::undecided);
    if (t.seg_collide) t.verdict = worst(t.verdict, Verdict::clash);
  }
  t.status = verdict_exit_status(t.verdict, o.fail_on);
  return t;
}

nlohmann::json cell_report_json(const CellRun& run, const CellReportOptions& o, const CellTotals& t) {
  const Cell& cell = run.cell;
  const CellScene& cs = run.cs;
  const JointPath& path = run.path;
  const scene::SceneClashResult& r = run.r;
  const auto& bodies = cs.scene.bodies;
  const std::size_t n = path.size();
  const auto rows = rows_by_frame(run);
  auto pair_json = [&](const scene::FramePairRow& row) {
    nlohmann::json e = {{"test", cs.tests[row.test].name},
                        {"a", bodies[row.a].id},
                        {"b", bodies[row.b].id},
                        {"verdict", verdict_name(row.verdict)},
                        {"min_distance", number_or_null(row.min_distance)}};
    if (row.max_depth_bound > 0) e["depth"] = row.max_depth, e["depth_bound"] = row.max_depth_bound;
    return e;
  };
  nlohmann::json j;
  j["command"] = "cell";
  j["cell"] = o.cell_file;
  j["path"] = o.path_file;
  if (o.ik) j["ik"] = o.ik_report;
  j["units"] = "mm";
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t m : cell.robot.movable) {
    const ChainJoint& jt = cell.robot.joints[m];
    joints.push_back({{"name", jt.name},
                      {"type", joint_kind_name(jt.kind)},
                      {"lower", jt.lower},
                      {"upper", jt.upper}});
  }
  j["robot"] = {{"name", cell.robot.name},
                {"format", cell.robot_format},
                {"file", cell.robot_file},
                {"joints", joints},
                {"tool_link", cell.tool.link},
                {"base", pose_json(cell.base)}};
  if (cell.robot_format == "urdf") j["robot"]["urdf"] = cell.robot_file;  // as before DH cells
  nlohmann::json jb = nlohmann::json::array();
  for (const scene::Body& b : bodies) {
    jb.push_back({{"id", b.id},
                  {"tags", b.tags},
                  {"triangles", b.mesh->num_triangles()},
                  {"source", b.source.file}});
  }
  j["bodies"] = std::move(jb);
  nlohmann::json jt = nlohmann::json::array();
  for (const scene::ClashTest& test : cs.tests) {
    nlohmann::json sup = nlohmann::json::array();
    for (const scene::Suppression& s : test.suppressions) {
      sup.push_back({{"a", s.a[0].pattern}, {"b", s.b[0].pattern}, {"reason", s.reason}});
    }
    jt.push_back(
        {{"name", test.name}, {"mode", scene::clash_mode_name(test.mode)}, {"suppressed", sup}});
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
    for (std::size_t m = 0; m < cell.robot.dof(); ++m)
      q[cell.robot.joints[cell.robot.movable[m]].name] = path.q[i][m];
    const std::vector<Transform> frames = link_frames(cell.robot, path.q[i], cell.base);
    const ToolCylinders tc = tool_cylinders(cell.tool, frames[cell.tool_link]);
    nlohmann::json p = {{"index", i},
                        {"line", path.lines[i]},
                        {"joints", std::move(q)},
                        {"verdict", verdict_name(t.point_verdict[i])},
                        {"tip", vec_json(tc.tip)},
                        {"axis", vec_json((tc.tip - tc.back) / norm(tc.tip - tc.back))},
                        {"pairs", std::move(pairs)}};
    if (o.link_poses) {
      nlohmann::json lp = nlohmann::json::object();
      for (std::size_t k = 0; k < frames.size(); ++k)
        lp[cell.robot.links[k].name] = pose_json(frames[k]);
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
    for (const SegmentResult& sr : run.between) {
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
      if (sr.state == robot::SegmentState::unresolved) e["unresolved_pairs"] = sr.unresolved_pairs;
      js.push_back(std::move(e));
    }
    j["between_points"] = {{"max_depth", o.max_depth}, {"segments", std::move(js)}};
  }
  j["summary"] = {{"points", n},
                  {"colliding_points", t.colliding_points},
                  {"colliding_segments", t.colliding_segments},
                  {"frames", cs.scene.frames.size()},
                  {"bodies", bodies.size()},
                  {"candidate_pairs", r.candidate_pairs},
                  {"suppressed", r.suppressed},
                  {"continuous", o.continuous},
                  {"colliding_between", t.seg_collide},
                  {"unresolved_between", t.seg_unresolved},
                  {"verdict", verdict_name(t.verdict)}};
  j["exit_status"] = t.status;
  return j;
}

std::string cell_report_csv(const CellRun& run) {
  const CellScene& cs = run.cs;
  const auto& bodies = cs.scene.bodies;
  const auto rows = rows_by_frame(run);
  std::string out = "point,line,t,verdict,test,a,b,pair_verdict,min_distance\n";
  for (std::size_t f = 0; f < cs.scene.frames.size(); ++f) {
    const std::size_t i = cs.frame_point[f];
    const std::string head = std::to_string(i) + "," + std::to_string(run.path.lines[i]) + "," +
                             short_number(cs.frame_t[f]) + "," +
                             verdict_name(run.r.frames[f].verdict) + ",";
    if (rows[f].empty()) {
      if (cs.frame_t[f] == 0) out += head + ",,,,\n";
      continue;
    }
    for (const scene::FramePairRow* row : rows[f]) {
      out += head + cs.tests[row->test].name + "," + bodies[row->a].id + "," + bodies[row->b].id +
             "," + verdict_name(row->verdict) + "," + csv_number(row->min_distance) + "\n";
    }
  }
  return out;
}

void print_cell_summary(std::FILE* out, const CellRun& run, const CellReportOptions& o, const CellTotals& t) {
  const CellScene& cs = run.cs;
  const scene::SceneClashResult& r = run.r;
  const auto& bodies = cs.scene.bodies;
  const std::size_t n = run.path.size();
  std::fprintf(out,
               "%s: %zu of %zu path points collide, %zu of %zu segments collide at a sampled "
               "between-point frame (%zu per segment); %zu bodies, %zu candidate body pairs checked "
               "over %zu frames (%zu adjacent pairs left out)\n",
               t.verdict == Verdict::clash ? "COLLISION" : verdict_name(t.verdict), t.colliding_points, n,
               t.colliding_segments, n ? n - 1 : 0, o.between, bodies.size(), r.candidate_pairs,
               cs.scene.frames.size(), r.suppressed);
  std::map<std::string, std::size_t> by_pair;
  for (const scene::FramePairRow& row : r.frame_pairs) {
    if (cs.frame_t[row.frame] == 0 && row.verdict == Verdict::clash) {
      ++by_pair[bodies[row.a].id + " / " + bodies[row.b].id];
    }
  }
  for (const auto& [k, v] : by_pair) std::fprintf(out, "  %s: %zu points\n", k.c_str(), v);
  if (o.continuous) {
    std::fprintf(out, "between points (conservative, depth %d): %zu of %zu segments collide, %zu unresolved\n",
                 o.max_depth, t.seg_collide, run.between.size(), t.seg_unresolved);
  }
}

}  // namespace interfere::cli
