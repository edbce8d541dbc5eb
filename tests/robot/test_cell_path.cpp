// The whole-path check with certified distances across path points (robot/cell.h,
// check_cell_path; issue #28, speed) against the plain check (the scene engine at every frame,
// check_between_points from scratch): on a generated cell (a 3-link URDF arm with probe and
// holder, a finely divided plate, two posts) along smooth and random joint paths, and on the
// shipped example densified, the frames' verdicts, rows, frames x pairs table, clashes (ids and
// frames) and pair summaries are identical; between points the same segments collide (same t and
// pairs), a segment is never proven clear where the plain check finds a collision, and no segment
// proven clear has a meeting pair among 255 engine samples inside it (an independent check of
// the certificates); one thread gives identical results. Also in clearance mode and with sampled
// frames between points.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <tbb/global_control.h>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/robot/cell.h"
#include "cell_checks.h"

namespace fs = std::filesystem;
using namespace interfere;
using namespace interfere::robot;

#if INTERFERE_TEST_URDF

namespace {

using checks::dense_meets;
using checks::describe;

// A yaw-pitch-pitch arm (metres in the URDF): base box, turret, upper arm (box along x, 0.4
// long), forearm (box along x, 0.3 long), flange at its end turned so that its z axis points
// along the forearm.
const char* kArm = R"(<robot name="arm3p">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="turret"><collision><origin xyz="0 0 -0.03"/><geometry><box size="0.12 0.12 0.06"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.36 0.06 0.06"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.05 0.05"/></geometry></collision></link>
  <link name="flange"/>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="turret"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="turret"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.4 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="tool" type="fixed"><parent link="fore"/><child link="flange"/><origin xyz="0.3 0 0" rpy="0 1.5707963267948966 0"/></joint>
</robot>)";

/// The generated cell: the plate (300 x 300 x 30 mm, each face divided 40 x 40) at x = 600, a post
/// beside it and one on it; clearance > 0: clearance tests.
Expected<Cell> generated_cell(const fs::path& d, double clearance = 0) {
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "arm.urdf") << kArm;
  if (Status s = write_mesh(d / "plate.stl", make_box({-150, -150, 0}, {150, 150, 30}, 40)); !s) return s.error();
  if (Status s = write_mesh(d / "post.stl", make_box({-20, -20, 0}, {20, 20, 120}, 4)); !s) return s.error();
  std::ostringstream json;
  json << R"({
  "robot": {"urdf": "arm.urdf", "tool_link": "flange"},
  "tool": {"tip": [0, 0, 120], "axis": [0, 0, 1], "probe_radius": 8, "probe_length": 50,
           "holder_radius": 20, "holder_length": 70, "sides": 12},
  "workpiece": {"mesh": "plate.stl", "pose": [1,0,0,600, 0,1,0,0, 0,0,1,0]},
  "fixtures": [{"id": "post", "mesh": "post.stl", "pose": [0,-1,0,450, 1,0,0,180, 0,0,1,0]},
               {"id": "rib", "mesh": "post.stl", "pose": [1,0,0,640, 0,1,0,-40, 0,0,1,30]}])";
  if (clearance > 0) json << R"(, "clearance": )" << clearance;
  json << "}";
  std::ofstream(d / "cell.json") << json.str();
  return read_cell_json(d / "cell.json");
}

/// Everything a report reads from the frames' result, one line per item, in order.
std::vector<std::string> describe(const scene::SceneClashResult& r) {
  std::vector<std::string> out;
  std::ostringstream o;
  o.precision(17);
  o << "verdict " << verdict_name(r.verdict) << " counts " << r.clash_count << " " << r.contact_count << " "
    << r.clearance_count << " " << r.undecided_count << " candidates " << r.candidate_pairs << " suppressed "
    << r.suppressed;
  out.push_back(o.str());
  for (const std::string& w : r.warnings) out.push_back("warning " + w);
  for (const scene::FrameRow& f : r.frames) {
    std::ostringstream s;
    s.precision(17);
    s << "frame " << f.frame << " " << f.label << " " << f.time << " " << verdict_name(f.verdict) << " " << f.clashes
      << " " << f.contacts << " " << f.clearances << " " << f.undecided << " " << f.min_distance << " " << f.max_depth;
    out.push_back(s.str());
  }
  for (const scene::FramePairRow& p : r.frame_pairs) {
    std::ostringstream s;
    s.precision(17);
    s << "row " << p.frame << " " << p.test << " " << p.a << " " << p.b << " " << verdict_name(p.verdict) << " "
      << p.clashes << " " << p.contacts << " " << p.clearances << " " << p.undecided << " " << p.min_distance << " "
      << p.max_depth_bound;
    out.push_back(s.str());
  }
  for (const scene::SceneClash& c : r.clashes) {
    std::ostringstream s;
    s.precision(17);
    s << "clash " << c.id << " " << c.test << " " << c.a << " " << c.b << " " << verdict_name(c.verdict) << " "
      << c.kind << " " << c.distance << " frames";
    for (std::uint32_t f : c.frames) s << " " << f;
    out.push_back(s.str());
  }
  for (const scene::PairSummary& p : r.pairs) {
    std::ostringstream s;
    s << "pair " << p.test << " " << p.a << " " << p.b << " " << verdict_name(p.verdict) << " " << p.first_frame
      << " " << p.first_clash_frame << " " << p.clashes.size();
    out.push_back(s.str());
  }
  return out;
}

/// "" when equal, else the first line that differs (both versions).
std::string first_difference(const std::vector<std::string>& x, const std::vector<std::string>& y) {
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (x[i] != y[i]) return "line " + std::to_string(i) + ": '" + x[i] + "' vs '" + y[i] + "'";
  return x.size() == y.size() ? "" : "lengths " + std::to_string(x.size()) + " vs " + std::to_string(y.size());
}

struct Tally {
  std::size_t frames = 0, colliding_frames = 0, segments_collide = 0, segments_clear = 0, certified = 0,
              engine_pair_frames = 0, plain_pair_frames = 0;
};

/// The accelerated check against the plain one on one path (cell_scene with `between` samples).
void expect_same_as_plain(const Cell& cell, const JointPath& path, std::size_t between, Tally& tally,
                          bool dense_check = true) {
  const CellScene cs = cell_scene(cell, path, between);
  PathCheckOptions plain;
  plain.engine.depth = false;
  plain.engine.curves = false;
  plain.between = true;
  plain.accelerate = false;
  PathCheckOptions fast = plain;
  fast.accelerate = true;
  const PathCheckResult a = check_cell_path(cell, cs, path, plain);
  const PathCheckResult b = check_cell_path(cell, cs, path, fast);
  // The frames: identical.
  const std::vector<std::string> da = describe(a.frames), db = describe(b.frames);
  EXPECT_EQ(first_difference(da, db), "");
  EXPECT_LE(b.frames.core_runs, a.frames.core_runs);
  // Between points: the same collisions; never clear where the plain check is not.
  ASSERT_EQ(a.segments.size(), b.segments.size());
  const std::vector<std::string> sa = describe(a.segments), sb = describe(b.segments);
  for (std::size_t s = 0; s < sa.size(); ++s) {
    if (a.segments[s].state != SegmentState::unresolved) EXPECT_EQ(sa[s], sb[s]) << "segment " << s;
    else EXPECT_NE(b.segments[s].state, SegmentState::collides) << sb[s];
    EXPECT_LE(b.segments[s].frames, a.segments[s].frames) << "segment " << s;
  }
  // Segments proven clear: no meeting sample inside (independent of the certificates).
  if (dense_check) {
    const std::vector<bool> dense = dense_meets(cell, path, 127);
    for (std::size_t s = 0; s < b.segments.size(); ++s)
      if (b.segments[s].state == SegmentState::clear)
        EXPECT_FALSE(dense[s]) << "segment " << s << " proven clear, a sample meets";
  }
  // One thread: identical, middles included.
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    PathCheckOptions serial = fast;
    serial.between_options.parallel = false;
    const PathCheckResult c = check_cell_path(cell, cs, path, serial);
    EXPECT_EQ(first_difference(describe(c.frames), db), "");
    EXPECT_EQ(first_difference(describe(c.segments), sb), "");
    for (std::size_t s = 0; s < c.segments.size(); ++s) EXPECT_EQ(c.segments[s].frames, b.segments[s].frames);
    EXPECT_EQ(c.engine_pair_frames, b.engine_pair_frames);
  }
  tally.frames += cs.scene.frames.size();
  for (const scene::FrameRow& f : b.frames.frames) tally.colliding_frames += f.verdict == Verdict::clash;
  for (const SegmentResult& s : b.segments) {
    tally.segments_collide += s.state == SegmentState::collides;
    tally.segments_clear += s.state == SegmentState::clear;
  }
  tally.certified += b.segments_certified;
  tally.engine_pair_frames += b.engine_pair_frames;
  tally.plain_pair_frames += a.frames.core_runs;
}

/// A smooth path: the arm sweeps back and forth over the plate in small joint steps (the probe
/// low over it, dipping into the plate and the rib post on some lines), `points` points.
JointPath sweep_path(std::size_t points, double lift) {
  JointPath p;
  for (std::size_t i = 0; i < points; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(points - 1);
    const double line = std::floor(u * 4), v = u * 4 - line;
    const double along = static_cast<int>(line) % 2 ? 1 - v : v;
    p.q.push_back({-20 + 40 * along, 30 + 6 * line + lift, 75 - 4 * line});
    p.lines.push_back(static_cast<std::int64_t>(i) + 2);
  }
  return p;
}

}  // namespace

TEST(CellPath, SameAsPlainOnGeneratedCell) {
  Expected<Cell> cell = generated_cell(fs::temp_directory_path() / "interfere_robot_path1");
  ASSERT_TRUE(cell) << cell.error().message();
  Tally t;
  for (const double lift : {-8.0, -16.0, -24.0}) {
    SCOPED_TRACE("sweep, lift " + std::to_string(lift));
    expect_same_as_plain(*cell, sweep_path(100, lift), 0, t);
  }
  for (const auto& [seed, size] : {std::pair{501, 2.0}, std::pair{502, 10.0}}) {
    SCOPED_TRACE("random walk " + std::to_string(seed));
    JointPath path;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> step(-size, size);
    std::vector<double> q{0, 20, 70};
    for (int i = 0; i < 40; ++i) {
      path.q.push_back(q);
      path.lines.push_back(i + 2);
      for (double& v : q) v += step(rng);
    }
    expect_same_as_plain(*cell, path, 0, t);
  }
  EXPECT_GT(t.colliding_frames, 10u);
  EXPECT_GT(t.segments_collide, 5u);
  EXPECT_GT(t.segments_clear, 50u);
  EXPECT_GT(t.certified, 20u);  // segments proven clear with no middle at all
  EXPECT_LT(t.engine_pair_frames, t.plain_pair_frames);
  RecordProperty("frames", static_cast<int>(t.frames));
  RecordProperty("colliding_frames", static_cast<int>(t.colliding_frames));
  RecordProperty("segments_collide", static_cast<int>(t.segments_collide));
  RecordProperty("segments_certified", static_cast<int>(t.certified));
  RecordProperty("engine_pair_decisions", static_cast<int>(t.engine_pair_frames));
  RecordProperty("plain_core_runs", static_cast<int>(t.plain_pair_frames));
}

TEST(CellPath, SameAsPlainInClearanceModeAndWithSampledFrames) {
  Expected<Cell> cell = generated_cell(fs::temp_directory_path() / "interfere_robot_path2", 12);
  ASSERT_TRUE(cell) << cell.error().message();
  Tally t;
  expect_same_as_plain(*cell, sweep_path(80, -20.0), 0, t, false);
  expect_same_as_plain(*cell, sweep_path(40, -12.0), 3, t, false);
  EXPECT_GT(t.colliding_frames, 0u);
}

TEST(CellPath, SameAsPlainOverSeveralWalkBlocks) {
  // 4,500 points: each pair's walk runs in blocks of 2,048 points (cell_path.cpp), so certificates
  // end and restart at block boundaries; the results stay the plain check's.
  Expected<Cell> cell = generated_cell(fs::temp_directory_path() / "interfere_robot_path3");
  ASSERT_TRUE(cell) << cell.error().message();
  Tally t;
  expect_same_as_plain(*cell, sweep_path(4500, -16.0), 0, t, false);
  EXPECT_GT(t.colliding_frames, 0u);
  EXPECT_GT(t.certified, 1000u);
}

TEST(CellPath, SameAsPlainOnTheExampleDensified) {
  const fs::path ex = fs::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";
  Expected<Cell> cell = read_cell_json(ex / "cell.json");
  ASSERT_TRUE(cell) << cell.error().message();
  Expected<JointPath> full = read_joint_csv(ex / "path.csv", cell->robot);
  ASSERT_TRUE(full) << full.error().message();
  // Each segment in 8 (joint interpolation: the same motion, 8x the points).
  JointPath dense;
  for (std::size_t i = 0; i + 1 < full->size(); ++i) {
    for (int k = 0; k < 8; ++k) {
      std::vector<double> q(full->q[i].size());
      for (std::size_t j = 0; j < q.size(); ++j) q[j] = full->q[i][j] + k / 8.0 * (full->q[i + 1][j] - full->q[i][j]);
      dense.q.push_back(q);
      dense.lines.push_back(static_cast<std::int64_t>(dense.q.size()) + 1);
    }
  }
  dense.q.push_back(full->q.back());
  dense.lines.push_back(static_cast<std::int64_t>(dense.q.size()) + 1);
  Tally t;
  expect_same_as_plain(*cell, dense, 0, t);
  EXPECT_GT(t.colliding_frames, 0u);
  EXPECT_GT(t.segments_collide, 0u);
  RecordProperty("segments_certified", static_cast<int>(t.certified));
}

#endif
