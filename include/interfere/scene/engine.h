// The scene clash engine (issue #24, items 3, 4 and 6): a broad phase over the bodies' world boxes
// (a BVH of boxes, refitted per frame), each candidate pair decided by the exact two-part core
// (query/clash.h: pairs, regions, curves, containment, touching overlap; query/depth.h: depth and
// its upper bound; distances for clearance), in parallel across pairs and inside large pairs
// (nested oneTBB tasks). Results are identical for any thread count and any order of the bodies.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/core/aabb.h"
#include "interfere/mesh/polyline.h"
#include "interfere/query/clash.h"
#include "interfere/query/verdict.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/scene.h"

namespace interfere::scene {

/// Status of a clash against a baseline (baseline.h): new (not in the baseline), active (in it),
/// resolved (in it, gone now: listed once, then dropped). Without a baseline every clash is new.
enum class ClashStatus : std::uint8_t { new_, active, resolved };
const char* clash_status_name(ClashStatus s);

/// The deepest vertex of a pair's depth maps: which body's vertex, its index and source id (FE: the
/// solver's node id), the source id of a triangle at it (FE: an element id), its depth in the
/// other body and where it is (world).
struct DeepestPoint {
  std::uint32_t body = 0;
  std::uint32_t vertex = 0;
  std::int64_t node = -1, element = -1;
  double depth = 0;
  Vec3 point;
  std::uint32_t frame = 0;  ///< motion: the frame (static: 0)
};

/// One clash: a connected clash region of a body pair (its crossing or touching triangle pairs),
/// a body lying inside the other, a clearance violation, or a duplicate.
struct SceneClash {
  /// Stable id: "C" + 16 hex digits of a 64-bit hash (FNV-1a) of the test name, the verdict (a
  /// contact that became a clash is a new clash: an approval does not carry over), the two bodies'
  /// ids (in sorted order) and the clash's location — the middle of the box of its intersection
  /// curves, of its touching triangles' common parts, of its clearance witnesses, or the inner
  /// body's box — in the local frames of both bodies, quantised at the test's id grid: unchanged
  /// when the inputs are reordered, an unrelated body moves, or the pair moves together; changed
  /// when the clash moves on either body by about a grid cell. "-2", "-3", ... distinguish
  /// clashes of one pair in one grid cell (ordered by location). With motion, a clash of a pair
  /// and kind in the previous frame that moved keeps its id (matched by the nearest location).
  std::string id;
  std::string test;            ///< the clash test's name
  std::uint32_t a = 0, b = 0;  ///< body indices; Scene::bodies[a].id < Scene::bodies[b].id
  Verdict verdict = Verdict::clash;  ///< clash, contact, clearance or undecided
  /// What it is: "crossing" (surfaces cross), "inside" (a body inside the other), "touching_overlap"
  /// (faces coincide while the solids overlap), "touch" (contact region), "nominal_fit",
  /// "within_tolerance" (hard clash no deeper than the tolerance), "clearance", "duplicate",
  /// "undecided".
  std::string kind;
  /// Crossing and touching-overlap clashes of closed bodies: how deep the surfaces reach into the solids, a sampled lower bound and a
  /// proven upper bound (query/depth.h), for the body pair (every region of it carries the pair's).
  /// The bound is refined until it is within 10 % of the sampled depth (or the splits run out); since
  /// 2026-11-28 each piece also gets the convexity bound (distance to one nearest face), so flat
  /// crossings (a face sunk into a face, a shaft in a bore) usually meet the 10 % at once: bounds
  /// are tighter than before, never below the true depth.
  double depth = 0, depth_bound = 0;
  double distance = 0;  ///< clearance: the smallest distance between the bodies; 0 when they meet
  Vec3 point;           ///< a representative point (world): on the curves, the contact, or the gap's middle
  /// Tight box (world) of the intersection curves and contact region (touching triangle pairs'
  /// common parts), or of the clearance witness segment, or of the inner body.
  Aabb box;
  double curve_length = 0;
  std::vector<Polyline> curves;                    ///< intersection curves (world)
  std::size_t cross_pairs = 0, touch_pairs = 0;    ///< triangle pairs of this clash
  std::vector<std::uint32_t> triangles_a, triangles_b;  ///< sorted triangle indices of each body
  std::vector<std::int64_t> source_ids_a, source_ids_b;  ///< their sorted distinct source ids (Body::source_id)
  Vec3 witness_a, witness_b;  ///< clearance: the closest points
  std::vector<std::string> reasons;  ///< undecided: why; others: notes
  // Across frames (motion) — the first frame's data above.
  std::vector<std::uint32_t> frames;  ///< the frames it is present in (sorted); empty when static
  /// With depth maps: the deepest vertex of the pair over the frames the clash is present in.
  bool has_deepest = false;
  DeepestPoint deepest;
  /// Deformed scenes checked in their reference configuration too (SceneClashOptions::reference):
  /// a contact of a pair that already touched there — a bonded or tied interface, a designed fit —
  /// is a designed contact (issue #26, item 4). False otherwise, and always for clashes.
  bool designed = false;
  // Status (baseline.h).
  ClashStatus status = ClashStatus::new_;
  /// The user's fields carried from the baseline clash with the same id ("status": "approved",
  /// "assignee", "comment", ...), as JSON text per key.
  std::map<std::string, std::string> user_fields;
  /// Resolved clashes only (SceneClashResult::resolved): the clash as the baseline reported it
  /// (JSON text); a and b are then meaningless (its bodies may be gone).
  std::string baseline_json;
};

/// The clashes of one body pair in one test (grouping by pair).
struct PairSummary {
  std::string test;
  std::uint32_t a = 0, b = 0;
  Verdict verdict = Verdict::clear;  ///< the worst of its clashes
  std::vector<std::uint32_t> clashes;  ///< indices into SceneClashResult::clashes
  double depth = 0, depth_bound = 0, min_distance = 0;
  /// Motion: the first frame with any finding of the pair, and the first whose verdict is clash
  /// (-1: none).
  std::int64_t first_frame = -1, first_clash_frame = -1;
  /// The pair's verdict in the reference configuration (SceneClashOptions::reference; clear when
  /// not checked or clear there).
  Verdict reference_verdict = Verdict::clear;
};

/// A group of clashes (SceneClashOptions::group_by): one body pair, or one location where clashes
/// cluster (boxes within SceneClashOptions::group_distance of each other, any pairs).
struct ClashGroup {
  std::string id;  ///< "G" + hash of its clashes' ids
  std::vector<std::uint32_t> clashes;
  Aabb box;
  Verdict verdict = Verdict::clear;
};

/// One row of the frames table (motion).
struct FrameRow {
  std::uint32_t frame = 0;
  std::string label;
  double time = 0;
  std::size_t clashes = 0, contacts = 0, clearances = 0, undecided = 0;
  double min_distance = -1;  ///< smallest clearance distance found (-1: none within any clearance)
  double max_depth = 0;      ///< largest depth bound of the frame's clashes
  Verdict verdict = Verdict::clear;
};

/// One row of the table frames x body pairs (motion; issue #26, item 2): a body pair of a test
/// with any finding in a frame (pairs clear in that frame have no row).
struct FramePairRow {
  std::uint32_t frame = 0;
  std::uint32_t test = 0;      ///< index of the clash test
  std::uint32_t a = 0, b = 0;  ///< body indices, as in SceneClash
  Verdict verdict = Verdict::clear;  ///< the worst of the pair's findings in the frame
  std::size_t clashes = 0, contacts = 0, clearances = 0, undecided = 0;
  /// Smallest distance between the bodies: 0 when they meet, the clearance distance when a
  /// clearance test found one, -1 when not measured (hard tests measure no gaps).
  double min_distance = -1;
  double max_depth = 0, max_depth_bound = 0;  ///< largest depth and depth bound of its clashes
  /// With depth maps: the deepest vertex of the pair in the frame.
  bool has_deepest = false;
  DeepestPoint deepest;
};

/// One body's vertices strictly inside the other body's solid, sparse: vertex indices (sorted) and
/// their depths (distance to the other surface).
struct VertexDepths {
  std::vector<std::uint32_t> vertices;
  std::vector<double> depths;
  std::size_t undecided = 0;  ///< vertices whose side could not be decided (never counted as outside)
};

/// The depth maps of one clashing body pair in one frame (SceneClashOptions::depth_maps).
struct PairDepthMap {
  std::uint32_t frame = 0;
  std::uint32_t a = 0, b = 0;  ///< body indices (a's id < b's id)
  VertexDepths a_in_b, b_in_a;
  bool has_deepest = false;
  DeepestPoint deepest;
};

/// A body pair's verdict in the reference configuration (SceneClashOptions::reference).
struct ReferencePair {
  std::uint32_t test = 0, a = 0, b = 0;
  Verdict verdict = Verdict::clear;
};

enum class GroupBy : std::uint8_t { none, pair, location };

struct SceneClashOptions {
  /// The exact core's settings (query/clash.h): triangle test, broad phase, parallel, regions,
  /// containment. The engine sets the clearance (per test and pair) and the statistics source.
  ClashRequest request;
  /// Measure the depth of crossing closed bodies (query/depth.h; SceneClash::depth, depth_bound).
  /// Off: depths stay 0 and penetration tolerances cannot apply (such clashes stay clashes).
  bool depth = true;
  /// Penetration depth maps (issue #26, item 3): per clashing pair of closed bodies (crossing,
  /// touching overlap, containment) and frame, every vertex of each body that lies inside the
  /// other with its depth (SceneClashResult::depth_maps; the deepest vertex also on the frame's
  /// pair row and on the clash). Needs `depth`.
  bool depth_maps = false;
  /// Splits per direction of a crossing pair for the depth upper bound (query/depth.h); 0: no bound
  /// (penetration tolerances then compare the sampled depth, which is flagged in the clash's reasons).
  std::size_t depth_bound_splits = 5000;
  /// With frames and no test with a penetration tolerance (nothing decided by the bound), the splits
  /// per direction of each frame's bound: still a proven upper bound, looser than the 10 % that
  /// depth_bound_splits usually reaches, at a small share of its cost (1,000 moving bodies: 42 ->
  /// 320 frames/s; issue #24, item 9). Set it to depth_bound_splits for the static bound per frame.
  std::size_t frame_depth_bound_splits = 50;
  bool curves = true;      ///< keep intersection curves (SceneClash::curves)
  bool triangles = true;   ///< keep triangle indices and source ids
  GroupBy group_by = GroupBy::pair;
  double group_distance = 0;  ///< location grouping: boxes closer than this join (0: touching boxes)
  /// Nominal-fit check (ClashTest::nominal_fits_are_contacts) supplied by sources that know B-Rep
  /// faces (cad/assembly_scene.h): given the two bodies, their models, the clash result and the
  /// sampled depth, whether the crossings are only where faces coincide. Unset: none is. The models
  /// and the result are in the pair's decision frame: the world, or the first body's local frame
  /// (its mesh as given, the other moved into it; src/scene/engine_frame.cpp), and a body pair in
  /// the same relative pose as an earlier one with the same meshes gets that pair's answer, so the
  /// answer must depend only on the geometry (and on what the bodies' meshes stand for).
  std::function<bool(std::uint32_t a, std::uint32_t b, const Model& wa, const Model& wb,
                     const ClashResult& r, double depth)>
      nominal_fit;
  /// Zero-clearance fits (issue #29, item 4), supplied by sources that know B-Rep faces
  /// (cad/assembly_scene.h, zero_clearance_fit_check): `reach(i)` how far body i's broad box is grown
  /// to find such pairs (0: none of its pairs is one), `check(a, b, gap)` whether bodies a and b meet
  /// on coincident B-Rep faces though their tessellations may not (the smallest distance of their
  /// placed triangles there in `gap`). A static scene only (no frames): a test with
  /// nominal_fits_are_contacts (not duplicates) reports such a pair of its selections, where it found
  /// no clash, contact or undecided pair, as a contact of kind "zero_clearance_fit" (distance: the
  /// gap), replacing its clearance record. Unset: none is. The one classification of assembly-clash
  /// and of clash --scene with STEP assemblies.
  struct ZeroClearanceFits {
    std::function<double(std::uint32_t body)> reach;
    std::function<bool(std::uint32_t a, std::uint32_t b, double* gap)> check;
  } zero_clearance_fits;
  /// Called once per checked candidate pair with the exact core's raw result (from any thread: the
  /// caller synchronises), test index, body indices (a's id < b's id): for callers that write
  /// per-pair outputs (`interfere clash A B`: --pairs, --region-a/-b) or aggregate per pair
  /// (assembly-clash). Not called for duplicates tests. The result's geometry is in the pair's
  /// decision frame: the first body's local frame when its pose is a rotation (the world when that
  /// pose is the identity, as for `interfere clash A B`), else the world; pairs in the same relative
  /// pose with the same meshes get the same result.
  std::function<void(std::size_t test, std::uint32_t a, std::uint32_t b, const ClashResult&)> on_pair;
  /// Called after each frame with (frames done, frame count): progress for long runs.
  std::function<void(std::size_t, std::size_t)> progress;
  /// A static scene (no frames): called as body pairs are decided with (done, count) of the
  /// distinct pair jobs (pairs in the same relative pose with the same meshes are one), from worker
  /// threads, possibly at once (it must be thread-safe): progress for large assemblies
  /// (assembly-clash, clash --scene).
  std::function<void(std::size_t, std::size_t)> pair_progress;
  /// When frames deform bodies (Frame::shapes, an FE model's load steps), check the bodies once
  /// more in their reference configuration (the scene's own meshes and poses) before frame 0, to
  /// tell designed contacts (bonded or tied interfaces: touching there already) from contacts and
  /// penetrations the load makes (issue #26, item 4). One frame's extra work.
  bool reference = true;
  /// Decide these body pairs only (body indices, either order; issue #31): when not empty, the
  /// broad phase still finds and counts every candidate (candidate_pairs, suppressed, selection
  /// warnings), but only candidates of a listed pair are decided and reported (clashes, frame
  /// rows, frames x pairs, reference verdicts, depth maps, core_runs). For callers that split one
  /// scene's pairs among several runs (interfere-mpi: each rank runs the scene of the bodies its
  /// pairs need, with its pairs here) and merge them with finish_result. Pairs in the same
  /// relative pose with the same meshes are decided once per run, so a caller that wants one
  /// process's core_runs keeps them in one run (PairClassKey).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> decide_pairs;
  /// Motion: decide a candidate pair in a frame only where this returns true for (frame, a, b)
  /// (issue #28, the cell's path check): the others are still found and counted by the broad phase
  /// (candidate_pairs, suppressed) but neither decided nor reported in that frame, as if clear
  /// there. For callers that have proven those pairs apart by more than the test's clearance, with
  /// neither body inside the other (robot/cell.h, check_cell_path: certified distances along the
  /// path), or that read only some pairs' verdicts. Unset: every candidate is decided.
  std::function<bool(std::size_t frame, std::uint32_t a, std::uint32_t b)> decide_in_frame;
};

struct SceneClashResult {
  /// Sorted by (test order, body a id, body b id, id). With motion: each distinct clash once.
  std::vector<SceneClash> clashes;
  std::vector<PairSummary> pairs;  ///< body pairs with clashes, same order
  std::vector<ClashGroup> groups;  ///< by SceneClashOptions::group_by (empty for none)
  /// Baseline clashes not found now (status resolved), for listing once.
  std::vector<SceneClash> resolved;
  std::vector<FrameRow> frames;  ///< motion: one row per frame
  /// Motion: the table frames x body pairs, sorted by (frame, test, body a id, body b id).
  std::vector<FramePairRow> frame_pairs;
  /// The reference configuration's findings per body pair (SceneClashOptions::reference), sorted as
  /// frame_pairs; `reference_checked` tells whether the pass ran.
  std::vector<ReferencePair> reference_pairs;
  /// SceneClashOptions::depth_maps: per frame (0 when static) and clashing body pair, sorted by
  /// (frame, body a id, body b id).
  std::vector<PairDepthMap> depth_maps;
  bool reference_checked = false;
  /// Contacts of pairs that touched in the reference configuration (designed), the other
  /// contacts, and the clashes of pairs that did not clash there (new penetrations).
  std::size_t designed_contact_count = 0, new_contact_count = 0, new_penetration_count = 0;
  std::size_t bodies = 0, triangles = 0;
  std::size_t candidate_pairs = 0;  ///< body pairs whose boxes (grown by the clearance) overlap, over tests and frames
  std::size_t suppressed = 0;       ///< candidate pairs left out by suppression rules
  /// Runs of the exact core (over frames): body pairs with the same two meshes in the same relative
  /// pose, bit for bit, and the same tests are decided once, in the first body's local frame (a
  /// product's repeated joints; engine_frame.cpp), so this is at most the candidate pairs left.
  std::size_t core_runs = 0;
  std::size_t clash_count = 0, contact_count = 0, clearance_count = 0, undecided_count = 0;
  Verdict verdict = Verdict::clear;  ///< the worst clash's (clear without any)
  std::vector<std::string> warnings;  ///< selections that select nothing, open bodies, ...
  double prepare_seconds = 0, broad_seconds = 0, narrow_seconds = 0;
};

/// Runs every test on the scene (and on every frame of its motion). Throws std::invalid_argument
/// for an invalid scene or test (Scene::validate, ClashTest::validate, duplicate test names).
SceneClashResult clash_scene(const Scene& scene, const std::vector<ClashTest>& tests,
                             const SceneClashOptions& options = {});

/// The end of clash_scene, for callers that merge the results of several runs on parts of one
/// scene (decide_pairs; interfere-mpi): sorts the clashes by (test order, body a id, body b id,
/// id), derives the clash counts, the verdict and the pair summaries, sorts the frames x pairs
/// table, the reference verdicts and the depth maps and derives first frames, designed contacts and
/// the designed / new counts (when reference_checked), then the groups of options.group_by. The
/// result holds the runs' clashes, frame_pairs, reference_pairs and depth_maps with body indices
/// into `scene` (whose bodies need ids only) and zero counts.
void finish_result(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashOptions& options,
                   SceneClashResult& result);

/// The broad phase's conservative world box of a body with local bounds `local` under `pose` (the
/// 8 corners mapped, padded by a relative 2^-40 so that rounding in the vertices' own transforms
/// cannot leave it, rounded outward to float): clash_scene's candidate boxes.
AabbF broad_box(const Aabb& local, const Transform& pose);

/// One candidate of the broad phase: a body pair of a test (a's id < b's id) and the clearance the
/// test requires of it (its override, or the test's; 0 unless clearance mode).
struct CandidatePair {
  std::uint32_t test = 0, a = 0, b = 0;
  double clearance = 0;
};

/// clash_scene's broad phase (issue #24, item 3), also for callers that plan a distributed run
/// (interfere-mpi, issue #31) on body metadata alone: per test its selections, box trees over
/// their broad boxes (a BVH of boxes, built once and refitted for later configurations), the
/// pairs whose boxes grown by the test's margin (its largest clearance, or the duplicates
/// tolerance, rounded up to float) overlap by the traversal's float test (bvh/traverse.h), then
/// the suppression rules.
class BroadPhase {
 public:
  /// Selections of every test over `bodies` (ids, names, tags, paths, sources: meshes unused).
  BroadPhase(const std::vector<Body>& bodies, const std::vector<ClashTest>& tests);
  /// "clash test 'x': selection A selects no body" (and B), as clash_scene reports them.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The candidates for the bodies' broad boxes in one configuration (boxes[i]: body i's
  /// broad_box), in clash_scene's order (test, then body indices a, b), suppressed pairs left out;
  /// adds the candidates found and those suppressed to the counters.
  std::vector<CandidatePair> candidates(const std::vector<AabbF>& boxes, std::size_t& candidate_count,
                                        std::size_t& suppressed_count);

 private:
  const std::vector<Body>& bodies_;
  const std::vector<ClashTest>& tests_;
  std::vector<std::vector<std::uint32_t>> a_, b_;  // selected body indices per test (b empty: within a)
  std::vector<double> margin_;
  std::vector<Bvh> tree_a_, tree_b_;
  bool built_ = false;
  std::vector<std::string> warnings_;
};

/// What makes two candidate body pairs one problem, decided once by clash_scene (engine_frame.cpp:
/// pairs with the same two meshes in the same relative pose, bit for bit, decided in the first
/// body's local frame): the relative pose of b in a's frame as clash_scene computes it (the
/// identity when both poses are equal), row-major. With the two meshes, a caller can keep such
/// pairs in one run (interfere-mpi keeps one process's core_runs that way).
std::array<double, 12> relative_pose_key(const Transform& pose_a, const Transform& pose_b);

/// The world model of every body (pose applied, BVH built; statistics computed lazily by the
/// engine, not here), in parallel: what clash_scene prepares first, for callers that query bodies
/// themselves.
std::vector<Model> world_models(const Scene& scene);

}  // namespace interfere::scene
