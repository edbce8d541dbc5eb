// The inputs of `interfere sweep` (issue #5; docs/probe.md): the option checks, the robot, the path
// and its motion between points, the sweep request and the collision geometry outputs. Shared by
// `interfere sweep` (cmd_sweep.cpp) and `interfere-mpi sweep` (apps/mpi/sweep.cpp, issue #31 item 3),
// so that both check and read alike: same messages (cli::InputError naming the flag or file), same order.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "interfere/probe/sweep.h"
#include "sweep_report.h"  // (SweepOptions)

namespace interfere::cli {

/// v finite and > 0 (>= 0 with allow_zero).
void check_positive(double v, const char* flag, bool allow_zero = false);
/// --holder-box W,D,L: three finite numbers > 0 (width, depth, length).
std::array<double, 3> parse_holder_box(const std::string& s);
/// --hierarchy NAME: bvh, patches, grid, distance-field, brute.
probe::Hierarchy parse_hierarchy(const std::string& s);

/// The probe and holder (--probe-*, --holder-*), --patch-size, --patch-rule, --max-clearance,
/// --clearance (against --no-clearance and --max-clearance) and --max-poses, in this order; the shape.
probe::ProbeShape check_sweep_probe(const SweepOptions& o);
/// The machine: --units mm with a robot, --hierarchy, --interpolate, --d1/--d2 (against --robot).
probe::Hierarchy check_sweep_machine(const SweepOptions& o);
/// --robot's file, else the paper's machine (§3.1) of --d1/--d2, else none.
std::optional<probe::Robot> read_sweep_robot(const SweepOptions& o);

/// The path as swept: its poses, and joint rows where the motion between points is the machine's.
struct SweepPath {
  probe::ProbePath path;
  bool pose_input = false;    ///< the path file held poses
  bool joint_motion = false;  ///< joint interpolation between points
};
/// --path read against the robot, its motion between points chosen (--interpolate; a pose path's
/// inverse kinematics: the paper's machine's, or numerical on a DH robot), every tip's coordinate
/// range and, with a holder box, the poses' reference frames checked.
SweepPath read_sweep_path(const SweepOptions& o, const probe::Robot* robot, const probe::ProbeShape& shape);
/// Scales the workpiece's vertices to the working unit (--units); a vertex out of the exact tests'
/// coordinate range after it names the workpiece file.
void scale_workpiece(std::vector<Vec3>& positions, double scale, const SweepOptions& o);

/// The sweep's request from the options (no progress callback).
probe::SweepRequest sweep_request(const SweepOptions& o, const probe::ProbeShape& shape);
/// --hits-obj and --probes-vtk (when given): the collision geometry; the first write's failure.
Status write_sweep_geometry(const SweepOptions& o, const probe::Workpiece& w, const probe::ProbePath& path,
                            const probe::Robot* motion_robot, const probe::ProbeShape& shape,
                            const probe::SweepResult& r);

}  // namespace interfere::cli
