// Re-planning help for colliding path points (include/interfere/probe/replan.h; issue #28,
// deliverable 4, after Li, Zhou & Zheng 2008, §5: "the colliding points are re-planned from the
// collision position"). The paper leaves the search to the planner; this one keeps the surface
// point, tilts the axis within a cone and varies the stand-off, nearest first, and accepts only
// poses the exact test proves clear (and the machine reaches).
#include "interfere/probe/replan.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "interfere/probe/paper_machine.h"

namespace interfere::probe {

Status validate(const ReplanRequest& r) {
  const auto bad = [](const std::string& field, const std::string& why) {
    return Error{.reason = "re-planning " + field + ": " + why};
  };
  if (!std::isfinite(r.max_tilt_deg) || !(r.max_tilt_deg > 0) || !(r.max_tilt_deg < 90))
    return bad("tilt cone", "the half-angle must be > 0 and < 90 degrees (got " + short_number(r.max_tilt_deg) + ")");
  if (!std::isfinite(r.standoff_min) || !std::isfinite(r.standoff_max))
    return bad("stand-off range", "not a finite number");
  if (r.standoff_min > r.standoff_max)
    return bad("stand-off range", "min " + short_number(r.standoff_min) + " > max " + short_number(r.standoff_max));
  if (r.tilt_rings < 1 || r.azimuth_steps < 1 || r.standoff_steps < 1) return bad("steps", "must be >= 1");
  return {};
}

namespace {

// Möller–Trumbore: the ray parameter t >= 0 of the hit of o + t d with the triangle, or -1. (Only
// places the surface point the probe aims at; every pose is then decided by the exact test.)
double ray_triangle(const Vec3& o, const Vec3& d, const std::array<Vec3, 3>& c) {
  const Vec3 e1 = c[1] - c[0], e2 = c[2] - c[0];
  const Vec3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (std::fabs(det) < 1e-300) return -1;
  const Vec3 s = o - c[0];
  const double u = dot(s, p) / det;
  if (u < 0 || u > 1) return -1;
  const Vec3 q = cross(s, e1);
  const double v = dot(d, q) / det;
  if (v < 0 || u + v > 1) return -1;
  const double t = dot(e2, q) / det;
  return t >= 0 ? t : -1;
}

bool ray_hits_box(const Vec3& o, const Vec3& d, const AabbF& b, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    const double lo = b.lo[k], hi = b.hi[k];
    if (d[k] == 0) {
      if (o[k] < lo || o[k] > hi) return false;
      continue;
    }
    double a = (lo - o[k]) / d[k], c = (hi - o[k]) / d[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a), t1 = std::min(t1, c);
    if (t0 > t1) return false;
  }
  return true;
}

// The nearest hit of the ray o + t d (t >= 0) with the workpiece, or +inf.
double first_hit(const Workpiece& w, const Vec3& o, const Vec3& d) {
  double best = std::numeric_limits<double>::infinity();
  if (w.bvh.empty()) return best;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const BvhNode& n = w.bvh.nodes[stack.back()];
    stack.pop_back();
    if (!ray_hits_box(o, d, n.box, best)) continue;
    if (n.is_leaf()) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const double t = ray_triangle(o, d, w.mesh.corners(w.bvh.prims[i]));
        if (t >= 0 && t < best) best = t;
      }
    } else {
      stack.push_back(n.first + 1);
      stack.push_back(n.first);
    }
  }
  return best;
}

Vec3 unit(const Vec3& v) { return v / norm(v); }

// Stand-off changes to try, nearest the original first (ties: the smaller value).
std::vector<double> standoffs(const ReplanRequest& r) {
  std::vector<double> s;
  if (r.standoff_min == 0 && r.standoff_max == 0) return {0.0};
  const int n = std::max(1, r.standoff_steps);
  for (int i = 0; i < n; ++i)
    s.push_back(n == 1 ? 0.5 * (r.standoff_min + r.standoff_max)
                       : r.standoff_min + (r.standoff_max - r.standoff_min) * i / (n - 1));
  if (r.standoff_min <= 0 && r.standoff_max >= 0) s.push_back(0.0);
  std::sort(s.begin(), s.end(), [](double a, double b) { return std::fabs(a) != std::fabs(b) ? std::fabs(a) < std::fabs(b) : a < b; });
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

ReplannedPoint replan_point(const Workpiece& w, const ProbePath& path, const Robot* robot, bool ik,
                            const ProbeShape& probe, std::uint32_t i, const ReplanRequest& r,
                            const std::vector<double>& offsets) {
  ReplannedPoint out;
  out.point = i;
  out.line = i < path.lines.size() ? path.lines[i] : 0;
  const ProbePose& p0 = path.poses[i];
  const Vec3 axis = unit(p0.axis);
  const double hit = first_hit(w, p0.tip, axis);
  out.target = std::isfinite(hit) ? p0.tip + axis * hit : p0.tip;
  const double s0 = std::isfinite(hit) ? hit : 0.0;
  // A basis perpendicular to the axis (from the pose's reference direction when it has one).
  Vec3 u = perpendicular_reference(p0.has_ref() ? p0.ref : Vec3{1, 0, 0}, axis);
  if (u == Vec3{}) u = perpendicular_reference(Vec3{0, 1, 0}, axis);
  const Vec3 v = cross(axis, u);
  const std::vector<double>* previous = path.joint_space && i < path.joints.size() ? &path.joints[i] : nullptr;
  std::size_t unreachable = 0, undecided = 0;
  std::string last_unreachable;
  const double max_tilt = r.max_tilt_deg * M_PI / 180;
  for (int k = 0; k <= r.tilt_rings; ++k) {  // (k = 0: the original axis, other stand-offs only)
    const double theta = max_tilt * k / r.tilt_rings;
    for (const double s : offsets) {
      if (s0 + s < 0 || (k == 0 && s == 0)) continue;
      for (int j = 0; j < (k == 0 ? 1 : r.azimuth_steps); ++j) {
        const double phi = 2 * M_PI * j / r.azimuth_steps;
        const Vec3 side = u * std::cos(phi) + v * std::sin(phi);
        ProbePose cand;
        cand.axis = unit(axis * std::cos(theta) + side * std::sin(theta));
        cand.tip = out.target - cand.axis * (s0 + s);
        if (p0.has_ref()) cand.ref = k == 0 ? p0.ref : rotate_about(p0.ref, unit(cross(axis, cand.axis)), theta);
        std::vector<double> q;
        if (ik) {
          auto sol = inverse_kinematics(*robot, cand, previous);
          if (!sol) {
            ++unreachable, last_unreachable = sol.error().reason;
            continue;
          }
          q = std::move(*sol);
          cand = forward_kinematics(*robot, q);  // the machine's own pose
        }
        ++out.poses_tested;
        bool undec = false;
        if (pose_collides(w, probe, cand, nullptr, nullptr, nullptr, &undec)) continue;
        if (undec) {
          ++undecided;
          continue;
        }
        out.found = true;
        out.pose = cand;
        out.joints = std::move(q);
        out.tilt_deg = std::acos(std::clamp(dot(axis, unit(cand.axis)), -1.0, 1.0)) * 180 / M_PI;
        out.standoff_change = s;
        if (robot && !ik) out.reason = "robot '" + robot->name + "' has no inverse kinematics: joint values not computed";
        return out;
      }
    }
  }
  out.reason = "no collision-free pose within " + short_number(r.max_tilt_deg) + " degrees of the axis" +
               (offsets.size() > 1 ? " and the stand-off range" : "") + " (" + std::to_string(out.poses_tested) +
               " poses tested";
  if (unreachable) out.reason += ", " + std::to_string(unreachable) + " unreachable: " + last_unreachable;
  if (undecided) out.reason += ", " + std::to_string(undecided) + " undecided (inside/outside)";
  out.reason += ")";
  return out;
}

}  // namespace

ReplanResult replan(const Workpiece& w, const ProbePath& path, const Robot* robot, const ProbeShape& probe,
                    const SweepResult& result, const ReplanRequest& request) {
  const auto t0 = std::chrono::steady_clock::now();
  ReplanResult out;
  std::vector<std::uint32_t> colliding;
  for (std::uint32_t i = 0; i < result.points.size(); ++i)
    if (result.points[i].collides) colliding.push_back(i);
  out.points.resize(colliding.size());
  const bool ik = robot && has_inverse_kinematics(*robot);
  const std::vector<double> offsets = standoffs(request);
  tbb::parallel_for(std::size_t{0}, colliding.size(), [&](std::size_t k) {
    out.points[k] = replan_point(w, path, robot, ik, probe, colliding[k], request, offsets);
  });
  for (const ReplannedPoint& p : out.points) out.found += p.found;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

ProbePath replanned_path(const ProbePath& path, const ReplanResult& replanned) {
  ProbePath out = path;
  for (const ReplannedPoint& p : replanned.points) {
    if (!p.found) continue;
    if (path.joint_space) {
      if (p.joints.empty()) continue;  // (no joint values: the point stays)
      out.joints[p.point] = p.joints;
    }
    out.poses[p.point] = p.pose;
  }
  return out;
}

}  // namespace interfere::probe
