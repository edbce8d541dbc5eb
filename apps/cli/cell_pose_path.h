// `interfere cell --pose-path` (issue #28): a probe pose path (the CSV of `interfere sweep`'s pose
// paths: px,py,pz,ax,ay,az[,rx,ry,rz]) turned into the cell robot's joint path by the numerical
// inverse kinematics of robot/ik.h, each point seeded with the previous point's solution.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "interfere/robot/cell.h"

namespace interfere::cli {

struct CellPoseInput {
  std::string file;          ///< --pose-path
  std::string start;         ///< --ik-start: comma-separated joint values (joint units), optional
  std::string write_joints;  ///< --write-joints: the solved joint path as CSV, optional
};

/// The joint path of `in.file` for `cell`'s robot; `report` receives the JSON "ik" section
/// (per point: seed, largest joint change, tip and axis errors). Throws InputError naming the
/// file, the line and the point (unreachable, outside the joint limits, not a pose path) or the
/// flag (--ik-start).
/// Writes nothing (--write-joints: cell_joints_csv), so that `interfere-mpi cell` (issue #31), which
/// solves the whole path on every rank, shares it.
robot::JointPath cell_pose_joint_path(const robot::Cell& cell, const CellPoseInput& in,
                                      nlohmann::json& report);
/// --write-joints: the solved joint path as CSV text (header = joint names).
std::string cell_joints_csv(const robot::Cell& cell, const robot::JointPath& path, const CellPoseInput& in);

}  // namespace interfere::cli
