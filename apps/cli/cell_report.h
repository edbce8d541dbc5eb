// The report of `interfere cell` (issue #28, deliverable 3): JSON, CSV and the summary lines, from
// the cell, its scene, the joint path and the path check's results. Shared by `interfere cell`
// (cmd_cell.cpp) and `interfere-mpi cell` (apps/mpi/cell.cpp, issue #31 item 3), whose rank 0 merges
// the ranks' blocks of path points into one result and writes the same report through here.
#pragma once
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "interfere/query/verdict.h"
#include "interfere/robot/cell.h"
#include "interfere/scene/engine.h"

namespace interfere::cli {

/// What the report says about the run itself (the command line's inputs and flags).
struct CellReportOptions {
  std::string cell_file, path_file;
  bool ik = false;           ///< --pose-path: the path came from inverse kinematics
  nlohmann::json ik_report;  ///< its "ik" section
  std::size_t between = 0;
  bool continuous = false;
  int max_depth = 12;
  bool link_poses = false;  ///< --poses
  FailOn fail_on;
};

/// The verdicts per point and per segment and the totals of the summary.
struct CellTotals {
  std::vector<Verdict> point_verdict, segment_verdict;
  std::size_t colliding_points = 0, colliding_segments = 0, seg_collide = 0, seg_unresolved = 0;
  Verdict verdict = Verdict::clear;
  int status = 0;  ///< verdict_exit_status(verdict, fail_on)
};

/// `r`: the check at cs's frames (frames rows, frames x pairs rows sorted by frame, pair
/// summaries, counts); `between`: the conservative check's segments (with `continuous`).
struct CellRun {
  const robot::Cell& cell;
  const robot::CellScene& cs;
  const robot::JointPath& path;
  const scene::SceneClashResult& r;
  const std::vector<robot::SegmentResult>& between;
};

CellTotals cell_totals(const CellRun& run, const CellReportOptions& o);
/// The JSON report without the envelope (report_text adds it).
nlohmann::json cell_report_json(const CellRun& run, const CellReportOptions& o, const CellTotals& t);
/// The CSV table: one row per finding (point, test, body pair), or per clear point.
std::string cell_report_csv(const CellRun& run);
/// The summary lines `interfere cell` prints.
void print_cell_summary(std::FILE* out, const CellRun& run, const CellReportOptions& o, const CellTotals& t);

}  // namespace interfere::cli
