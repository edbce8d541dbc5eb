// What the cell tests share (tests/robot/test_cell_scene.cpp, test_cell_path.cpp; issue #28): the
// segments between points as comparable text, and the engine's exact test at the path's points or at
// dense samples inside its segments (the independent checks of the conservative motion sweeps).
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "interfere/robot/cell.h"

namespace interfere::robot::checks {

/// The segments' states, pairs (test, bodies, parameter) and unresolved pairs as one comparable
/// text per segment.
inline std::vector<std::string> describe(const std::vector<SegmentResult>& segs) {
  std::vector<std::string> out;
  for (const SegmentResult& r : segs) {
    std::ostringstream o;
    o.precision(17);
    o << r.from << " " << segment_state_name(r.state) << " t " << r.t;
    for (const SegmentPair& p : r.pairs) o << " [" << p.test << " " << p.a << " " << p.b << " " << p.t << "]";
    for (const std::string& u : r.unresolved_pairs) o << " {" << u << "}";
    out.push_back(o.str());
  }
  return out;
}

/// The engine without depths and curves (the verdicts only).
inline scene::SceneClashOptions verdicts_only() {
  scene::SceneClashOptions opt;
  opt.depth = false;
  opt.curves = false;
  return opt;
}

/// Per segment, whether any of `samples` evenly spaced frames strictly inside it has a meeting
/// pair (the exact engine test at each sample; an independent check of the conservative sweep).
inline std::vector<bool> dense_meets(const Cell& cell, const JointPath& path, std::size_t samples) {
  const CellScene dense = cell_scene(cell, path, samples);
  const scene::SceneClashResult r = scene::clash_scene(dense.scene, dense.tests, verdicts_only());
  std::vector<bool> meets(path.size() > 1 ? path.size() - 1 : 0, false);
  for (const scene::FramePairRow& row : r.frame_pairs) {
    if (dense.frame_t[row.frame] > 0 && row.verdict != Verdict::clear && row.verdict != Verdict::clearance)
      meets[dense.frame_point[row.frame]] = true;  // clash, contact or undecided
  }
  return meets;
}

/// Whether the path's points are all clear (the engine at the points).
inline bool points_clear(const Cell& cell, const JointPath& path) {
  const CellScene cs = cell_scene(cell, path);
  return scene::clash_scene(cs.scene, cs.tests, verdicts_only()).verdict == Verdict::clear;
}

}  // namespace interfere::robot::checks
