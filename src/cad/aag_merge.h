// Faces split by the modeller merged into one AAG node (issue #6 item 3; shared by the pattern matching
// of features.cpp and the MAAG decomposition of maag.cpp, issue #29). Internal to src/cad.
#pragma once
#include <cstdint>
#include <vector>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

struct MergedAag {
  Aag aag;                                          ///< node g = merged face group g (AagNode::face = g)
  std::vector<std::uint32_t> group_of;              ///< input face -> group
  std::vector<std::uint32_t> rep;                   ///< group -> its smallest input face
  std::vector<std::vector<std::uint32_t>> members;  ///< group -> its input faces, sorted
};

/// Faces joined by a smooth arc and lying on the same plane/cylinder/cone/sphere (within
/// max(tolerance, 1e-6)) become one node; arcs inside a group are dropped.
MergedAag merge_split_faces(const Aag& input, double tolerance);

}  // namespace interfere::cad::detail
