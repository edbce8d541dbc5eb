// The scene clash report (issue #24, items 5 and 7): one JSON schema (docs/report.md, "Scene
// clash report"), a CSV clash table, and the status of each clash against a previous report.
#pragma once
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/scene/engine.h"

namespace interfere::scene {

/// The report's schema: "interfere.scene-clash", version kReportSchemaVersion.
inline constexpr const char* kReportSchema = "interfere.scene-clash";
inline constexpr int kReportSchemaVersion = 1;

/// Marks every clash of `result` new or active against the baseline report (the JSON text of an
/// earlier report of this schema), carries the user's fields of the baseline clash with the same
/// id onto it (every key that is not one the engine writes: "status" when the user set it to
/// "approved" or another word of their own, "assignee", "comment", ...), and lists in
/// result.resolved the baseline clashes not found now, unless they were already resolved there
/// (a resolved clash is listed once, then dropped). Errors name `baseline_name` and the JSON path:
/// invalid JSON, another schema or schema version, a clash without an id.
Status apply_baseline(SceneClashResult& result, const std::string& baseline_json, const std::string& baseline_name);

/// What the report says besides the result.
struct ReportContext {
  std::string command;  ///< "interfere clash ...", as run
  std::string tool_version;
  std::vector<std::string> inputs;  ///< the files read
  int threads = 0;
  double total_seconds = 0;
  /// The report's `seconds` (docs/report.md: the process's wall time when the report is written);
  /// < 0: total_seconds.
  double process_seconds = -1;
  int exit_status = 0;
  std::vector<std::string> warnings;  ///< the caller's, besides the result's
};

/// The JSON report (2-space indented, ending in a newline), with the keys every command's report
/// has (schema_version, command, version, inputs, options, result, warnings, seconds; docs/report.md).
std::string report_json(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashResult& result,
                        const ReportContext& context);

/// The CSV clash table: one row per clash (and per resolved baseline clash), header
/// id,test,status,verdict,kind,body_a,name_a,path_a,body_b,name_b,path_b,depth,depth_bound,distance,
/// x,y,z,box_min_x,box_min_y,box_min_z,box_max_x,box_max_y,box_max_z,curve_length,cross_pairs,touch_pairs,
/// triangles_a,triangles_b,first_frame,frames,user_status,assignee,comment (RFC 4180 quoting).
std::string clash_table_csv(const Scene& scene, const SceneClashResult& result);

/// The frames table (motion) as CSV: frame,label,time,clashes,contacts,clearances,undecided,min_distance,max_depth,verdict.
std::string frames_table_csv(const SceneClashResult& result);
/// The table frames x body pairs (SceneClashResult::frame_pairs; issue #26, item 2), one row per
/// pair with a finding in a frame: frame,label,time,test,body_a,body_b,verdict,clashes,contacts,
/// clearances,undecided,min_distance (empty: not measured),max_depth,max_depth_bound,
/// reference_verdict (empty: no reference pass).
std::string frame_pairs_table_csv(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashResult& result);

}  // namespace interfere::scene
