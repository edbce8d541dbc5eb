// Small helpers shared by the assembly sources (assembly*.cpp): rigid transforms.
#pragma once
#include <cmath>

#include "interfere/core/transform.h"

namespace interfere::bearing::detail {

/// a after b: x -> a(b(x)).
inline Transform compose(const Transform& a, const Transform& b) {
  Transform out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.r[i][j] = a.r[i][0] * b.r[0][j] + a.r[i][1] * b.r[1][j] + a.r[i][2] * b.r[2][j];
  out.t = a.apply(b.t);
  return out;
}
inline Transform rotation_z(double a) {
  Transform t;
  const double c = std::cos(a), s = std::sin(a);
  t.r = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  return t;
}
inline Transform rotation_y(double a) {
  Transform t;
  const double c = std::cos(a), s = std::sin(a);
  t.r = {{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
  return t;
}
inline Transform translation(const Vec3& v) {
  Transform t;
  t.t = v;
  return t;
}

}  // namespace interfere::bearing::detail
