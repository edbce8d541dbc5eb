// Robot kinematics for the inspection probe (issue #5, item 1): a serial chain in standard
// (distal) Denavit-Hartenberg convention, read from JSON, and a 5-axis pivot machine (prismatic
// x, y, z; revolute a about the vertical, b tilting the probe; data/examples/probe_5axis.json).
// The paper's own machine (Li, Zhou & Zheng 2008, §3.1) is in paper_machine.h
// (data/examples/probe_paper_machine.json).
//
// Conventions (the file's "convention" key; issue #28, deliverable 2):
//   standard (distal, Spong & Vidyasagar; the default):
//     T_i = Rot_z(theta_i) * Trans_z(d_i) * Trans_x(a_i) * Rot_x(alpha_i),  joint i about / along z_{i-1};
//   modified (proximal, Craig), row i holding alpha_{i-1}, a_{i-1}, d_i, theta_i:
//     T_i = Rot_x(alpha_{i-1}) * Trans_x(a_{i-1}) * Rot_z(theta_i) * Trans_z(d_i),  joint i about / along z_i;
// world <- base * T_1 ... T_n; a prismatic joint adds its value to d_i, a revolute joint to theta_i. Units: lengths in the file's unit (mm for the bundled machine), angles in DEGREES in the
// JSON file, in path files and in every joint-value vector of this API.
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/core/vec.h"

namespace interfere::probe {

enum class JointType { prismatic, revolute };

enum class DhConvention { standard, modified };
const char* dh_convention_name(DhConvention c);

struct DhJoint {
  std::string name;
  JointType type = JointType::revolute;
  double a = 0;      ///< link length (along x_i)
  double alpha = 0;  ///< link twist, degrees
  double d = 0;      ///< link offset (along z_{i-1}); the prismatic joint value is added to it
  double theta = 0;  ///< joint angle, degrees; the revolute joint value is added to it
  double min = -1e300, max = 1e300;  ///< joint limits in joint units (length or degrees)
};

/// Probe pose: centre of the probe's end circle (the tip), the unit direction it points to, and the
/// holder's reference direction `ref`: unit and perpendicular to `axis`, or zero when unknown. Only
/// a box holder needs it (its width runs along ref, its depth along axis x ref; docs/probe.md).
struct ProbePose {
  Vec3 tip;
  Vec3 axis{0, 0, -1};
  Vec3 ref{};
  bool has_ref() const { return !(ref == Vec3{}); }
};

/// The unit component of `ref` perpendicular to the unit `axis`; the zero vector when `ref` is zero,
/// not finite, or makes less than kMinReferenceSine (sine of the angle) with `axis` (no usable
/// reference direction).
inline constexpr double kMinReferenceSine = 1e-6;
Vec3 perpendicular_reference(const Vec3& ref, const Vec3& axis);

/// Rodrigues' rotation of v about the unit vector n by phi radians.
Vec3 rotate_about(const Vec3& v, const Vec3& n, double phi);

struct Robot {
  std::string name;
  Transform base;  ///< world <- DH frame 0
  DhConvention convention = DhConvention::standard;
  std::vector<DhJoint> joints;
  Vec3 tool_tip{};          ///< end-circle centre in the last DH frame
  Vec3 tool_axis{0, 0, 1};  ///< probe direction in the last DH frame (unit)
  /// Holder reference direction in the last DH frame (its component perpendicular to tool_axis is
  /// used): the frame's x axis by default, or its y axis when tool_axis is along x.
  Vec3 tool_ref{1, 0, 0};
};

/// Frames world <- i for i = 0..n (frames[0] = base). `q` in joint units (degrees for revolute).
std::vector<Transform> forward_frames(const Robot& robot, const std::vector<double>& q);

/// Index into forward_frames(...) of the frame whose z axis (through its origin) is joint j's axis
/// of motion: j (z_{j-1} of the 1-based table) in the standard convention, j + 1 in the modified one.
inline std::size_t joint_axis_frame(const Robot& robot, std::size_t j) {
  return robot.convention == DhConvention::modified ? j + 1 : j;
}

/// One row's transform T_i at joint value v (the convention's product above).
Transform dh_transform(DhConvention convention, const DhJoint& joint, double v);

/// The probe pose at joint values `q` (q.size() == joints.size()), `ref` included (zero when
/// tool_ref is parallel to tool_axis).
ProbePose forward_kinematics(const Robot& robot, const std::vector<double>& q);

/// The probe pose carried by the last DH frame `last` (world <- n): tip, axis and ref of the tool.
ProbePose tool_pose(const Robot& robot, const Transform& last);

/// Joint values outside [min, max]: an error naming the joint (file/line left for the caller).
Status check_joint_limits(const Robot& robot, const std::vector<double>& q);

/// Parses a robot JSON document (docs/probe.md, "Robot file"); errors name the file, the line and
/// the field (e.g. "joints[3].alpha: missing").
Expected<Robot> parse_robot_json(std::string_view text, const std::string& file_name);
Expected<Robot> read_robot_json(const std::filesystem::path& path);
std::string robot_to_json(const Robot& robot);

/// A 5-axis "pivot" machine (the project's reconstruction from issue #5, before the paper's text was
/// available; NOT the machine of §3.1, which is paper_machine_31 in paper_machine.h): pivot
/// (intersection of the A4 and A5 axes) at base_origin + (x, y, z); A4 rotates by a about the
/// vertical z; A5 tilts by b about the rotated y axis; the probe's end circle is `pivot_to_tip` from
/// the pivot along the probe axis, which points down (-z) at a = b = 0. Limits: x, y, z in
/// [-2000, 2000], a in [-360, 360], b in [-120, 120]. Named "pivot-5-axis"; bundled as
/// data/examples/probe_5axis.json; used by the path generator, the benchmarks and older tests.
Robot pivot_machine(double pivot_to_tip = 150.0, const Vec3& base_origin = {});

/// The closed form of that machine's end-circle centre (not §3.1's formula):
///   P = (x, y, z) + L (-sin b cos a, -sin b sin a, -cos b),  axis = (P - pivot) / L.
ProbePose pivot_end_circle(const std::array<double, 5>& xyzab, double pivot_to_tip, const Vec3& base_origin = {});

/// Inverse of paper_end_circle: joint values (x, y, z, a, b) putting the end circle at pose.tip with
/// direction pose.axis (b in [0, 180], a in (-180, 180]; a = 0 when the axis is vertical).
std::array<double, 5> pivot_inverse(const ProbePose& pose, double pivot_to_tip, const Vec3& base_origin = {});

}  // namespace interfere::probe
