// Axis-aligned boxes: exact double boxes, and compact float boxes rounded outward so that a float box
// always contains the double geometry it bounds (ARCHITECTURE.md: BVH boxes may be float, rounded outward).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/core/vec.h"

namespace interfere {

struct Aabb {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void expand(const Vec3& p) { lo = min(lo, p), hi = max(hi, p); }
  void expand(const Aabb& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
  Vec3 center() const { return (lo + hi) * 0.5; }
  Vec3 extent() const { return hi - lo; }
  bool overlaps(const Aabb& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
           lo.z <= b.hi.z && b.lo.z <= hi.z;
  }
  bool contains(const Vec3& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
};

/// Float box; `lo`/`hi` are rounded toward -inf/+inf from the double box they were made from.
struct AabbF {
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()};

  void expand(const AabbF& b) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
  }
  bool overlaps(const AabbF& b) const {
    return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] &&
           lo[2] <= b.hi[2] && b.lo[2] <= hi[2];
  }
  float surface_area() const {
    const float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return 2.0f * (dx * dy + dy * dz + dz * dx);
  }
  float volume() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

/// Largest float <= v.
inline float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
/// Smallest float >= v.
inline float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

inline AabbF to_float_outward(const Aabb& b) {
  AabbF f;
  for (int k = 0; k < 3; ++k) f.lo[k] = round_down(b.lo[k]), f.hi[k] = round_up(b.hi[k]);
  return f;
}

}  // namespace interfere
