// One report schema for every command (issue #30, item 4; docs/report.md, docs/schema/).
//
// Every JSON report has the same eight top-level keys:
//   schema_version (int: the version of that command's report schema, docs/schema/<command>.schema.json),
//   command, version (the tool's), inputs (what was read), options (what was asked),
//   result (what was found: at least `verdict` and `exit_status` where the command has them, and its
//   headline figures), warnings (array of strings), seconds (number: wall time of the process
//   until the report was written).
// Commands build their report as before; finish_report() adds the envelope keys each lacks from the
// keys it has (copies: the older keys stay, documented as such), so the per-command details keep
// their documented places.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace interfere::cli {

/// Adds the envelope keys to `report` (a JSON object with "command"). `inputs`, when not null, is the
/// `inputs` object for commands whose report names no input file (bearing's parameters file).
void finish_report(nlohmann::json& report, const nlohmann::json& inputs = nullptr);

/// finish_report(report, inputs), serialised with `indent` and a final newline.
std::string report_text(nlohmann::json report, int indent = 2, const nlohmann::json& inputs = nullptr);

/// The wall time of the process so far (the reports' `seconds`).
double process_seconds();

/// The same on a report serialised by the library; returns it serialised.
std::string finish_report_text(const std::string& report);

}  // namespace interfere::cli
