// Assembly semantics (issue #6, item 4), after He & Xu (SJTU 2023) §3: JSON rules from constraint
// types to feature types and roles, a JSON process description, and the selection of the assembly
// features of one process step.
#include "interfere/cad/semantics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
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
                                             const std::vector<Feature>& features) {
  auto sel = select_step_features(process, step_id, rules, part_name, features);
  if (sel && !step_includes(process, step_id, part_name)) return Selection{};
  return sel;
}

Expected<Selection> select_step_features(const Process& process, const std::string& step_id,
                                         const SemanticRules& rules, const std::string& part_name,
                                         const std::vector<Feature>& features) {
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
    for (const SemanticRule::Need& n : r.needs) {
      bool found = false;
      for (const Feature& f : features) {
        if (f.type != n.feature) continue;
        found = true;
        sel.features_used.push_back(&f);
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
      if (!found)
        sel.warnings.push_back("step '" + step_id + "', part '" + part_name + "': rule '" + r.name + "' found no '" +
                               n.feature + "'");
    }
  }
  std::sort(sel.faces.begin(), sel.faces.end());
  sel.faces.erase(std::unique(sel.faces.begin(), sel.faces.end()), sel.faces.end());
  return sel;
}

}  // namespace interfere::cad
