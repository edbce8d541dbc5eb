// The reports' common top-level keys (report_envelope.h; issue #30, item 4).
#include "report_envelope.h"

#include <chrono>
#include <initializer_list>
#include <string>

namespace interfere::cli {
namespace {

using nlohmann::json;

// Process start, near enough: static initialisation, before main().
const std::chrono::steady_clock::time_point g_start = std::chrono::steady_clock::now();

/// {key: report[key]} for the keys present.
json pick(const json& report, std::initializer_list<const char*> keys) {
  json out = json::object();
  for (const char* k : keys)
    if (report.contains(k)) out[k] = report[k];
  return out;
}

json size_of(const json& report, const char* key) {
  return report.contains(key) && report[key].is_array() ? json(report[key].size()) : json(nullptr);
}

/// The envelope's inputs, options, result for a report lacking them, per command (docs/report.md).
void fill(json& j, const std::string& command, const json& given_inputs) {
  const bool has_inputs = j.contains("inputs"), has_options = j.contains("options"), has_result = j.contains("result");
  json inputs = given_inputs.is_null() ? json::object() : given_inputs, options = json::object(), result = json::object();
  if (command == "clash" || command == "distance") {
    options = pick(j, {"units", "threads"});
    result = pick(j, {"verdict", "exit_status", "summary"});
  } else if (command == "check") {
    inputs = pick(j, {"file", "format"});
    result = j;
    for (const char* k : {"command", "version", "interfere_version", "file", "format", "warnings", "schema_version"})
      result.erase(k);
  } else if (command == "sweep") {
    result = pick(j, {"verdict", "exit_status", "summary"});
  } else if (command == "bearing") {
    if (j.value("mode", "") == "assembly") {
      if (inputs.empty()) inputs = pick(j, {"assembly", "motion"});
      options = pick(j, {"mode", "frames", "seed", "threads"});
    } else {
      if (j.contains("scar_import")) inputs["scar_import"] = j["scar_import"];
      options = pick(j, {"parameters", "threads"});
    }
    result = pick(j, {"verdict", "exit_status", "undecided_reasons", "worst", "results"});
  } else if (command == "surface") {
    inputs = {{"input", j.value("input", json(nullptr))}};
    options = pick(j, {"step", "scale", "linear_faces"});
    result = pick(j, {"output", "triangles", "vertices", "parts"});
  } else if (command == "simplify") {
    inputs = {{"input", j.value("input", json(nullptr))}};
    options = pick(j, {"units", "target_triangles", "feature_mode", "sharp_angle", "seams", "max_error"});
    result = pick(j, {"output", "input_triangles", "output_triangles", "output_vertices", "reached", "hausdorff",
                      "error_bound"});
  } else if (command == "features") {
    inputs = {{"input", j.value("input", json(nullptr))}};
    options = pick(j, {"units"});
    result = {{"parts", size_of(j, "parts")}, {"instances", size_of(j, "instances")}};
    if (j.contains("parts") && j["parts"].is_array()) {
      std::size_t features = 0;
      for (const json& p : j["parts"])
        if (p.contains("features") && p["features"].is_array()) features += p["features"].size();
      result["features"] = features;
    }
  } else if (command == "assembly-clash") {
    inputs = {{"input", j.value("input", json(nullptr))}};
    options = pick(j, {"units", "clearance"});
    result = pick(j, {"verdict", "exit_status", "candidate_pairs", "clashes", "clashes_within_tessellation_error",
                      "contacts", "within_clearance", "undecided"});
    result["instances"] = size_of(j, "instances");
  } else if (command == "cell") {
    inputs = pick(j, {"cell", "path"});
    options = pick(j, {"units", "between"});
    result = pick(j, {"exit_status", "summary"});
  } else {  // (a command not listed here yet: its verdict and summary)
    options = pick(j, {"units", "threads"});
    result = pick(j, {"verdict", "exit_status", "summary"});
  }
  if (!has_inputs) j["inputs"] = std::move(inputs);
  if (!has_options) j["options"] = std::move(options);
  if (!has_result) j["result"] = std::move(result);
}

}  // namespace

double process_seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - g_start).count(); }

void finish_report(json& j, const json& inputs) {
  const std::string command = j.value("command", "");
  if (!j.contains("schema_version")) j["schema_version"] = 1;
  if (!j.contains("version")) j["version"] = j.value("interfere_version", INTERFERE_VERSION);
  fill(j, command, inputs);
  if (!j.contains("warnings") || !j["warnings"].is_array())
    j["warnings"] = j.contains("input_warnings") && j["input_warnings"].is_array() ? j["input_warnings"] : json::array();
  // `seconds` is the process's wall time; a command's own breakdown (simplify, features wrote it
  // under `seconds` before issue #30) is `timings_s`, as in every other report.
  if (j.contains("seconds") && j["seconds"].is_object() && !j.contains("timings_s")) j["timings_s"] = j["seconds"];
  j["seconds"] = process_seconds();
}

std::string report_text(json report, int indent, const json& inputs) {
  finish_report(report, inputs);
  return report.dump(indent) + "\n";
}

std::string finish_report_text(const std::string& report) {
  json j = json::parse(report);
  finish_report(j);
  return j.dump(2) + "\n";
}

}  // namespace interfere::cli
