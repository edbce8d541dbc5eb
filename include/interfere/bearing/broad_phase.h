// Broad phases over the parts' boxes (Jia & Zheng 2019, §3.3 compares sweep-and-prune with a loose
// octree): all-pairs (brute force), sweep-and-prune with insertion sort on the previous frame's
// order (Baraff 1992; Cohen et al., I-COLLIDE 1995), a loose octree (Ulrich, "Loose octrees", Game
// Programming Gems 2000) and the project's BVH (bvh/bvh.h) refitted every frame.
// Every method returns the same sorted list of index pairs (i < j) whose closed boxes overlap.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "interfere/bearing/cylinder.h"

namespace interfere::bearing {

enum class BroadPhaseKind : std::uint8_t { brute_force, sweep_and_prune, loose_octree, bvh };
const char* broad_phase_name(BroadPhaseKind k);
bool parse_broad_phase(const std::string& name, BroadPhaseKind& out);

using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

/// A broad phase with state between frames (SAP order, BVH topology).
class BroadPhase {
 public:
  virtual ~BroadPhase() = default;
  /// Sorted pairs (i < j) of overlapping boxes.
  virtual std::vector<IndexPair> update(const std::vector<Box3>& boxes) = 0;
};

std::unique_ptr<BroadPhase> make_broad_phase(BroadPhaseKind kind);

}  // namespace interfere::bearing
