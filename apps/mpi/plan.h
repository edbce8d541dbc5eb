// The distribution plan of `interfere-mpi clash` (issue #31, item 2; docs/mpi.md): from what every
// rank knows after the allgather (each body's metadata, world box, triangle count and mesh key),
// the same deterministic broad phase on every rank (the engine's own: scene::BroadPhase), the
// candidate body pairs (work units), their estimated cost (CostModel, fitted to measured ranks:
// docs/scaling.md) and their partition over the ranks. Pure functions, no MPI: unit-tested alone.
//
// Each rank then runs the scene engine once on the bodies its pairs need, deciding exactly its
// pairs (scene::SceneClashOptions::decide_pairs): no pair is decided twice, nothing is filtered
// afterwards. A body pair's clashes depend only on its two bodies (engine.h: ids, locations,
// continuity over frames are per pair), so a rank gives the same clashes for its pairs as the
// whole scene does. Pairs the engine decides once (the same two meshes in the same relative pose:
// a product's repeated joints) are kept on one rank, so the ranks' core runs add up to one
// process's.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/scene.h"

namespace interfere::mpi {

/// The broad phase's conservative world box of a body (scene::broad_box, the engine's).
AabbF broad_box(const Aabb& local, const Transform& pose);

/// One candidate body pair over every test and frame (a, b: global body indices, a's id < b's id).
struct Unit {
  std::uint32_t a = 0, b = 0;
  double cost = 0;           ///< estimated seconds (CostModel::pair over its frames)
  std::uint32_t frames = 0;  ///< frames in which some test has it as a candidate
  std::uint32_t item = 0;    ///< its class group (join_classes): units of one item go to one rank
};

struct BroadResult {
  std::vector<Unit> units;  ///< sorted by (a, b)
  std::size_t candidate_pairs = 0;  ///< over tests and frames, as SceneClashResult::candidate_pairs
  std::size_t suppressed = 0;
  std::vector<std::string> warnings;  ///< selections that select nothing, as the engine words them
};

/// The broad phase over `bodies` (metadata only: ids, names, tags, ... for the selectors; meshes
/// unused) with `boxes[frame][body]` (one frame for a static scene): scene::BroadPhase, the
/// engine's own (trees built for the first box set, refitted for the others, as clash_scene).
/// The first `uncounted` box sets (the reference configuration of deformed scenes) give units but
/// are not counted in candidate_pairs and suppressed, as the engine's reference pass. Every unit
/// is its own item until join_classes.
BroadResult broad_phase(const std::vector<scene::Body>& bodies, const std::vector<scene::ClashTest>& tests,
                        const std::vector<std::vector<AabbF>>& boxes, std::size_t uncounted = 0);

/// Joins into one item the units the engine decides once as a class (engine.h, relative_pose_key):
/// the same two mesh keys and the same relative pose, bit for bit, in some configuration
/// (`poses[config][body]`; every configuration is compared, a superset of the engine's rule, so
/// an item may be larger than needed, never split). An item's units go to one rank, whose single
/// engine call decides the class once, as one process does.
void join_classes(BroadResult& broad, const std::vector<std::uint64_t>& mesh_key,
                  const std::vector<std::vector<Transform>>& poses);

/// Estimated seconds of the engine's work (docs/scaling.md fits the coefficients to every rank's
/// measured engine time: tools/mpi_scaling.py): per candidate pair and frame, per triangle of its
/// two bodies and frame, and per triangle of every body a rank holds (its model and tree built
/// once, its statistics).
struct CostModel {
  // Defaults: the fit of docs/scaling.md of 2026-11-29 16:13 UTC (engine and read CPU seconds of
  // the 10^5-body product and two sphere swarms at K = 1, 2; the pair-triangle term came out 0;
  // its runs used the previous defaults, 2.34e-5, 0, 1.3e-6, 4.57e-7, 3.5e-6).
  double pair_s = 1.81e-5;
  double pair_tri_s = 0;
  double body_tri_s = 1.4e-6;
  double read_tri_s = 5.03e-7;  ///< reading a body a rank did not read in the first step
  /// Work rank 0 does after its engine call and before the others' findings arrive, per candidate
  /// pair (unit) of the scene: its run of the curve is that much shorter. Default 0: rank 0's
  /// merge needs every rank's findings, so it starts only when the last rank ends (the gather);
  /// a shorter run for rank 0 only made it wait (10^5-body product, K = 2, 17:18 UTC: rank 0's
  /// engine ended 1.6 s before rank 1's, then it merged for 1.5 s). Since the merge got cheap
  /// (binary findings, rank 0's own not encoded: issue #31) the job is the balanced engine runs
  /// plus that short merge. Until then: 4.23e-6 (rank 0's merge CPU seconds per pair, K = 1).
  double merge_pair_s = 0;
  double pair(std::uint64_t triangles_a, std::uint64_t triangles_b) const {
    return pair_s + pair_tri_s * static_cast<double>(triangles_a + triangles_b);
  }
  double body(std::uint64_t triangles) const { return body_tri_s * static_cast<double>(triangles); }
  double read(std::uint64_t triangles) const { return read_tri_s * static_cast<double>(triangles); }
  double merge(std::size_t units) const { return merge_pair_s * static_cast<double>(units); }
};

/// The estimated cost of a pair in one frame by the default model (CostModel{}.pair).
double pair_cost(std::uint64_t triangles_a, std::uint64_t triangles_b);

struct Partition {
  std::vector<std::vector<std::uint32_t>> rank_units;   ///< per rank: sorted indices into BroadResult::units
  std::vector<std::vector<std::uint32_t>> rank_bodies;  ///< per rank: the bodies its units need (sorted)
  std::vector<double> rank_cost;  ///< per rank: its units' costs + its bodies' (CostModel::body)
  std::size_t pieces = 0;         ///< runs of the curve and giants placed
};

/// Partitions the units over `ranks` by estimated cost with locality: items (class groups) whole,
/// each weighing its cost and a share of its bodies' (each body's CostModel::body split among the
/// items that touch it). Items lie on a space-filling curve: grouped by the rank that read their
/// first body in step 2 (`reader`, optional), then by the Morton order (box centres) of that body,
/// a connected component costing at most total / (4 ranks) at its first body's place (kept
/// together). An item heavier than the mean of what is left gets a rank of its own (one huge pair
/// dominating); the curve is cut into runs of about equal weight over the other ranks, so a body's
/// pairs mostly lie in one run and a rank holds a compact region of bodies (those at the runs'
/// borders are held twice). rank_cost: each rank's items, its bodies' CostModel::body, and the
/// read of bodies it did not read in step 2. `first_extra`: seconds rank 0 works beyond its items
/// (merging every rank's findings: CostModel::merge), so its run of the curve is that much shorter
/// (not counted in rank_cost). Deterministic.
Partition partition(const BroadResult& broad, const std::vector<AabbF>& boxes, const std::vector<std::uint64_t>& triangles,
                    const CostModel& model, std::size_t ranks, const std::vector<std::uint32_t>& reader = {},
                    double first_extra = 0);

/// FNV-1a (64 bits) of bytes, continuing from h.
std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes);

}  // namespace interfere::mpi
