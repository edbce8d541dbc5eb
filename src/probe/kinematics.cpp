// Forward kinematics of a standard Denavit-Hartenberg chain and the paper's 5-axis inspection
// machine (Li, Zhou & Zheng 2008, §3.1, end-circle centre of the probe). See kinematics.h for the
// convention: T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i), angles in degrees at the API.
#include <algorithm>
#include <cmath>
#include <string>

#include "interfere/probe/kinematics.h"

namespace interfere::probe {
namespace {

constexpr double kDeg = M_PI / 180.0;

Transform compose(const Transform& a, const Transform& b) {
  Transform r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.r[i][j] = a.r[i][0] * b.r[0][j] + a.r[i][1] * b.r[1][j] + a.r[i][2] * b.r[2][j];
    }
  }
  r.t = a.apply(b.t);
  return r;
}

/// Exact sine/cosine at multiples of 90 degrees (so the bundled table's +-90 twists are exact).
void sincos_deg(double deg, double& s, double& c) {
  const double q = deg / 90.0;
  if (q == std::floor(q) && std::fabs(q) < 1e15) {
    const long long k = ((static_cast<long long>(q) % 4) + 4) % 4;
    const double ss[4] = {0, 1, 0, -1}, cc[4] = {1, 0, -1, 0};
    s = ss[k], c = cc[k];
    return;
  }
  s = std::sin(deg * kDeg), c = std::cos(deg * kDeg);
}

Transform dh(double theta_deg, double d, double a, double alpha_deg) {
  double st, ct, sa, ca;
  sincos_deg(theta_deg, st, ct);
  sincos_deg(alpha_deg, sa, ca);
  Transform t;
  t.r = {{{ct, -st * ca, st * sa}, {st, ct * ca, -ct * sa}, {0, sa, ca}}};
  t.t = {a * ct, a * st, d};
  return t;
}

}  // namespace

const char* dh_convention_name(DhConvention c) {
  return c == DhConvention::modified ? "modified" : "standard";
}

Transform dh_transform(DhConvention convention, const DhJoint& j, double v) {
  const double theta = j.type == JointType::prismatic ? j.theta : j.theta + v;
  const double d = j.type == JointType::prismatic ? j.d + v : j.d;
  if (convention == DhConvention::standard) return dh(theta, d, j.a, j.alpha);
  // modified: Rx(alpha) Tx(a) Rz(theta) Tz(d) = [Rx(alpha), (a, 0, 0)] * [Rz(theta), (0, 0, d)]
  double st, ct, sa, ca;
  sincos_deg(theta, st, ct);
  sincos_deg(j.alpha, sa, ca);
  Transform t;
  t.r = {{{ct, -st, 0}, {st * ca, ct * ca, -sa}, {st * sa, ct * sa, ca}}};
  t.t = {j.a, -sa * d, ca * d};
  return t;
}

std::vector<Transform> forward_frames(const Robot& robot, const std::vector<double>& q) {
  std::vector<Transform> frames;
  frames.reserve(robot.joints.size() + 1);
  frames.push_back(robot.base);
  for (std::size_t i = 0; i < robot.joints.size(); ++i) {
    const double v = i < q.size() ? q[i] : 0.0;
    frames.push_back(compose(frames.back(), dh_transform(robot.convention, robot.joints[i], v)));
  }
  return frames;
}

Vec3 perpendicular_reference(const Vec3& ref, const Vec3& axis) {
  const double n = norm(ref);
  if (!(n > 0) || !std::isfinite(n)) return {};
  const Vec3 r = ref / n;
  const Vec3 p = r - axis * dot(r, axis);
  const double s = norm(p);
  if (!(s >= kMinReferenceSine)) return {};
  return p / s;
}

ProbePose tool_pose(const Robot& robot, const Transform& last) {
  Vec3 axis = last.rotate(robot.tool_axis);
  axis = axis / norm(axis);
  return {last.apply(robot.tool_tip), axis, perpendicular_reference(last.rotate(robot.tool_ref), axis)};
}

ProbePose forward_kinematics(const Robot& robot, const std::vector<double>& q) {
  return tool_pose(robot, forward_frames(robot, q).back());
}

Status check_joint_limits(const Robot& robot, const std::vector<double>& q) {
  for (std::size_t i = 0; i < robot.joints.size() && i < q.size(); ++i) {
    const DhJoint& j = robot.joints[i];
    if (!(q[i] >= j.min && q[i] <= j.max)) {
      return Error{.reason = "joint " + j.name + " = " + std::to_string(q[i]) + " outside its limits [" +
                             std::to_string(j.min) + ", " + std::to_string(j.max) + "]"};
    }
  }
  return {};
}

Robot pivot_machine(double pivot_to_tip, const Vec3& base_origin) {
  Robot r;
  r.name = "pivot-5-axis";
  // DH frame 0: x0 = world y, y0 = world z, z0 = world x (so A1 slides along world x).
  r.base.r = {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};
  r.base.t = base_origin;
  const double big = 2000;
  r.joints = {
      {"x", JointType::prismatic, 0, 90, 0, 90, -big, big},   // along z0 = world x; z1 = world y
      {"y", JointType::prismatic, 0, 90, 0, 90, -big, big},   // along world y; z2 = world z
      {"z", JointType::prismatic, 0, 0, 0, 0, -big, big},     // along world z
      {"a", JointType::revolute, 0, -90, 0, 0, -360, 360},    // about world z; z4 = Rz(a) y
      {"b", JointType::revolute, 0, -90, 0, 0, -120, 120},    // tilt; z5 = probe axis
  };
  r.tool_tip = {0, 0, pivot_to_tip};
  r.tool_axis = {0, 0, 1};
  return r;
}

ProbePose pivot_end_circle(const std::array<double, 5>& q, double pivot_to_tip, const Vec3& base_origin) {
  const double a = q[3] * kDeg, b = q[4] * kDeg;
  const Vec3 axis{-std::sin(b) * std::cos(a), -std::sin(b) * std::sin(a), -std::cos(b)};
  const Vec3 pivot = base_origin + Vec3{q[0], q[1], q[2]};
  return {pivot + axis * pivot_to_tip, axis};
}

std::array<double, 5> pivot_inverse(const ProbePose& pose, double pivot_to_tip, const Vec3& base_origin) {
  const Vec3 u = pose.axis / norm(pose.axis);
  const double b = std::acos(std::clamp(-u.z, -1.0, 1.0));
  const double sb = std::sin(b);
  const double a = sb > 1e-12 ? std::atan2(-u.y, -u.x) : 0.0;
  const Vec3 pivot = pose.tip - u * pivot_to_tip - base_origin;
  return {pivot.x, pivot.y, pivot.z, a / kDeg, b / kDeg};
}

}  // namespace interfere::probe
