// Re-planning help for colliding path points (issue #28, deliverable 4; Li, Zhou & Zheng 2008,
// §5: colliding points are re-planned from the collision position). For each colliding point the
// probe keeps aiming at the same surface point (the point its axis meets on the workpiece, or its
// tip when the axis meets nothing within reach) and its orientation is searched within a cone of
// half-angle max_tilt_deg about the original axis, and its stand-off within a range, for the
// nearest collision-free pose: smallest tilt first (the original axis with another stand-off before
// any tilt), then the stand-off nearest the original, then the azimuth order (deterministic). Each candidate pose is decided by the exact test
// (pose_collides: cylinder/box-triangle and containment) and, for a robot with inverse kinematics,
// must be reachable within the joint limits (the suggested joint values nearest the original's).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"
#include "interfere/probe/sweep.h"

namespace interfere::probe {

struct ReplanRequest {
  double max_tilt_deg = 10;  ///< half-angle of the search cone about the original axis (> 0, < 90)
  /// Stand-off range as changes of the original stand-off (mm): the tip moves along the new axis
  /// by s in [standoff_min, standoff_max] away from (s > 0) or towards the surface point; 0, 0 keeps it.
  double standoff_min = 0, standoff_max = 0;
  int tilt_rings = 10;      ///< tilt angles searched: max_tilt * k / tilt_rings, k = 1..tilt_rings
  int azimuth_steps = 24;   ///< directions per tilt angle
  int standoff_steps = 5;   ///< stand-off values per direction (when the range is not 0, 0)
};

/// Error naming the field when the request is invalid (a tilt cone <= 0 or >= 90 degrees, steps < 1,
/// min > max, a non-finite value).
Status validate(const ReplanRequest& request);

struct ReplannedPoint {
  std::uint32_t point = 0;   ///< index in the path
  std::int64_t line = 0;     ///< its line in the path file
  bool found = false;
  ProbePose pose;            ///< the suggested pose (found)
  std::vector<double> joints;  ///< its joint values (found, robot with inverse kinematics)
  double tilt_deg = 0;       ///< angle between the original and the suggested axis
  double standoff_change = 0;  ///< s of the suggested pose
  Vec3 target;               ///< the surface point kept
  std::size_t poses_tested = 0;
  std::string reason;        ///< not found: why (no free pose in the cone; unreachable ones)
};

struct ReplanResult {
  std::vector<ReplannedPoint> points;  ///< one per colliding point, in path order
  std::size_t found = 0;
  double seconds = 0;
};

/// Re-plans every colliding point of `result` (a sweep of `path`). `robot` may be null (pose
/// paths); a robot without inverse kinematics gives poses without joint values (a note in reason).
/// Results do not depend on the thread count.
ReplanResult replan(const Workpiece& workpiece, const ProbePath& path, const Robot* robot, const ProbeShape& probe,
                    const SweepResult& result, const ReplanRequest& request);

/// The path with every found suggestion in place of its point (joint values for a joint path,
/// poses for a pose path); points without one are kept.
ProbePath replanned_path(const ProbePath& path, const ReplanResult& replanned);

}  // namespace interfere::probe
