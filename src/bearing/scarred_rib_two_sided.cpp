// The rib rows of scarred rollers, two-sided (scarred_rib_two_sided.h; issue #27).
#include "scarred_rib_two_sided.h"

#include <algorithm>
#include <cmath>

#include "raceway_detail.h"

namespace interfere::bearing::detail {

bool scarred_rib_two_sided(const PairDistance& d, const Rib& rib, double thickness, std::span<const Cylinder> ends,
                           const Cylinder& middle) {
  if (d.path == AnalyticPath::apart || !std::isfinite(d.distance)) return false;  // (a bound)
  if (d.distance <= 0) {
    // fwd = r_f at the witness (its depth in the rib block's meridian rectangle); rev <= r_f always
    const double rf = -d.distance;
    const double rho = norm(cross(d.point_a - rib.center, rib.axis));
    return rf <= rib.outer_radius - rho && 2 * rf <= thickness;
  }
  // apart: the lowest point of every piece (a rim point: centre.n - r sqrt(1 - (n.axis)^2); the pieces
  // share the roller's axis) not below v
  double low = lowest_height(middle, rib.center, rib.normal);
  for (const Cylinder& c : ends) low = std::min(low, lowest_height(c, rib.center, rib.normal));
  const Vec3 m = middle.center();
  const double scale = std::max({std::fabs(m.x), std::fabs(m.y), std::fabs(m.z)}) + middle.height + middle.max_radius() +
                       rib.outer_radius;
  return low >= d.distance - 0x1p-44 * scale;
}

}  // namespace interfere::bearing::detail
