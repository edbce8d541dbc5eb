// Hole recognition on the AAG (issue #29, item 1), internal to src/cad: see hole_recognition.cpp.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "interfere/cad/features.h"

namespace interfere::cad::detail {

struct HoleFeature {
  Feature feature;                   ///< face ids of the AAG given
  std::vector<std::uint32_t> owned;  ///< its own faces (walls, seats, floors), sorted; not the entry/exit faces
};

/// Holes of the types in `types` (through_hole, blind_hole, counterbored_hole, counterdrilled_hole,
/// countersunk_hole, stepped_hole; a counterdrilled hole missing there is counterbored; a type missing there falls back to through_hole/blind_hole), sorted by smallest face.
std::vector<HoleFeature> recognize_holes(const Aag& aag, const std::set<std::string>& types);

/// The hole types recognize_holes can produce.
const std::set<std::string>& hole_types();

}  // namespace interfere::cad::detail
