// Minimum distance between two parts with witness points (issue #2, item 5).
#pragma once
#include <cstdint>

#include "interfere/query/model.h"

namespace interfere {

struct DistanceRequest {
  double upper_bound = 0;  ///< > 0: stop searching beyond this distance (result.distance may be +inf)
};

struct DistanceResult {
  bool intersecting = false;  ///< surfaces intersect (exact test); distance is then 0
  double distance = 0;
  Vec3 point_a, point_b;      ///< witness points on A and B
  std::uint32_t triangle_a = 0, triangle_b = 0;
};

DistanceResult distance(const Model& a, const Model& b, const DistanceRequest& request = {});

/// The distance from the point p to the surface of m (the nearest triangle, by the BVH; +inf for
/// an empty part). Floating point: the closest point on each triangle as np/distance.h computes it.
double surface_distance(const Model& m, const Vec3& p);

inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;

/// Squared distance from p to the nearest triangle of `mesh` (its BVH `bvh`), and that triangle
/// (+inf, `tri` untouched, for an empty mesh). With stop_d2 >= 0 the search ends at the first
/// triangle found within sqrt(stop_d2) (its squared distance, an upper bound of the nearest's, is
/// returned): exact whenever the nearest is farther. `seed`: a triangle likely near p (a nearby
/// sample's), tried first: it may end the search at once (within stop_d2) and otherwise prunes it;
/// the exact result is the same. surface_distance and the simplification's Hausdorff measure use it.
/// `owner`: for a tree built over pieces of the triangles (bvh.prims number pieces, each box
/// covering its piece), owner[piece] is the triangle of `mesh` it belongs to; distances are always
/// to whole triangles, so the result is the same as with a tree over the triangles.
double nearest_triangle_d2(const TriMesh& mesh, const Bvh& bvh, const Vec3& p, std::uint32_t* tri = nullptr,
                           double stop_d2 = -1, std::uint32_t seed = kNoTriangle,
                           const std::uint32_t* owner = nullptr);

}  // namespace interfere
