// The distribution plan of `interfere-mpi clash` (issue #31, item 2; docs/mpi.md): from what every
// rank knows after the allgather (each body's metadata, world box and triangle count), the same
// deterministic broad phase on every rank, the candidate body pairs (work units), their estimated
// cost, and their partition into blocks and ranks. Pure functions, no MPI: unit-tested alone.
//
// A block is a set of bodies decided by one call of the scene engine (scene::clash_scene) on the
// sub-scene of those bodies, which decides every candidate pair among them; a body pair's clashes
// depend only on the two bodies (engine.h: ids, locations, continuity over frames are per pair), so
// a block gives the same clashes for its pairs as the whole scene does. Blocks never overlap in
// pairs (no pair is decided twice, nothing is filtered afterwards): a connected component of the
// candidate graph is a block; a component costing more than a share of a rank is cut into groups
// of bodies by the spatial (Morton) order of their box centres, each group a block (its pairs
// within), and each pair between two groups a block of its own two bodies, placed on the rank of
// one of its groups. A rank runs its blocks in as few engine calls as keep that property.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/scene.h"

namespace interfere::mpi {

/// The broad phase's conservative world box of a body (the engine's: the local box's 8 corners
/// under the pose, padded by a relative 2^-40, rounded outward to float).
AabbF broad_box(const Aabb& local, const Transform& pose);

/// One candidate body pair over every test and frame (a, b: global body indices, a's id < b's id).
struct Unit {
  std::uint32_t a = 0, b = 0;
  double cost = 0;       ///< estimated (plan_cost)
  std::uint32_t frames = 0;  ///< frames in which some test has it as a candidate
};

struct BroadResult {
  std::vector<Unit> units;  ///< sorted by (a, b)
  std::size_t candidate_pairs = 0;  ///< over tests and frames, as SceneClashResult::candidate_pairs
  std::size_t suppressed = 0;
  std::vector<std::string> warnings;  ///< selections that select nothing, as the engine words them
};

/// The broad phase over `bodies` (metadata only: ids, names, tags, ... for the selectors; meshes
/// unused) with `boxes[frame][body]` (one frame for a static scene): the engine's candidate rule
/// (engine.cpp: selections per test, boxes grown by the test's margin rounded up to float, the
/// traversal's float test bvh/traverse.h boxes_overlap, suppression rules), with the engine's own
/// box trees (src/scene/engine_internal.h build_box_tree) and traversal (for_each_overlap).
/// The first `uncounted` box sets (the reference configuration of deformed scenes) give units but
/// are not counted in candidate_pairs and suppressed, as the engine's reference pass.
BroadResult broad_phase(const std::vector<scene::Body>& bodies, const std::vector<scene::ClashTest>& tests,
                        const std::vector<std::vector<AabbF>>& boxes, std::size_t uncounted = 0);

/// Estimated cost of deciding a body pair in one frame (seconds, roughly): per pair, per triangle
/// of the two bodies (a fixed estimate; docs/scaling.md fits a model to measured times).
double pair_cost(std::uint64_t triangles_a, std::uint64_t triangles_b);

struct Block {
  std::vector<std::uint32_t> bodies;  ///< sorted global indices
  std::vector<std::uint32_t> units;   ///< sorted indices into BroadResult::units: every candidate pair among `bodies`
  double cost = 0;
};

struct Partition {
  std::vector<Block> blocks;
  std::vector<std::uint32_t> rank_of_block;
  std::vector<double> rank_cost;
  /// Per rank, its engine calls: blocks merged where the union of their bodies holds no pair of
  /// another rank (every whole component of a rank in one call; a cut component's blocks on a rank
  /// in one call when that holds, else one call each).
  std::vector<std::vector<Block>> calls;
};

/// Partitions the units over `ranks` (units' costs set): components as blocks, components costing
/// more than total / (4 ranks) cut by the Morton order of their bodies' box centres; groups to
/// ranks by longest processing time first, then each pair between groups (costliest first) to the
/// less loaded of its two groups' ranks, or to the least loaded rank when that one would pass the
/// mean load by 1 %. Deterministic.
Partition partition(const BroadResult& broad, const std::vector<AabbF>& boxes, std::size_t ranks);

/// FNV-1a (64 bits) of bytes, continuing from h.
std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes);

}  // namespace interfere::mpi
