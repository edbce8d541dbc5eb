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

}  // namespace interfere
