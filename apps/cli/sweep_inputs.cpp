// The inputs of `interfere sweep`, moved out of cmd_sweep.cpp and apps/mpi/sweep.cpp (issue #31,
// item 3) so that `interfere sweep` and `interfere-mpi sweep` check and read them alike (sweep_inputs.h).
#include "sweep_inputs.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "common.h"  // (cli::InputError: a header type only; nothing of common.cpp, which interfere-mpi does not link)
#include "interfere/core/coordinate_range.h"
#include "interfere/probe/export.h"
#include "interfere/probe/paper_machine.h"
#include "interfere/robot/ik.h"

namespace interfere::cli {

using namespace interfere::probe;

void check_positive(double v, const char* flag, bool allow_zero) {
  if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0)) {
    throw InputError(std::string(flag) + ": must be a finite number " + (allow_zero ? ">= 0" : "> 0") + ", got " +
                     (std::isnan(v) ? std::string("nothing") : std::to_string(v)));
  }
}

std::array<double, 3> parse_holder_box(const std::string& s) {
  std::array<double, 3> v{};
  std::size_t start = 0, k = 0;
  bool ok = true;
  for (std::size_t i = 0; i <= s.size() && ok; ++i) {
    if (i < s.size() && s[i] != ',') continue;
    const std::string field = s.substr(start, i - start);
    start = i + 1;
    char* end = nullptr;
    const double x = field.empty() ? NAN : std::strtod(field.c_str(), &end);
    ok = k < 3 && end && *end == 0 && std::isfinite(x) && x > 0;
    if (ok) v[k++] = x;
  }
  if (!ok || k != 3) {
    throw InputError("--holder-box: expected three numbers > 0 as W,D,L (width, depth, length), got '" + s + "'");
  }
  return v;
}

probe::Hierarchy parse_hierarchy(const std::string& s) {
  if (s == "bvh") return probe::Hierarchy::bvh;
  if (s == "patches") return probe::Hierarchy::patches;
  if (s == "grid") return probe::Hierarchy::grid;
  if (s == "distance-field" || s == "distance_field" || s == "field") return probe::Hierarchy::distance_field;
  if (s == "brute" || s == "brute-force") return probe::Hierarchy::brute_force;
  throw InputError("--hierarchy: unknown hierarchy '" + s + "' (bvh, patches, grid, distance-field, brute)");
}

ProbeShape check_sweep_probe(const SweepOptions& o) {
  check_positive(o.probe_radius, "--probe-radius");
  check_positive(o.probe_length, "--probe-length");
  check_positive(o.holder_radius, "--holder-radius", true);
  check_positive(o.holder_length, "--holder-length", true);
  if ((o.holder_radius > 0) != (o.holder_length > 0)) {
    throw InputError("--holder-radius and --holder-length: give both (> 0) or neither");
  }
  std::array<double, 3> box{};
  if (!o.holder_box.empty()) {
    box = parse_holder_box(o.holder_box);
    if (o.holder_radius > 0 || o.holder_length > 0) {
      throw InputError("--holder-box and --holder-radius/--holder-length: give one holder, a box or a cylinder");
    }
  }
  check_positive(o.patch_size, "--patch-size", true);
  check_positive(o.patch_rule, "--patch-rule");
  check_positive(o.max_clearance, "--max-clearance", true);
  check_positive(o.clearance, "--clearance", true);
  if (o.clearance > 0 && o.no_clearance) throw InputError("--clearance and --no-clearance: a requested clearance needs the clearance");
  if (o.clearance > 0 && o.max_clearance > 0 && o.max_clearance < o.clearance) {
    throw InputError("--max-clearance must be at least --clearance (clearances beyond it are not measured)");
  }
  if (o.max_poses < 1) throw InputError("--max-poses: must be >= 1");
  return ProbeShape{.radius = o.probe_radius,
                    .length = o.probe_length,
                    .holder_radius = o.holder_radius,
                    .holder_length = o.holder_length,
                    .holder_box_width = box[0],
                    .holder_box_depth = box[1],
                    .holder_box_length = box[2]};
}

Hierarchy check_sweep_machine(const SweepOptions& o) {
  if ((!o.robot.empty() || !std::isnan(o.d1) || !std::isnan(o.d2)) && o.units != "mm") {
    // The robot file and a joint path's prismatic values are in mm (a robot file's "units" must be
    // mm): another working unit would mix units silently (issue #23, item 9).
    throw InputError("--units " + o.units + ": a sweep with --robot works in mm (robot files and joint paths are in "
                     "mm); convert the workpiece to mm");
  }
  const Hierarchy hierarchy = parse_hierarchy(o.hierarchy);
  if (!o.interpolate.empty() && o.interpolate != "joint" && o.interpolate != "pose") {
    throw InputError("--interpolate: unknown motion '" + o.interpolate + "' (joint or pose)");
  }
  const bool paper_flags = !std::isnan(o.d1) || !std::isnan(o.d2);
  if (paper_flags && !o.robot.empty()) {
    throw InputError("--d1/--d2 build the paper's machine (§3.1): give them or --robot, not both");
  }
  if (paper_flags) {
    if (!std::isnan(o.d1) && !std::isfinite(o.d1)) throw InputError("--d1: must be a finite number");
    if (!std::isnan(o.d2)) check_positive(o.d2, "--d2");
  }
  return hierarchy;
}

std::optional<Robot> read_sweep_robot(const SweepOptions& o) {
  if (!o.robot.empty()) {
    auto r = read_robot_json(o.robot);
    if (!r) throw InputError(r.error());
    return std::move(r.value());
  }
  if (!std::isnan(o.d1) || !std::isnan(o.d2)) {
    return paper_machine_31({.d1 = std::isnan(o.d1) ? 30.0 : o.d1,
                             .d2 = std::isnan(o.d2) ? 120.0 : o.d2,
                             .probe_length = o.probe_length});
  }
  return std::nullopt;
}

SweepPath read_sweep_path(const SweepOptions& o, const Robot* robot, const ProbeShape& shape) {
  auto path_r = read_path_csv(o.path, robot);
  if (!path_r) throw InputError(path_r.error());
  SweepPath s{.path = std::move(path_r.value())};
  ProbePath& path = s.path;
  s.pose_input = !path.joint_space;
  if (path.joint_space) resolve_poses(path, *robot);
  // Motion between points (docs/probe.md, "Motion between points"): the machine's own (joint
  // interpolation) by default when it is known: joint paths, and pose paths for a robot with
  // inverse kinematics (the paper's machine); straight pose interpolation otherwise or on request.
  const bool can_joint = path.joint_space || (robot && has_inverse_kinematics(*robot));
  // An explicit --interpolate joint for a DH robot without an analytic inverse (a 6-axis arm): the
  // numerical inverse kinematics of robot/ik.h on the DH chain, each point from the previous one's
  // solution (issue #28). The default stays straight pose interpolation for such robots.
  const bool numeric_ik = o.interpolate == "joint" && !can_joint && robot;
  if (o.interpolate == "joint" && !can_joint && !numeric_ik) {
    throw InputError("--interpolate joint: " + o.path + " is a pose path and " +
                     (robot ? "robot '" + robot->name + "' has no inverse kinematics" : std::string("no --robot is given")) +
                     " (only the paper's machine of §3.1 has: --robot data/examples/probe_paper_machine.json or --d1/--d2)");
  }
  s.joint_motion = o.interpolate == "pose" ? false : (can_joint || numeric_ik);
  if (s.joint_motion && !path.joint_space && numeric_ik) {
    robot::IkTool tool;
    const robot::Chain chain = robot::chain_from_dh(*robot, &tool);
    auto r = robot::pose_path_to_joints(chain, robot->base, tool, path, o.path);
    if (!r) throw InputError(r.error());
    ProbePath jp;
    jp.joint_space = true;
    for (const DhJoint& j : robot->joints) jp.columns.push_back(j.name);
    jp.lines = r->path.lines;
    jp.joints = std::move(r->path.q);
    resolve_poses(jp, *robot);
    path = std::move(jp);
  } else if (s.joint_motion && !path.joint_space) {
    auto j = pose_path_to_joint_path(path, *robot, o.path);
    if (!j) throw InputError(j.error());
    path = std::move(j.value());
  } else if (!s.joint_motion && path.joint_space) {
    path.joint_space = false;  // straight pose interpolation between the forward-kinematics poses
  }
  for (std::size_t i = 0; i < path.poses.size(); ++i)  // the exact tests' coordinate range (item 7)
    if (!coordinates_in_range(path.poses[i].tip))
      throw InputError(o.path + ":" + std::to_string(path.lines[i]) + ": probe tip " +
                       coordinate_range_reason(path.poses[i].tip));
  if (shape.has_holder_box()) {
    const Status frames = check_reference_frames(path, o.path);
    if (!frames) throw InputError(frames.error());
  }
  return s;
}

void scale_workpiece(std::vector<Vec3>& positions, double scale, const SweepOptions& o) {
  for (Vec3& v : positions) v = v * scale;
  if (const std::size_t i = first_out_of_range(positions); i < positions.size())
    throw InputError(o.workpiece + ": vertex " + std::to_string(i) + " (after welding), once converted to " + o.units +
                     ": " + coordinate_range_reason(positions[i]));
}

SweepRequest sweep_request(const SweepOptions& o, const ProbeShape& shape) {
  return {.probe = shape,
          .continuous = !o.no_continuous,
          .clearance = !o.no_clearance,
          .max_clearance = o.max_clearance > 0 ? o.max_clearance : std::numeric_limits<double>::infinity(),
          .max_depth = o.depth,
          .max_poses = o.max_poses,
          .clearance_limit = o.clearance};
}

Status write_sweep_geometry(const SweepOptions& o, const Workpiece& w, const ProbePath& path, const Robot* motion_robot,
                            const ProbeShape& shape, const SweepResult& r) {
  if (o.hits_obj.empty() && o.probes_vtk.empty()) return {};
  const CollisionGeometry g = collision_geometry(w, path, motion_robot, shape, r);
  for (const std::string& f : {o.hits_obj, o.probes_vtk}) {
    if (f.empty()) continue;
    if (const Status s = write_collision_geometry(f, g); !s) return s;
  }
  return {};
}

}  // namespace interfere::cli
