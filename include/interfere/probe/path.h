// Probe path input (issue #5, item 2): a CSV file whose header row decides its kind.
//  - Joint path: one column per robot joint, in chain order (names free, e.g. "x,y,z,a,b" for the
//    paper's machine); values in joint units (length, or degrees for revolute joints).
//  - Pose path: header exactly "px,py,pz,ax,ay,az": the end-circle centre and the probe direction
//    (normalised on reading; a zero vector is an error), optionally followed by "rx,ry,rz": the
//    holder's reference direction (needed by a box holder; its component perpendicular to the axis
//    is used; zero or parallel to the axis is an error).
// '#' starts a comment line; blank lines are skipped; separators are commas (spaces around values
// are allowed). Errors name the file, the 1-based line and the column (field).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/probe/kinematics.h"

namespace interfere::probe {

struct ProbePath {
  bool joint_space = true;                ///< joint values (needs a robot) or probe poses
  std::vector<std::string> columns;       ///< header names
  std::vector<std::vector<double>> joints;  ///< joint_space: one row per point
  std::vector<ProbePose> poses;           ///< the probe pose of every point (filled by resolve_poses
                                          ///< for joint paths)
  std::vector<std::int64_t> lines;        ///< source line of every point
  std::size_t size() const { return lines.size(); }
};

/// Parses CSV text. `robot` (may be null for pose paths) fixes the expected column count of joint
/// paths and their limits: a row with the wrong number of values, a value that is not a finite
/// number or a joint value outside its limits is an error naming file, line and column.
Expected<ProbePath> parse_path_csv(std::string_view text, const std::string& file_name, const Robot* robot);
Expected<ProbePath> read_path_csv(const std::filesystem::path& path, const Robot* robot);

/// Fills path.poses from path.joints by forward kinematics (no-op for pose paths).
void resolve_poses(ProbePath& path, const Robot& robot);

/// Every pose (resolved) has a reference direction, as a box holder needs: otherwise an error naming
/// `file_name`, the line of the first pose without one and the field (rx,ry,rz of a pose path, or
/// the robot's tool.ref for a joint path).
Status check_reference_frames(const ProbePath& path, const std::string& file_name);

/// CSV text of a joint path (header = the robot's joint names) or of a pose path.
std::string path_to_csv(const ProbePath& path);

}  // namespace interfere::probe
