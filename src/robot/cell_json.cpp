// Cell file (issue #28, deliverable 3; robot/cell.h, docs/probe.md "Cell file"). Errors name the
// cell file, the line of the field (best effort: the key's first occurrence) and the field.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "interfere/mesh/io.h"
#include "interfere/probe/kinematics.h"
#include "interfere/robot/ik.h"
#include "interfere/scene/scene.h"
#include "interfere/robot/cell.h"

namespace interfere::robot {
namespace {

using nlohmann::json;

struct P {
  const std::string& text;
  std::string file;
  std::filesystem::path dir;

  std::int64_t line(const std::string& key) const {
    const std::size_t p = text.find("\"" + key + "\"");
    return p == std::string::npos
               ? -1
               : 1 + std::count(text.begin(), text.begin() + static_cast<long>(p), '\n');
  }
  Error fail(const std::string& field, const std::string& reason) const {
    const std::size_t dot = field.find_last_of('.');
    std::string key = dot == std::string::npos ? field : field.substr(dot + 1);
    if (const std::size_t b = key.find('['); b != std::string::npos) key = key.substr(0, b);
    return Error{.file = file, .line = line(key), .reason = field + ": " + reason};
  }
  Status keys(const json& o, const std::string& where,
              std::initializer_list<const char*> known) const {
    if (!o.is_object()) return fail(where, "expected a JSON object");
    for (auto it = o.begin(); it != o.end(); ++it) {
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; })) {
        std::string list;
        for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        return fail(where + "." + it.key(), "unknown key (expected " + list + ")");
      }
    }
    return {};
  }
  Expected<double> number(const json& o, const std::string& where, const char* key, double fallback,
                          bool required, bool positive) const {
    auto it = o.find(key);
    const std::string field = where + "." + key;
    if (it == o.end()) {
      if (required) return fail(field, "missing");
      return fallback;
    }
    if (!it->is_number() || !std::isfinite(it->get<double>()))
      return fail(field, "expected a finite number");
    const double v = it->get<double>();
    if (positive ? !(v > 0) : !(v >= 0))
      return fail(field, positive ? "must be > 0" : "must be >= 0");
    return v;
  }
  Expected<Vec3> vec(const json& o, const std::string& where, const char* key,
                     Vec3 fallback) const {
    auto it = o.find(key);
    if (it == o.end()) return fallback;
    const std::string field = where + "." + key;
    if (!it->is_array() || it->size() != 3) return fail(field, "expected 3 numbers");
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      if (!(*it)[i].is_number() || !std::isfinite((*it)[i].get<double>())) {
        return fail(field + "[" + std::to_string(i) + "]", "expected a finite number");
      }
      v[i] = (*it)[i].get<double>();
    }
    return v;
  }
  Expected<Transform> pose(const json& o, const std::string& where, const char* key) const {
    auto it = o.find(key);
    if (it == o.end()) return Transform{};
    const std::string field = where + "." + key;
    if (!it->is_array() || it->size() != 12)
      return fail(field, "expected 12 numbers (row-major [R|t], mm)");
    Transform t;
    for (int i = 0; i < 12; ++i) {
      if (!(*it)[i].is_number() || !std::isfinite((*it)[i].get<double>())) {
        return fail(field + "[" + std::to_string(i) + "]", "expected a finite number");
      }
      const double v = (*it)[i].get<double>();
      if (i % 4 == 3)
        t.t[i / 4] = v;
      else
        t.r[i / 4][i % 4] = v;
    }
    if (!t.is_rigid()) return fail(field, "not a rigid transform (R must be a rotation)");
    return t;
  }
  Expected<std::string> string(const json& o, const std::string& where, const char* key,
                               bool required) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) return fail(where + "." + key, "missing");
      return std::string();
    }
    if (!it->is_string() || it->get<std::string>().empty())
      return fail(where + "." + key, "expected a file name");
    return it->get<std::string>();
  }
  Expected<CellObject> object(const json& o, const std::string& where, bool need_id) const {
    if (Status s = keys(o, where, {"id", "mesh", "pose", "comment"}); !s) return s.error();
    CellObject out;
    if (need_id) {
      Expected<std::string> id = string(o, where, "id", true);
      if (!id) return id.error();
      out.id = *id;
    }
    Expected<std::string> mesh = string(o, where, "mesh", true);
    if (!mesh) return mesh.error();
    const std::filesystem::path p = dir / *mesh;
    out.file = p.string();
    Expected<TriMesh> m = read_mesh(p);
    if (!m) {
      Error e = m.error();
      e.reason = "(" + where + ".mesh of " + file + ") " + e.reason;
      return e;
    }
    out.mesh = std::make_shared<TriMesh>(std::move(*m));
    Expected<Transform> t = pose(o, where, "pose");
    if (!t) return t.error();
    out.pose = *t;
    return out;
  }
};

}  // namespace

Expected<Cell> parse_cell_json(const std::string& text, const std::filesystem::path& file) {
  P p{text, file.string(), file.parent_path()};
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    return Error{.file = file.string(), .reason = std::string("invalid JSON: ") + e.what()};
  }
  if (Status s = p.keys(doc, "cell",
                        {"robot", "tool", "workpiece", "fixtures", "clearance", "path", "comment"});
      !s) {
    return s.error();
  }
  Cell cell;
  cell.file = file.string();
  // robot
  if (!doc.contains("robot")) return p.fail("cell.robot", "missing");
  const json& r = doc["robot"];
  if (Status s = p.keys(r, "robot",
                        {"urdf", "dh", "package_paths", "links", "base", "tool_link", "comment"});
      !s)
    return s.error();
  // the robot: a URDF file, or a DH table of the probe module (standard or modified) whose DH
  // frames frame0..frameN carry the meshes of "links" (issue #28, deliverable 2)
  const bool is_dh = r.contains("dh");
  if (is_dh == r.contains("urdf"))
    return p.fail("robot", is_dh ? "give \"urdf\" or \"dh\", not both"
                                 : "missing: \"urdf\" (a URDF file) or \"dh\" (a DH robot JSON)");
  Expected<std::string> robot_file = p.string(r, "robot", is_dh ? "dh" : "urdf", true);
  if (!robot_file) return robot_file.error();
  cell.robot_file = (p.dir / *robot_file).string();
  cell.robot_format = is_dh ? "dh" : "urdf";
  Expected<Transform> base = p.pose(r, "robot", "base");
  if (!base) return base.error();
  cell.base = *base;
  if (is_dh) {
    if (r.contains("package_paths"))
      return p.fail("robot.package_paths", "only for a URDF robot (package:// mesh names)");
    Expected<probe::Robot> dh = probe::read_robot_json(cell.robot_file);
    if (!dh) return dh.error();
    cell.robot = chain_from_dh(*dh);
    cell.robot.file = cell.robot_file;
    cell.base = scene::compose(cell.base, dh->base);  // the chain's frame0 is DH frame 0
    if (auto it = r.find("links"); it != r.end()) {
      if (!it->is_object())
        return p.fail("robot.links", "expected an object {\"frameI\": {\"mesh\": ..., \"pose\": ...}}");
      for (auto l = it->begin(); l != it->end(); ++l) {
        const std::string where = "robot.links." + l.key();
        const std::int64_t k = cell.robot.find_link(l.key());
        if (k < 0 || l.key().rfind("frame", 0) != 0)
          return p.fail(where, "not a DH frame of " + cell.robot_file + " (frame0..frame" +
                                   std::to_string(dh->joints.size()) + ")");
        Expected<CellObject> o = p.object(l.value(), where, false);
        if (!o) return o.error();
        ChainLink& link = cell.robot.links[static_cast<std::size_t>(k)];
        link.mesh = std::make_shared<TriMesh>(transformed(*o->mesh, o->pose));  // link <- mesh
        link.mesh_files = {o->file};
      }
    }
  } else {
    if (r.contains("links"))
      return p.fail("robot.links", "only for a DH robot (a URDF file carries its links' meshes)");
    UrdfOptions uo;
    if (auto it = r.find("package_paths"); it != r.end()) {
      if (!it->is_array()) return p.fail("robot.package_paths", "expected an array of directories");
      for (const json& d : *it) {
        if (!d.is_string()) return p.fail("robot.package_paths", "expected an array of directories");
        uo.package_paths.push_back(p.dir / d.get<std::string>());
      }
    }
    Expected<Chain> chain = read_urdf(cell.robot_file, uo);
    if (!chain) return chain.error();
    cell.robot = std::move(*chain);
  }
  Expected<std::string> tool_link = p.string(r, "robot", "tool_link", false);
  if (!tool_link) return tool_link.error();
  cell.tool.link = tool_link->empty() ? cell.robot.links.back().name : *tool_link;
  const std::int64_t tl = cell.robot.find_link(cell.tool.link);
  if (tl < 0)
    return p.fail("robot.tool_link", "'" + cell.tool.link + "' is not a link of " + cell.robot_file);
  cell.tool_link = static_cast<std::size_t>(tl);
  // tool
  if (!doc.contains("tool")) return p.fail("cell.tool", "missing");
  const json& t = doc["tool"];
  if (Status s = p.keys(t, "tool",
                        {"tip", "axis", "probe_radius", "probe_length", "holder_radius",
                         "holder_length", "sides", "comment"});
      !s) {
    return s.error();
  }
  Expected<Vec3> tip = p.vec(t, "tool", "tip", {});
  Expected<Vec3> axis = p.vec(t, "tool", "axis", {0, 0, 1});
  if (!tip) return tip.error();
  if (!axis) return axis.error();
  if (!(norm(*axis) > 0)) return p.fail("tool.axis", "must not be zero");
  cell.tool.tip = *tip;
  cell.tool.axis = *axis / norm(*axis);
  Expected<double> pr = p.number(t, "tool", "probe_radius", 0, true, true);
  Expected<double> pl = p.number(t, "tool", "probe_length", 0, true, true);
  Expected<double> hr = p.number(t, "tool", "holder_radius", 0, false, false);
  Expected<double> hl = p.number(t, "tool", "holder_length", 0, false, false);
  Expected<double> sides = p.number(t, "tool", "sides", 24, false, true);
  for (const auto* e : {&pr, &pl, &hr, &hl, &sides}) {
    if (!*e) return e->error();
  }
  if ((*hr > 0) != (*hl > 0))
    return p.fail("tool.holder_radius",
                  "give holder_radius and holder_length both > 0, or neither");
  if (*sides < 3 || *sides > 1024 || *sides != std::floor(*sides))
    return p.fail("tool.sides", "expected an integer in [3, 1024]");
  cell.tool.probe_radius = *pr, cell.tool.probe_length = *pl, cell.tool.holder_radius = *hr;
  cell.tool.holder_length = *hl, cell.tool.sides = static_cast<int>(*sides);
  // workpiece and fixtures
  if (!doc.contains("workpiece")) return p.fail("cell.workpiece", "missing");
  Expected<CellObject> w = p.object(doc["workpiece"], "workpiece", false);
  if (!w) return w.error();
  cell.workpiece = std::move(*w);
  cell.workpiece.id = "workpiece";
  if (auto it = doc.find("fixtures"); it != doc.end()) {
    if (!it->is_array()) return p.fail("cell.fixtures", "expected an array");
    for (std::size_t i = 0; i < it->size(); ++i) {
      Expected<CellObject> f = p.object((*it)[i], "fixtures[" + std::to_string(i) + "]", true);
      if (!f) return f.error();
      for (const CellObject& g : cell.fixtures) {
        if (g.id == f->id)
          return p.fail("fixtures[" + std::to_string(i) + "].id", "'" + f->id + "' used twice");
      }
      cell.fixtures.push_back(std::move(*f));
    }
  }
  Expected<double> c = p.number(doc, "cell", "clearance", 0, false, false);
  if (!c) return c.error();
  cell.clearance = *c;
  Expected<std::string> path = p.string(doc, "cell", "path", false);
  if (!path) return path.error();
  if (!path->empty()) cell.path = (p.dir / *path).string();
  return cell;
}

Expected<Cell> read_cell_json(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{.file = file.string(), .reason = "cannot open the cell file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_cell_json(ss.str(), file);
}

}  // namespace interfere::robot
