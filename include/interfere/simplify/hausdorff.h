// Approximation error of a simplification (issue #6, item 5) measured with the engine's BVH and
// closest-point queries (np/distance.h): one-sided distances from sample points of one mesh to the
// other mesh, and the symmetric Hausdorff distance (the larger of the two directions).
//
// Sampling: every vertex, every edge midpoint and every triangle centroid (a lower bound of the
// true Hausdorff distance that is tight where the error is largest at vertices, as it is for QEM).
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
  double symmetric() const { return a_to_b > b_to_a ? a_to_b : b_to_a; }
  std::size_t samples = 0;
};

/// Largest distance from the samples of `from` to the surface `to` (parallel, deterministic: max).
/// 0 when `from` is empty; +inf when `to` is empty and `from` is not.
double one_sided_distance(const TriMesh& from, const TriMesh& to, std::size_t* samples = nullptr);

HausdorffResult hausdorff(const TriMesh& a, const TriMesh& b);

/// Pairs of triangles of `mesh` that intersect without sharing a vertex position (the engine's
/// exact clash of the mesh against itself): 0 for a mesh free of self-intersections.
std::size_t count_self_intersections(const TriMesh& mesh);

/// The intersecting pairs themselves (triangle indices, smaller first), sorted. With `skip` (one
/// flag per triangle), pairs whose triangles are both flagged are not tested (a simplification's
/// result: triangles left as in the input, whose mutual intersections were the input's own).
std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs(
    const TriMesh& mesh, const std::vector<std::uint8_t>* skip = nullptr);

}  // namespace interfere
