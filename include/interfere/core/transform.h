// Rigid (or general affine) part pose: p' = R·p + t evaluated in double, row-major [R|t].
// A pose is applied exactly as given: a scaled or sheared R scales or shears the geometry, and
// every distance is then measured in the transformed space (docs/robustness.md, "Transforms").
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

  /// Parses 12 numbers "r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz" (spaces and/or commas) and
  /// validates them (validate()). Empty text is an error, not the identity: a caller that means
  /// "no transform" does not parse.
  static Expected<Transform> parse(std::string_view text);
  /// Error (naming the offending value) when a number is not finite or R is singular (det R = 0,
  /// decided exactly with orient3d): a singular R collapses the part onto a plane, a line or a point.
  Status validate() const;
  /// The sign of det R (-1, 0, +1), exact.
  int determinant_sign() const;
  /// The smallest and largest factor by which R stretches a length (the singular values of R,
  /// from the eigenvalues of R^T·R by Jacobi rotations; for reports and warnings, not for bounds).
  std::array<double, 2> stretch_range() const;
  /// True when R is a rotation up to rounding: |R^T·R - I| <= 1e-9 entrywise and det R > 0.
  bool is_rigid() const;
  /// Empty for a rigid pose; otherwise one sentence saying what this pose does to the geometry
  /// (scales by [min, max], mirrors) and how results are to be read, for a warning.
  std::string non_rigid_note() const;
  /// The same 12 numbers, row-major.
  std::array<double, 12> to_row_major() const;
  /// As three rows of four: [R|t] (the placement of the CAD reports).
  std::array<std::array<double, 4>, 3> to_rows() const;
};

}  // namespace interfere
