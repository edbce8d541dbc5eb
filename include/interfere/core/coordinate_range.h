// The supported coordinate range (issue #23, item 7): every coordinate that reaches a query is 0 or
// has a magnitude between 2^-250 (about 5.5e-76) and 2^100 (about 1.27e30), in any unit. The
// readers (read_mesh, read_fem, cad::import_step) and the CLI's unit conversion and transforms
// reject a point outside it with an error naming the file and the point; NaN and infinities are
// outside it too.
//
// Why these bounds (the exact predicates of core/predicates.h, Shewchuk 1997, need no overflow and
// no underflow; constructions and measures in double need headroom too):
//  - Upper: |x| <= 2^100 gives differences <= 2^101, orient3d's degree-3 products <= 2^303 and its
//    permanent < 2^306, so neither the filter nor an expansion component can overflow. Measures
//    computed in double (squared distances, |normal|^2, quadric error metrics: degree <= 8 in
//    coordinates) stay below 2^820, far from the largest double (2^1024). (1e110, cubed, is not a
//    double: today's failures started there.)
//  - Lower: a double with |x| >= 2^-250 is an integer multiple of 2^-302 (its ulp), and so are all
//    coordinate differences; products of k of them are multiples of 2^-302k. orient3d (k = 3) only
//    forms sums and products of such numbers, so each of its nonzero intermediates, rounded or
//    exact, is at least 2^-906 in magnitude, and its error bound (about 2^-50 times that) at least
//    2^-959: all inside the normal range (>= 2^-1022), where rounding has the relative error the
//    filter's bound assumes and two_product's error term is exact. Real files hold tiny nonzero
//    coordinates (gmsh writes rounding noise such as -1.5e-32 for 0; every float32 is >= 1.4e-45),
//    so the bound sits far below them.
//  - Zero is always allowed (it is exact and adds no bits).
// Constructions and measures (distances, volumes, simplification error bounds) are computed in
// double: for a part whose whole extent is below about 2^-100 they may lose accuracy to underflow;
// the exact decisions are not affected.
// Points the engine builds from in-range input (ray ends for containment, posed probe shapes) are
// not checked again: they stay in the range, except a coordinate that rounds to a nonzero magnitude
// below 2^-250, for which the lower-bound argument does not hold.
#pragma once
#include <cstddef>
#include <span>
#include <string>

#include "interfere/core/error.h"
#include "interfere/core/vec.h"

namespace interfere {

inline constexpr double kMaxCoordinate = 0x1p100;          ///< largest supported |x|
inline constexpr double kMinNonzeroCoordinate = 0x1p-250;  ///< smallest supported nonzero |x|

/// True when x is 0 or kMinNonzeroCoordinate <= |x| <= kMaxCoordinate (false for NaN and Inf).
constexpr bool coordinate_in_range(double x) {
  const double a = x < 0 ? -x : x;
  return a == 0 || (a >= kMinNonzeroCoordinate && a <= kMaxCoordinate);
}

constexpr bool coordinates_in_range(const Vec3& p) {
  return coordinate_in_range(p.x) && coordinate_in_range(p.y) && coordinate_in_range(p.z);
}

/// Index of the first point with a coordinate outside the range; points.size() when all are in it.
std::size_t first_out_of_range(std::span<const Vec3> points);

/// Why p is outside the range, naming its first bad coordinate: "y = 1.2e+110 is outside the
/// supported coordinate range (0, or 2^-250 <= |x| <= 2^100: about 5.5e-76 to 1.3e+30 in any unit;
/// docs/robustness.md, 'Coordinate range')". Also for NaN and Inf. Empty when p is in range.
std::string coordinate_range_reason(const Vec3& p);

/// The check the readers share: ok, or an Error on `file` whose reason is "<what> <index>: " and
/// coordinate_range_reason of the first point outside the range (index: position in `points`,
/// plus `index_base`). `what` names the points as the file does ("vertex", "node").
Status check_coordinate_range(std::span<const Vec3> points, const std::string& file,
                              const std::string& what = "vertex", std::size_t index_base = 0);

}  // namespace interfere
