// core/predicates.h: signs on hand cases, the sign convention, and near-degenerate input checked
// against an independent exact evaluation: inputs are dyadic (integers times 2^-s) so that scaled
// coordinate differences are integers and the determinant is evaluated exactly in __int128.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "interfere/core/predicates.h"

namespace interfere {
namespace {

using i128 = __int128;

int sign128(i128 v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

/// Point given by integer coordinates in units of 2^-shift (exactly representable: |X| < 2^53).
struct IPoint {
  std::int64_t x, y, z;
};

Vec3 to_vec(const IPoint& p, int shift) {
  return {std::ldexp(double(p.x), -shift), std::ldexp(double(p.y), -shift),
          std::ldexp(double(p.z), -shift)};
}

/// Exact sign of det[a-d, b-d, c-d] (Shewchuk's orient3d) for integer points with differences
/// below 2^40 (products of three stay below 2^123).
i128 det3_exact(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d) {
  const i128 adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
  const i128 bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
  const i128 cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
  return adx * (bdy * cdz - bdz * cdy) - ady * (bdx * cdz - bdz * cdx) +
         adz * (bdx * cdy - bdy * cdx);
}

/// Exact det[a-c, b-c] for integer 2D points.
i128 det2_exact(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                std::int64_t cy) {
  return i128(ax - cx) * i128(by - cy) - i128(ay - cy) * i128(bx - cx);
}

TEST(Predicates, Orient3dHandCasesAndConvention) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};    // counter-clockwise seen from +z
  EXPECT_EQ(orient3d(a, b, c, Vec3{0, 0, 1}), -1);  // above: negative (Shewchuk)
  EXPECT_EQ(orient3d(a, b, c, Vec3{0, 0, -1}), 1);  // below: positive
  EXPECT_EQ(orient3d(a, b, c, Vec3{5, -7, 0}), 0);  // in the plane
  EXPECT_EQ(orient3d(a, c, b, Vec3{0, 0, 1}), 1);   // reversed triangle
  EXPECT_EQ(orient3d(a, b, c, a), 0);               // repeated point
  EXPECT_EQ(orient3d(a, a, c, Vec3{0, 0, 1}), 0);   // degenerate plane
  // Shewchuk's definition: sign of det[a-d, b-d, c-d].
  const Vec3 d{0.3, 0.2, 0.7};
  const Vec3 ad = a - d, bd = b - d, cd = c - d;
  const double det = dot(ad, cross(bd, cd));
  EXPECT_EQ(orient3d(a, b, c, d), det > 0 ? 1 : -1);
}

TEST(Predicates, Orient2dHandCases) {
  EXPECT_EQ(orient2d(0, 0, 1, 0, 0, 1), 1);   // counter-clockwise
  EXPECT_EQ(orient2d(0, 0, 0, 1, 1, 0), -1);  // clockwise
  EXPECT_EQ(orient2d(0, 0, 1, 1, 3, 3), 0);   // collinear
  EXPECT_EQ(orient2d(1, 1, 1, 1, 1, 1), 0);
  // Projection: equals the sign of the normal's dropped component.
  const Vec3 a{0, 0, 0}, b{1, 2, -1}, c{-2, 1, 3};
  const Vec3 n = cross(b - a, c - a);  // exact for these small integers
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(orient2d_projected(a, b, c, k), n[k] > 0 ? 1 : (n[k] < 0 ? -1 : 0)) << k;
  EXPECT_TRUE(collinear(Vec3{1, 2, 3}, Vec3{2, 4, 6}, Vec3{-1, -2, -3}));
  EXPECT_FALSE(collinear(Vec3{1, 2, 3}, Vec3{2, 4, 6}, Vec3{-1, -2, -2.5}));
  EXPECT_TRUE(collinear(Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{7, 8, 9}));  // repeated corner
  // A plane parallel to z: collinear in the xy projection only.
  EXPECT_FALSE(collinear(Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{2, 2, 5}));
}

TEST(Predicates, Orient2dOneUlpGridNearALine) {
  // Shewchuk's classic failure case for naive orient2d: points on a 1-ulp grid around (0.5, 0.5),
  // against the line through (12, 12) and (24, 24). Scaled by 2^53 every value is an integer.
  const int shift = 53;
  const std::int64_t half = std::int64_t(1) << 52;
  const std::int64_t bx = std::int64_t(12) << 53, cx = std::int64_t(24) << 53;
  const unsigned long long before = exact_fallback_count();
  int wrong_naive = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const std::int64_t ax = half + i, ay = half + j;
      const double x = std::ldexp(double(ax), -shift), y = std::ldexp(double(ay), -shift);
      const int expected = sign128(det2_exact(ax, ay, bx, bx, cx, cx));
      EXPECT_EQ(orient2d(x, y, 12, 12, 24, 24), expected) << i << " " << j;
      const double naive = (x - 24) * (12 - 24) - (y - 24) * (12 - 24);
      wrong_naive += (naive > 0 ? 1 : (naive < 0 ? -1 : 0)) != expected;
    }
  EXPECT_GT(wrong_naive, 100);  // the input really is hard for plain doubles
  EXPECT_GT(exact_fallback_count(), before);
}

TEST(Predicates, Orient3dNearDegenerateLargeOffsetMatchesInt128) {
  // Coordinates 1e6 + k * 2^-33 (one ulp at 1e6), points on a common plane in exact integer
  // arithmetic and then nudged by -1, 0 or +1 ulp.
  const int shift = 33;
  const std::int64_t base = std::int64_t(1000000) << shift;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> off(-(std::int64_t(1) << 35), std::int64_t(1) << 35);
  std::uniform_int_distribution<int> small(-3, 3), nudge(-1, 1), axis(0, 2);
  const unsigned long long before = exact_fallback_count();
  int zeros = 0, nonzeros = 0;
  for (int i = 0; i < 20000; ++i) {
    const IPoint a{base + off(rng), base + off(rng), base + off(rng)};
    const IPoint u{off(rng) / 16, off(rng) / 16, off(rng) / 16};
    const IPoint v{off(rng) / 16, off(rng) / 16, off(rng) / 16};
    const IPoint b{a.x + u.x, a.y + u.y, a.z + u.z};
    const IPoint c{a.x + v.x, a.y + v.y, a.z + v.z};
    const int s = small(rng), t = small(rng);
    IPoint d{a.x + s * u.x + t * v.x, a.y + s * u.y + t * v.y, a.z + s * u.z + t * v.z};
    const int k = axis(rng), n = nudge(rng);
    (k == 0 ? d.x : (k == 1 ? d.y : d.z)) += n;
    const int expected = sign128(det3_exact(a, b, c, d));
    const Vec3 pa = to_vec(a, shift), pb = to_vec(b, shift), pc = to_vec(c, shift),
               pd = to_vec(d, shift);
    ASSERT_EQ(orient3d(pa, pb, pc, pd), expected) << i;
    ASSERT_EQ(Orient3dPlane(pa, pb, pc).side(pd), expected) << i;
    // Permutations: even ones keep the sign, odd ones flip it.
    ASSERT_EQ(orient3d(pb, pc, pa, pd), expected);
    ASSERT_EQ(orient3d(pb, pa, pc, pd), -expected);
    ASSERT_EQ(orient3d(pa, pb, pd, pc), -expected);
    ASSERT_EQ(orient3d(pd, pb, pc, pa), -expected);
    // Values: exact sign, relative error below 2^-40.
    const double value = orient3d_value(pa, pb, pc, pd);
    const double exact = std::ldexp(double(det3_exact(a, b, c, d)), -3 * shift);
    ASSERT_EQ(value > 0 ? 1 : (value < 0 ? -1 : 0), expected);
    ASSERT_LE(std::fabs(value - exact), 0x1p-40 * std::fabs(exact)) << i;
    zeros += expected == 0;
    nonzeros += expected != 0;
  }
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(nonzeros, 1000);
  EXPECT_GT(exact_fallback_count() - before, 1000u);
}

/// Minimal sign-magnitude big integer (products of three 61-bit differences need ~183 bits).
struct Big {
  bool neg = false;
  std::vector<std::uint32_t> mag;  // little-endian limbs, no leading zeros

  static Big from(i128 v) {
    Big b;
    b.neg = v < 0;
    unsigned __int128 m = b.neg ? (unsigned __int128)(-(v + 1)) + 1 : (unsigned __int128)v;
    while (m != 0) {
      b.mag.push_back(std::uint32_t(m));
      m >>= 32;
    }
    return b;
  }
  int sign() const { return mag.empty() ? 0 : (neg ? -1 : 1); }
};

int compare_mag(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
  for (std::size_t i = a.size(); i-- > 0;)
    if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
  return 0;
}

void trim(std::vector<std::uint32_t>& m) {
  while (!m.empty() && m.back() == 0) m.pop_back();
}

Big mul(const Big& a, const Big& b) {
  Big r;
  r.mag.assign(a.mag.size() + b.mag.size(), 0);
  for (std::size_t i = 0; i < a.mag.size(); ++i) {
    std::uint64_t carry = 0;
    for (std::size_t j = 0; j < b.mag.size(); ++j) {
      const std::uint64_t t = std::uint64_t(a.mag[i]) * b.mag[j] + r.mag[i + j] + carry;
      r.mag[i + j] = std::uint32_t(t);
      carry = t >> 32;
    }
    r.mag[i + b.mag.size()] += std::uint32_t(carry);
  }
  trim(r.mag);
  r.neg = !r.mag.empty() && (a.neg != b.neg);
  return r;
}

Big add(const Big& a, const Big& b) {
  Big r;
  if (a.neg == b.neg) {
    r.neg = a.neg;
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < std::max(a.mag.size(), b.mag.size()); ++i) {
      const std::uint64_t t = std::uint64_t(i < a.mag.size() ? a.mag[i] : 0) +
                              (i < b.mag.size() ? b.mag[i] : 0) + carry;
      r.mag.push_back(std::uint32_t(t));
      carry = t >> 32;
    }
    if (carry) r.mag.push_back(std::uint32_t(carry));
  } else {
    const int c = compare_mag(a.mag, b.mag);
    if (c == 0) return r;
    const Big& big = c > 0 ? a : b;
    const Big& small = c > 0 ? b : a;
    r.neg = big.neg;
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < big.mag.size(); ++i) {
      std::int64_t t =
          std::int64_t(big.mag[i]) - (i < small.mag.size() ? small.mag[i] : 0) - borrow;
      borrow = t < 0;
      if (t < 0) t += std::int64_t(1) << 32;
      r.mag.push_back(std::uint32_t(t));
    }
  }
  trim(r.mag);
  if (r.mag.empty()) r.neg = false;
  return r;
}

Big neg(Big a) {
  if (!a.mag.empty()) a.neg = !a.neg;
  return a;
}

/// A double as an exact integer in units of 2^-80 (the test keeps inputs in that range).
i128 units(double v) {
  const double scaled = std::ldexp(v, 80);
  EXPECT_EQ(scaled, std::trunc(scaled));
  EXPECT_LT(std::fabs(scaled), 0x1p120);
  i128 r = 0;  // exact conversion of an integral double above 2^64
  double rest = std::fabs(scaled);
  for (int bit = 119; bit >= 0; --bit) {
    const double p = std::ldexp(1.0, bit);
    if (rest >= p) {
      rest -= p;
      r |= i128(1) << bit;
    }
  }
  return scaled < 0 ? -r : r;
}

/// Exact sign of det[a-d, b-d, c-d] for doubles that are multiples of 2^-80.
int orient3d_big(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Big m[3][3];
  const Vec3* rows[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) m[i][k] = Big::from(units((*rows[i])[k]) - units(d[k]));
  auto minor = [&](int r0, int r1, int c0, int c1) {
    return add(mul(m[r0][c0], m[r1][c1]), neg(mul(m[r0][c1], m[r1][c0])));
  };
  const Big det = add(add(mul(m[0][0], minor(1, 2, 1, 2)), neg(mul(m[0][1], minor(1, 2, 0, 2)))),
                      mul(m[0][2], minor(1, 2, 0, 1)));
  return det.sign();
}

TEST(Predicates, BigIntegerReferenceSelfCheck) {
  // The reference itself against __int128 where both apply.
  std::mt19937_64 rng(10);
  std::uniform_int_distribution<std::int64_t> d(-(std::int64_t(1) << 38), std::int64_t(1) << 38);
  for (int i = 0; i < 2000; ++i) {
    const IPoint a{d(rng), d(rng), d(rng)}, b{d(rng), d(rng), d(rng)}, c{d(rng), d(rng), d(rng)},
        p{d(rng), d(rng), d(rng)};
    ASSERT_EQ(orient3d_big(to_vec(a, 60), to_vec(b, 60), to_vec(c, 60), to_vec(p, 60)),
              sign128(det3_exact(a, b, c, p)));
  }
}

TEST(Predicates, Orient3dInexactDifferencesMatchBigInteger) {
  // Corners mix magnitudes ~2^-21 and ~2^-77, so coordinate differences are not representable
  // in double and the exact path must carry two-term differences. d is an affine combination of
  // a, b, c rounded to double (on the plane up to rounding), sometimes nudged by one unit.
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<std::int64_t> big(-(std::int64_t(1) << 50), std::int64_t(1) << 50);
  std::uniform_int_distribution<std::int64_t> tiny(-8, 8);
  std::uniform_int_distribution<int> coin(0, 1), small(-2, 2);
  auto coordinate = [&]() {
    return coin(rng) ? std::ldexp(double(big(rng)), -72) : std::ldexp(double(tiny(rng)), -80);
  };
  const unsigned long long before = exact_fallback_count();
  int zeros = 0, nonzeros = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a{coordinate(), coordinate(), coordinate()},
        b{coordinate(), coordinate(), coordinate()}, c{coordinate(), coordinate(), coordinate()};
    Vec3 d = a + (b - a) * double(small(rng)) + (c - a) * double(small(rng));
    if (i % 4 == 0) d = b;
    // Keep d a multiple of 2^-80 (true unless it underflowed the unit).
    for (int k = 0; k < 3; ++k) d[k] = std::ldexp(std::nearbyint(std::ldexp(d[k], 80)), -80);
    if (i % 3 == 0) d.z += 0x1p-80;
    const int expected = orient3d_big(a, b, c, d);
    ASSERT_EQ(orient3d(a, b, c, d), expected) << i;
    ASSERT_EQ(orient3d(b, a, c, d), -expected) << i;
    zeros += expected == 0;
    nonzeros += expected != 0;
  }
  EXPECT_GT(zeros, 300);
  EXPECT_GT(nonzeros, 300);
  EXPECT_GT(exact_fallback_count() - before, 1000u);
}

TEST(Predicates, Orient2dRandomNearCollinearMatchesInt128) {
  const int shift = 30;
  const std::int64_t base = std::int64_t(3) << 50;  // large offset: 3 * 2^20 in real units
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<std::int64_t> off(-(std::int64_t(1) << 40), std::int64_t(1) << 40);
  std::uniform_int_distribution<int> small(-4, 4), nudge(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    const std::int64_t ax = base + off(rng), ay = base + off(rng);
    const std::int64_t ux = off(rng) / 64, uy = off(rng) / 64;
    const std::int64_t bx = ax + ux, by = ay + uy;
    const int s = small(rng);
    const std::int64_t cx = ax + s * ux + nudge(rng), cy = ay + s * uy + nudge(rng);
    const int expected = sign128(det2_exact(ax, ay, bx, by, cx, cy));
    auto f = [&](std::int64_t v) { return std::ldexp(double(v), -shift); };
    ASSERT_EQ(orient2d(f(ax), f(ay), f(bx), f(by), f(cx), f(cy)), expected) << i;
    const double value = orient2d_value(f(ax), f(ay), f(bx), f(by), f(cx), f(cy));
    const double exact = std::ldexp(double(det2_exact(ax, ay, bx, by, cx, cy)), -2 * shift);
    ASSERT_LE(std::fabs(value - exact), 0x1p-40 * std::fabs(exact)) << i;
  }
}

TEST(Predicates, FallbackCounterCountsOnlyUncertainCases) {
  const unsigned long long before = exact_fallback_count();
  // Well-separated input: decided by the filter.
  for (int i = 0; i < 100; ++i)
    EXPECT_EQ(orient3d(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0.25, 0.25, 1.0 + i}), -1);
  EXPECT_EQ(exact_fallback_count(), before);
  // Exactly coplanar on an axis plane: every term has a zero factor, decided without fallback.
  EXPECT_EQ(orient3d(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0.1, 0.7, 0}), 0);
  EXPECT_EQ(orient2d(0.1, 3, 0.7, 3, -5, 3), 0);
  EXPECT_EQ(exact_fallback_count(), before);
  // Exactly coplanar on a tilted plane (x + y + z = 1): the filter cannot certify zero.
  EXPECT_EQ(orient3d(Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{0.25, 0.25, 0.5}), 0);
  EXPECT_EQ(exact_fallback_count(), before + 1);
  EXPECT_EQ(orient2d(0, 0, 1, 1, 0.375, 0.375), 0);
  EXPECT_EQ(exact_fallback_count(), before + 2);
}

TEST(Predicates, PlaneCertifiesNondegeneracy) {
  EXPECT_TRUE(Orient3dPlane(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}).certainly_nondegenerate());
  EXPECT_FALSE(
      Orient3dPlane(Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{2, 2, 2}).certainly_nondegenerate());
  EXPECT_FALSE(
      Orient3dPlane(Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{2, 2, 2}).certainly_nondegenerate());
}

}  // namespace
}  // namespace interfere
