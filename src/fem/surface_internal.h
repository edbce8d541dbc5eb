// Internal interface between the surface extraction sources (src/fem/surface*.cpp).
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "interfere/fem/surface.h"

namespace interfere::fem_detail {

inline constexpr std::uint32_t kNoPart = std::numeric_limits<std::uint32_t>::max();

struct PartAssignment {
  std::vector<std::uint32_t> part;  ///< per element; kNoPart for points and lines
  std::vector<std::string> names;
  std::vector<std::int32_t> groups;
};

/// `split` automatic resolves to by_group when an element with a surface has a group, else
/// connectivity.
PartAssignment assign_parts(const FemMesh& mesh, PartSplit split);

}  // namespace interfere::fem_detail
