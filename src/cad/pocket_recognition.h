// Floor features on the AAG (issue #29, item 1: pockets, slots, blind slots and steps), internal to
// src/cad: see pocket_recognition.cpp.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

struct FloorFeature {
  std::string type;                    ///< pocket, slot, blind_slot, through_step
  std::uint32_t floor = 0;
  std::vector<std::uint32_t> walls;    ///< every wall, sorted
  std::vector<std::uint32_t> sides;    ///< slot, blind_slot: the two opposite side walls (wall1, wall2)
  std::vector<std::uint32_t> ends;     ///< blind_slot: the closing end's walls (plane or round), sorted
  std::vector<std::uint32_t> fillets;  ///< floor fillets between the floor and its walls, sorted
};

/// The floor features of `aag` (split faces already merged) of the types in `types` (pocket, slot,
/// blind_slot, through_step): faces with `claimed[f]` set take no part. A floor belongs to one feature
/// and is no other's face (pockets first, then blind slots, slots, steps); walls and fillets may be
/// shared, but not all of them by two features of one type. Sorted by type, then floor.
std::vector<FloorFeature> recognize_floor_features(const Aag& aag, const std::vector<char>& claimed,
                                                   const std::set<std::string>& types);

/// The types recognize_floor_features can produce.
const std::set<std::string>& floor_feature_types();

}  // namespace interfere::cad::detail
