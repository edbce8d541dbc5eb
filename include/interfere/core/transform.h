// Rigid (or general affine) part pose: p' = R·p + t evaluated in double, row-major [R|t].
#pragma once
#include <array>
#include <string>
#include <string_view>

#include "interfere/core/error.h"
#include "interfere/core/vec.h"

namespace interfere {

struct Transform {
  std::array<std::array<double, 3>, 3> r{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3 t{};

  static Transform identity() { return {}; }
  bool is_identity() const { return *this == Transform{}; }
  Vec3 apply(const Vec3& p) const {
    return {r[0][0] * p.x + r[0][1] * p.y + r[0][2] * p.z + t.x,
            r[1][0] * p.x + r[1][1] * p.y + r[1][2] * p.z + t.y,
            r[2][0] * p.x + r[2][1] * p.y + r[2][2] * p.z + t.z};
  }
  /// The rotation alone (a direction or a normal: R·v).
  Vec3 rotate(const Vec3& v) const {
    return {r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
            r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
  }
  friend bool operator==(const Transform&, const Transform&) = default;

  /// Parses 12 numbers "r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz" (spaces and/or commas).
  static Expected<Transform> parse(std::string_view text);
  /// The same 12 numbers, row-major.
  std::array<double, 12> to_row_major() const;
  /// As three rows of four: [R|t] (the placement of the CAD reports).
  std::array<std::array<double, 4>, 3> to_rows() const;
};

}  // namespace interfere
