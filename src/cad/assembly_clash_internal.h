// Internal (src/cad): the parts of assembly_clash (assembly_clash.cpp) kept in their own files.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interfere/cad/assembly_clash.h"
#include "interfere/query/depth.h"
#include "interfere/query/model.h"

namespace interfere::cad::detail {


/// Whether the crossings of instances a and b (`r`, on their world models) are a nominal fit
/// (assembly_fit.cpp): every crossing pair has a face coinciding with one of the other part, and
/// the sampled depth is within the tessellation error.
bool nominal_fit(const CadModel& model, std::uint32_t a, std::uint32_t b,
                 const std::vector<Model>& world, const ClashResult& r, double depth,
                 double tessellation_error);

}  // namespace interfere::cad::detail
