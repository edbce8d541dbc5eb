// Approximation error of a simplification (issue #6, item 5) measured with the engine's BVH and
// closest-point queries (np/distance.h): one-sided distances from sample points of one mesh to the
// other mesh, and the symmetric Hausdorff distance (the larger of the two directions).
//
// Sampling: every vertex used by a triangle, every edge midpoint and every triangle centroid (a lower bound of the
// true Hausdorff distance that is tight where the error is largest at vertices, as it is for QEM);
// from the same samples, an upper bound of the one-sided distance (OneSidedDistance::bound).
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "interfere/mesh/tri_mesh.h"

namespace interfere {

struct HausdorffResult {
  double a_to_b = 0;  ///< max over samples of A of the distance to B
  double b_to_a = 0;
  /// Upper bound of the distance from any point of A's surface to B (see OneSidedDistance::bound):
  /// what a conservative clash check of B in place of A needs.
  double a_to_b_bound = 0;
  double symmetric() const { return a_to_b > b_to_a ? a_to_b : b_to_a; }
  std::size_t samples = 0;
};

struct OneSidedDistance {
  double sampled = 0;  ///< the largest distance from a sample of `from` to `to`
  /// Upper bound of the distance from every point of `from`'s triangles to `to`, per triangle the
  /// smaller of (a) the largest corner or edge-midpoint distance plus (longest edge) / (2 sqrt 3)
  /// (the distance is 1-Lipschitz; the midpoint split leaves triangles whose points lie within half
  /// the longest edge / sqrt 3 of a corner) and (b) the largest corner distance to one triangle of
  /// `to` (convex: largest at a corner; the triangles nearest to its samples are tried) or to a
  /// convex planar region of `to` holding the corners' nearest triangles (plus the region's
  /// deviation and dents); where it exceeds `sampled` by 25 %, refined (more candidates, midpoint
  /// subdivision) worst triangle first, for at most 2048 + n/16 triangles: past that budget the
  /// next triangle's unrefined bound, which bounds all the rest (issue #23, item 12); plus 1e-9 of
  /// the meshes' joint extent for rounding. Never below `sampled`.
  double bound = 0;
  std::size_t samples = 0;
};

/// Distances from the samples of `from` to the surface `to` and, with_bound, the bound (else +inf)
/// (parallel, deterministic: maxima). 0 when `from` is empty; +inf when `to` is empty and `from` is
/// not.
OneSidedDistance one_sided(const TriMesh& from, const TriMesh& to, bool with_bound = true);

/// one_sided(from, to).sampled.
double one_sided_distance(const TriMesh& from, const TriMesh& to, std::size_t* samples = nullptr);

/// Both sampled directions and, with_bound, a_to_b_bound (else +inf: the bound costs about as much
/// again as the a -> b samples).
HausdorffResult hausdorff(const TriMesh& a, const TriMesh& b, bool with_bound = true);

/// Pairs of triangles of `mesh` that intersect without sharing a vertex position (the engine's
/// exact clash of the mesh against itself): 0 for a mesh free of self-intersections.
std::size_t count_self_intersections(const TriMesh& mesh);

/// The intersecting pairs themselves (triangle indices, smaller first), sorted. With `skip` (one
/// flag per triangle), pairs whose triangles are both flagged are not tested (a simplification's
/// result: triangles left as in the input, whose mutual intersections were the input's own).
std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs(
    const TriMesh& mesh, const std::vector<std::uint8_t>* skip = nullptr);

}  // namespace interfere
