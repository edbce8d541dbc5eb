// Pocket recognition on the AAG (issue #29, item 3), internal to src/cad: see pocket_recognition.cpp.
#pragma once
#include <cstdint>
#include <vector>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

struct PocketFeature {
  std::uint32_t floor = 0;
  std::vector<std::uint32_t> walls;  ///< sorted
};

/// Closed pockets of `aag` (split faces already merged): faces with `claimed[f]` set are no floor or
/// wall. Sorted by floor.
std::vector<PocketFeature> recognize_pockets(const Aag& aag, const std::vector<char>& claimed);

}  // namespace interfere::cad::detail
