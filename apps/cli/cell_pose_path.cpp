// `interfere cell --pose-path` (issue #28; cell_pose_path.h).
#include "cell_pose_path.h"

#include <cmath>
#include <sstream>

#include "common.h"  // (InputError only: also built into interfere-mpi, without common.cpp)
#include "interfere/probe/path.h"
#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"

namespace interfere::cli {

robot::JointPath cell_pose_joint_path(const robot::Cell& cell, const CellPoseInput& in,
                                      nlohmann::json& report) {
  Expected<probe::ProbePath> poses = probe::read_path_csv(in.file, nullptr);
  if (!poses) throw InputError(poses.error());
  robot::IkOptions o;
  nlohmann::json first_branch;  // --ik-start collision-free: how the first point's branch was chosen
  if (in.start == "collision-free") {
    if (poses->poses.empty()) throw InputError(Error{.file = in.file, .reason = "no path points"});
    Expected<robot::StartChoice> c = robot::collision_free_start(cell, poses->poses[0]);
    if (!c) throw InputError(c.error());
    o.start = c->q;
    first_branch = {{"rule", "collision-free"},
                    {"seed", c->seed},
                    {"collision_free", c->collision_free},
                    {"solutions_checked", c->candidates},
                    {"solutions_colliding", c->colliding}};
  } else if (!in.start.empty()) {
    std::stringstream ss(in.start);
    std::string item;
    while (std::getline(ss, item, ',')) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (end == item.c_str() || !std::isfinite(v))
        throw InputError("--ik-start: '" + item + "' is not a finite number");
      o.start.push_back(v);
    }
    if (o.start.size() != cell.robot.dof()) {
      throw InputError("--ik-start: " + std::to_string(o.start.size()) + " values for the " +
                       std::to_string(cell.robot.dof()) + " movable joints of " + cell.robot_file);
    }
    if (Status s = robot::check_limits(cell.robot, o.start); !s)
      throw InputError("--ik-start: " + s.error().reason);
  }
  const robot::IkTool tool = robot::cell_ik_tool(cell);
  Expected<robot::PoseIkPath> r =
      robot::pose_path_to_joints(cell.robot, cell.base, tool, *poses, in.file, o);
  if (!r) throw InputError(r.error());
  nlohmann::json pts = nlohmann::json::array();
  std::size_t branch_changes = 0;
  double worst_tip = 0, worst_angle = 0;
  for (std::size_t i = 0; i < r->path.size(); ++i) {
    pts.push_back({{"index", i},
                   {"line", r->path.lines[i]},
                   {"seed", r->seed[i]},
                   {"jump", r->jump[i]},
                   {"tip_error", r->position_error[i]},
                   {"angle_error", r->angle_error[i]}});
    branch_changes += i > 0 && r->seed[i] != "previous";
    worst_tip = std::max(worst_tip, r->position_error[i]);
    worst_angle = std::max(worst_angle, r->angle_error[i]);
  }
  report = {{"method", "damped least squares (Levenberg-Marquardt), previous point as seed"},
            {"pose_path", in.file},
            {"reference_direction", !poses->poses.empty() && poses->poses[0].has_ref()},
            {"branch_changes", branch_changes},
            {"max_tip_error", worst_tip},
            {"max_angle_error", worst_angle},
            {"points", std::move(pts)}};
  if (!first_branch.is_null()) report["first_branch"] = std::move(first_branch);
  return std::move(r->path);
}

std::string cell_joints_csv(const robot::Cell& cell, const robot::JointPath& path, const CellPoseInput& in) {
  return robot::joint_path_csv(cell.robot, path,
                               "joint path of " + cell.robot.name + " solved from the pose path " + in.file +
                                   " by interfere cell --pose-path (degrees, mm)");
}

}  // namespace interfere::cli
