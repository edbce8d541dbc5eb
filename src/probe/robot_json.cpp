// Robot file (issue #5, item 1): a Denavit-Hartenberg chain in JSON (docs/probe.md, "Robot file").
// Every error names the file, the line (of the offending value where known) and the field.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "interfere/core/units.h"
#include "interfere/probe/kinematics.h"

namespace interfere::probe {
namespace {

using nlohmann::json;

/// 1-based line of byte offset `pos` in `text`.
std::int64_t line_of(std::string_view text, std::size_t pos) {
  std::int64_t line = 1;
  for (std::size_t i = 0; i < pos && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

/// Line of the first occurrence of "key" after the `nth` occurrence of "\"joints\"" entry starts
/// (best effort: used only to point the reader near the field).
std::int64_t find_key_line(std::string_view text, const std::string& key, std::size_t from = 0) {
  const std::string quoted = "\"" + key + "\"";
  const std::size_t p = text.find(quoted, from);
  return p == std::string_view::npos ? -1 : line_of(text, p);
}

struct Parser {
  std::string_view text;
  std::string file;
  Error fail(const std::string& field, const std::string& reason, std::int64_t line = -1) const {
    return Error{.file = file, .line = line, .reason = field + ": " + reason};
  }
};

bool get_number(const json& obj, const char* key, double& out) {
  auto it = obj.find(key);
  if (it == obj.end() || !it->is_number()) return false;
  out = it->get<double>();
  return std::isfinite(out);
}

/// Byte offsets where each element of the "joints" array starts (by scanning for '{' at depth 1 of
/// the array), to report lines of joint fields.
std::vector<std::size_t> joint_offsets(std::string_view text) {
  std::vector<std::size_t> out;
  const std::size_t j = text.find("\"joints\"");
  if (j == std::string_view::npos) return out;
  std::size_t i = text.find('[', j);
  if (i == std::string_view::npos) return out;
  int depth = 0;
  bool in_string = false;
  for (; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\') ++i;
      else if (ch == '"') in_string = false;
      continue;
    }
    if (ch == '"') in_string = true;
    else if (ch == '[' || ch == '{') {
      if (ch == '{' && depth == 1) out.push_back(i);
      ++depth;
    } else if (ch == ']' || ch == '}') {
      if (--depth == 0) break;
    }
  }
  return out;
}

/// The keys an object may have (issue #23, item 9: a misspelt key is an error, not ignored): the
/// first other key, or nullptr.
const std::string* unknown_key(const json& obj, const std::vector<const char*>& known) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; })) return &it.key();
  }
  return nullptr;
}

std::string key_list(const std::vector<const char*>& known) {
  std::string s;
  for (const char* k : known) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

/// Tolerance of the base's rotation: every entry of R^T R - I within this (rounded decimals of a
/// rotation written by hand pass; a scale or shear of more than about 1e-6 does not).
constexpr double kRotationTolerance = 1e-6;

}  // namespace

Expected<Robot> parse_robot_json(std::string_view text, const std::string& file_name) {
  Parser p{text, file_name};
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    return Error{.file = file_name, .line = line_of(text, e.byte > 0 ? e.byte - 1 : 0),
                 .reason = std::string("invalid JSON: ") + e.what()};
  } catch (const json::exception& e) {  // a number beyond double ("9e308")
    return Error{.file = file_name, .reason = std::string("invalid JSON: ") + e.what()};
  }
  if (!doc.is_object()) return p.fail("(document)", "expected a JSON object", 1);
  static const std::vector<const char*> kTop{"name", "units", "comment", "convention", "base", "joints",
                                                          "tool"};
  if (const std::string* k = unknown_key(doc, kTop)) {
    return p.fail(*k, "unknown key (expected " + key_list(kTop) + ")", find_key_line(text, *k));
  }
  Robot robot;
  if (auto it = doc.find("name"); it != doc.end()) {
    if (!it->is_string()) return p.fail("name", "expected a string", find_key_line(text, "name"));
    robot.name = it->get<std::string>();
  } else {
    robot.name = "robot";
  }
  // Lengths (a, d, base translation, tool tip, prismatic joint values and limits) are read in mm,
  // the unit of path files and of the working geometry; another unit would silently scale the
  // robot, so it is refused rather than ignored.
  if (auto it = doc.find("units"); it != doc.end()) {
    const std::int64_t uline = find_key_line(text, "units");
    if (!it->is_string()) return p.fail("units", "expected a string (\"mm\")", uline);
    const std::string u = it->get<std::string>();
    if (u != "mm") {
      return p.fail("units", "'" + u + "'" +
                                 (millimetres_per_unit(u) ? "" : std::string(" is not a known unit (") + known_units() + ") and") +
                                 " is not supported: robot files are in mm (lengths, prismatic joint values of the "
                                 "path, tool tip); convert the file to mm",
                    uline);
    }
  }
  // "standard" (the default) or "modified" DH (kinematics.h); the text robot_to_json writes ("standard
  // DH: ...") is read back as its first word. Any other value is an error: read as the other
  // convention, a table gives a different robot without a word.
  if (auto it = doc.find("convention"); it != doc.end()) {
    const std::int64_t cline = find_key_line(text, "convention");
    const std::string c = it->is_string() ? it->get<std::string>() : std::string();
    const auto starts = [&](const char* w) {
      const std::string word(w);
      return c == word || c.rfind(word + " DH", 0) == 0;
    };
    if (starts("standard")) robot.convention = DhConvention::standard;
    else if (starts("modified")) robot.convention = DhConvention::modified;
    else
      return p.fail("convention",
                    (it->is_string() ? "'" + c + "'" : std::string("not a string")) +
                        ": expected \"standard\" (distal DH: T_i = Rz(theta) Tz(d) Tx(a) Rx(alpha)) or "
                        "\"modified\" (proximal, Craig: T_i = Rx(alpha) Tx(a) Rz(theta) Tz(d))",
                    cline);
  }
  if (auto it = doc.find("base"); it != doc.end()) {
    if (!it->is_array() || it->size() != 12) {
      return p.fail("base", "expected 12 numbers (row-major [R|t])", find_key_line(text, "base"));
    }
    std::array<double, 12> v{};
    for (std::size_t i = 0; i < 12; ++i) {
      if (!(*it)[i].is_number()) return p.fail("base[" + std::to_string(i) + "]", "not a number", find_key_line(text, "base"));
      v[i] = (*it)[i].get<double>();
    }
    for (int r = 0; r < 3; ++r) {
      robot.base.r[r] = {v[4 * r], v[4 * r + 1], v[4 * r + 2]};
      robot.base.t[r] = v[4 * r + 3];
    }
    // A rigid transform: R orthonormal (R^T R = I within kRotationTolerance) with det R = +1.
    const auto& R = robot.base.r;
    double worst = 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double rtr = R[0][i] * R[0][j] + R[1][i] * R[1][j] + R[2][i] * R[2][j];
        worst = std::max(worst, std::fabs(rtr - (i == j ? 1.0 : 0.0)));
      }
    }
    const double det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) -
                       R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
                       R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
    if (!std::isfinite(robot.base.t.x) || !std::isfinite(robot.base.t.y) || !std::isfinite(robot.base.t.z) ||
        !(worst <= kRotationTolerance) || !(det > 0)) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "not a rigid transform: the rotation part must be orthonormal with determinant +1 "
                    "(max |R^T R - I| = %.3g, tolerance %.0e; det = %.6g)",
                    worst, kRotationTolerance, det);
      return p.fail("base", buf, find_key_line(text, "base"));
    }
  }
  auto joints = doc.find("joints");
  if (joints == doc.end()) return p.fail("joints", "missing", 1);
  if (!joints->is_array() || joints->empty()) {
    return p.fail("joints", "expected a non-empty array", find_key_line(text, "joints"));
  }
  const std::vector<std::size_t> offsets = joint_offsets(text);
  for (std::size_t i = 0; i < joints->size(); ++i) {
    const json& j = (*joints)[i];
    const std::size_t at = i < offsets.size() ? offsets[i] : 0;
    const std::string where = "joints[" + std::to_string(i) + "]";
    const std::int64_t jline = i < offsets.size() ? line_of(text, at) : -1;
    if (!j.is_object()) return p.fail(where, "expected an object", jline);
    static const std::vector<const char*> kJoint{"name", "type", "a", "alpha", "d", "theta", "min", "max",
                                                               "comment"};
    if (const std::string* k = unknown_key(j, kJoint)) {
      return p.fail(where + "." + *k, "unknown key (expected " + key_list(kJoint) + ")", find_key_line(text, *k, at));
    }
    DhJoint dj;
    std::string default_name = "J";
    default_name += std::to_string(i + 1);
    if (auto n = j.find("name"); n != j.end() && !n->is_string()) {
      return p.fail(where + ".name", "expected a string", find_key_line(text, "name", at));
    }
    dj.name = j.value("name", default_name);
    for (const DhJoint& other : robot.joints) {
      if (other.name == dj.name) {
        return p.fail(where + ".name", "'" + dj.name + "' names two joints (path columns are matched by joint name)",
                      jline);
      }
    }
    auto type = j.find("type");
    if (type == j.end()) return p.fail(where + ".type", "missing (prismatic or revolute)", jline);
    if (!type->is_string()) return p.fail(where + ".type", "expected a string", find_key_line(text, "type", at));
    const std::string t = type->get<std::string>();
    if (t == "prismatic" || t == "P") dj.type = JointType::prismatic;
    else if (t == "revolute" || t == "R") dj.type = JointType::revolute;
    else return p.fail(where + ".type", "unknown joint type '" + t + "' (prismatic or revolute)", find_key_line(text, "type", at));
    for (const char* key : {"a", "alpha", "d", "theta"}) {
      double v = 0;
      if (!j.contains(key)) return p.fail(where + "." + key, "missing", jline);
      if (!get_number(j, key, v)) return p.fail(where + "." + key, "not a finite number", find_key_line(text, key, at));
      (key[0] == 'a' && key[1] == 0 ? dj.a : key[0] == 'a' ? dj.alpha : key[0] == 'd' ? dj.d : dj.theta) = v;
    }
    for (const char* key : {"min", "max"}) {
      if (!j.contains(key)) continue;
      double v = 0;
      if (!get_number(j, key, v)) return p.fail(where + "." + key, "not a finite number", find_key_line(text, key, at));
      (key[1] == 'i' ? dj.min : dj.max) = v;
    }
    if (!(dj.min <= dj.max)) return p.fail(where + ".min", "min > max", jline);
    robot.joints.push_back(dj);
  }
  if (auto tool = doc.find("tool"); tool != doc.end()) {
    const std::int64_t tline = find_key_line(text, "tool");
    if (!tool->is_object()) return p.fail("tool", "expected an object {\"tip\": [x,y,z], \"axis\": [x,y,z]}", tline);
    static const std::vector<const char*> kTool{"tip", "axis", "ref", "comment"};
    if (const std::string* k = unknown_key(*tool, kTool)) {
      return p.fail("tool." + *k, "unknown key (expected " + key_list(kTool) + ")",
                    find_key_line(text, *k, text.find("\"tool\"")));
    }
    for (const char* key : {"tip", "axis"}) {
      auto it = tool->find(key);
      if (it == tool->end()) return p.fail(std::string("tool.") + key, "missing", tline);
      if (!it->is_array() || it->size() != 3 || !(*it)[0].is_number() || !(*it)[1].is_number() || !(*it)[2].is_number()) {
        return p.fail(std::string("tool.") + key, "expected 3 numbers", tline);
      }
      const Vec3 v{(*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>()};
      (key[0] == 't' ? robot.tool_tip : robot.tool_axis) = v;
    }
    if (!(norm(robot.tool_axis) > 0)) return p.fail("tool.axis", "zero vector", tline);
    robot.tool_axis = robot.tool_axis / norm(robot.tool_axis);
    // Optional holder reference direction (box holders): default x of the last frame, y when the
    // tool axis is along x.
    if (auto it = tool->find("ref"); it != tool->end()) {
      if (!it->is_array() || it->size() != 3 || !(*it)[0].is_number() || !(*it)[1].is_number() || !(*it)[2].is_number()) {
        return p.fail("tool.ref", "expected 3 numbers", find_key_line(text, "ref"));
      }
      robot.tool_ref = {(*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>()};
      if (perpendicular_reference(robot.tool_ref, robot.tool_axis) == Vec3{}) {
        return p.fail("tool.ref", "zero, or parallel to tool.axis (it fixes the holder's width direction)",
                      find_key_line(text, "ref"));
      }
    } else if (perpendicular_reference(robot.tool_ref, robot.tool_axis) == Vec3{}) {
      robot.tool_ref = {0, 1, 0};
    }
  } else {
    return p.fail("tool", "missing ({\"tip\": [x,y,z], \"axis\": [x,y,z]} in the last DH frame)", 1);
  }
  return robot;
}

Expected<Robot> read_robot_json(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path.string(), .reason = "cannot open robot file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_robot_json(ss.str(), path.string());
}

std::string robot_to_json(const Robot& robot) {
  json j;
  j["name"] = robot.name;
  j["units"] = "mm";
  std::vector<double> base;
  for (int r = 0; r < 3; ++r) {
    base.insert(base.end(), {robot.base.r[r][0], robot.base.r[r][1], robot.base.r[r][2], robot.base.t[r]});
  }
  j["base"] = base;
  j["convention"] = robot.convention == DhConvention::modified
                        ? "modified DH: T_i = Rx(alpha) Tx(a) Rz(theta) Tz(d); angles in degrees"
                        : "standard DH: T_i = Rz(theta) Tz(d) Tx(a) Rx(alpha); angles in degrees";
  for (const DhJoint& d : robot.joints) {
    json o{{"name", d.name}, {"type", d.type == JointType::prismatic ? "prismatic" : "revolute"},
           {"a", d.a}, {"alpha", d.alpha}, {"d", d.d}, {"theta", d.theta}};
    if (d.min > -1e300) o["min"] = d.min;
    if (d.max < 1e300) o["max"] = d.max;
    j["joints"].push_back(o);
  }
  j["tool"] = {{"tip", {robot.tool_tip.x, robot.tool_tip.y, robot.tool_tip.z}},
               {"axis", {robot.tool_axis.x, robot.tool_axis.y, robot.tool_axis.z}},
               {"ref", {robot.tool_ref.x, robot.tool_ref.y, robot.tool_ref.z}}};
  return j.dump(2) + "\n";
}

}  // namespace interfere::probe
