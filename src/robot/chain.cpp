// Serial chain forward kinematics and limits (issue #28, deliverable 2; robot/chain.h).
#include "interfere/robot/chain.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "interfere/scene/scene.h"

namespace interfere::robot {
namespace {

/// Rotation by `deg` degrees about the unit `u` (Rodrigues).
Transform rotation_about(const Vec3& u, double deg) {
  const double a = deg * std::numbers::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a), k = 1 - c;
  Transform t;
  t.r = {{{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
          {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
          {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}}};
  return t;
}

}  // namespace

const char* joint_kind_name(JointKind k) {
  switch (k) {
    case JointKind::revolute:
      return "revolute";
    case JointKind::continuous:
      return "continuous";
    case JointKind::prismatic:
      return "prismatic";
    case JointKind::fixed:
      return "fixed";
  }
  return "?";
}

std::int64_t Chain::find_link(std::string_view n) const {
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].name == n) return static_cast<std::int64_t>(i);
  }
  return -1;
}

std::int64_t Chain::find_movable(std::string_view n) const {
  for (std::size_t i = 0; i < movable.size(); ++i) {
    if (joints[movable[i]].name == n) return static_cast<std::int64_t>(i);
  }
  return -1;
}

std::vector<Transform> link_frames(const Chain& chain, const std::vector<double>& q,
                                   const Transform& base) {
  if (q.size() != chain.dof()) {
    throw std::invalid_argument("link_frames: " + std::to_string(q.size()) + " joint values for " +
                                std::to_string(chain.dof()) + " movable joints");
  }
  std::vector<Transform> f(chain.links.size());
  f[0] = base;
  std::size_t m = 0;
  for (std::size_t i = 0; i < chain.joints.size(); ++i) {
    const ChainJoint& j = chain.joints[i];
    Transform motion;
    if (j.kind == JointKind::revolute || j.kind == JointKind::continuous) {
      motion = rotation_about(j.axis, q[m++]);
    } else if (j.kind == JointKind::prismatic) {
      motion.t = j.axis * q[m++];
    }
    f[i + 1] = scene::compose(scene::compose(f[i], j.origin), motion);
  }
  return f;
}

Status check_limits(const Chain& chain, const std::vector<double>& q) {
  for (std::size_t m = 0; m < chain.movable.size() && m < q.size(); ++m) {
    const ChainJoint& j = chain.joints[chain.movable[m]];
    if (!(q[m] >= j.lower && q[m] <= j.upper)) {
      return Error{.file = chain.file,
                   .reason = "joint '" + j.name + "': value " + short_number(q[m]) +
                             " outside its limits [" + short_number(j.lower) + ", " +
                             short_number(j.upper) + "] (" +
                             (j.kind == JointKind::prismatic ? "mm" : "degrees") + ")"};
    }
  }
  return {};
}

}  // namespace interfere::robot
