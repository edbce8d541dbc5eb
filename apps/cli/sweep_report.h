// The report of `interfere sweep` (issue #5; docs/probe.md): JSON, CSV and the summary lines, from the
// options, the workpiece, the path and the sweep's result. Shared by `interfere sweep` (cmd_sweep.cpp)
// and `interfere-mpi sweep` (apps/mpi/sweep.cpp, issue #31 item 3), whose rank 0 merges the ranks'
// blocks of path points into one SweepResult and writes the same report through here.
#pragma once
#include <array>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common.h"  // (StepTessellation: a header type only)
#include "interfere/probe/paper_tests.h"
#include "interfere/probe/replan.h"
#include "interfere/probe/sweep.h"
#include "view_output.h"

namespace interfere::cli {

struct SweepOptions {
  StepTessellation tessellation;
  std::string workpiece, robot, path, json, csv, hits_obj, probes_vtk, hierarchy = "bvh", units = "mm", holder_box;
  std::string units_workpiece;  ///< --units-workpiece (empty: by the format)
  std::string fail_on;
  std::string interpolate;    ///< --interpolate joint|pose (empty: joint when the machine can, docs/probe.md)
  double d1 = std::numeric_limits<double>::quiet_NaN();  ///< --d1: the paper's machine (§3.1)
  double d2 = std::numeric_limits<double>::quiet_NaN();  ///< --d2
  double clearance = 0;       ///< requested clearance (--clearance), 0 = none
  std::size_t max_poses = std::size_t(1) << 16;
  double probe_radius = std::numeric_limits<double>::quiet_NaN();
  double probe_length = std::numeric_limits<double>::quiet_NaN();
  double holder_radius = 0, holder_length = 0;
  double patch_size = 0, patch_rule = 33, max_clearance = 0;
  int threads = 0, depth = 16;
  bool no_continuous = false, no_clearance = false;
  bool paper_levels = false;  ///< --paper-levels: the paper's three levels beside the exact test
  double replan_tilt = 0;     ///< --replan-tilt: re-plan colliding points within this cone (degrees)
  std::string replan_standoff;  ///< --replan-standoff MIN,MAX (mm, changes of the stand-off)
  std::string replanned_path;   ///< --replanned-path: the path with the suggestions in place (CSV)
  ViewOutputs views;
};

/// Everything the report shows besides the options.
struct SweepRun {
  const SweepOptions& o;
  std::string format;              ///< the workpiece's format (mesh_format_name or "step")
  std::string unit, unit_source;   ///< the workpiece's own unit and where it comes from
  double workpiece_scale = 1, linear_deflection = 0;
  const probe::Workpiece& w;
  const probe::ProbePath& path;
  bool pose_input = false;         ///< the path file held poses
  const probe::Robot* robot = nullptr;
  const probe::ProbeShape& shape;
  probe::Hierarchy hierarchy;
  bool joint_motion = false;
  int threads = 0;                 ///< the report's options.threads
  const probe::SweepResult& r;
  const std::vector<probe::PaperPointCheck>& paper;  ///< --paper-levels, per point
  std::size_t paper_colliding = 0, paper_fp = 0, paper_fn = 0;
  bool replanning = false;
  const probe::ReplanRequest& replan_request;
  const probe::ReplanResult& replanned;
  const probe::SweepResult& after;  ///< the re-planned path's sweep
  double read_seconds = 0, total_seconds = 0;
  int status = 0;
};

/// The smallest clearance over the points (0 at a colliding one) and its point (-1: none).
void sweep_min_clearance(const probe::SweepResult& r, double& min_clear, long& min_point);
/// The JSON report without the envelope (report_text adds it).
nlohmann::json sweep_report_json(const SweepRun& run);
/// The per-point CSV table.
std::string sweep_report_csv(const probe::ProbePath& path, const probe::SweepResult& r);
/// The summary lines `interfere sweep` prints.
void print_sweep_summary(const SweepRun& run);

}  // namespace interfere::cli
