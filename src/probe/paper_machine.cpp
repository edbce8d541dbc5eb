// The §3.1 machine of Li, Zhou & Zheng 2008 as a DH chain, its recognition in a robot file and its
// analytic inverse kinematics (issue #28, deliverables 1-2). Geometry and table: paper_machine.h.
#include "interfere/probe/paper_machine.h"

#include <cmath>
#include <limits>
#include <string>

namespace interfere::probe {
namespace {

constexpr double kDeg = M_PI / 180.0;

bool same_rotation(const Transform& t, const double (&r)[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::fabs(t.r[i][j] - r[i][j]) > 1e-12) return false;
  return true;
}

constexpr double kBase[3][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};

std::string num(double v) { return short_number(v); }

std::string vec_text(const Vec3& v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

}  // namespace

Robot paper_machine_31(const PaperMachine& m) {
  Robot r;
  r.name = "paper-3P2R";
  r.base.r = {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};  // x0 = world y, y0 = world z, z0 = world x
  r.base.t = m.origin;
  const double t = m.travel;
  r.joints = {
      {"x", JointType::prismatic, 0, 90, 0, 90, -t, t},   // along world x; z1 = world y
      {"y", JointType::prismatic, 0, 90, 0, -90, -t, t},  // along world y; z2 = world -z
      {"z", JointType::prismatic, 0, 0, 0, 0, -t, t},     // along world -z (the -z of §3.1)
      {"a", JointType::revolute, 0, 90, 0, -90, -m.a_limit, m.a_limit},    // about world -z; z4 = e
      {"b", JointType::revolute, m.d2, 0, m.d1, 180, -m.b_limit, m.b_limit},  // about e; x5 = u
  };
  r.tool_tip = {m.probe_length, 0, 0};
  r.tool_axis = {1, 0, 0};
  r.tool_ref = {0, 0, 1};  // the A5 axis e: the holder's width runs along it
  return r;
}

std::optional<PaperGeometry> paper_geometry(const Robot& r) {
  if (r.joints.size() != 5 || r.convention != DhConvention::standard || !same_rotation(r.base, kBase)) return std::nullopt;
  struct Want {
    JointType type;
    double theta, alpha;
  };
  const Want want[5] = {{JointType::prismatic, 90, 90},
                        {JointType::prismatic, -90, 90},
                        {JointType::prismatic, 0, 0},
                        {JointType::revolute, -90, 90},
                        {JointType::revolute, 180, 0}};
  for (int i = 0; i < 5; ++i) {
    const DhJoint& j = r.joints[i];
    if (j.type != want[i].type || j.theta != want[i].theta || j.alpha != want[i].alpha) return std::nullopt;
    if (i < 4 && (j.a != 0 || j.d != 0)) return std::nullopt;
  }
  if (r.tool_tip.y != 0 || r.tool_tip.z != 0 || r.tool_axis.x <= 0 || r.tool_axis.y != 0 || r.tool_axis.z != 0)
    return std::nullopt;
  return PaperGeometry{.d1 = r.joints[4].d, .reach = r.joints[4].a + r.tool_tip.x, .origin = r.base.t};
}

Expected<std::vector<double>> inverse_kinematics(const Robot& robot, const ProbePose& pose,
                                                 const std::vector<double>* previous) {
  const std::optional<PaperGeometry> g = paper_geometry(robot);
  if (!g) {
    return Error{.reason = "robot '" + robot.name +
                           "' has no inverse kinematics (only the paper's 3P+2R machine of §3.1 has: "
                           "docs/probe.md)"};
  }
  const double n = norm(pose.axis);
  if (!(n > 0) || !std::isfinite(n) || !std::isfinite(pose.tip.x) || !std::isfinite(pose.tip.y) ||
      !std::isfinite(pose.tip.z)) {
    return Error{.reason = "pose not finite or zero axis"};
  }
  const Vec3 u = pose.axis / n;
  const double h = std::hypot(u.x, u.y);
  const bool prev = previous && previous->size() == 5;
  // u = (sin a cos b, cos a cos b, sin b).
  const double b0 = std::atan2(u.z, h) / kDeg;
  const double a0 = h > 0 ? std::atan2(u.x, u.y) / kDeg : (prev ? (*previous)[3] : 0.0);
  const DhJoint* J = robot.joints.data();
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<double> best;
  std::string nearest_violation;
  int nearest_count = 99;
  for (int branch = 0; branch < 2; ++branch) {
    const double a_base = branch == 0 ? a0 : a0 + 180;
    const double b_base = branch == 0 ? b0 : 180 - b0;
    for (int ka = -2; ka <= 2; ++ka) {
      for (int kb = -2; kb <= 2; ++kb) {
        const double a = a_base + 360.0 * ka, b = b_base + 360.0 * kb;
        // Exactly the DH chain's angles: b enters as theta = 180 + b.
        const double ar = a * kDeg, br = b * kDeg;
        const double ca = std::cos(ar), sa = std::sin(ar), cb = std::cos(br), sb = std::sin(br);
        const Vec3 e{ca, -sa, 0}, uu{sa * cb, ca * cb, sb};
        const Vec3 wrist = pose.tip - uu * g->reach - e * g->d1 - g->origin;  // (x, y, -z)
        const std::vector<double> q{wrist.x, wrist.y, -wrist.z, a, b};
        std::string violation;
        int count = 0;
        for (int i = 0; i < 5; ++i) {
          if (!(q[i] >= J[i].min && q[i] <= J[i].max)) {
            if (count++ == 0)
              violation = "joint " + J[i].name + " = " + num(q[i]) + " outside its limits [" + num(J[i].min) + ", " +
                          num(J[i].max) + "]";
          }
        }
        if (count > 0) {
          // Report the candidate nearest to feasibility (fewest violated joints; ka = kb = 0 first).
          if (count < nearest_count) nearest_count = count, nearest_violation = violation;
          continue;
        }
        double cost = 0;
        if (prev) {
          for (int i = 3; i < 5; ++i) cost += std::fabs(q[i] - (*previous)[i]);
        } else {
          cost = std::fabs(a) + std::fabs(b);
        }
        if (cost < best_cost) best_cost = cost, best = q;
      }
    }
  }
  if (best.empty()) return Error{.reason = nearest_violation};
  return best;
}

Expected<ProbePath> pose_path_to_joint_path(const ProbePath& path, const Robot& robot, const std::string& file_name) {
  if (path.joint_space) return path;
  ProbePath out;
  out.joint_space = true;
  for (const DhJoint& j : robot.joints) out.columns.push_back(j.name);
  out.lines = path.lines;
  out.joints.reserve(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const ProbePose& p = path.poses[i];
    auto q = inverse_kinematics(robot, p, out.joints.empty() ? nullptr : &out.joints.back());
    if (!q) {
      return Error{.file = file_name,
                   .line = i < path.lines.size() ? path.lines[i] : -1,
                   .reason = "point " + std::to_string(i) + " (tip " + vec_text(p.tip) + ", axis " +
                             vec_text(p.axis) + "): not reachable by robot '" + robot.name + "': " + q.error().reason};
    }
    out.joints.push_back(std::move(*q));
  }
  resolve_poses(out, robot);
  return out;
}

}  // namespace interfere::probe
