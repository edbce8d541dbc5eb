// Probe path CSV reader/writer (issue #5, item 2); format in path.h and docs/probe.md.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "interfere/probe/path.h"

namespace interfere::probe {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      out.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return out;
}

bool parse_double(std::string_view s, double& v) {
  if (s.empty()) return false;
  if (s.front() == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

std::string fmt(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

Expected<ProbePath> parse_path_csv(std::string_view text, const std::string& file, const Robot* robot) {
  ProbePath path;
  std::int64_t line_no = 0;
  std::size_t pos = 0;
  bool have_header = false;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim(text.substr(pos, end - pos));
    ++line_no;
    pos = end + 1;
    if (line.empty() || line.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<std::string_view> f = split(line);
    if (!have_header) {
      have_header = true;
      for (auto s : f) path.columns.emplace_back(s);
      const std::vector<std::string> pose_cols{"px", "py", "pz", "ax", "ay", "az"};
      const std::vector<std::string> frame_cols{"px", "py", "pz", "ax", "ay", "az", "rx", "ry", "rz"};
      path.joint_space = path.columns != pose_cols && path.columns != frame_cols;
      if (path.joint_space) {
        if (!robot) {
          return Error{.file = file, .line = line_no,
                       .reason = "header: a joint path needs a robot (--robot); a pose path has the header "
                                 "px,py,pz,ax,ay,az (optionally followed by rx,ry,rz)"};
        }
        if (path.columns.size() != robot->joints.size()) {
          return Error{.file = file, .line = line_no,
                       .reason = "header: " + std::to_string(path.columns.size()) + " columns but the robot '" +
                                 robot->name + "' has " + std::to_string(robot->joints.size()) +
                                 " joints (or use the pose header px,py,pz,ax,ay,az)"};
        }
      }
      for (std::size_t i = 0; i < path.columns.size(); ++i) {
        double dummy;
        if (path.columns[i].empty() || parse_double(path.columns[i], dummy)) {
          return Error{.file = file, .line = line_no,
                       .reason = "header: column " + std::to_string(i + 1) + " must be a name, got '" +
                                 path.columns[i] + "' (the first non-comment row is the header)"};
        }
      }
      if (end == text.size()) break;
      continue;
    }
    if (f.size() != path.columns.size()) {
      return Error{.file = file, .line = line_no,
                   .reason = "row has " + std::to_string(f.size()) + " values, expected " +
                             std::to_string(path.columns.size()) + " (" + "columns " +
                             [&] {
                               std::string s;
                               for (auto& c : path.columns) s += (s.empty() ? "" : ",") + c;
                               return s;
                             }() + ")"};
    }
    std::vector<double> v(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!parse_double(f[i], v[i])) {
        return Error{.file = file, .line = line_no,
                     .reason = "field '" + path.columns[i] + "' (column " + std::to_string(i + 1) +
                               "): not a finite number: '" + std::string(f[i]) + "'"};
      }
    }
    if (path.joint_space) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const DhJoint& j = robot->joints[i];
        if (!(v[i] >= j.min && v[i] <= j.max)) {
          return Error{.file = file, .line = line_no,
                       .reason = "field '" + path.columns[i] + "' (joint " + j.name + "): " + fmt(v[i]) +
                                 " outside the joint limits [" + fmt(j.min) + ", " + fmt(j.max) + "]"};
        }
      }
      path.joints.push_back(std::move(v));
    } else {
      Vec3 axis{v[3], v[4], v[5]};
      const double n = norm(axis);
      if (!(n > 0)) {
        return Error{.file = file, .line = line_no, .reason = "field 'ax,ay,az': zero probe axis"};
      }
      ProbePose pose{{v[0], v[1], v[2]}, axis / n};
      if (v.size() == 9) {
        const Vec3 ref{v[6], v[7], v[8]};
        pose.ref = perpendicular_reference(ref, pose.axis);
        if (!pose.has_ref()) {
          return Error{.file = file, .line = line_no,
                       .reason = std::string("field 'rx,ry,rz': ") +
                                 (norm(ref) > 0 ? "reference direction parallel to the probe axis"
                                                : "zero reference direction") +
                                 " (it fixes the holder's width direction)"};
        }
      }
      path.poses.push_back(pose);
    }
    path.lines.push_back(line_no);
    if (end == text.size()) break;
  }
  if (!have_header) return Error{.file = file, .line = 1, .reason = "empty path file (no header row)"};
  if (path.lines.empty()) return Error{.file = file, .line = line_no, .reason = "no path points after the header"};
  return path;
}

Expected<ProbePath> read_path_csv(const std::filesystem::path& p, const Robot* robot) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return Error{.file = p.string(), .reason = "cannot open path file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_path_csv(ss.str(), p.string(), robot);
}

Status check_reference_frames(const ProbePath& path, const std::string& file_name) {
  for (std::size_t i = 0; i < path.poses.size(); ++i) {
    if (path.poses[i].has_ref()) continue;
    const std::int64_t line = i < path.lines.size() ? path.lines[i] : -1;
    if (path.joint_space) {
      return Error{.file = file_name, .line = line,
                   .reason = "a box holder needs the holder's reference direction: the robot's tool.ref is "
                             "parallel to tool.axis (field 'tool.ref' of the robot file)"};
    }
    return Error{.file = file_name, .line = line,
                 .reason = "field 'rx,ry,rz': missing: a box holder needs the holder's reference direction "
                           "(header px,py,pz,ax,ay,az,rx,ry,rz)"};
  }
  return {};
}

void resolve_poses(ProbePath& path, const Robot& robot) {
  if (!path.joint_space) return;
  path.poses.resize(path.joints.size());
  for (std::size_t i = 0; i < path.joints.size(); ++i) path.poses[i] = forward_kinematics(robot, path.joints[i]);
}

std::string path_to_csv(const ProbePath& path) {
  std::string out;
  if (path.joint_space) {
    for (std::size_t i = 0; i < path.columns.size(); ++i) {
      if (i) out += ',';
      out += path.columns[i];
    }
    out += "\n";
    for (const auto& row : path.joints) {
      for (std::size_t i = 0; i < row.size(); ++i) {
        if (i) out += ',';
        out += fmt(row[i]);
      }
      out += "\n";
    }
  } else {
    const bool refs = !path.poses.empty() &&
                      std::all_of(path.poses.begin(), path.poses.end(), [](const ProbePose& p) { return p.has_ref(); });
    out += refs ? "px,py,pz,ax,ay,az,rx,ry,rz\n" : "px,py,pz,ax,ay,az\n";
    for (const ProbePose& p : path.poses) {
      out += fmt(p.tip.x) + "," + fmt(p.tip.y) + "," + fmt(p.tip.z) + "," + fmt(p.axis.x) + "," + fmt(p.axis.y) +
             "," + fmt(p.axis.z);
      if (refs) out += "," + fmt(p.ref.x) + "," + fmt(p.ref.y) + "," + fmt(p.ref.z);
      out += "\n";
    }
  }
  return out;
}

}  // namespace interfere::probe
