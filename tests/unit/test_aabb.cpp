// Float boxes must contain the double geometry they bound: the outward rounding must survive the
// optimiser (GCC 12.2 can fold neighbouring (double)(float)x round trips when SLP-vectorising).
#include <gtest/gtest.h>

#include <random>

#include "interfere/core/aabb.h"

namespace interfere {
namespace {

TEST(Aabb, OutwardRoundingContainsDoubleBox) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::size_t strictly_rounded = 0;
  for (int i = 0; i < 100000; ++i) {
    Aabb b;
    b.expand(Vec3{u(rng), u(rng), u(rng)});
    b.expand(Vec3{u(rng), u(rng), u(rng)});
    const AabbF f = to_float_outward(b);
    for (int k = 0; k < 3; ++k) {
      ASSERT_LE(static_cast<double>(f.lo[k]), b.lo[k]);
      ASSERT_GE(static_cast<double>(f.hi[k]), b.hi[k]);
      strictly_rounded += static_cast<double>(f.lo[k]) < b.lo[k];
    }
  }
  EXPECT_GT(strictly_rounded, 1000u);  // random doubles are almost never floats
}

TEST(Aabb, RoundDownAndUpBracketEachValue) {
  struct V3 {
    double x, y, z;
  };
  const V3 v{0.1, 0.2, 0.3};
  const float lo[3] = {round_down(v.x), round_down(v.y), round_down(v.z)};
  const float hi[3] = {round_up(v.x), round_up(v.y), round_up(v.z)};
  const double d[3] = {v.x, v.y, v.z};
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(static_cast<double>(lo[k]), d[k]);
    EXPECT_GT(static_cast<double>(hi[k]), d[k]);
  }
}

TEST(Aabb, OverlapIsClosed) {
  Aabb a, b;
  a.expand(Vec3{0, 0, 0}), a.expand(Vec3{1, 1, 1});
  b.expand(Vec3{1, 0, 0}), b.expand(Vec3{2, 1, 1});
  EXPECT_TRUE(a.overlaps(b));
  b.lo.x = std::nextafter(1.0, 2.0);
  EXPECT_FALSE(a.overlaps(b));
}

}  // namespace
}  // namespace interfere
