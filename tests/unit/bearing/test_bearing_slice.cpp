// The `slice` path of the standard solver (analytic.h, issue #27): untapered pairs whose
// certificate fails (nearest or deepest points at an end face of B: rollers side by side with an
// axial offset, a long raceway cylinder against a short roller in the reverse direction of a
// two-sided value) are solved by one convex search over B's cross-sections instead of the nested
// general path. Checked against the independent bracket of bearing_oracle.h (A's surface
// tessellated, sd_B bracketed by subdivision; nothing of the bearing module's distance code) and
// against the general path.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "interfere/bearing/analytic.h"
#include "unit/bearing/bearing_oracle.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

Cylinder cyl(const Vec3& base, const Vec3& axis, double h, double r) {
  Cylinder c;
  c.base = base, c.axis = axis / norm(axis), c.height = h, c.radius = r;
  return c;
}

}  // namespace

TEST(BearingSlice, RollersSideBySideAndRacewayIntoRoller) {
  std::mt19937_64 g(2719);
  const auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  int slice = 0, clear = 0, overlap = 0;
  for (int trial = 0; trial < 48; ++trial) {
    const double tilt = uni(0, 0.02), az = uni(0, 2 * std::numbers::pi);
    const Vec3 axis{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
    Cylinder a, b;
    if (trial % 2 == 0) {  // two rollers (radius 10, length 38) side by side, axially offset
      b = cyl({0, 0, 0}, {0, 0, 1}, 38, 10);
      a = cyl({20 + uni(-0.3, 0.3), uni(-2, 2), uni(-20, 20)}, axis, 38, 10);
    } else {  // the raceway cylinder (radius 110, width 50) into a roller pressed on it
      b = cyl({0, 0, 0}, {0, 0, 1}, 38, 10);
      a = cyl({-120 + uni(-0.3, 0.2), uni(-1, 1), uni(-12, -6)}, axis, 50, 110);
    }
    const PairDistance fast = cylinder_pair_distance(a, b);
    ASSERT_TRUE(std::isfinite(fast.distance));
    SCOPED_TRACE(testing::Message() << "trial " << trial << " path " << analytic_path_name(fast.path) << " s "
                                    << fast.distance);
    slice += fast.path == AnalyticPath::slice;
    clear += fast.distance > 0, overlap += fast.distance < 0;
    const int n = trial % 2 == 0 ? 4096 : 16384;
    bearing_oracle::Bracket br =
        bearing_oracle::surface_min_bracket(bearing_oracle::cylinder_triangles(a, n), b, 1e-8);
    br.lower -= bearing_oracle::facet_gap(a, n);
    EXPECT_LE(fast.distance, br.upper + 1e-9);
    EXPECT_GE(fast.distance, br.lower - 1e-9);
    // the witness is on A and attains the value (the oracle's own signed distance)
    EXPECT_NEAR(bearing_oracle::oracle_sd(b, fast.point_a).value, fast.distance, 1e-9);
    if (fast.path == AnalyticPath::slice && trial < 16)
      EXPECT_NEAR(cylinder_pair_distance_general(a, b).distance, fast.distance, 1e-9 * std::max(1.0, std::fabs(fast.distance)));
  }
  EXPECT_GT(slice, 10);
  EXPECT_GT(clear, 5);
  EXPECT_GT(overlap, 5);
}
