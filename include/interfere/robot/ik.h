// Numerical inverse kinematics for serial chains (issue #28, deliverable 1 for robots users have):
// a probe pose (end-circle centre `tip`, direction `axis`, optionally the holder's reference
// direction `ref`) is turned into joint values of a URDF or DH chain, so that a pose path (the
// same CSV as `interfere sweep`'s pose path, probe/path.h) drives a cell (`interfere cell
// --pose-path`). The §3.1 machine keeps its analytic inverse (probe/paper_machine.h).
//
// Method: damped least squares (Levenberg-Marquardt; Wampler 1986, Nakamura & Hanafusa 1986) on
// the task error e = (tip error in mm, orientation error scaled by a length L to mm):
//   dq = J^T (J J^T + lambda^2 I)^-1 e,
// J the geometric Jacobian (revolute joint: w x (p - o) and w; prismatic: w and 0). Without a
// reference direction the task has 5 rows: the rotation about the probe axis is free (a 6-axis arm
// is redundant for it) and the damped minimum-norm step keeps it near the seed, so along a path
// the roll follows the previous point's. With `ref` the task has 6 rows (full orientation, the
// rotation vector of R_target R^T). lambda is adapted (smaller after a step that lowers |e|,
// larger and the step retried otherwise) down to 0 (Gauss-Newton) near the solution, so the
// tolerances (1e-10 mm, 1e-12 rad by default) are met to rounding. Joint limits are kept by
// projecting every step onto the limits; several seeds are tried: the previous point's solution
// first (the branch stays continuous along a path), then a start configuration, the home
// configuration (zeros clamped into the limits) and deterministic pseudo-random configurations
// within the limits.
//
// Failures say why: a pose that no seed reaches within the limits but that is reached with the
// limits lifted is a limit error naming the joint, its value and its limits; otherwise the pose is
// unreachable (the closest tip and axis error found are reported).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"
#include "interfere/robot/chain.h"

namespace interfere::robot {

struct Cell;

/// The probe on a chain: its end-circle centre and direction (unit) in the frame of link `link`,
/// and the holder's reference direction there (unit, perpendicular to axis), used when a target
/// pose has one.
struct IkTool {
  std::size_t link = 0;
  Vec3 tip{};
  Vec3 axis{0, 0, 1};
  Vec3 ref{1, 0, 0};
};

/// The cell's tool as an IkTool: the tool link, tip and axis of the cell file, and as ref the tool
/// link's x axis made perpendicular to the probe axis (its y axis when the probe lies along x).
IkTool cell_ik_tool(const Cell& cell);

/// The probe pose (tip, axis, ref) carried by the chain at q (world frame, base = world <- root).
probe::ProbePose tool_pose(const Chain& chain, const Transform& base, const IkTool& tool,
                           const std::vector<double>& q);

struct IkOptions {
  int random_seeds = 24;                ///< pseudo-random seeds after previous / start / home
  int max_iterations = 300;             ///< per seed (each tried step counts)
  double position_tolerance = 1e-10;    ///< mm
  double angle_tolerance = 1e-12;       ///< rad
  double length_scale = 0;              ///< L (mm) for the orientation rows; 0: the chain's reach
  std::uint64_t random_state = 0x2545F4914F6CDD1DULL;  ///< the seeds' generator state
  std::vector<double> start;            ///< optional start configuration (joint units)
};

struct IkSolution {
  bool ok = false;
  std::vector<double> q;            ///< joint units (degrees, mm); within the limits when ok
  double position_error = 0;        ///< |tip - target tip|, mm
  double angle_error = 0;           ///< radians (axis only, or full orientation with ref)
  std::string seed;                 ///< "previous", "start", "home" or "random k"
  int iterations = 0;               ///< of the seed that succeeded
  /// !ok: why, e.g. "joint 'elbow' = 200.5 outside its limits [-180, 180] (degrees)" or
  /// "unreachable: the closest tip found is 812.3 mm from the target, the axis 3.2 degrees off
  /// (27 seeds)".
  std::string reason;
};

/// Solves for joint values putting the tool at `target` (ref used when target.has_ref()).
/// `previous` (may be null): the previous path point's solution, tried first as the seed.
IkSolution solve_ik(const Chain& chain, const Transform& base, const IkTool& tool,
                    const probe::ProbePose& target, const std::vector<double>* previous,
                    const IkOptions& options = {});

/// A pose path turned into the chain's joint path, each point seeded with the previous point's
/// solution. Per point, the seed that succeeded and the largest joint change from the previous
/// point (`jump`, joint units): a seed other than "previous" after the first point means the
/// solver left the previous branch (reported, not an error).
struct PoseIkPath {
  JointPath path;
  std::vector<std::string> seed;
  std::vector<double> jump;
  std::vector<double> position_error, angle_error;
};
/// Errors name the file, the line and the point: "poses.csv:7: point 5 (tip (...), axis (...)):
/// not reachable by robot 'ur5': unreachable: ..." or "...: joint 'wrist_2' = 130 outside its
/// limits [-120, 120] (degrees)". A joint path (path.joint_space) is an error naming the file.
Expected<PoseIkPath> pose_path_to_joints(const Chain& chain, const Transform& base,
                                         const IkTool& tool, const probe::ProbePath& path,
                                         const std::string& file, const IkOptions& options = {});

/// A DH chain of the probe module (probe/kinematics.h, standard or modified convention) as a
/// Chain whose links "frame0".."frameN" are the DH frames: per row a movable joint (frame i-1 ->
/// "moving i"; origin Rz(theta_i), modified Rx(alpha) Tx(a) Rz(theta_i); axis z) and a fixed joint
/// "dh_frame i" with the rest of the row (standard Tz(d) Tx(a) Rx(alpha), modified Tz(d)). Links
/// have no geometry (a cell file attaches meshes to them). The tool (tool_tip, tool_axis, tool_ref)
/// is returned in `tool` (link frameN) when not null. base = robot.base.
Chain chain_from_dh(const probe::Robot& robot, IkTool* tool = nullptr);

/// The joint path as CSV text: a comment line, the header (movable joint names) and one row per
/// point (%.17g, so reading it back gives the same values).
std::string joint_path_csv(const Chain& chain, const JointPath& path, const std::string& comment);

}  // namespace interfere::robot
