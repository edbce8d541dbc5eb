// How deep two crossing solids reach into each other (issue #24, item 3: the depth and depth bound
// that assembly-clash computed, now shared by every clash of the scene engine), and per vertex of
// each part (issue #26, item 3: penetration depth maps). OCCT-free.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
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

inline constexpr std::uint32_t kNoVertex = 0xffffffffu;

/// How deep each vertex of one part (x) lies inside the solid of the other (y) (issue #26, item 3).
struct DepthMap {
  /// Per vertex of x: its distance to y's surface when it lies strictly inside the solid y (exact
  /// ray parity), 0 otherwise (outside, on y's surface, undecided).
  std::vector<double> depth;
  /// Per vertex of x: 1 inside y, 0 outside or on y's surface, -1 undecided (y is open, or every
  /// ray of point_in_solid was degenerate): never a silent 0, see `undecided`.
  std::vector<signed char> side;
  double max_depth = 0;                 ///< the largest `depth` (0 when no vertex is inside)
  std::uint32_t max_vertex = kNoVertex;  ///< the smallest vertex index of depth max_depth; none when 0
  std::size_t inside = 0;                ///< vertices with side 1
  std::size_t undecided = 0;             ///< vertices with side -1
};

/// The two maps of a clash: a's vertices in b's solid, b's in a's.
struct DepthMaps {
  DepthMap a, b;
};

enum class DepthOf {
  a_in_b,  ///< the vertices of the clash's part a (its first model) against the solid b
  b_in_a,  ///< the vertices of part b against the solid a
};

struct DepthMapRequest {
  /// Where the parts' statistics (closedness) come from, as ClashRequest::stats: unset, the
  /// models' own (Model::stats, which make_model(.., with_stats = false) leaves empty, i.e. open);
  /// set, called with 0 (a) or 1 (b) for the solid the vertices are tested against.
  std::function<const MeshStats&(int side)> stats;
};

/// Per vertex of one part of the clash r of (a, b) (a is r's first part, as for clash(a, b)), its
/// depth in the other part's solid. Vertices outside the solid's bounding box are outside without
/// a test; vertices of x's triangles that meet nothing of y (no pair in r) take the side of their
/// connected set of such triangles (one point_in_solid per set, as detail::untouched_sides); the
/// vertices of triangles that cross or touch y each get their own point_in_solid. Inside vertices
/// are measured with nearest_triangle_d2 (exact nearest triangle, floating-point distance). An
/// open solid leaves every vertex in its box undecided (-1). r may hold no pair at all (disjoint,
/// or one part inside the other: the containment case, whole sets inside). Cost: O(V) passes over
/// x's vertices and triangles, one ray per set and per crossing vertex, one nearest-triangle search
/// per inside vertex (seeded by the previous one's triangle).
DepthMap depth_map(const Model& a, const Model& b, const ClashResult& r, DepthOf of,
                   const DepthMapRequest& request = {});
/// Both maps (depth_map with a_in_b and b_in_a).
DepthMaps depth_maps(const Model& a, const Model& b, const ClashResult& r, const DepthMapRequest& request = {});

/// Depth of closed parts a and b whose surfaces cross or touch while their solids overlap (r: their
/// clash; an empty result without surface pairs). Both closed: the side tests use point_in_solid.
/// `maps`, when given, receives depth_maps(a, b, r) (both closed), computed once and shared with the
/// sampled depth (whose vertex samples are exactly the maps' inside vertices): also for a clash
/// without surface pairs (containment), where the depth itself stays 0.
PenetrationDepth penetration_depth(const Model& a, const Model& b, const ClashResult& r, std::size_t max_splits,
                                   DepthMaps* maps = nullptr);

namespace detail {
/// Per triangle of x that touches nothing of y (paired[t] == 0): the side of y its connected set of
/// such triangles lies on (point_in_solid of one vertex: 1 inside, 0 outside, -1 undecided); 0 for
/// the paired ones.
std::vector<signed char> untouched_sides(const Model& x, const Model& y, const std::vector<char>& paired);
/// The engine of depth_map, for a closed y: x's vertices classified and measured against y, given
/// the triangles of x that meet y (`paired`) and untouched_sides(x, y, paired) (`side`).
DepthMap depth_map(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side);
/// Sampled depth of x's surface in the solid y (see PenetrationDepth::depth): the largest of
/// map.max_depth (map: depth_map(x, y, paired, side)) and the depths of the inside middles of the
/// stretches of the crossing triangles' edges between their crossings of y's surface.
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired, const DepthMap& map);
/// The same, the map computed here.
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side);
/// Upper bound of x's reach into y (see PenetrationDepth::depth_bound). `map`, when given, is
/// depth_map(x, y, paired, side): its inside vertices' distances spare their searches where a
/// triangle's Lipschitz bound already stays within `lower` (such a triangle cannot raise the
/// bound, so it is not kept; the result is the same as without the map).
double depth_bound(const Model& x, const Model& y, const std::vector<char>& paired, const std::vector<signed char>& side,
                   double lower, std::size_t max_splits, const DepthMap* map = nullptr);
}  // namespace detail

}  // namespace interfere
