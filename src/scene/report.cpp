// The scene clash report (include/interfere/scene/report.h; docs/report.md, "Scene clash report").
#include "interfere/scene/report.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

namespace interfere::scene {
namespace {

using json = nlohmann::json;

json vec(const Vec3& v) { return json::array({v.x, v.y, v.z}); }
json box(const Aabb& b) {
  if (b.empty()) return nullptr;
  return {{"min", vec(b.lo)}, {"max", vec(b.hi)}};
}
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json body_ref(const Scene& s, std::uint32_t i) {
  const Body& b = s.bodies[i];
  return {{"index", i}, {"id", b.id}, {"name", b.name}, {"path", b.path}};
}

json selection_json(const Selection& sel) {
  json a = json::array();
  for (const Selector& x : sel) a.push_back(x.to_string());
  return a;
}

// The keys the engine writes on a clash; every other key of a baseline clash is the user's.
const std::set<std::string>& engine_keys() {
  static const std::set<std::string> k{"id", "test", "status", "run_status", "verdict", "kind", "body_a", "body_b",
                                       "depth", "depth_bound", "distance", "point", "box", "curve_length",
                                       "cross_pairs", "touch_pairs", "triangle_count_a", "triangle_count_b",
                                       "source_id_kind_a", "source_id_kind_b", "source_ids_a", "source_ids_b",
                                       "curves", "witness_a", "witness_b", "reasons", "frames", "first_frame",
                                       "designed", "deepest"};
  return k;
}

json deepest_json(const Scene& s, const DeepestPoint& d) {
  return {{"body", s.bodies[d.body].id}, {"vertex", d.vertex}, {"node", d.node}, {"element", d.element},
          {"depth", d.depth},       {"point", vec(d.point)}, {"frame", d.frame}};
}

bool engine_status_word(const std::string& s) { return s == "new" || s == "active" || s == "resolved"; }

json clash_json(const Scene& scene, const SceneClash& c) {
  json j{{"id", c.id}, {"test", c.test}};
  const auto user_status = c.user_fields.find("status");
  j["status"] = user_status != c.user_fields.end() ? json::parse(user_status->second) : json(clash_status_name(c.status));
  j["run_status"] = clash_status_name(c.status);
  for (const auto& [k, v] : c.user_fields)
    if (k != "status") j[k] = json::parse(v);
  j["verdict"] = verdict_name(c.verdict);
  j["kind"] = c.kind;
  j["body_a"] = body_ref(scene, c.a);
  j["body_b"] = body_ref(scene, c.b);
  j["depth"] = c.depth;
  j["depth_bound"] = c.depth_bound;
  j["distance"] = c.distance;
  j["point"] = vec(c.point);
  j["box"] = box(c.box);
  j["curve_length"] = c.curve_length;
  j["cross_pairs"] = c.cross_pairs;
  j["touch_pairs"] = c.touch_pairs;
  j["triangle_count_a"] = c.triangles_a.size();
  j["triangle_count_b"] = c.triangles_b.size();
  j["source_id_kind_a"] = source_id_kind_name(scene.bodies[c.a].source_id_kind);
  j["source_id_kind_b"] = source_id_kind_name(scene.bodies[c.b].source_id_kind);
  j["source_ids_a"] = c.source_ids_a;
  j["source_ids_b"] = c.source_ids_b;  // (copied: the result stays the caller's)
  if (c.verdict == Verdict::clearance) {
    j["witness_a"] = vec(c.witness_a);
    j["witness_b"] = vec(c.witness_b);
  }
  json curves = json::array();
  for (const Polyline& l : c.curves) {
    json pts = json::array();
    for (const Vec3& p : l.points) pts.push_back(vec(p));
    curves.push_back({{"closed", l.closed}, {"length", l.length}, {"points", std::move(pts)}});
  }
  j["curves"] = std::move(curves);
  j["reasons"] = c.reasons;
  if (!c.frames.empty()) {
    j["frames"] = c.frames;
    j["first_frame"] = c.frames.front();
  }
  if (c.verdict == Verdict::contact) j["designed"] = c.designed;
  if (c.has_deepest) j["deepest"] = deepest_json(scene, c.deepest);
  return j;
}

}  // namespace

Status apply_baseline(SceneClashResult& result, const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    return Error{.file = name, .byte = static_cast<std::int64_t>(e.byte), .reason = std::string("invalid JSON: ") + e.what()};
  }
  const auto fail = [&](const std::string& path, const std::string& why) { return Error{.file = name, .reason = path + ": " + why}; };
  if (!j.is_object()) return fail("$", "a baseline is an earlier report (a JSON object)");
  if (!j.contains("schema") || j["schema"] != kReportSchema)
    return fail("$.schema", std::string("not a scene clash report (expected \"") + kReportSchema + "\")");
  if (!j.contains("schema_version") || !j["schema_version"].is_number_integer())
    return fail("$.schema_version", "missing or not an integer");
  if (j["schema_version"].get<long long>() != kReportSchemaVersion)
    return fail("$.schema_version", "version " + j["schema_version"].dump() + "; this build reads version " +
                                        std::to_string(kReportSchemaVersion));
  if (!j.contains("clashes") || !j["clashes"].is_array()) return fail("$.clashes", "missing or not an array");
  std::map<std::string, const json*> old;
  for (std::size_t i = 0; i < j["clashes"].size(); ++i) {
    const json& c = j["clashes"][i];
    const std::string path = "$.clashes[" + std::to_string(i) + "]";
    if (!c.is_object() || !c.contains("id") || !c["id"].is_string()) return fail(path + ".id", "missing or not a string");
    if (!old.emplace(c["id"].get<std::string>(), &c).second) return fail(path + ".id", "duplicate id " + c["id"].dump());
  }
  std::set<std::string> seen;
  for (SceneClash& c : result.clashes) {
    const auto it = old.find(c.id);
    if (it == old.end()) {
      c.status = ClashStatus::new_;
      continue;
    }
    seen.insert(c.id);
    c.status = ClashStatus::active;
    for (const auto& [k, v] : it->second->items()) {
      if (k == "status") {
        if (v.is_string() && !engine_status_word(v.get<std::string>())) c.user_fields["status"] = v.dump();
      } else if (!engine_keys().count(k)) {
        c.user_fields[k] = v.dump();
      }
    }
  }
  // Baseline clashes gone now: resolved, listed this once (those the baseline already listed as
  // resolved are dropped).
  result.resolved.clear();
  for (const json& c : j["clashes"]) {
    const std::string id = c["id"].get<std::string>();
    if (seen.count(id)) continue;
    const std::string run = c.contains("run_status") && c["run_status"].is_string() ? c["run_status"].get<std::string>() : "";
    if (run == "resolved") continue;
    SceneClash r;
    r.id = id;
    r.test = c.contains("test") && c["test"].is_string() ? c["test"].get<std::string>() : "";
    r.status = ClashStatus::resolved;
    r.kind = c.contains("kind") && c["kind"].is_string() ? c["kind"].get<std::string>() : "";
    r.baseline_json = c.dump();
    for (const auto& [k, v] : c.items())
      if (k == "status") {
        if (v.is_string() && !engine_status_word(v.get<std::string>())) r.user_fields["status"] = v.dump();
      } else if (!engine_keys().count(k)) {
        r.user_fields[k] = v.dump();
      }
    result.resolved.push_back(std::move(r));
  }
  return {};
}

std::string report_json(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashResult& r,
                        const ReportContext& ctx) {
  json j{{"schema", kReportSchema}, {"schema_version", kReportSchemaVersion}};
  j["command"] = ctx.command;
  j["version"] = ctx.tool_version;
  j["units"] = scene.units;
  j["inputs"] = ctx.inputs;
  j["verdict"] = verdict_name(r.verdict);
  j["exit_status"] = ctx.exit_status;
  j["summary"] = {{"bodies", r.bodies},
                  {"triangles", r.triangles},
                  {"candidate_pairs", r.candidate_pairs},
                  {"suppressed", r.suppressed},
                  {"core_runs", r.core_runs},
                  {"clashes", r.clash_count},
                  {"contacts", r.contact_count},
                  {"clearances", r.clearance_count},
                  {"undecided", r.undecided_count},
                  {"resolved", r.resolved.size()},
                  {"frames", r.frames.size()},
                  {"reference_checked", r.reference_checked},
                  {"designed_contacts", r.designed_contact_count},
                  {"new_contacts", r.new_contact_count},
                  {"new_penetrations", r.new_penetration_count}};
  json bodies = json::array();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const auto m = b.pose.to_row_major();
    bodies.push_back({{"index", i},
                      {"id", b.id},
                      {"name", b.name},
                      {"path", b.path},
                      {"source", {{"kind", source_kind_name(b.source.kind)}, {"file", b.source.file}, {"detail", b.source.detail}}},
                      {"unit", b.unit},
                      {"tags", b.tags},
                      {"triangles", b.mesh ? b.mesh->num_triangles() : 0},
                      {"source_id_kind", source_id_kind_name(b.source_id_kind)},
                      {"pose", std::vector<double>(m.begin(), m.end())}});
  }
  j["bodies"] = bodies;
  json jt = json::array();
  for (const ClashTest& t : tests) {
    json overrides = json::array(), sup = json::array();
    for (const ClearanceOverride& o : t.clearance_overrides)
      overrides.push_back({{"a", selection_json(o.a)}, {"b", selection_json(o.b)}, {"clearance", o.clearance}});
    for (const Suppression& s : t.suppressions)
      sup.push_back({{"a", selection_json(s.a)}, {"b", selection_json(s.b)}, {"reason", s.reason}});
    jt.push_back({{"name", t.name},
                  {"a", selection_json(t.a)},
                  {"b", selection_json(t.b)},
                  {"mode", clash_mode_name(t.mode)},
                  {"tolerance", t.tolerance},
                  {"clearance", t.clearance},
                  {"clearance_overrides", overrides},
                  {"suppress", sup},
                  {"nominal_fits_are_contacts", t.nominal_fits_are_contacts},
                  {"id_grid", t.id_grid}});
  }
  j["tests"] = std::move(jt);
  json clashes = json::array();
  for (const SceneClash& c : r.clashes) clashes.push_back(clash_json(scene, c));
  j["clashes"] = std::move(clashes);
  json resolved = json::array();
  for (const SceneClash& c : r.resolved) {
    json x = json::parse(c.baseline_json);
    x["run_status"] = "resolved";
    if (!c.user_fields.count("status")) x["status"] = "resolved";
    resolved.push_back(x);
  }
  j["resolved"] = std::move(resolved);
  json pairs = json::array();
  for (const PairSummary& p : r.pairs)
    pairs.push_back({{"test", p.test},
                     {"body_a", body_ref(scene, p.a)},
                     {"body_b", body_ref(scene, p.b)},
                     {"verdict", verdict_name(p.verdict)},
                     {"clashes", p.clashes},
                     {"depth", p.depth},
                     {"depth_bound", p.depth_bound},
                     {"min_distance", p.min_distance < 0 ? json(nullptr) : json(p.min_distance)},
                     {"first_frame", p.first_frame < 0 ? json(nullptr) : json(p.first_frame)},
                     {"first_clash_frame", p.first_clash_frame < 0 ? json(nullptr) : json(p.first_clash_frame)},
                     {"reference_verdict", r.reference_checked ? json(verdict_name(p.reference_verdict)) : json(nullptr)}});
  j["pairs"] = std::move(pairs);
  json groups = json::array();
  for (const ClashGroup& g : r.groups)
    groups.push_back({{"id", g.id}, {"clashes", g.clashes}, {"box", box(g.box)}, {"verdict", verdict_name(g.verdict)}});
  j["groups"] = std::move(groups);
  json frames = json::array();
  for (const FrameRow& f : r.frames)
    frames.push_back({{"frame", f.frame},
                      {"label", f.label},
                      {"time", f.time},
                      {"clashes", f.clashes},
                      {"contacts", f.contacts},
                      {"clearances", f.clearances},
                      {"undecided", f.undecided},
                      {"min_distance", f.min_distance < 0 ? json(nullptr) : json(f.min_distance)},
                      {"max_depth", f.max_depth},
                      {"verdict", verdict_name(f.verdict)}});
  j["frames"] = std::move(frames);
  json frame_pairs = json::array();
  for (const FramePairRow& f : r.frame_pairs)
    frame_pairs.push_back({{"frame", f.frame},
                           {"test", tests[f.test].name},
                           {"body_a", scene.bodies[f.a].id},
                           {"body_b", scene.bodies[f.b].id},
                           {"verdict", verdict_name(f.verdict)},
                           {"clashes", f.clashes},
                           {"contacts", f.contacts},
                           {"clearances", f.clearances},
                           {"undecided", f.undecided},
                           {"min_distance", f.min_distance < 0 ? json(nullptr) : json(f.min_distance)},
                           {"max_depth", f.max_depth},
                           {"max_depth_bound", f.max_depth_bound},
                           {"deepest", f.has_deepest ? deepest_json(scene, f.deepest) : json(nullptr)}});
  j["frame_pairs"] = std::move(frame_pairs);
  json reference = json::array();
  for (const ReferencePair& p : r.reference_pairs)
    reference.push_back({{"test", tests[p.test].name},
                         {"body_a", scene.bodies[p.a].id},
                         {"body_b", scene.bodies[p.b].id},
                         {"verdict", verdict_name(p.verdict)}});
  j["reference_pairs"] = std::move(reference);
  std::vector<std::string> warnings = r.warnings;
  warnings.insert(warnings.end(), ctx.warnings.begin(), ctx.warnings.end());
  j["warnings"] = warnings;
  j["threads"] = ctx.threads;
  j["timings_s"] = {{"prepare", r.prepare_seconds}, {"broad", r.broad_seconds}, {"narrow", r.narrow_seconds},
                    {"total", ctx.total_seconds}};
  // The keys every command's report has (docs/report.md, docs/schema/report.schema.json).
  j["options"] = {{"units", scene.units}, {"threads", ctx.threads}};
  j["result"] = {{"verdict", j["verdict"]}, {"exit_status", ctx.exit_status}, {"summary", j["summary"]}};
  j["seconds"] = ctx.process_seconds >= 0 ? ctx.process_seconds : ctx.total_seconds;
  return j.dump(2) + "\n";
}

namespace {

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
std::string csv_num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string user(const SceneClash& c, const std::string& k) {
  const auto it = c.user_fields.find(k);
  if (it == c.user_fields.end()) return "";
  const json v = json::parse(it->second);
  return v.is_string() ? v.get<std::string>() : v.dump();
}

}  // namespace

std::string clash_table_csv(const Scene& scene, const SceneClashResult& r) {
  std::string out =
      "id,test,status,verdict,kind,body_a,name_a,path_a,body_b,name_b,path_b,depth,depth_bound,distance,x,y,z,"
      "box_min_x,box_min_y,box_min_z,box_max_x,box_max_y,box_max_z,curve_length,cross_pairs,touch_pairs,"
      "triangles_a,triangles_b,first_frame,frames,user_status,assignee,comment\n";
  for (const SceneClash& c : r.clashes) {
    const Body& a = scene.bodies[c.a];
    const Body& b = scene.bodies[c.b];
    std::vector<std::string> cells{c.id, c.test, clash_status_name(c.status), verdict_name(c.verdict), c.kind,
                                   a.id, a.name, a.path, b.id, b.name, b.path, csv_num(c.depth), csv_num(c.depth_bound),
                                   csv_num(c.distance), csv_num(c.point.x), csv_num(c.point.y), csv_num(c.point.z)};
    for (const Vec3& p : {c.box.lo, c.box.hi})
      for (int k = 0; k < 3; ++k) cells.push_back(c.box.empty() ? "" : csv_num(p[k]));
    cells.push_back(csv_num(c.curve_length));
    cells.push_back(std::to_string(c.cross_pairs));
    cells.push_back(std::to_string(c.touch_pairs));
    cells.push_back(std::to_string(c.triangles_a.size()));
    cells.push_back(std::to_string(c.triangles_b.size()));
    cells.push_back(c.frames.empty() ? "" : std::to_string(c.frames.front()));
    cells.push_back(std::to_string(c.frames.size()));
    cells.push_back(user(c, "status"));
    cells.push_back(user(c, "assignee"));
    cells.push_back(user(c, "comment"));
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + csv_cell(cells[i]);
    out += "\n";
  }
  for (const SceneClash& c : r.resolved) {
    const json x = json::parse(c.baseline_json);
    const auto field = [&](const char* body, const char* k) {
      return x.contains(body) && x[body].is_object() && x[body].contains(k) && x[body][k].is_string()
                 ? x[body][k].get<std::string>()
                 : std::string();
    };
    const auto s = [&](const char* k) { return x.contains(k) && x[k].is_string() ? x[k].get<std::string>() : std::string(); };
    std::vector<std::string> cells{c.id, c.test, "resolved", s("verdict"), c.kind, field("body_a", "id"),
                                   field("body_a", "name"), field("body_a", "path"), field("body_b", "id"),
                                   field("body_b", "name"), field("body_b", "path")};
    cells.resize(28);
    cells.push_back("");
    cells.push_back("0");
    cells.push_back(user(c, "status"));
    cells.push_back(user(c, "assignee"));
    cells.push_back(user(c, "comment"));
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + csv_cell(cells[i]);
    out += "\n";
  }
  return out;
}

std::string frames_table_csv(const SceneClashResult& r) {
  std::string out = "frame,label,time,clashes,contacts,clearances,undecided,min_distance,max_depth,verdict\n";
  for (const FrameRow& f : r.frames)
    out += std::to_string(f.frame) + "," + csv_cell(f.label) + "," + csv_num(f.time) + "," + std::to_string(f.clashes) +
           "," + std::to_string(f.contacts) + "," + std::to_string(f.clearances) + "," + std::to_string(f.undecided) +
           "," + (f.min_distance < 0 ? std::string() : csv_num(f.min_distance)) + "," + csv_num(f.max_depth) + "," +
           verdict_name(f.verdict) + "\n";
  return out;
}

std::string frame_pairs_table_csv(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashResult& r) {
  std::string out = "frame,label,time,test,body_a,body_b,verdict,clashes,contacts,clearances,undecided,min_distance,max_depth,"
                    "max_depth_bound,reference_verdict\n";
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>, Verdict> reference;
  for (const ReferencePair& p : r.reference_pairs) reference[{p.test, p.a, p.b}] = p.verdict;
  std::size_t row = 0;  // frame_pairs and frames are both in frame order
  for (const FramePairRow& f : r.frame_pairs) {
    while (row < r.frames.size() && r.frames[row].frame < f.frame) ++row;
    const bool labelled = row < r.frames.size() && r.frames[row].frame == f.frame;
    const auto it = reference.find({f.test, f.a, f.b});
    const Verdict ref = it == reference.end() ? Verdict::clear : it->second;
    out += std::to_string(f.frame) + "," + (labelled ? csv_cell(r.frames[row].label) : std::string()) + "," +
           (labelled ? csv_num(r.frames[row].time) : std::string()) + "," + csv_cell(tests[f.test].name) + "," +
           csv_cell(scene.bodies[f.a].id) + "," + csv_cell(scene.bodies[f.b].id) + "," + verdict_name(f.verdict) + "," +
           std::to_string(f.clashes) + "," + std::to_string(f.contacts) + "," + std::to_string(f.clearances) + "," +
           std::to_string(f.undecided) + "," + (f.min_distance < 0 ? std::string() : csv_num(f.min_distance)) + "," +
           csv_num(f.max_depth) + "," + csv_num(f.max_depth_bound) + "," +
           (r.reference_checked ? verdict_name(ref) : "") + "\n";
  }
  return out;
}

}  // namespace interfere::scene
