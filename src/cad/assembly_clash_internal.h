// Internal (src/cad): the parts of assembly_clash (assembly_clash.cpp) kept in their own files.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interfere/cad/assembly_clash.h"
#include "interfere/query/model.h"

namespace interfere::cad::detail {


/// Per triangle of x that touches nothing of y (paired[t] == 0): the side of y its connected set
/// of such triangles lies on, which one vertex exactly off y's surface decides (point_in_solid:
/// 1 inside, 0 outside, -1 undecided); 0 for the paired ones (assembly_depth.cpp).
std::vector<signed char> untouched_sides(const Model& x, const Model& y, const std::vector<char>& paired);

/// How deep the surface of x reaches into the solid y, sampled (assembly_depth.cpp); paired[t]:
/// triangle t of x crosses or touches y; side: untouched_sides(x, y, paired).
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired,
                  const std::vector<signed char>& side);

/// An upper bound of how deep the surface of x reaches into the solid y (assembly_depth.cpp): branch
/// and bound over pieces of x's triangles until within 10 % of `lower` (the sampled depth) or
/// `max_splits` splits.
double depth_bound(const Model& x, const Model& y, const std::vector<char>& paired,
                   const std::vector<signed char>& side, double lower, std::size_t max_splits);

/// Whether the crossings of instances a and b (`r`, on their world models) are a nominal fit
/// (assembly_fit.cpp): every crossing pair has a face coinciding with one of the other part, and
/// the sampled depth is within the tessellation error.
bool nominal_fit(const CadModel& model, std::uint32_t a, std::uint32_t b,
                 const std::vector<Model>& world, const ClashResult& r, double depth,
                 double tessellation_error);

}  // namespace interfere::cad::detail
