// Probe path checking (issue #5, items 3-5): for every path point, does the probe (and its optional
// holder) touch the workpiece, its clearance, the triangles and patch involved; and between
// consecutive points a conservative continuous check of the swept probe.
//
// Hierarchy (item 3, after Li, Zhou & Zheng 2008, §3.2): candidates come from the project's BVH
// (default), from the paper's workpiece patches (boxes of about `volume_ratio` x probe volume),
// from a uniform grid or a distance field (the paper's comparison methods, §4), or from all
// triangles; then triangle box vs probe box; then the exact cylinder-triangle test
// (probe/cylinder.h), or box-triangle test for a box holder (probe/box.h). Every hierarchy gives
// the same decisions (tests check it).
//
// Continuous check (item 4; issue #23, item 4): consecutive points are joined by linear
// interpolation of the joint values (joint paths) or of the tip position plus a slerp of the axis
// and a twist of the reference direction about it (pose paths). On a parameter interval [t0, t1]
// the probe moves at most delta from its pose at the midpoint (a Lipschitz bound derived from the
// joint increments and the distances of the probe to the joint axes, docs/probe.md), so the swept
// volume lies inside the cylinders (and holder box) grown by delta. If those grown bodies touch no
// triangle the interval is clear; otherwise the midpoint pose is tested exactly and the interval is
// halved, level by level, down to 2^-max_depth or until max_poses poses were tested. Each segment
// ends in one of three states: `collides` (a pose of it was proved to collide), `clear` (every
// interval cleared) or `unresolved` (intervals neither cleared nor holding a proved collision: the
// probe passes closer than the resolution can separate; reported with the smallest gap measured
// there, never called clear or colliding).
//
// Solids (issue #23, item 3): the closed components of the workpiece bound its material. A pose
// whose bodies touch no triangle lies wholly inside or wholly outside each closed component (the
// bodies are connected), so one point (the tip) decides it by exact ray parity per component
// (query/clash.h point_in_solid, the engine's containment test), summed with the components'
// orientations (a cavity shell subtracts): inside the material collides. Open components bound
// nothing: their inside is not checked and Workpiece::warnings says so.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/probe/box.h"
#include "interfere/probe/cylinder.h"
#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"
#include "interfere/query/model.h"
#include "interfere/query/verdict.h"

namespace interfere::probe {

inline constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Probe body: a cylinder of `radius` and `length` going back from the end circle (the tip), and an
/// optional holder behind it: a cylinder (used when holder_radius > 0 and holder_length > 0) or a
/// box (used when its width, depth and length are > 0; docs/probe.md, "Box holder"). The box's
/// front face is centred on the probe's back end circle, it extends holder_box_length further back,
/// holder_box_width along the pose's reference direction and holder_box_depth along axis x ref, so
/// poses need a reference direction (ProbePose::ref). The CLI accepts one holder kind; the library
/// checks both when both are given.
struct ProbeShape {
  double radius = 5.0;
  double length = 40.0;
  double holder_radius = 0.0;
  double holder_length = 0.0;
  double holder_box_width = 0.0;
  double holder_box_depth = 0.0;
  double holder_box_length = 0.0;
  bool has_holder() const { return holder_radius > 0 && holder_length > 0; }
  bool has_holder_box() const { return holder_box_width > 0 && holder_box_depth > 0 && holder_box_length > 0; }
  double volume() const;  ///< pi r^2 l of the probe (the holder is not counted)
  /// Bound on the distance of any body point from the tip (motion bound of pose paths).
  double reach() const;
  /// Bound on the distance of any body point from the probe axis line (twist about the axis).
  double axis_reach() const;
};

/// The probe (index 0) and holder (index 1, when present) cylinders at `pose`.
std::vector<Cylinder> probe_cylinders(const ProbeShape& shape, const ProbePose& pose);

/// The holder box at `pose`. Preconditions: shape.has_holder_box() and pose.has_ref().
OrientedBox probe_holder_box(const ProbeShape& shape, const ProbePose& pose);

/// Workpiece patches (§3.2): triangles split recursively at the centroid median of the longest
/// box axis until a patch's box volume (each extent floored at `min_extent`, so flat patches are
/// not volume-free) is at most `target_volume` and its normals spread less than `max_normal_angle`
/// degrees (the curvature criterion). The paper's rule is target_volume = 30..35 x probe volume.
struct PatchOptions {
  double target_volume = 0;       ///< required > 0
  double min_extent = 0;          ///< e.g. the probe diameter
  double max_normal_angle = 60;   ///< degrees
};
struct Patches {
  std::vector<Aabb> boxes;                       ///< one per patch
  std::vector<std::vector<std::uint32_t>> tris;  ///< triangles of each patch (sorted)
  std::vector<std::uint32_t> patch_of;           ///< patch of each triangle
  std::size_t size() const { return boxes.size(); }
};
Patches make_patches(const TriMesh& mesh, const PatchOptions& options);

/// Uniform spatial subdivision (the paper's first comparison method): cells of size `cell` holding
/// the triangles whose boxes overlap them (CSR layout).
struct UniformGrid {
  Aabb bounds;
  double cell = 1;
  int nx = 1, ny = 1, nz = 1;
  std::vector<std::uint32_t> start;  ///< size cells + 1
  std::vector<std::uint32_t> items;
};
UniformGrid make_uniform_grid(const TriMesh& mesh, double cell);

/// Distance field (the paper's second comparison method): unsigned distance to the surface at the
/// nodes of a regular lattice of spacing `spacing` covering the workpiece box grown by `margin`.
/// Far from the surface a probe is cleared by the field alone; near it, the grid supplies
/// candidates for the exact test.
struct DistanceField {
  Aabb bounds;
  double spacing = 1;
  int nx = 1, ny = 1, nz = 1;
  std::vector<float> values;  ///< rounded down to float (lower bounds)
  UniformGrid grid;
};
DistanceField make_distance_field(const TriMesh& mesh, const Bvh& bvh, double spacing, double margin);

enum class Hierarchy { bvh, patches, grid, distance_field, brute_force };
const char* hierarchy_name(Hierarchy h);

/// The prepared workpiece: mesh, BVH (always: clearance uses it), patches (always: reported per
/// point) and the optional baseline structures.
struct Workpiece {
  TriMesh mesh;
  Bvh bvh;
  Patches patches;
  UniformGrid grid;        ///< built for Hierarchy::grid
  DistanceField field;     ///< built for Hierarchy::distance_field
  Hierarchy hierarchy = Hierarchy::bvh;
  /// Closed connected components of the mesh and their orientation: +1 bounds material (outward
  /// normals, or an inside-out shell enclosed by nothing), -1 a cavity (inward normals, inside
  /// another component). A point is in the material when the sum of the signs of the components
  /// containing it is positive (winding number; two overlapping solids count, a cavity does not).
  std::vector<Model> solids;
  std::vector<int> solid_sign;
  std::size_t open_components = 0;  ///< components that bound nothing (inside not checked)
  std::vector<std::string> warnings;  ///< e.g. open components: inside/behind them is not checked
  double build_seconds = 0;
};

struct WorkpieceOptions {
  Hierarchy hierarchy = Hierarchy::bvh;
  /// Patch size: box volume = patch_volume_ratio x probe volume (the paper's rule: 30-35; 33 by
  /// default), or an absolute box volume when patch_volume > 0.
  double patch_volume_ratio = 33;
  double patch_volume = 0;
  double patch_max_normal_angle = 60;
  double grid_cell = 0;       ///< 0: twice the probe diameter
  double field_spacing = 0;   ///< 0: the probe radius
};
Workpiece prepare_workpiece(TriMesh mesh, const ProbeShape& probe, const WorkpieceOptions& options = {});

struct SweepRequest {
  ProbeShape probe;
  bool continuous = true;   ///< check the motion between consecutive points
  bool clearance = true;    ///< compute the clearance of non-colliding points
  double max_clearance = std::numeric_limits<double>::infinity();  ///< farther: reported as inf
  int max_depth = 16;       ///< continuous check resolution 2^-max_depth of a segment
  std::size_t max_poses = std::size_t(1) << 16;  ///< budget of poses tested per segment (and pass)
  /// Pose paths: a candidate triangle whose plane the swept probe or holder cylinder stays clear of
  /// (motion along the plane's normal: the tip's component plus the turn about the tip, per axial
  /// slice) does not stop an interval from being cleared (issue #28, speed; docs/probe.md, "Plane
  /// filter"). Sound either way; false keeps the isotropic motion bound alone.
  bool plane_filter = true;
  /// Requested clearance (> 0): points and segments closer than this get Verdict::clearance
  /// (points by their exact clearance; segments by a second refinement with the bodies grown by it).
  double clearance_limit = 0;
  bool parallel = true;     ///< oneTBB over path points and segments
  /// Progress (done, count) over the passes' work items (points, their clearances, segments), from
  /// worker threads, possibly at once (it must be thread-safe).
  std::function<void(std::size_t, std::size_t)> progress;
};

struct PointResult {
  bool collides = false;
  bool inside = false;                 ///< collides by lying inside a closed component (no triangle hit)
  bool undecided = false;              ///< inside/outside undecided (every ray degenerate): never clear
  Verdict verdict = Verdict::clear;    ///< clash, undecided, clearance (< clearance_limit) or clear
  bool holder = false;                 ///< the holder (not the probe) is involved
  double clearance = 0;                ///< 0 when colliding; inf beyond max_clearance
  std::uint32_t triangle = kNone;      ///< closest triangle, or the lowest-index hit triangle
  std::uint32_t patch = kNone;         ///< patch of `triangle`
  std::vector<std::uint32_t> hits;     ///< every triangle touching the probe or holder, sorted
  Vec3 point_probe, point_workpiece;   ///< closest points (non-colliding, finite clearance)
};

enum class SegmentState { clear, unresolved, collides };
const char* segment_state_name(SegmentState s);  ///< "clear", "unresolved", "collides"

struct SegmentResult {
  std::uint32_t from = 0;                            ///< segment between points from and from+1
  SegmentState state = SegmentState::clear;
  Verdict verdict = Verdict::clear;                  ///< clash, undecided, clearance or clear
  /// Colliding parameter intervals, sorted, disjoint: each holds a pose proved to collide; no pose
  /// outside `intervals` and `unresolved` collides. Their ends are within 2^-max_depth of the true
  /// contact unless the pose budget ran out.
  std::vector<std::array<double, 2>> intervals;
  /// Intervals neither cleared nor holding a proved collision (sorted, disjoint).
  std::vector<std::array<double, 2>> unresolved;
  /// Unresolved only: the smallest clearance measured at the midpoints of the unresolved intervals
  /// (exact poses; between them the probe may come closer by at most `unresolved_motion`).
  double smallest_gap = std::numeric_limits<double>::infinity();
  double unresolved_motion = 0;                      ///< largest motion bound of an unresolved interval
  /// With SweepRequest::clearance_limit: state of the clearance pass (collides = closer than the
  /// limit proved somewhere), its intervals as above.
  SegmentState clearance_state = SegmentState::clear;
  std::vector<std::array<double, 2>> clearance_intervals, clearance_unresolved;
  bool between_samples = false;                      ///< neither end point collides
  std::vector<std::uint32_t> triangles;              ///< hit at tested interior poses, sorted
  std::uint32_t poses_tested = 0;                    ///< interior sub-intervals examined
};

struct SweepResult {
  std::vector<PointResult> points;
  std::vector<SegmentResult> segments;  ///< only segments whose verdict is not clear, by `from`
  std::size_t colliding_points = 0;
  std::size_t inside_points = 0;        ///< colliding by lying inside a closed component
  std::size_t colliding_segments = 0;
  std::size_t unresolved_segments = 0;  ///< state unresolved (verdict undecided)
  std::size_t undecided_points = 0;
  Verdict verdict = Verdict::clear;     ///< the worst of every point's and segment's verdict
  std::size_t between_samples_segments = 0;
  std::size_t candidate_tests = 0;      ///< exact cylinder/box-triangle tests at the path points
  double discrete_seconds = 0, continuous_seconds = 0, clearance_seconds = 0;
  bool any_collision() const { return colliding_points + colliding_segments > 0; }
};

/// Checks `path` (poses resolved; `robot` non-null for joint paths, used by the continuous check)
/// against the workpiece. Results do not depend on the thread count. With a box holder every pose
/// needs a reference direction (check_reference_frames); std::invalid_argument otherwise.
SweepResult sweep(const Workpiece& workpiece, const ProbePath& path, const Robot* robot, const SweepRequest& request);

/// Exact: does the probe (or holder) at `pose` touch the workpiece or lie inside one of its closed
/// components; appends the hit triangles to `hits` (sorted, unique) when not null, else returns at
/// the first hit. `inside` (when not null) is set when the pose collides by containment only.
/// `undecided` (when not null) is set when the pose touches nothing and whether it lies inside a
/// closed component could not be decided (every ray degenerate): false is then returned, which is
/// not a proof of clear (callers that need one check it).
bool pose_collides(const Workpiece& workpiece, const ProbeShape& probe, const ProbePose& pose,
                   std::vector<std::uint32_t>* hits = nullptr, std::size_t* tests = nullptr, bool* inside = nullptr,
                   bool* undecided = nullptr);

/// Bound on how far any probe point moves on [t0, t1] of segment `from` away from its position at
/// the midpoint (docs/probe.md, "Motion bound").
double motion_bound(const ProbePath& path, const Robot* robot, const ProbeShape& probe, std::uint32_t from,
                    double t0, double t1);
/// The probe pose at parameter t of segment `from`.
ProbePose pose_at(const ProbePath& path, const Robot* robot, std::uint32_t from, double t);

}  // namespace interfere::probe
