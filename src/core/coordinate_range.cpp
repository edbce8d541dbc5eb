// The supported coordinate range (see interfere/core/coordinate_range.h for the bounds and why).
#include "interfere/core/coordinate_range.h"

#include <charconv>
#include <cmath>

namespace interfere {

std::size_t first_out_of_range(std::span<const Vec3> points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!coordinates_in_range(points[i])) return i;
  return points.size();
}

std::string coordinate_range_reason(const Vec3& p) {
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    const double v = p[k];
    if (coordinate_in_range(v)) continue;
    std::string what;
    if (std::isnan(v)) {
      what = "NaN";
    } else if (std::isinf(v)) {
      what = v > 0 ? "inf" : "-inf";
    } else {
      char b[32];
      const auto end = std::to_chars(b, b + sizeof b, v).ptr;  // shortest text that reads back as v
      what.assign(b, end);
    }
    return std::string(kAxis[k]) + " = " + what +
           " is outside the supported coordinate range (0, or 2^-250 <= |x| <= 2^100: about 5.5e-76 "
           "to 1.3e+30 in any unit; see docs/robustness.md, 'Coordinate range')";
  }
  return {};
}

Status check_coordinate_range(std::span<const Vec3> points, const std::string& file,
                              const std::string& what, std::size_t index_base) {
  const std::size_t i = first_out_of_range(points);
  if (i == points.size()) return {};
  return Error{.file = file,
               .reason = what + " " + std::to_string(i + index_base) + ": " +
                         coordinate_range_reason(points[i])};
}

}  // namespace interfere
