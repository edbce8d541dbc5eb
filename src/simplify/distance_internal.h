// Internals of the distance measurements of simplify/hausdorff.h (issue #6, items 5-6): the
// nearest-triangle query on the engine's BVH and the per-triangle samples (hausdorff.cpp), and the
// upper bound of the distance from a triangle to a mesh (distance_bound.cpp). Not installed.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/query/distance.h"

namespace interfere::detail {

inline constexpr std::uint32_t kNoSeed = kNoTriangle;  // (query/distance.h)

/// A distance at a point and the triangle of `to` nearest to it.
struct Near {
  double d = 0;  ///< distance (not squared)
  std::uint32_t tri = 0;
};

/// Of two samples, the nearer (its triangle seeds the search at a point between them).
inline const Near& nearer(const Near& x, const Near& y) { return x.d <= y.d ? x : y; }

Near nearest(const TriMesh& to, const Bvh& bvh, const Vec3& p, double stop_d2 = -1, std::uint32_t seed = kNoSeed);

/// One triangle c of `from` with its samples: distances at the corners, edge midpoints (m[k] on
/// edge k, k+1) and centroid, each with its nearest triangle of `to`.
struct Sampled {
  std::array<Vec3, 3> c, m;
  std::array<Near, 3> at, mid;
  Near centre;
  double max_sample() const;
};

/// The samples of triangle c whose corners' distances `at` (and, if given, edge midpoints' `mid`)
/// are known; the others' searches stop as nearest_triangle_d2's at stop_d2.
Sampled sample(const TriMesh& to, const Bvh& bvh, const std::array<Vec3, 3>& c, const std::array<Near, 3>& at,
               const std::array<Near, 3>* mid = nullptr, double stop_d2 = -1);

/// Upper bound of the distance from every point of triangle s.c to `to` (distance_bound.cpp),
/// computed lazily down to `floor` (a bound at or below it is not improved).
double local_bound(const TriMesh& to, const Sampled& s, double floor);

/// The triangles of a mesh around each vertex (compressed rows).
struct Fans {
  std::vector<std::uint32_t> start, tris;
};
Fans fans_of(const TriMesh& m);

/// local_bound with more candidates: every triangle around the vertices of the samples' nearest
/// ones (an input triangle over a vertex of the output where several meet).
double ring_bound(const TriMesh& to, const Fans& fans, const Sampled& s, double floor);

/// local_bound refined by midpoint subdivision (depth levels) where it exceeds `floor`.
double refined_bound(const TriMesh& to, const Bvh& bvh, const Sampled& s, double floor, int depth);

}  // namespace interfere::detail
