// Adversarial review (issue #27): cylinder_pair_distance (analytic.cpp) for nearly parallel axes in a
// general orientation: a bearing's rollers are parallel to each other and to the rings up to the
// rounding of their poses, so the angle between two axes is often 1e-16 .. 1e-12 rather than 0.
// The frames built from cross(d, u) / |d x u| there are rounding noise (raceway.cpp's rim maximum
// had exactly that bug; test_review_bore_rim.cpp). Side-by-side cylinders overlapping along their
// axes: the oracle is the distance between the axis segments (sampled densely along A's axis, the
// point-to-segment distance from its definition, refined by golden-section search) less the two
// radii, which is the distance between the solids for parallel axes and within h * angle of it
// otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "interfere/bearing/analytic.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

using SplitMix = interfere::bearing::test::SplitMix;

Vec3 unit(Vec3 v) { return v / norm(v); }

double point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return norm(p - (a + ab * t));
}

double segment_distance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const auto f = [&](double s) { return point_segment(a0 + (a1 - a0) * s, b0, b1); };
  constexpr int N = 2000;
  int bi = 0;
  double best = f(0);
  for (int i = 1; i <= N; ++i)
    if (const double v = f(double(i) / N); v < best) best = v, bi = i;
  double lo = std::max(0, bi - 1) / double(N), hi = std::min(N, bi + 1) / double(N);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo), fc = f(c), fd = f(d);
  for (int it = 0; it < 100; ++it) {
    if (fc <= fd) hi = d, d = c, fd = fc, c = hi - g * (hi - lo), fc = f(c);
    else lo = c, c = d, fc = fd, d = lo + g * (hi - lo), fd = f(d);
  }
  return std::min({best, fc, fd});
}

}  // namespace

TEST(ReviewParallelAxes, SideBySideAgainstAxisSegments) {
  SplitMix rng{0x9a7a11e1};
  double worst = 0;
  int cases = 0, failures = 0, wrong_clear = 0;
  const double angles[] = {0, 1e-17, 1e-16, 3e-16, 1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9};
  for (int i = 0; i < 4000; ++i) {
    const double eps = angles[i % 11];
    const Vec3 axis = unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)});
    const Vec3 n = unit(cross(axis, std::fabs(axis.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 w = cross(axis, n);
    const double ra = rng.in(2, 12), rb = rng.in(2, 12), ha = rng.in(10, 40), hb = rng.in(10, 40);
    const double gap = rng.in(-0.05, 0.05);  // apart or pressed
    const Vec3 origin = Vec3{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)} * std::pow(10.0, rng.in(0, 3));
    Cylinder a;
    a.axis = axis, a.radius = ra, a.height = ha, a.base = origin;
    Cylinder b;
    const double tw = rng.in(0, 2 * std::numbers::pi);
    b.axis = unit(axis + (n * std::cos(tw) + w * std::sin(tw)) * eps);
    b.radius = rb, b.height = hb;
    const double phi = rng.in(0, 2 * std::numbers::pi);
    const Vec3 side = n * std::cos(phi) + w * std::sin(phi);
    // B's centre beside A's, the axial overlap at least 5
    const double shift = rng.in(-0.5, 0.5) * (std::min(ha, hb) - 5);
    const Vec3 bc = a.center() + side * (ra + rb + gap) + axis * shift;
    b.base = bc - b.axis * (0.5 * hb);
    const PairDistance got = cylinder_pair_distance(a, b);
    const double ref = segment_distance(a.base, a.top_center(), b.base, b.top_center()) - ra - rb;
    const double tol = 1e-9 * (ra + rb + ha + hb) + 1e-15 * norm(origin) * 16 + eps * (ha + hb);
    const double diff = std::fabs(got.distance - ref);
    worst = std::max(worst, diff);
    ++cases;
    wrong_clear += got.distance > 0 && ref < -tol;
    if (diff > tol && ++failures <= 10)
      ADD_FAILURE() << "case " << i << " angle " << eps << " path " << analytic_path_name(got.path) << ": got "
                    << got.distance << ", the axis segments give " << ref;
  }
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(wrong_clear, 0);
  std::printf("[review] nearly parallel axes: %d cases, worst |analytic - segments| %.3g, %d failures, %d wrong clears\n",
              cases, worst, failures, wrong_clear);
}
