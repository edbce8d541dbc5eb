// Numerical inverse kinematics for serial chains (issue #28; robot/ik.h): damped least squares
// (Levenberg-Marquardt) on the probe's tip and direction, joint limits by projection, several
// seeds, the previous path point's solution first.
#include "interfere/robot/ik.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "interfere/robot/cell.h"
#include "interfere/scene/scene.h"

namespace interfere::robot {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

bool is_angle(JointKind k) {
  return k == JointKind::revolute || k == JointKind::continuous;
}

/// A unit vector perpendicular to the unit `a`.
Vec3 any_perpendicular(const Vec3& a) {
  const Vec3 e = std::abs(a.x) <= std::abs(a.y) && std::abs(a.x) <= std::abs(a.z) ? Vec3{1, 0, 0}
                 : std::abs(a.y) <= std::abs(a.z)                                  ? Vec3{0, 1, 0}
                                                                                   : Vec3{0, 0, 1};
  const Vec3 p = cross(a, e);
  return p / norm(p);
}

/// The rotation vector (axis * angle, radians) of the rotation taking the unit `from` to the unit
/// `to` about their common perpendicular; antiparallel vectors: pi about any perpendicular.
Vec3 rotation_between(const Vec3& from, const Vec3& to) {
  const Vec3 k = cross(from, to);
  const double s = norm(k), c = dot(from, to);
  const double theta = std::atan2(s, c);
  if (s > 1e-300) return k * (theta / s);
  if (c > 0) return {};
  return any_perpendicular(from) * std::numbers::pi;
}

/// The rotation vector of the rotation matrix m (columns), by its quaternion (Shepperd's method).
Vec3 rotation_log(const Eigen::Matrix3d& m) {
  const Eigen::Quaterniond q(m);
  double w = q.w();
  Eigen::Vector3d v = q.vec();
  if (w < 0) w = -w, v = -v;
  const double s = v.norm();
  if (s < 1e-300) return {};
  const double angle = 2 * std::atan2(s, w);
  v *= angle / s;
  return {v.x(), v.y(), v.z()};
}

Eigen::Matrix3d frame_matrix(const Vec3& a, const Vec3& r) {
  const Vec3 c = cross(a, r);
  Eigen::Matrix3d m;
  m << a.x, r.x, c.x, a.y, r.y, c.y, a.z, r.z, c.z;
  return m;
}

/// splitmix64: the seeds' deterministic generator.
struct Random {
  std::uint64_t s;
  double uniform() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

class Solver {
 public:
  Solver(const Chain& chain, const Transform& base, const IkTool& tool,
         const probe::ProbePose& target, const IkOptions& options)
      : chain_(chain), base_(base), tool_(tool), target_(target), o_(options) {
    use_ref_ = target.has_ref();
    target_axis_ = target.axis / norm(target.axis);
    if (use_ref_) target_ref_ = probe::perpendicular_reference(target.ref, target_axis_);
    use_ref_ = use_ref_ && !(target_ref_ == Vec3{});
    rows_ = use_ref_ ? 6 : 5;
    double reach = norm(tool.tip);
    for (const ChainJoint& j : chain.joints) reach += norm(j.origin.t);
    length_ = o_.length_scale > 0 ? o_.length_scale : std::max(reach, 1.0);
  }

  struct Eval {
    Eigen::VectorXd e;
    double pos = 0, angle = 0, norm = 0;
  };

  /// The task error at q, and the Jacobian (rows_ x dof, per radian / per mm) when J is not null.
  Eval evaluate(const std::vector<double>& q, Eigen::MatrixXd* J) const {
    const std::vector<Transform> f = link_frames(chain_, q, base_);
    const Transform& T = f[tool_.link];
    const Vec3 p = T.apply(tool_.tip);
    Vec3 a = T.rotate(tool_.axis);
    a = a / norm(a);
    Eval ev;
    ev.e.resize(rows_);
    const Vec3 ep = target_.tip - p;
    ev.e(0) = ep.x, ev.e(1) = ep.y, ev.e(2) = ep.z;
    ev.pos = norm(ep);
    Vec3 u, v;
    if (use_ref_) {
      Vec3 r = T.rotate(tool_.ref);
      r = r - a * dot(r, a);
      r = r / norm(r);
      const Eigen::Matrix3d err =
          frame_matrix(target_axis_, target_ref_) * frame_matrix(a, r).transpose();
      const Vec3 w = rotation_log(err);
      ev.e(3) = length_ * w.x, ev.e(4) = length_ * w.y, ev.e(5) = length_ * w.z;
      ev.angle = norm(w);
    } else {
      const Vec3 w = rotation_between(a, target_axis_);
      u = any_perpendicular(a);
      v = cross(a, u);
      ev.e(3) = length_ * dot(u, w), ev.e(4) = length_ * dot(v, w);
      ev.angle = std::atan2(norm(cross(a, target_axis_)), dot(a, target_axis_));
    }
    ev.norm = ev.e.norm();
    if (!J) return ev;
    J->setZero(rows_, static_cast<Eigen::Index>(chain_.dof()));
    std::size_t m = 0;
    for (std::size_t i = 0; i < chain_.joints.size() && i < tool_.link; ++i) {
      const ChainJoint& j = chain_.joints[i];
      if (!j.movable()) continue;
      const Transform jf = scene::compose(f[i], j.origin);
      const Vec3 w = jf.rotate(j.axis);
      Vec3 dp, dw{};
      if (is_angle(j.kind)) {
        dp = cross(w, p - jf.t);
        dw = w;
      } else {
        dp = w;
      }
      const auto c = static_cast<Eigen::Index>(m);
      (*J)(0, c) = dp.x, (*J)(1, c) = dp.y, (*J)(2, c) = dp.z;
      if (use_ref_) {
        (*J)(3, c) = length_ * dw.x, (*J)(4, c) = length_ * dw.y, (*J)(5, c) = length_ * dw.z;
      } else {
        (*J)(3, c) = length_ * dot(u, dw), (*J)(4, c) = length_ * dot(v, dw);
      }
      ++m;
    }
    return ev;
  }

  bool converged(const Eval& ev) const {
    return ev.pos <= o_.position_tolerance && ev.angle <= o_.angle_tolerance;
  }

  void clamp(std::vector<double>& q) const {
    for (std::size_t m = 0; m < q.size(); ++m) {
      const ChainJoint& j = chain_.joints[chain_.movable[m]];
      q[m] = std::clamp(q[m], j.lower, j.upper);
    }
  }

  struct Run {
    std::vector<double> q;
    Eval ev;
    int iterations = 0;
  };

  /// Levenberg-Marquardt from `seed`, limits projected when `limits`.
  Run run(std::vector<double> q, bool limits) const {
    if (limits) clamp(q);
    Eigen::MatrixXd J;
    Run r;
    r.ev = evaluate(q, &J);
    double lambda = 1e-3 * length_;
    const auto n = static_cast<Eigen::Index>(q.size());
    for (int it = 0; it < o_.max_iterations; ++it) {
      r.iterations = it;
      if (converged(r.ev)) break;
      const Eigen::MatrixXd A =
          J * J.transpose() + lambda * lambda * Eigen::MatrixXd::Identity(rows_, rows_);
      const Eigen::VectorXd y = A.ldlt().solve(r.ev.e);
      Eigen::VectorXd dq = J.transpose() * y;
      // A trust region on the step: at most 0.5 rad per revolute joint, L/4 per prismatic joint.
      double scale = 1;
      for (Eigen::Index m = 0; m < n; ++m) {
        const bool ang = is_angle(chain_.joints[chain_.movable[m]].kind);
        const double cap = ang ? 0.5 : 0.25 * length_;
        if (std::abs(dq(m)) * scale > cap) scale = cap / std::abs(dq(m));
      }
      dq *= scale;
      bool finite = dq.allFinite();
      std::vector<double> q2 = q;
      if (finite) {
        for (Eigen::Index m = 0; m < n; ++m) {
          const bool ang = is_angle(chain_.joints[chain_.movable[m]].kind);
          q2[m] += ang ? dq(m) * kDeg : dq(m);
        }
        if (limits) clamp(q2);
      }
      Eigen::MatrixXd J2;
      const Eval ev2 = finite ? evaluate(q2, &J2) : Eval{};
      if (finite && std::isfinite(ev2.norm) && ev2.norm < r.ev.norm) {
        q = std::move(q2);
        r.ev = ev2;
        J = std::move(J2);
        lambda *= 0.2;
        if (lambda < 1e-12 * length_) lambda = 0;
      } else {
        if (converged(r.ev)) break;
        lambda = lambda == 0 ? 1e-9 * length_ : lambda * 5;
        if (lambda > 1e4 * length_) break;  // stuck: a local minimum or the limits
      }
    }
    r.q = std::move(q);
    return r;
  }

  /// Shifts revolute joints by multiples of 360 degrees towards `near` while staying within the
  /// limits (limits ignored when !limits).
  void wrap(std::vector<double>& q, const std::vector<double>& near) const {
    for (std::size_t m = 0; m < q.size(); ++m) {
      const ChainJoint& j = chain_.joints[chain_.movable[m]];
      if (!is_angle(j.kind)) continue;
      double best = q[m];
      double best_d = std::abs(q[m] - near[m]);
      const double k0 = std::round((near[m] - q[m]) / 360.0);
      for (double k = k0 - 2; k <= k0 + 2; ++k) {
        const double v = q[m] + 360.0 * k;
        if (v < j.lower || v > j.upper) continue;
        if ((best < j.lower || best > j.upper) || std::abs(v - near[m]) < best_d) {
          best = v;
          best_d = std::abs(v - near[m]);
        }
      }
      q[m] = best;
    }
  }

  std::vector<std::pair<std::string, std::vector<double>>> seeds(
      const std::vector<double>* previous) const {
    std::vector<std::pair<std::string, std::vector<double>>> s;
    const std::size_t n = chain_.dof();
    if (previous && previous->size() == n) s.emplace_back("previous", *previous);
    if (o_.start.size() == n) s.emplace_back("start", o_.start);
    std::vector<double> home(n, 0.0);
    clamp(home);
    s.emplace_back("home", home);
    Random rng{o_.random_state};
    for (int k = 0; k < o_.random_seeds; ++k) {
      std::vector<double> q(n);
      for (std::size_t m = 0; m < n; ++m) {
        const ChainJoint& j = chain_.joints[chain_.movable[m]];
        const double span = is_angle(j.kind) ? 180.0 : length_;
        double lo = std::max(j.lower, -span), hi = std::min(j.upper, span);
        if (lo > hi) lo = j.lower, hi = j.upper;
        q[m] = lo + (hi - lo) * rng.uniform();
      }
      s.emplace_back("random " + std::to_string(k + 1), std::move(q));
    }
    return s;
  }

  IkSolution solve(const std::vector<double>* previous) const {
    IkSolution out;
    const auto list = seeds(previous);
    double best_norm = std::numeric_limits<double>::infinity();
    Eval best;
    for (const bool limits : {true, false}) {
      for (const auto& [name, seed] : list) {
        Run r = run(seed, limits);
        if (r.ev.norm < best_norm) best_norm = r.ev.norm, best = r.ev;
        if (!converged(r.ev)) continue;
        wrap(r.q, previous && previous->size() == r.q.size() ? *previous : seed);
        if (Status s = check_limits(chain_, r.q); !s) {
          // Reached only outside the limits (the limits were lifted for this run).
          if (out.reason.empty())
            out.reason = "no solution found within the joint limits (" +
                         std::to_string(list.size()) + " seeds); one outside them: " +
                         s.error().reason;
          continue;
        }
        const Eval ev = evaluate(r.q, nullptr);  // after the 360-degree shifts
        out.ok = true;
        out.q = std::move(r.q);
        out.position_error = ev.pos;
        out.angle_error = ev.angle;
        out.seed = name;
        out.iterations = r.iterations;
        out.reason.clear();
        return out;
      }
      if (!out.reason.empty()) break;  // reachable only outside the limits: say which joint
    }
    if (out.reason.empty()) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "unreachable: the closest tip found is %.6g mm from the target, the axis %.6g "
                    "degrees off (%zu seeds, limits kept and lifted)",
                    best.pos, best.angle * kDeg, list.size());
      out.reason = buf;
    }
    out.position_error = best.pos;
    out.angle_error = best.angle;
    return out;
  }

 private:
  const Chain& chain_;
  Transform base_;
  IkTool tool_;
  probe::ProbePose target_;
  IkOptions o_;
  bool use_ref_ = false;
  Vec3 target_axis_, target_ref_{};
  Eigen::Index rows_ = 5;
  double length_ = 1;
};

std::string vec_text(const Vec3& v) {
  return "(" + short_number(v.x) + ", " + short_number(v.y) + ", " + short_number(v.z) + ")";
}

Transform rot_z(double deg) {
  const double a = deg / kDeg, c = std::cos(a), s = std::sin(a);
  Transform t;
  t.r = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  return t;
}

/// Rx(alpha) Tx(a): the part of a modified DH row before its joint's motion.
Transform rx_tx(const probe::DhJoint& j) {
  const double al = j.alpha / kDeg, c = std::cos(al), s = std::sin(al);
  Transform t;
  t.r = {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
  t.t = {j.a, 0, 0};
  return t;
}

/// Tz(d): the part of a modified DH row after its joint's motion.
Transform tz(double d) {
  Transform t;
  t.t = {0, 0, d};
  return t;
}

/// Tz(d) Tx(a) Rx(alpha): the constant part of a standard DH transform.
Transform dh_constant(const probe::DhJoint& j) {
  const double al = j.alpha / kDeg, c = std::cos(al), s = std::sin(al);
  Transform t;
  t.r = {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
  t.t = {j.a, 0, j.d};
  return t;
}

}  // namespace

IkTool cell_ik_tool(const Cell& cell) {
  IkTool t;
  t.link = cell.tool_link;
  t.tip = cell.tool.tip;
  t.axis = cell.tool.axis / norm(cell.tool.axis);
  t.ref = probe::perpendicular_reference({1, 0, 0}, t.axis);
  if (t.ref == Vec3{}) t.ref = probe::perpendicular_reference({0, 1, 0}, t.axis);
  return t;
}

probe::ProbePose tool_pose(const Chain& chain, const Transform& base, const IkTool& tool,
                           const std::vector<double>& q) {
  const std::vector<Transform> f = link_frames(chain, q, base);
  const Transform& T = f[tool.link];
  probe::ProbePose p;
  p.tip = T.apply(tool.tip);
  p.axis = T.rotate(tool.axis);
  p.axis = p.axis / norm(p.axis);
  p.ref = probe::perpendicular_reference(T.rotate(tool.ref), p.axis);
  return p;
}

IkSolution solve_ik(const Chain& chain, const Transform& base, const IkTool& tool,
                    const probe::ProbePose& target, const std::vector<double>* previous,
                    const IkOptions& options) {
  if (chain.dof() == 0 || tool.link >= chain.links.size() || !(norm(target.axis) > 0)) {
    IkSolution s;
    s.reason = chain.dof() == 0 ? "the chain has no movable joint"
               : tool.link >= chain.links.size() ? "the tool link is not a link of the chain"
                                                 : "the target axis is zero";
    return s;
  }
  return Solver(chain, base, tool, target, options).solve(previous);
}

Expected<PoseIkPath> pose_path_to_joints(const Chain& chain, const Transform& base,
                                         const IkTool& tool, const probe::ProbePath& path,
                                         const std::string& file, const IkOptions& options) {
  if (path.joint_space) {
    return Error{.file = file,
                 .reason = "not a pose path: the header must be px,py,pz,ax,ay,az (optionally "
                           "followed by rx,ry,rz)"};
  }
  PoseIkPath out;
  const std::size_t n = path.poses.size();
  out.path.q.reserve(n);
  out.path.lines = path.lines;
  for (std::size_t i = 0; i < n; ++i) {
    const probe::ProbePose& p = path.poses[i];
    const std::vector<double>* prev = out.path.q.empty() ? nullptr : &out.path.q.back();
    IkSolution s = solve_ik(chain, base, tool, p, prev, options);
    if (!s.ok) {
      return Error{.file = file,
                   .line = i < path.lines.size() ? path.lines[i] : -1,
                   .reason = "point " + std::to_string(i) + " (tip " + vec_text(p.tip) +
                             ", axis " + vec_text(p.axis) + "): not reachable by robot '" +
                             chain.name + "': " + s.reason};
    }
    double jump = 0;
    if (prev) {
      for (std::size_t m = 0; m < s.q.size(); ++m) jump = std::max(jump, std::abs(s.q[m] - (*prev)[m]));
    }
    out.jump.push_back(jump);
    out.seed.push_back(s.seed);
    out.position_error.push_back(s.position_error);
    out.angle_error.push_back(s.angle_error);
    out.path.q.push_back(std::move(s.q));
  }
  return out;
}

Chain chain_from_dh(const probe::Robot& robot, IkTool* tool) {
  const bool modified = robot.convention == probe::DhConvention::modified;
  Chain c;
  c.name = robot.name;
  c.links.push_back({.name = "frame0", .mesh = nullptr, .mesh_files = {}});
  for (std::size_t i = 0; i < robot.joints.size(); ++i) {
    const probe::DhJoint& d = robot.joints[i];
    // the movable joint: DH frame i -> the moving frame after its motion (about / along its z)
    ChainJoint j;
    j.name = d.name;
    j.kind = d.type == probe::JointType::revolute ? JointKind::revolute : JointKind::prismatic;
    j.parent = c.links.back().name;
    j.child = "moving" + std::to_string(i + 1);
    j.origin = modified ? scene::compose(rx_tx(d), rot_z(d.theta)) : rot_z(d.theta);
    j.axis = {0, 0, 1};
    j.lower = d.min;
    j.upper = d.max;
    c.movable.push_back(c.joints.size());
    c.joints.push_back(j);
    c.links.push_back({.name = j.child, .mesh = nullptr, .mesh_files = {}});
    // the rest of the row, fixed: the moving frame -> DH frame i + 1
    ChainJoint f;
    f.name = "dh_frame" + std::to_string(i + 1);
    f.kind = JointKind::fixed;
    f.parent = j.child;
    f.child = "frame" + std::to_string(i + 1);
    f.origin = modified ? tz(d.d) : dh_constant(d);
    c.joints.push_back(f);
    c.links.push_back({.name = f.child, .mesh = nullptr, .mesh_files = {}});
  }
  if (tool) {
    tool->link = c.links.size() - 1;
    tool->tip = robot.tool_tip;
    tool->axis = robot.tool_axis / norm(robot.tool_axis);
    tool->ref = probe::perpendicular_reference(robot.tool_ref, tool->axis);
    if (tool->ref == Vec3{}) tool->ref = any_perpendicular(tool->axis);
  }
  return c;
}

std::string joint_path_csv(const Chain& chain, const JointPath& path, const std::string& comment) {
  std::string out;
  if (!comment.empty()) out += "# " + comment + "\n";
  for (std::size_t m = 0; m < chain.movable.size(); ++m)
    out += (m ? "," : "") + chain.joints[chain.movable[m]].name;
  out += "\n";
  char buf[40];
  for (const std::vector<double>& q : path.q) {
    for (std::size_t m = 0; m < q.size(); ++m) {
      std::snprintf(buf, sizeof buf, "%.17g", q[m]);
      out += (m ? "," : "") + std::string(buf);
    }
    out += "\n";
  }
  return out;
}

}  // namespace interfere::robot
