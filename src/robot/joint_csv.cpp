// Joint paths matched by joint name (issue #28, deliverable 2; robot/chain.h, JointPath).
#include <cmath>
#include <fstream>
#include <sstream>

#include "interfere/core/text_cells.h"
#include "interfere/robot/chain.h"

namespace interfere::robot {

Expected<JointPath> parse_joint_csv(std::string_view text, const std::string& file,
                                    const Chain& chain) {
  JointPath path;
  std::vector<std::size_t> column_joint;  // column -> index into chain.movable
  bool header = false;
  std::int64_t line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim_blanks(text.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    if (line.empty() || line[0] == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<std::string_view> cells = split_csv_cells(line);
    if (!header) {
      header = true;
      std::vector<bool> seen(chain.dof(), false);
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::int64_t m = chain.find_movable(cells[c]);
        if (m < 0) {
          std::string names;
          for (std::size_t k : chain.movable)
            names += (names.empty() ? "" : ", ") + chain.joints[k].name;
          return Error{.file = file,
                       .line = line_no,
                       .reason = "column " + std::to_string(c + 1) + " '" + std::string(cells[c]) +
                                 "': not a movable joint of robot '" + chain.name + "' (" + names +
                                 ")"};
        }
        if (seen[m]) {
          return Error{.file = file,
                       .line = line_no,
                       .reason = "column " + std::to_string(c + 1) + " '" + std::string(cells[c]) +
                                 "': joint named twice"};
        }
        seen[m] = true;
        column_joint.push_back(static_cast<std::size_t>(m));
      }
      for (std::size_t m = 0; m < seen.size(); ++m) {
        if (!seen[m]) {
          return Error{.file = file,
                       .line = line_no,
                       .reason = "header: joint '" + chain.joints[chain.movable[m]].name +
                                 "' has no column"};
        }
      }
      if (end == text.size()) break;
      continue;
    }
    if (cells.size() != column_joint.size()) {
      return Error{.file = file,
                   .line = line_no,
                   .reason = std::to_string(cells.size()) + " values, expected " +
                             std::to_string(column_joint.size()) + " (one per header column)"};
    }
    std::vector<double> q(chain.dof());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const ChainJoint& j = chain.joints[chain.movable[column_joint[c]]];
      double v = 0;
      if (!parse_finite_cell(cells[c], v)) {
        return Error{.file = file,
                     .line = line_no,
                     .reason = "column " + std::to_string(c + 1) + " '" + j.name + "': '" +
                               std::string(cells[c]) + "' is not a finite number"};
      }
      if (!(v >= j.lower && v <= j.upper)) {
        return Error{.file = file,
                     .line = line_no,
                     .reason = "column " + std::to_string(c + 1) + " '" + j.name +
                               "': " + std::string(cells[c]) + " outside the joint's limits [" +
                               short_number(j.lower) + ", " + short_number(j.upper) + "] (" +
                               (j.kind == JointKind::prismatic ? "mm" : "degrees") + ")"};
      }
      q[column_joint[c]] = v;
    }
    path.q.push_back(std::move(q));
    path.lines.push_back(line_no);
    if (end == text.size()) break;
  }
  if (!header) return Error{.file = file, .reason = "no header row (one column per movable joint)"};
  if (path.q.empty()) return Error{.file = file, .reason = "no path points after the header"};
  return path;
}

Expected<JointPath> read_joint_csv(const std::filesystem::path& file, const Chain& chain) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{.file = file.string(), .reason = "cannot open the joint path file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_joint_csv(ss.str(), file.string(), chain);
}

}  // namespace interfere::robot
