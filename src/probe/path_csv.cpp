// Probe path CSV reader/writer (issue #5, item 2); format in path.h and docs/probe.md.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "interfere/core/text_cells.h"
#include "interfere/probe/path.h"

namespace interfere::probe {
namespace {

std::string fmt(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

namespace {

const std::vector<std::string> kPoseColumns{"px", "py", "pz", "ax", "ay", "az", "rx", "ry", "rz"};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& c : names) s += (s.empty() ? "" : ",") + c;
  return s;
}

/// Reads the header `cols` (file order) by meaning (issue #23, item 9): a joint path when every
/// name is a joint of the robot, a pose path when every name is a pose column; each needed name
/// exactly once. Fills `path` (columns in meaning order, joint_space) and `slot` (for each file
/// column, where its value goes: the joint index, or the pose-column index).
Status read_header(const std::vector<std::string>& cols, const std::string& file, std::int64_t line,
                   const Robot* robot, ProbePath& path, std::vector<std::size_t>& slot) {
  auto fail = [&](std::size_t col, const std::string& reason) {
    return Error{.file = file, .line = line,
                 .reason = "header" + (col ? ", column " + std::to_string(col) : std::string()) + ": " + reason};
  };
  for (std::size_t i = 0; i < cols.size(); ++i) {
    double dummy;
    if (cols[i].empty() || parse_finite_cell(cols[i], dummy)) {
      return fail(i + 1, "must be a name, got '" + cols[i] + "' (the first non-comment row is the header)");
    }
  }
  std::vector<std::string> joints;
  if (robot) {
    for (const DhJoint& j : robot->joints) joints.push_back(j.name);
  }
  auto index_in = [](const std::vector<std::string>& names, const std::string& c) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), c) - names.begin());
  };
  const bool all_joints = robot && std::all_of(cols.begin(), cols.end(), [&](const std::string& c) {
    return index_in(joints, c) < joints.size();
  });
  const bool all_pose = std::all_of(cols.begin(), cols.end(),
                                    [&](const std::string& c) { return index_in(kPoseColumns, c) < kPoseColumns.size(); });
  const std::vector<std::string>* names = nullptr;
  if (all_joints) {
    names = &joints;
    path.joint_space = true;
  } else if (all_pose) {
    names = &kPoseColumns;
    path.joint_space = false;
  } else {
    // Name the first column that fits neither kind.
    const bool posey = std::any_of(cols.begin(), cols.end(),
                                   [&](const std::string& c) { return index_in(kPoseColumns, c) < kPoseColumns.size(); });
    for (std::size_t i = 0; i < cols.size(); ++i) {
      const bool is_joint = index_in(joints, cols[i]) < joints.size();
      const bool is_pose = index_in(kPoseColumns, cols[i]) < kPoseColumns.size();
      if (posey ? is_pose : is_joint) continue;
      if (!robot && !posey) {
        return fail(0, "a joint path needs a robot (--robot); a pose path has the header px,py,pz,ax,ay,az "
                       "(optionally followed by rx,ry,rz)");
      }
      return fail(i + 1, "unknown column '" + cols[i] + "' (" +
                             (robot ? "joints of the robot '" + robot->name + "': " + joined(joints) + "; or " : "") +
                             "pose columns px,py,pz,ax,ay,az[,rx,ry,rz])");
    }
    return fail(0, "columns mix joint names and pose columns");
  }
  slot.assign(cols.size(), 0);
  std::vector<int> seen(names->size(), 0);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    slot[i] = index_in(*names, cols[i]);
    if (seen[slot[i]]++) return fail(i + 1, "column '" + cols[i] + "' given twice");
  }
  const std::size_t needed = path.joint_space ? names->size() : (seen[6] || seen[7] || seen[8] ? 9 : 6);
  std::vector<std::string> missing;
  for (std::size_t k = 0; k < needed; ++k) {
    if (!seen[k]) missing.push_back((*names)[k]);
  }
  if (!missing.empty()) {
    return fail(0, "missing column" + std::string(missing.size() > 1 ? "s " : " ") + joined(missing) +
                       (path.joint_space ? " (a joint path gives every joint of the robot '" + robot->name + "': " +
                                               joined(joints) + ")"
                                         : " (a pose path has px,py,pz,ax,ay,az, optionally rx,ry,rz)"));
  }
  path.columns.assign(names->begin(), names->begin() + static_cast<std::ptrdiff_t>(needed));
  return {};
}

}  // namespace

Expected<ProbePath> parse_path_csv(std::string_view text, const std::string& file, const Robot* robot) {
  ProbePath path;
  std::int64_t line_no = 0;
  std::size_t pos = 0;
  bool have_header = false;
  std::vector<std::string> header;  // file order
  std::vector<std::size_t> slot;    // file column -> joint / pose-column index
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim_blanks(text.substr(pos, end - pos));
    ++line_no;
    pos = end + 1;
    if (line.empty() || line.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<std::string_view> f = split_csv_cells(line);
    if (!have_header) {
      have_header = true;
      for (auto s : f) header.emplace_back(s);
      const Status h = read_header(header, file, line_no, robot, path, slot);
      if (!h) return h.error();
      if (end == text.size()) break;
      continue;
    }
    if (f.size() != header.size()) {
      return Error{.file = file, .line = line_no,
                   .reason = "row has " + std::to_string(f.size()) + " values, expected " +
                             std::to_string(header.size()) + " (columns " + joined(header) + ")"};
    }
    std::vector<double> v(path.columns.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!parse_finite_cell(f[i], v[slot[i]])) {
        return Error{.file = file, .line = line_no,
                     .reason = "field '" + header[i] + "' (column " + std::to_string(i + 1) +
                               "): not a finite number: '" + std::string(f[i]) + "'"};
      }
    }
    if (path.joint_space) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const DhJoint& j = robot->joints[i];
        if (!(v[i] >= j.min && v[i] <= j.max)) {
          const std::size_t col = static_cast<std::size_t>(std::find(slot.begin(), slot.end(), i) - slot.begin());
          return Error{.file = file, .line = line_no,
                       .reason = "field '" + j.name + "' (column " + std::to_string(col + 1) + ", joint " + j.name +
                                 "): " + fmt(v[i]) + " outside the joint limits [" + fmt(j.min) + ", " + fmt(j.max) +
                                 "]"};
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
