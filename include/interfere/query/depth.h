// How deep two crossing solids reach into each other (issue #24, item 3: the depth and depth bound
// that assembly-clash computed, now shared by every clash of the scene engine). OCCT-free.
#pragma once
#include <cstddef>
#include <vector>

#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere {

struct PenetrationDepth {
  /// The largest distance to the other surface of sampled points of either surface that lie inside
  /// the other solid (exact ray parity): a lower bound of the true depth, 0 when no sample is inside.
  double depth = 0;
  /// An upper bound of that depth over every point of either surface inside the other solid (branch
  /// and bound, 1-Lipschitz distance), within 10 % of `depth` or looser after `max_splits` splits per
  /// direction; equal to `depth` when max_splits is 0 (no bound computed: `bounded` false).
  double depth_bound = 0;
  bool bounded = false;
};

/// Depth of closed parts a and b whose surfaces cross or touch while their solids overlap (r: their
/// clash; an empty result without surface pairs). Both closed: the side tests use point_in_solid.
PenetrationDepth penetration_depth(const Model& a, const Model& b, const ClashResult& r, std::size_t max_splits);

namespace detail {
/// Per triangle of x that touches nothing of y (paired[t] == 0): the side of y its connected set of
/// such triangles lies on (point_in_solid of one vertex: 1 inside, 0 outside, -1 undecided); 0 for
/// the paired ones.
std::vector<signed char> untouched_sides(const Model& x, const Model& y, const std::vector<char>& paired);
/// Sampled depth of x's surface in the solid y (see PenetrationDepth::depth).
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side);
/// Upper bound of x's reach into y (see PenetrationDepth::depth_bound).
double depth_bound(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side,
                   double lower, std::size_t max_splits);
}  // namespace detail

}  // namespace interfere
