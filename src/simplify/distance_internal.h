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
inline const Near& nearer(const Near& x, const Near& y) {
  return x.d <= y.d ? x : y;
}

/// The search tree of `to` (piece_bvh.cpp): the BVH over pieces of its sliver triangles (owner:
/// the triangle of each piece) or, without slivers, over its triangles (owner empty).
struct PieceBvh {
  Bvh bvh;
  std::vector<std::uint32_t> owner;
  const std::uint32_t* owners() const { return owner.empty() ? nullptr : owner.data(); }
};
PieceBvh piece_bvh(const TriMesh& to, std::size_t max_pieces);

/// nearest_triangle_d2 on that tree, as a distance.
Near nearest(const TriMesh& to, const PieceBvh& bvh, const Vec3& p, double stop_d2 = -1,
             std::uint32_t seed = kNoSeed);

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
Sampled sample(const TriMesh& to, const PieceBvh& bvh, const std::array<Vec3, 3>& c,
               const std::array<Near, 3>& at, const std::array<Near, 3>* mid = nullptr,
               double stop_d2 = -1);

/// The triangles of a mesh around each vertex (compressed rows).
struct Fans {
  std::vector<std::uint32_t> start, tris;
};
Fans fans_of(const TriMesh& m);

/// Convex planar regions of a mesh (planar_regions.cpp): edge-connected, consistently oriented
/// triangles in one plane (within a measured deviation) whose union is a convex polygon.
struct ConvexRegions {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> of;  ///< per triangle: its region, or kNone (in none of two or more)
  std::vector<double> slack;      ///< per region: what region_bound adds (twice the deviation)
  std::vector<std::uint32_t>
      neighbour;  ///< per triangle edge k (corner k to k + 1): the triangle across a manifold,
                  ///< consistently oriented edge, or kNoSeed
};
ConvexRegions convex_planar_regions(const TriMesh& m);

/// What the bounds of a triangle of `from` need of `to`.
struct BoundContext {
  const TriMesh& to;
  const PieceBvh& bvh;
  const Fans& fans;
  const ConvexRegions& regions;
};

/// Upper bound of the distance from every point of the triangle with corners c to `to` through a
/// convex planar region (planar_regions.cpp) holding the corners' nearest triangles (at: each at
/// distance at[k].d from c[k]) or, for a corner whose nearest is outside it, a triangle of it
/// across an edge or around a vertex of that nearest one: the largest such corner distance plus
/// the region's slack. +inf where no region serves all three corners.
double region_bound(const BoundContext& ctx, const std::array<Vec3, 3>& c,
                    const std::array<Near, 3>& at);

/// Upper bound of the distance from every point of triangle s.c to `to` (distance_bound.cpp),
/// computed lazily down to `floor` (a bound at or below it is not improved).
double local_bound(const BoundContext& ctx, const Sampled& s, double floor);

/// local_bound with more candidates: every triangle around the vertices of the samples' nearest
/// ones (an input triangle over a vertex of the output where several meet).
double ring_bound(const BoundContext& ctx, const Sampled& s, double floor);

/// local_bound refined by midpoint subdivision (depth levels) where it exceeds `floor`; the new
/// samples' searches stop as nearest_triangle_d2's at stop_d2.
double refined_bound(const BoundContext& ctx, const Sampled& s, double floor, int depth,
                     double stop_d2 = -1);

}  // namespace interfere::detail
