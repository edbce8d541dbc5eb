// Internals of the scene clash engine (src/scene/engine*.cpp; include/interfere/scene/engine.h).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"
#include "interfere/query/model.h"
#include "interfere/scene/engine.h"

namespace interfere::scene::detail {

/// A BVH over boxes (one primitive per box, prims = box indices), built by median splits of the
/// longest axis (deterministic), in the layout of bvh.h so the tree traversals apply; refit keeps
/// the topology and recomputes every box (body_tree.cpp).
Bvh build_box_tree(const std::vector<AabbF>& boxes);
void refit_box_tree(Bvh& tree, const std::vector<AabbF>& boxes);

/// Whether selections x and y select bodies p and q (either way round), and the clearance a test
/// requires of a pair (its override's, or the test's) (engine_broad.cpp).
bool pair_matches(const Selection& x, const Selection& y, const Body& p, const Body& q);
double pair_clearance(const ClashTest& t, const Body& p, const Body& q);

/// Sorts result.clashes by test, body ids and clash id, and derives from them the counts, the
/// verdict and the per-pair summaries (engine.cpp; finish_result).
void sort_and_summarise(const Scene& scene, const std::vector<ClashTest>& tests, SceneClashResult& result);

/// A body in the current frame: its world model (statistics computed at most once, on demand).
struct WorldBody {
  Model own;                          ///< built and moved by the engine
  const Model* prebuilt = nullptr;    ///< Body::world_model, used as is
  Aabb box;                           ///< exact world bounds
  const Model& model() const { return prebuilt ? *prebuilt : own; }
  std::unique_ptr<std::once_flag> stats_once = std::make_unique<std::once_flag>();
  MeshStats lazy_stats;
  const MeshStats& stats();
};

/// The two models a body pair is decided on, in its decision frame (engine_frame.cpp; issue #24,
/// item 9): body a's own local frame when a's pose is a rotation (a's local model, shared by every
/// body with its mesh, and b's moved by T = inv(T_a)·T_b), so that pairs in the same relative pose
/// are one problem, bit for bit; else the world (both bodies' world models).
struct PairFrame {
  const Model* a = nullptr;
  const Model* b = nullptr;
  std::function<const MeshStats&(int side)> stats;  ///< of a (0) and b (1), computed once on demand
  Aabb box_a, box_b;                                ///< exact bounds of the two models in the frame
  std::array<Transform, 2> to_frame;  ///< a's and b's local frame -> the decision frame
  std::array<Transform, 2> to_local;  ///< the decision frame -> a's and b's local frame
  bool world = true;                  ///< the decision frame is the world
};

/// Everything pair evaluation needs besides the two bodies' models.
struct PairContext {
  const Scene& scene;
  const ClashTest& test;
  std::size_t test_index;
  const SceneClashOptions& options;
  /// The current local positions of a body (its mesh's, or a frame's shape).
  std::function<const std::vector<Vec3>&(std::uint32_t)> local_positions;
  /// Many pairs run side by side: a small pair's core runs on one thread (no nested tasks; the
  /// core's result does not depend on it), a large one stays parallel inside.
  bool many_pairs = false;
  /// Splits per direction of the depth bound for this evaluation (SceneClashOptions::depth_bound_splits,
  /// or frame_depth_bound_splits in frames where no test has a penetration tolerance).
  std::size_t depth_bound_splits = 5000;
};

/// The exact core's answer for bodies a and b at one clearance (the largest any test of the pair
/// needs), with the depth of crossing closed bodies: computed once per body pair and frame, and
/// every test of the pair derives its clashes from it (derive_pair).
struct PairCore {
  ClashResult r;
  double clearance = 0;  ///< the clearance r's pairs are within (narrowed by derive_pair)
  PenetrationDepth depth;
  bool depth_known = false;
  /// SceneClashOptions::depth_maps: per vertex of each body, its depth in the other's solid
  /// (query/depth.h), for crossing, touching-overlap and containment clashes of closed bodies.
  DepthMaps maps;
  bool maps_known = false;
};
PairCore core_pair(const PairContext& c, const PairFrame& f, std::uint32_t a, std::uint32_t b, double clearance);
/// The clashes of one test from the core's answer at a clearance >= this test's: the clearance
/// pairs at or beyond `clearance` are dropped (the exact core reports the same crossing, touching
/// and clearance pairs with the same distances at any larger clearance; its verdict is clearance
/// only through them), so derive from the largest clearance first. core may be null in duplicates
/// mode (no core needed). Geometry (boxes, points, curves, witnesses) is in f's frame; curves are
/// kept whatever SceneClashOptions::curves says when the frame is not the world (place_clashes
/// needs them for tight world boxes).
std::vector<SceneClash> derive_pair(const PairContext& c, const PairFrame& f, std::uint32_t a, std::uint32_t b,
                                    double clearance, PairCore* core, std::vector<std::array<Vec3, 2>>& locations);

/// The id locations of derive_pair: per clash, the locations its id hashes, in a's and in b's
/// local frame: the middle of the box of its intersection curves; of the common parts of its
/// touching triangles' boxes; of every witness segment within the clearance; the inner body's box;
/// a's box.

/// The source ids of a clash's triangles from its bodies (Body::source_id), sorted and unique.
void set_sources(SceneClash& c, const Body& a, const Body& b);
/// The reason of an "inside" clash.
std::string inside_reason(const Body& inner, const Body& outer);

/// Decision frames (engine_frame.cpp). b's model in a's frame: b's local model moved by t (its
/// winding turned when t mirrors), its tree the local tree refitted (same topology).
Model moved_model(const Model& local_b, const Transform& t);
/// Clashes decided in body a's local frame, mapped to the world by a's rigid pose: points,
/// witnesses and curves moved; a box from its moved curve points or witnesses where it has them
/// (tight as in the world), else the world box of its frame box's corners (exact for axis-aligned
/// poses, conservative otherwise); curves dropped unless kept.
void place_clashes(std::vector<SceneClash>& list, const Transform& pose_a, bool keep_curves);
/// Clashes derived for one body pair (rep_a, rep_b) given to another pair (a, b) with the same
/// models in the same relative pose: body indices, the inside reason, source ids.
void rehome(std::vector<SceneClash>& list, const Scene& scene, std::uint32_t rep_a, std::uint32_t rep_b,
            std::uint32_t a, std::uint32_t b);

/// The id of a clash: test name, body ids and its locations in a's and b's local frames quantised
/// at `grid` (clash_id.cpp).
std::string clash_id(const std::string& test, const std::string& id_a, const std::string& id_b,
                     const std::array<Vec3, 2>& local, double grid);
std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes);

}  // namespace interfere::scene::detail

namespace interfere::scene::detail {
/// Fills result.groups by options.group_by (engine_groups.cpp).
void group_clashes(SceneClashResult& result, const SceneClashOptions& options);
}  // namespace interfere::scene::detail

namespace interfere::scene::detail {
/// Sorts the frames x pairs table and the reference pairs, and derives from them each pair's first
/// (clashing) frame and reference verdict, each contact's `designed` flag and the designed / new
/// counts (engine_frames.cpp; issue #26, items 2 and 4).
void summarise_frames(const Scene& scene, const std::vector<ClashTest>& tests, SceneClashResult& result);
/// The sparse depth maps of bodies a and b in one frame and their deepest vertex (node and element
/// ids from the bodies' sources, the point in the world from `point`: body, vertex) (engine_frames.cpp).
PairDepthMap pair_depth_map(const Scene& scene, const std::function<Vec3(std::uint32_t, std::uint32_t)>& point,
                            std::uint32_t frame,
                            std::uint32_t a, std::uint32_t b, const DepthMaps& maps);
/// Keeps the deeper of two deepest points (ties: the earlier frame, then body, then vertex).
void keep_deeper(bool& has, DeepestPoint& kept, const DeepestPoint& candidate);
}  // namespace interfere::scene::detail
