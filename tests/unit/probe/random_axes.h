// Test helper shared by the box-holder unit and CGAL oracle tests: a random rotation as three axes.
#pragma once
#include <array>
#include <cmath>
#include <random>

#include "interfere/core/vec.h"

namespace interfere::probe::test {

/// Random rotation (unit quaternion, Shoemake 1992) as three orthonormal right-handed axes.
inline std::array<Vec3, 3> random_axes(std::mt19937_64& g) {
  std::normal_distribution<double> n;
  double w = n(g), x = n(g), y = n(g), z = n(g);
  const double s = std::sqrt(w * w + x * x + y * y + z * z);
  w /= s, x /= s, y /= s, z /= s;
  return {Vec3{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
          Vec3{2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
          Vec3{2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
}

}  // namespace interfere::probe::test
