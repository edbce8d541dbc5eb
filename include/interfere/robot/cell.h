// The whole inspection cell as a scene (issue #28, deliverable 3): a URDF robot's links, the probe
// and its holder on the tool link, the workpiece and the fixtures become bodies of the scene engine
// (scene/engine.h, scene::clash_scene), each path point one frame whose poses come from the
// robot's forward kinematics. Three clash tests cover every pair that can meet:
//   "tool": probe and holder vs workpiece and fixtures;
//   "arm":  robot links vs workpiece and fixtures;
//   "self": links, probe and holder among themselves, adjacent ones suppressed (consecutive link
//           bodies of the chain, links with no geometry between them skipped; probe and holder
//           with each other and with the last link body at or before the tool link).
// Every body is a triangle mesh (the probe and holder are tessellated cylinders, `sides` facets,
// inscribed): the scene engine's exact mesh core decides every pair. The probe-only sweep
// (`interfere sweep`) keeps the exact cylinder test; docs/probe.md, "The cell as a scene", says
// what differs.
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/robot/chain.h"
#include "interfere/robot/ik.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/scene.h"

namespace interfere::robot {

/// The probe on the robot: its end-circle centre `tip` and direction `axis` in the tool link's
/// frame (mm); the probe cylinder goes back from the tip against the axis over probe_length, the
/// optional holder cylinder (holder_radius, holder_length > 0) continues behind it.
struct CellTool {
  std::string link;  ///< tool link name (default: the chain's last link)
  Vec3 tip{};
  Vec3 axis{0, 0, 1};
  double probe_radius = 0, probe_length = 0;
  double holder_radius = 0, holder_length = 0;
  int sides = 24;  ///< facets of the tessellated cylinders
};

/// A static body of the cell: the workpiece or a fixture (mesh in mm, local -> world pose).
struct CellObject {
  std::string id;
  std::string file;
  std::shared_ptr<const TriMesh> mesh;
  Transform pose;
};

struct Cell {
  std::string file;  ///< the cell JSON (errors, reports)
  Chain robot;
  std::string robot_file;   ///< the robot description read: a URDF file or a DH robot JSON
  std::string robot_format;  ///< "urdf" or "dh"
  Transform base;    ///< world <- robot root link
  CellTool tool;
  std::size_t tool_link = 0;  ///< index into robot.links
  CellObject workpiece;
  std::vector<CellObject> fixtures;
  double clearance = 0;  ///< > 0: pairs closer than this are reported (clearance tests)
  std::string path;      ///< optional joint path CSV named by the cell file (resolved), "" if none
};

/// Reads a cell file (docs/probe.md, "Cell file"):
///   {"robot": {"urdf": "arm.urdf", "package_paths": ["dir"], "base": [12 numbers], "tool_link":
///   "tool0"},
///   or {"robot": {"dh": "robot.json", "links": {"frame3": {"mesh": "forearm.stl", "pose": [...]}},
///   "base": [...]}} (a DH table of probe/kinematics.h, standard or modified; its DH frames
///   frame0..frameN are the links, meshes attached with a link <- mesh pose; tool_link defaults to
///   frameN; base places DH frame 0 with the table's own base after it),
///    "tool": {"tip": [x,y,z], "axis": [x,y,z], "probe_radius": r, "probe_length": l,
///             "holder_radius": R, "holder_length": L, "sides": 24},
///    "workpiece": {"mesh": "part.stl", "pose": [12 numbers]},
///    "fixtures": [{"id": "clamp", "mesh": "clamp.stl", "pose": [...]}, ...],
///    "clearance": 0, "path": "joints.csv"}
/// Files are relative to the cell file; meshes in mm (STL, OBJ, PLY, OFF). Unknown keys, missing or
/// non-finite numbers, sizes <= 0, an unknown tool link, unreadable files are errors naming the
/// cell file, the line and the field (or the URDF/mesh file and its element).
Expected<Cell> read_cell_json(const std::filesystem::path& file);
Expected<Cell> parse_cell_json(const std::string& text, const std::filesystem::path& file);

/// The cell's bodies and where they sit in the scene.
struct CellScene {
  scene::Scene scene;
  std::vector<scene::ClashTest> tests;  ///< "tool", "arm", "self" (those with bodies on both sides)
  std::vector<std::int64_t> link_body;  ///< per chain link: body index, -1 without geometry
  std::int64_t probe_body = -1, holder_body = -1;
  /// Per frame: the path point (index into the joint path) and, for frames between two points, the
  /// fraction t in (0, 1) along the joint-space segment from that point to the next (0 at points).
  std::vector<std::size_t> frame_point;
  std::vector<double> frame_t;
};

/// Builds the scene: one frame per path point and, with `between` > 0, `between` evenly spaced
/// frames inside each segment (joint interpolation: the robot's own motion between points). The
/// between-point frames are samples, not a conservative sweep: a clash shorter than the spacing can
/// be missed. Throws std::invalid_argument when a joint vector has the wrong size.
CellScene cell_scene(const Cell& cell, const JointPath& path, std::size_t between = 0);

/// The tool's cylinders at the tool link frame `tool_frame` (world <- tool link): probe (c0 at the
/// tip) and holder (behind it; radius 0 when there is none), for reports and tests.
struct ToolCylinders {
  Vec3 tip, back, holder_back;
  double probe_radius = 0, holder_radius = 0;
};
ToolCylinders tool_cylinders(const CellTool& tool, const Transform& tool_frame);

}  // namespace interfere::robot

namespace interfere::robot {

/// The conservative check between path points (issue #28, deliverable 3): along each segment the
/// robot moves by joint interpolation; a body's points move at most
///   delta_k(interval) <= sum over movable joints j before link k of |dq_j| * R_jk  (revolute; dq
///   in radians) or |dq_j| (prismatic),
/// with R_jk >= the distance from joint j's origin to any point of link k's body, bounded from the
/// chain's constant lengths (the joint origins' offsets and the body's mesh radius about its link
/// origin) by the triangle inequality. A sub-interval is clear for a body pair when the pair's
/// distance at its middle exceeds the sum of the two bodies' bounds over half the interval (static
/// bodies: 0); a pair that meets at a middle makes the segment collide there; otherwise the
/// interval is halved, up to `max_depth` levels, after which the segment is `unresolved` (never
/// clear, never a collision). How the distances and bounds are obtained: BetweenMethod.
///
/// How a sub-interval's body pairs are proven clear:
///   advancement (default): conservative advancement with certified distances (issue #28, speed):
///     per body a motion bound measured at the middle pose (motion_bounds_at: each joint's angle
///     change times the body's largest distance from that joint's axis there, plus prismatic
///     strokes), per pair the smallest distance at the middle from the BVH distance query
///     (query/distance.h, distance(); pairs whose bounding cubes are apart by more than the bound
///     skip it). A pair whose distance exceeds the sum of its two bounds is clear over the whole
///     sub-interval. The scene engine decides a middle only where a pair's surfaces meet there or
///     one body could lie inside the other (a component's vertex inside the other's closed solid
///     by exact ray parity, or near an open body's box), so the verdicts at the middles are the
///     engine's as before; elsewhere no pair meets there.
///   subdivision: the previous method, kept as the reference of the tests: each level's middles
///     in one scene-engine run with clearance tests at the largest bound of the level, and the
///     bound from the chain's whole reach (motion_bounds).
/// Both refine the same dyadic intervals and stop a segment at the first level where a pair is
/// found meeting, so they report the same states, pairs and parameters wherever the subdivision
/// resolves every segment; advancement proves more segments clear within max_depth.
enum class BetweenMethod : std::uint8_t { advancement, subdivision };
struct BetweenOptions {
  int max_depth = 12;  ///< halvings of a segment (2^-12 of it at the finest)
  BetweenMethod method = BetweenMethod::advancement;
  bool parallel = true;  ///< advancement: middles of a level in parallel (results identical)
  scene::SceneClashOptions engine;
};
enum class SegmentState : std::uint8_t { clear, collides, unresolved };
const char* segment_state_name(SegmentState s);
struct SegmentPair {
  std::string test, a, b;  ///< body ids
  double t = 0;  ///< parameter in (0, 1) of the first middle where the pair was found meeting
};
struct SegmentResult {
  std::size_t from = 0;  ///< the segment from point `from` to `from + 1`
  SegmentState state = SegmentState::clear;
  double t = -1;  ///< collides: the smallest parameter where a meeting pair was found
  std::vector<SegmentPair> pairs;  ///< collides: the pairs found meeting (one entry per pair)
  std::vector<std::string> unresolved_pairs;  ///< "a / b" pairs left undecided at max_depth
  std::size_t frames = 0;                     ///< middles checked
  std::size_t engine_frames = 0;  ///< of those, decided by a scene-engine run (advancement)
};
/// Checks every segment of `path` (cs = cell_scene(cell, path), for its bodies and tests).
std::vector<SegmentResult> check_between_points(const Cell& cell, const CellScene& cs,
                                                const JointPath& path,
                                                const BetweenOptions& options = {});
/// The whole path at once (issue #28, speed): the check at the path's frames (as
/// scene::clash_scene(cs.scene, cs.tests, engine)) and, with `between`, the conservative check
/// between points (as check_between_points), with certified distances carried across path points
/// (conservative advancement over the path): a body pair's certified distance at a point (a lower
/// bound of the distance between the two bodies there, from their bounding spheres or the BVH
/// distance query, with neither body inside the other by exact ray parity) proves the pair apart
/// at the following points and on the segments between them for as long as the sum of the two
/// bodies' motion bounds since that point (per segment the larger of motion_bounds_at at its two
/// ends) stays below it, less the tests' largest clearance. The scene engine decides a pair at a
/// frame only where no certificate covers it (SceneClashOptions::decide_in_frame), in chunks of
/// frames run in parallel (cut after frames without a pair to decide, merged as one run makes
/// them); between points only the pairs not proven clear on a segment go to the advancement
/// (BetweenMethod::advancement; a segment with none is clear without a middle). Pairs with an open
/// body are never certified (the engine decides them at every frame). Results: the frames' rows,
/// frames x pairs table, clashes (ids, frames), pair summaries, verdict and candidate counts as the
/// plain run's; core_runs smaller. Segments: the same collisions (state, t, pairs) as
/// check_between_points; a segment it leaves unresolved may be proven clear here; fewer middles.
struct PathCheckOptions {
  scene::SceneClashOptions engine;  ///< the engine at the frames (as clash_scene's options)
  bool between = false;             ///< also the conservative check between points
  BetweenOptions between_options;
  bool accelerate = true;  ///< false: the plain run (clash_scene on every frame, check_between_points)
};
struct PathCheckResult {
  scene::SceneClashResult frames;
  std::vector<SegmentResult> segments;  ///< with `between`
  std::size_t certificates = 0;         ///< certified distances computed (spheres or BVH queries)
  std::size_t bvh_queries = 0;          ///< of those, BVH distance queries
  std::size_t engine_pair_frames = 0;   ///< (pair, frame) decisions left to the engine
  std::size_t segments_certified = 0;   ///< segments proven clear by the points' certificates alone
  /// Wall seconds: the certificates (motion bounds, distances), the engine at the frames, the
  /// check between points.
  double certify_seconds = 0, engine_seconds = 0, between_seconds = 0;
};
PathCheckResult check_cell_path(const Cell& cell, const CellScene& cs, const JointPath& path,
                                const PathCheckOptions& options = {});

/// The motion bound delta of every body of cs.scene (0 for static bodies) when the joints move by
/// |dq| (joint units: degrees, mm), for tests and reports.
std::vector<double> motion_bounds(const Cell& cell, const CellScene& cs,
                                  const std::vector<double>& dq);
/// The tighter bound of the advancement method: every point of each body (0 for static bodies)
/// stays within the returned distance of its position at joint values q while the joints move by
/// at most |dq| from q (joint units). Revolute joint j adds |dq_j| (radians) times rho_j, the
/// largest distance of the body from joint j's axis at q (its bounding sphere's centre's distance
/// from the axis plus its radius); prismatic joints add |dq_j|. Distal to proximal, a point's
/// motion in joint j's frame is at most its motion in the next frame plus the chord of joint j's
/// rotation at its radius at q (the argument of probe/sweep.cpp's joint-path bound). Never larger
/// than motion_bounds(dq) (the smaller of the two is returned).
std::vector<double> motion_bounds_at(const Cell& cell, const CellScene& cs,
                                     const std::vector<double>& q, const std::vector<double>& dq);

/// The first path point's inverse-kinematics branch chosen with collisions in mind (issue #28): the
/// pose `first` is solved from every seed on its own (options.start when given, home, then `seeds`
/// deterministic pseudo-random configurations within the limits); the distinct solutions within the
/// limits are checked in that order with the scene engine (every test of the cell, hard) and the
/// first clear one is returned. None clear: the first solution, collision_free false. None at all:
/// an error naming the cell file. Give the result as IkOptions::start to pose_path_to_joints so
/// that the path follows that branch (`interfere cell --ik-start collision-free`).
struct StartChoice {
  std::vector<double> q;
  std::string seed;             ///< "start", "home" or "seed k"
  bool collision_free = false;
  std::size_t candidates = 0;   ///< distinct solutions checked
  std::size_t colliding = 0;    ///< of those, colliding (or undecided) ones
};
Expected<StartChoice> collision_free_start(const Cell& cell, const probe::ProbePose& first,
                                           const IkOptions& options = {}, int seeds = 24);

}  // namespace interfere::robot
