// Assembly semantics (issue #6, item 4), after He & Xu (SJTU 2023) §3: JSON rules from constraint
// types to feature types and roles, a JSON process description, and the selection of the assembly
// features of one process step.
#include "interfere/cad/semantics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fstream>
#include <sstream>

#include "data_dir.h"

namespace interfere::cad {
namespace {
using json = nlohmann::json;

Expected<std::string> slurp(const std::filesystem::path& p, const char* what) {
  std::ifstream in(p);
  if (!in) return Error{.file = p.string(), .reason = std::string("cannot open the ") + what};
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// 'a', 'b', 'c': names as the error and warning texts list them.
std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}
}  // namespace

Expected<SemanticRules> parse_semantic_rules(const std::string& text, const FeatureLibrary& library,
                                             const std::string& source) {
  SemanticRules out;
  try {
    const json j = json::parse(text);
    if (!j.is_object() || !j.contains("rules") || !j["rules"].is_array())
      return Error{.file = source, .reason = "semantic rules are an object with a \"rules\" array"};
    for (const json& jr : j["rules"]) {
      SemanticRule r;
      r.name = jr.at("name").get<std::string>();
      r.constraint = jr.at("constraint").get<std::string>();
      for (const SemanticRule& o : out.rules)
        if (o.name == r.name) return Error{.file = source, .reason = "rule name '" + r.name + "' appears twice"};
      if (!jr.at("features").is_array() || jr.at("features").empty())
        return Error{.file = source, .reason = "rule '" + r.name + "' names no feature (\"features\": [{\"type\": ...}])"};
      for (const json& jf : jr.at("features")) {
        SemanticRule::Need n;
        n.feature = jf.at("type").get<std::string>();
        n.roles = jf.value("roles", std::vector<std::string>{});
        if (!library.has(n.feature))
          return Error{.file = source, .reason = "rule '" + r.name + "' refers to unknown feature type '" + n.feature + "'"};
        // A misspelt role would drop its faces from every selection: an error naming the roles there are.
        const std::vector<std::string> known = library.roles(n.feature);
        for (const std::string& role : n.roles)
          if (std::find(known.begin(), known.end(), role) == known.end())
            return Error{.file = source, .reason = "rule '" + r.name + "' names role '" + role + "' of '" +
                                                   n.feature + "', whose patterns have the roles " + quoted_list(known)};
        n.add = jf.value("add", std::vector<std::string>{});
        for (const std::string& a : n.add)
          if (a != "TopFace" && a != "BottomFace")
            return Error{.file = source, .reason = "rule '" + r.name + "' adds '" + a +
                                                   "': the faces a rule can add are 'TopFace' and 'BottomFace'"};
        n.clamp_radius_factor = jf.value("clamp_radius_factor", 2.0);
        if (!(n.clamp_radius_factor == 0 || (n.clamp_radius_factor >= 1 && n.clamp_radius_factor < 1e6)))
          return Error{.file = source, .reason = "rule '" + r.name + "': clamp_radius_factor " +
                                                 std::to_string(n.clamp_radius_factor) +
                                                 " must be 0 (whole faces) or at least 1 (times the hole's radius)"};
        n.require_clamp_fit = jf.value("require_clamp_fit", true);
        r.needs.push_back(n);
      }
      out.rules.push_back(std::move(r));
    }
  } catch (const json::exception& e) {
    return Error{.file = source, .reason = std::string("malformed semantic rules: ") + e.what()};
  }
  return out;
}

Expected<SemanticRules> load_semantic_rules(const std::filesystem::path& path, const FeatureLibrary& library) {
  auto t = slurp(path, "semantic rules");
  if (!t) return t.error();
  return parse_semantic_rules(*t, library, path.string());
}

Expected<SemanticRules> default_semantic_rules(const FeatureLibrary& library) {
  return load_semantic_rules(data_file("semantics.json"), library);
}

Expected<Process> parse_process(const std::string& text, const std::string& source) {
  Process out;
  try {
    const json j = json::parse(text);
    if (!j.is_object() || !j.contains("steps") || !j["steps"].is_array())
      return Error{.file = source, .reason = "a process is an object with a \"steps\" array"};
    for (const json& js : j["steps"]) {
      ProcessStep s;
      s.id = js.at("id").get<std::string>();
      if (s.id.empty() || s.id == "all")
        return Error{.file = source, .reason = s.id.empty() ? std::string("a step has an empty id")
                                                            : "step id 'all' is reserved (--step all: every step)"};
      s.parts = js.value("parts", std::vector<std::string>{"*"});
      if (s.parts.empty())
        return Error{.file = source, .reason = "step '" + s.id + "' has an empty parts list, which keeps no feature: "
                                               "name its parts, or leave \"parts\" out for every part"};
      s.constraint = js.at("constraint").get<std::string>();
      for (const ProcessStep& o : out.steps)
        if (o.id == s.id) return Error{.file = source, .reason = "step id '" + s.id + "' appears twice"};
      out.steps.push_back(std::move(s));
    }
  } catch (const json::exception& e) {
    return Error{.file = source, .reason = std::string("malformed process description: ") + e.what()};
  }
  return out;
}

Expected<Process> load_process(const std::filesystem::path& path) {
  auto t = slurp(path, "process description");
  if (!t) return t.error();
  return parse_process(*t, path.string());
}

std::vector<std::string> unknown_step_parts(const Process& process, const std::string& step_id,
                                            const std::vector<std::string>& part_names) {
  std::vector<std::string> out;
  for (const ProcessStep& s : process.steps) {
    if (s.id != step_id) continue;
    for (const std::string& p : s.parts) {
      if (p == "*" || std::find(part_names.begin(), part_names.end(), p) != part_names.end()) continue;
      out.push_back("step '" + step_id + "' names part '" + p + "', which is not in the model (parts: " +
                    quoted_list(part_names) + "): no feature of it is kept");
    }
  }
  return out;
}

bool step_includes(const Process& process, const std::string& step_id, const std::string& name) {
  for (const ProcessStep& s : process.steps)
    if (s.id == step_id)
      return std::any_of(s.parts.begin(), s.parts.end(), [&](const std::string& p) { return p == "*" || p == name; });
  return false;
}

Expected<Selection> select_assembly_features(const Process& process, const std::string& step_id,
                                             const SemanticRules& rules, const std::string& part_name,
                                             const std::vector<Feature>& features, const Aag* aag) {
  auto sel = select_step_features(process, step_id, rules, part_name, features, aag);
  if (sel && !step_includes(process, step_id, part_name)) return Selection{};
  return sel;
}

namespace {
// He & Xu §3: "If feature Is Type (Circular Through Hole), Then feature.Add(TopFace and
// BottomFace)". The faces `add` names for feature `f`: TopFace its "top" role; BottomFace its
// "bottom" role, else (a counterbored or countersunk hole, whose pattern ends at the bore) the AAG
// neighbours of its innermost bore that are not its own or top faces. Each with the radius its
// clamped region is measured from (top: the largest of the feature's radii, bottom: the smallest).
struct Added {
  std::uint32_t face;
  double radius;
};
std::vector<Added> added_faces(const Feature& f, const std::vector<std::string>& add, const Aag* aag) {
  std::vector<Added> out;
  if (add.empty()) return out;
  double r_max = 0, r_min = 0;
  for (double r : f.radii) r_max = std::max(r_max, r), r_min = r_min == 0 ? r : std::min(r_min, r);
  const auto role = [&](const char* name) {
    auto it = f.role_faces.find(name);
    return it == f.role_faces.end() ? std::vector<std::uint32_t>{} : it->second;
  };
  const std::vector<std::uint32_t> top = role("top");
  for (const std::string& a : add) {
    if (a == "TopFace") {
      for (std::uint32_t x : top) out.push_back({x, r_max});
      continue;
    }
    std::vector<std::uint32_t> bottom = role("bottom");
    if (bottom.empty() && aag) {
      std::vector<std::uint32_t> bore = role("bore");
      if (bore.empty()) bore = role("wall");
      const auto own = [&](std::uint32_t x) {
        return std::binary_search(f.faces.begin(), f.faces.end(), x) || std::find(top.begin(), top.end(), x) != top.end();
      };
      for (const AagArc& arc : aag->arcs) {
        const bool a_in = std::find(bore.begin(), bore.end(), arc.a) != bore.end();
        const bool b_in = std::find(bore.begin(), bore.end(), arc.b) != bore.end();
        if (a_in == b_in) continue;
        const std::uint32_t other = a_in ? arc.b : arc.a;
        if (!own(other) && std::find(bottom.begin(), bottom.end(), other) == bottom.end()) bottom.push_back(other);
      }
    }
    for (std::uint32_t x : bottom) out.push_back({x, r_min});
  }
  return out;
}

bool has_axis(const Feature& f) { return norm(f.axis) > 0.5; }
}  // namespace

Expected<Selection> select_step_features(const Process& process, const std::string& step_id,
                                         const SemanticRules& rules, const std::string& part_name,
                                         const std::vector<Feature>& features, const Aag* aag) {
  const ProcessStep* step = nullptr;
  for (const ProcessStep& s : process.steps)
    if (s.id == step_id) step = &s;
  if (!step) return Error{.reason = "unknown process step '" + step_id + "'"};
  // A constraint without a rule is an error, not an empty selection: a misspelt constraint would
  // otherwise leave the step's assembly features unprotected without a word.
  if (std::none_of(rules.rules.begin(), rules.rules.end(),
                   [&](const SemanticRule& r) { return r.constraint == step->constraint; })) {
    std::vector<std::string> known;
    for (const SemanticRule& r : rules.rules)
      if (std::find(known.begin(), known.end(), r.constraint) == known.end()) known.push_back(r.constraint);
    return Error{.reason = "step '" + step_id + "': no assembly-semantics rule for constraint '" + step->constraint +
                           "' (the rules know " + (known.empty() ? std::string("none") : quoted_list(known)) + ")"};
  }
  Selection sel;
  for (const SemanticRule& r : rules.rules) {
    if (r.constraint != step->constraint) continue;
    std::vector<std::string> missing;  // the needs' types found on none of the features
    for (const SemanticRule::Need& n : r.needs) {
      bool found = false;
      for (const Feature& f : features) {
        if (f.type != n.feature) continue;
        found = true;
        // The faces the rule adds, clamped to the annulus around the hole (issue #29, item 3).
        const std::vector<Added> added = added_faces(f, n.add, aag);
        if (n.clamp_radius_factor > 0 && n.require_clamp_fit && aag) {
          std::string misfit;
          for (const Added& a : added) {
            const AagNode& node = aag->nodes[a.face];
            const double rc = n.clamp_radius_factor * a.radius;
            // At least half the annulus: a nut's or a small lug's face is smaller than a washer
            // but is itself the clamped face; a flange ring around a main bore is far smaller.
            const double need = 0.5 * std::numbers::pi * (rc * rc - a.radius * a.radius);
            if (node.type == SurfaceType::plane && a.radius > 0 && node.area < need)
              misfit = "face " + std::to_string(a.face) + " (area " + std::to_string(std::lround(node.area)) +
                       ") is smaller than half the clamped annulus of radius " + std::to_string(std::lround(rc)) + " (" +
                       std::to_string(std::lround(need)) + ")";
          }
          if (!misfit.empty()) {
            sel.warnings.push_back("step '" + step_id + "', part '" + part_name + "': rule '" + r.name + "' skips the '" +
                                   f.type + "' of radius " + std::to_string(std::lround(f.radii.empty() ? 0.0 : f.radii.front())) +
                                   " (faces " + std::to_string(f.faces.front()) + "...): " + misfit +
                                   ", so no washer or head clamps there");
            continue;
          }
        }
        sel.features_used.push_back(&f);
        for (const Added& a : added) {
          if (n.clamp_radius_factor > 0 && has_axis(f) && a.radius > 0)
            sel.annuli.push_back({a.face, f.axis_point, f.axis, n.clamp_radius_factor * a.radius});
          else
            sel.faces.push_back(a.face);
        }
        if (n.roles.empty()) {
          sel.faces.insert(sel.faces.end(), f.faces.begin(), f.faces.end());
        } else {
          for (const std::string& role : n.roles) {
            auto it = f.role_faces.find(role);
            if (it != f.role_faces.end()) sel.faces.insert(sel.faces.end(), it->second.begin(), it->second.end());
            else sel.warnings.push_back("rule '" + r.name + "': feature '" + f.type + "' has no role '" + role + "'");
          }
        }
      }
      if (!found) missing.push_back(n.feature);
    }
    // One warning when the rule found none of its types (a rule naming alternatives, counterbored
    // or countersunk holes for a screw, is satisfied by either).
    if (!missing.empty() && missing.size() == r.needs.size())
      sel.warnings.push_back("step '" + step_id + "', part '" + part_name + "': rule '" + r.name + "' found no " +
                             (missing.size() == 1 ? "'" + missing[0] + "'" : quoted_list(missing)));
  }
  std::sort(sel.faces.begin(), sel.faces.end());
  sel.faces.erase(std::unique(sel.faces.begin(), sel.faces.end()), sel.faces.end());
  // An annulus on a face kept whole anyway adds nothing.
  std::erase_if(sel.annuli, [&](const Annulus& a) { return std::binary_search(sel.faces.begin(), sel.faces.end(), a.face); });
  return sel;
}

std::vector<std::uint32_t> annulus_triangles(const TriMesh& mesh, const std::vector<std::uint32_t>& face_ids,
                                             const std::vector<Annulus>& annuli) {
  std::vector<std::uint32_t> out;
  if (annuli.empty()) return out;
  std::vector<std::vector<const Annulus*>> by_face;
  for (const Annulus& a : annuli) {
    if (a.face >= by_face.size()) by_face.resize(std::size_t{a.face} + 1);
    by_face[a.face].push_back(&a);
  }
  for (std::size_t t = 0; t < mesh.num_triangles() && t < face_ids.size(); ++t) {
    if (face_ids[t] >= by_face.size()) continue;
    for (const Annulus* a : by_face[face_ids[t]]) {
      // Every corner within the radius of the axis (distance to the axis line): the region's own
      // triangles. A triangle reaching out of it (on a planar face BRepMesh fans the hole's rim to
      // the face's far border) is not taken: the rim it shares is kept by the hole's wall, and its
      // far corners are no part of the clamped region.
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const Vec3 d = mesh.positions[mesh.triangles[t][k]] - a->axis_point;
        const Vec3 q = d - dot(d, a->axis) * a->axis;
        inside = dot(q, q) <= a->radius * a->radius;
      }
      if (inside) {
        out.push_back(static_cast<std::uint32_t>(t));
        break;
      }
    }
  }
  return out;
}

}  // namespace interfere::cad
