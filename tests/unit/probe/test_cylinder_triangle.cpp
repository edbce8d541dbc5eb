// Exact cylinder-triangle test (issue #5, items 3c and 7): against a dense brute-force reference on
// random configurations, exact degenerate contacts (rim, edge parallel to the axis, triangle in the
// end-cap plane) moved by one ulp, and the incompleteness of the frame-plane projection test (the paper's §3.4: test_paper_tests.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "interfere/probe/cylinder.h"
#include "unit/reference_distance.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

using Tri3 = std::array<Vec3, 3>;

/// Point to solid cylinder, written here (axial overshoot and radial excess are orthogonal) so that
/// the oracles below share no code with probe::point_cylinder_distance, which
/// cylinder_triangle_distance minimises along the edges (issue #23, item 14).
double reference_point_cylinder(const Cylinder& c, const Vec3& p) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const Vec3 u = d / len;
  const double s = dot(p - c.c0, u);
  const double radial = norm((p - c.c0) - u * s);
  const double axial = s < 0 ? -s : (s > len ? s - len : 0.0);
  return std::hypot(axial, std::max(0.0, radial - c.radius));
}

/// Brute-force distance: dense sampling of the triangle (barycentric grid) against the analytic
/// point-cylinder distance; an upper bound that converges to the true distance.
double sampled_distance(const Cylinder& c, const Tri3& t, int n) {
  double best = 1e300;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double a = double(i) / n, b = double(j) / n;
      const Vec3 p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
      best = std::min(best, reference_point_cylinder(c, p));
    }
  }
  return best;
}

/// Brute-force: sample the cylinder volume finely and keep the smallest distance to the triangle
/// (reference::point_triangle_distance, unit/reference_distance.h: not np::closest_point_on_triangle,
/// which cylinder_triangle_distance uses for its witness points; issue #23, item 14).
double sampled_cylinder_to_triangle(const Cylinder& c, const Tri3& t, int n) {
  const Vec3 d = c.c1 - c.c0;
  const Vec3 u = d / norm(d);
  const Vec3 helper = std::fabs(u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 e1 = cross(u, helper);
  e1 = e1 / norm(e1);
  const Vec3 e2 = cross(u, e1);
  double best = 1e300;
  for (int i = 0; i <= n; ++i) {
    for (int k = 0; k <= n; ++k) {
      const double rr = c.radius * k / n;
      const int m = std::max(1, 4 * k);
      for (int j = 0; j < m; ++j) {
        const double phi = 2 * M_PI * j / m;
        const Vec3 p = c.c0 + d * (double(i) / n) + e1 * (rr * std::cos(phi)) + e2 * (rr * std::sin(phi));
        best = std::min(best, reference::point_triangle_distance(p, t));
      }
    }
  }
  return best;
}

Vec3 rnd(std::mt19937_64& g, double s) {
  std::uniform_real_distribution<double> u(-s, s);
  return {u(g), u(g), u(g)};
}

}  // namespace

TEST(ProbeCylinderTriangle, RandomAgainstBruteForce) {
  std::mt19937_64 g(12345);
  int hits = 0, misses = 0, checked = 0;
  for (int it = 0; it < 400; ++it) {
    Cylinder c{rnd(g, 1.0), rnd(g, 1.0), 0.2 + 0.5 * std::uniform_real_distribution<double>(0, 1)(g)};
    const Tri3 t{rnd(g, 1.5), rnd(g, 1.5), rnd(g, 1.5)};
    const bool exact = cylinder_triangle_intersect(c, t);
    const CylinderTriangleDistance dist = cylinder_triangle_distance(c, t);
    EXPECT_EQ(dist.intersecting, exact);
    // Exact oracle for misses: a sampled triangle point inside the cylinder (exact point test)
    // proves contact.
    bool sampled_inside = false;
    for (int i = 0; i <= 60 && !sampled_inside; ++i) {
      for (int j = 0; i + j <= 60 && !sampled_inside; ++j) {
        sampled_inside = point_in_cylinder(c, t[0] + (t[1] - t[0]) * (i / 60.0) + (t[2] - t[0]) * (j / 60.0));
      }
    }
    if (sampled_inside) EXPECT_TRUE(exact) << "it " << it;
    const double ref = sampled_distance(c, t, 120);
    const double ref2 = sampled_cylinder_to_triangle(c, t, 24);
    const double scale = norm(t[1] - t[0]) + norm(t[2] - t[0]) + norm(c.c1 - c.c0) + c.radius;
    // Sampling resolutions give upper bounds within h of the truth.
    const double h1 = 2.0 * scale / 120, h2 = 2.0 * scale / 24;
    if (exact) {
      ++hits;
      EXPECT_LE(std::min(ref, ref2), std::min(h1, h2)) << "it " << it;
    } else {
      ++misses;
      EXPECT_GT(dist.distance, 0.0);
      EXPECT_LE(dist.distance, ref + 1e-9) << "it " << it;   // never above a sampled value
      EXPECT_LE(dist.distance, ref2 + 1e-9) << "it " << it;
      EXPECT_GE(dist.distance, ref - h1) << "it " << it;    // close to the sampled values
      EXPECT_GE(dist.distance, ref2 - h2) << "it " << it;
      // The witness points realise the distance.
      EXPECT_NEAR(distance(dist.on_triangle, dist.on_cylinder), dist.distance, 1e-9 * scale);
      EXPECT_NEAR(reference_point_cylinder(c, dist.on_triangle), dist.distance, 1e-9 * scale);
      // The library's point distance agrees with the independent one.
      EXPECT_NEAR(point_cylinder_distance(c, dist.on_triangle), reference_point_cylinder(c, dist.on_triangle),
                  1e-12 * scale);
      // Sampled points of clearly separated pairs.
      if (ref > h1) ++checked;
    }
  }
  EXPECT_GT(hits, 50);
  EXPECT_GT(misses, 50);
  EXPECT_GT(checked, 20);
}

TEST(ProbeCylinderTriangle, SampledIntersectionsAreFound) {
  // Triangles built around a point sampled inside the cylinder always intersect it.
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int it = 0; it < 300; ++it) {
    const Cylinder c{rnd(g, 1.0), rnd(g, 1.0), 0.1 + 0.4 * u01(g)};
    const Vec3 d = c.c1 - c.c0;
    const Vec3 helper = std::fabs(d.x) < 0.9 * norm(d) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 e1 = cross(d, helper);
    e1 = e1 / norm(e1);
    const Vec3 e2 = cross(d / norm(d), e1);
    const double phi = 2 * M_PI * u01(g), rr = c.radius * std::sqrt(u01(g)) * 0.999;
    const Vec3 p = c.c0 + d * (0.001 + 0.998 * u01(g)) + e1 * (rr * std::cos(phi)) + e2 * (rr * std::sin(phi));
    ASSERT_TRUE(point_in_cylinder(c, p));
    // A triangle having p inside: p = a*A + b*B + (1-a-b)*C.
    const Vec3 a = p + rnd(g, 2.0), b = p + rnd(g, 2.0);
    const Vec3 cc = p * 3.0 - a - b;  // p is the centroid
    EXPECT_TRUE(cylinder_triangle_intersect(c, {a, b, cc})) << it;
  }
}

TEST(ProbeCylinderTriangle, TriangleInEndCapPlane) {
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  // In the cap plane z = 0, overlapping the disk: contact.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{-3, -3, 0}, Vec3{3, -3, 0}, Vec3{0, 3, 0}}));
  // One ulp below the cap plane: clear.
  const double below = std::nextafter(0.0, -1.0);
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{-3, -3, below}, Vec3{3, -3, below}, Vec3{0, 3, below}}));
  const double tiny = -1e-300 * 1e-8;  // well below one ulp of 1, still a double
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{-3, -3, tiny}, Vec3{3, -3, tiny}, Vec3{0, 3, tiny}}));
  // In the top cap plane, edge tangent to the rim circle (x = 1): touching.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{1, -3, 2}, Vec3{1, 3, 2}, Vec3{5, 0, 2}}));
  // The same edge one ulp outside the rim: clear.
  const double x1 = std::nextafter(1.0, 2.0);
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{x1, -3, 2}, Vec3{x1, 3, 2}, Vec3{5, 0, 2}}));
}

TEST(ProbeCylinderTriangle, EdgeParallelToAxisTouchingSide) {
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  // Edge on the line x = 1, y = 0 (parallel to the axis), spanning beyond both caps.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{1, 0, -5}, Vec3{1, 0, 5}, Vec3{4, 0, 0}}));
  const double x1 = std::nextafter(1.0, 2.0);
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{x1, 0, -5}, Vec3{x1, 0, 5}, Vec3{4, 0, 0}}));
  // Tilted axis: edge parallel to c1 - c0 at distance exactly r (3-4-5 geometry, exact in double).
  const Cylinder t{{0, 0, 0}, {3, 4, 0}, 5.0};
  // Offset by (0, 0, 5): distance 5 from the axis line, edge direction (3, 4, 0).
  EXPECT_TRUE(cylinder_triangle_intersect(t, {Vec3{-3, -4, 5}, Vec3{6, 8, 5}, Vec3{0, 0, 9}}));
  const double z5 = std::nextafter(5.0, 6.0);
  EXPECT_FALSE(cylinder_triangle_intersect(t, {Vec3{-3, -4, z5}, Vec3{6, 8, z5}, Vec3{0, 0, 9}}));
}

TEST(ProbeCylinderTriangle, TouchingTheRim) {
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  // A vertex exactly on the rim circle (1, 0, 2), triangle outside otherwise.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{1, 0, 2}, Vec3{3, 0, 4}, Vec3{3, 1, 4}}));
  const double z = std::nextafter(2.0, 3.0);
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{1, 0, z}, Vec3{3, 0, 4}, Vec3{3, 1, 4}}));
  // An edge through the rim point (1, 0, 2) at 45 degrees, only touching the corner (x + z = 3).
  // The whole triangle lies in the plane x + z = 3, which supports the cylinder (x <= 1, z <= 2 in
  // it) at that rim point alone; its edge from (0, 0, 3) to (3, 0, 0) passes through it (at 1/3).
  // Hand-checked: contact at exactly one point, and none once the plane is one ulp farther out.
  const Vec3 rim{1, 0, 2};
  ASSERT_TRUE(point_in_cylinder(c, rim));
  ASSERT_EQ(rim.x + rim.z, 3.0);
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{0, 0, 3}, Vec3{3, 0, 0}, Vec3{3, 5, 0}}));
  EXPECT_FALSE(cylinder_triangle_intersect(
      c, {Vec3{0, 0, std::nextafter(3.0, 4.0)}, Vec3{std::nextafter(3.0, 4.0), 0, 0}, Vec3{std::nextafter(3.0, 4.0), 5, 0}}));
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{0, 0, 3}, Vec3{3, 0, 0}, Vec3{4, 0, 4}}));
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{0, 0, std::nextafter(3.0, 4.0)}, Vec3{std::nextafter(3.0, 4.0), 0, 0},
                                               Vec3{4, 0, 4}}));
  // A face interior touching the rim: the plane x + z = 3 (normal (1,0,1)) supports the cylinder at
  // the rim point (1, 0, 2); a large triangle in that plane around it.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{1, -5, 2}, Vec3{-1, 5, 4}, Vec3{3, 5, 0}}));
  EXPECT_FALSE(cylinder_triangle_intersect(
      c, {Vec3{1, -5, std::nextafter(2.0, 3.0)}, Vec3{-1, 5, std::nextafter(4.0, 5.0)}, Vec3{3, 5, std::nextafter(0.0, 1.0)}}));
}

TEST(ProbeCylinderTriangle, DegenerateTriangles) {
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{0.5, 0, 1}, Vec3{0.5, 0, 1}, Vec3{0.5, 0, 1}}));
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{1.5, 0, 1}, Vec3{1.5, 0, 1}, Vec3{1.5, 0, 1}}));
  // A segment crossing the cylinder sideways.
  EXPECT_TRUE(cylinder_triangle_intersect(c, {Vec3{-3, 0.5, 1}, Vec3{3, 0.5, 1}, Vec3{0, 0.5, 1}}));
  EXPECT_FALSE(cylinder_triangle_intersect(c, {Vec3{-3, 1.5, 1}, Vec3{3, 1.5, 1}, Vec3{0, 1.5, 1}}));
}

TEST(ProbeCylinderTriangle, FrameProjectionIsIncomplete) {
  // Axis z, r = 1, length 1. The plane (x + y)/sqrt(2) + z = 2.1 is at distance 0.1/sqrt(2) from
  // the rim at azimuth 45 degrees and separates; a large triangle in it projects onto every frame
  // plane over the cylinder's projection.
  const Cylinder c{{0, 0, 0}, {0, 0, 1}, 1.0};
  const double s = 1 / std::sqrt(2.0);
  const Tri3 t{Vec3{3, -3, 2.1}, Vec3{-3, 3, 2.1}, Vec3{2, 2, 2.1 - 4 * s}};
  EXPECT_TRUE(frame_projection_test(c, t));        // the frame-plane projections: contact (wrong)
  EXPECT_FALSE(cylinder_triangle_intersect(c, t));  // ours: clear
  const double ref = sampled_distance(c, t, 400);
  EXPECT_GT(ref, 0.05);  // brute force confirms a clear gap (0.1/|(s, s, 1)| = 0.0816)
  EXPECT_NEAR(cylinder_triangle_distance(c, t).distance, 0.1 / std::sqrt(2.0), 1e-9);
  // Where projections do not overlap, both agree.
  const Tri3 far{Vec3{5, 5, 5}, Vec3{6, 5, 5}, Vec3{5, 6, 5}};
  EXPECT_FALSE(frame_projection_test(c, far));
  // The paper's own projections (§3.4, along an edge of the triangle) separate this one: its plane
  // separates, and projecting along an edge in that plane maps the plane to a line.
  EXPECT_FALSE(three_projection_test(c, t));
}

TEST(ProbeCylinderTriangle, FrameProjectionNeverMissesAContact) {
  std::mt19937_64 g(99);
  int false_contacts = 0;
  for (int it = 0; it < 2000; ++it) {
    const Cylinder c{rnd(g, 1.0), rnd(g, 1.0), 0.3};
    const Tri3 t{rnd(g, 1.5), rnd(g, 1.5), rnd(g, 1.5)};
    const bool exact = cylinder_triangle_intersect(c, t);
    const bool paper = frame_projection_test(c, t);
    if (exact) EXPECT_TRUE(paper) << it;
    false_contacts += paper && !exact;
  }
  EXPECT_GT(false_contacts, 0);  // the incompleteness shows up on random input too
}

TEST(ProbeCylinderTriangle, GrownContainsMinkowskiSum) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int it = 0; it < 200; ++it) {
    const Cylinder c{rnd(g, 1.0), rnd(g, 1.0), 0.2};
    const double delta = 0.3 * u01(g);
    const Cylinder big = grown(c, delta);
    // Points at distance <= delta from c (closest point + outward offset) are inside `big`.
    const Vec3 q = rnd(g, 2.0);
    Vec3 cp;
    const double dq = point_cylinder_distance(c, q, &cp);
    if (dq > 0) {
      const Vec3 p = cp + (q - cp) * (delta / dq);
      EXPECT_TRUE(point_in_cylinder(big, p)) << it;
    }
    const Aabb box = cylinder_box(c);
    EXPECT_TRUE(box.contains(c.c0) && box.contains(c.c1));
  }
}

// The two evaluation stages of the exact signs (src/probe/exact_poly.h): the running-error filter
// never returns a wrong sign, and the expansion arithmetic is exact where double rounding is not.
#include "../../../src/probe/exact_poly.h"

TEST(ProbeExactPoly, ExpansionIsExactAndFilterIsSound) {
  using probe::detail::Expansion;
  using probe::detail::Filtered;
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int undecided = 0;
  for (int it = 0; it < 2000; ++it) {
    const double a = u(g) * std::ldexp(1.0, static_cast<int>(g() % 40) - 20), b = u(g), c = u(g) * 1e-9;
    // (a + b)^2 - a^2 - 2ab - b^2 == 0 exactly; plus c^3 gives a known sign.
    auto poly = [&]<class N>() {
      const N A(a), B(b), C(c), two(2.0);
      return (A + B) * (A + B) - A * A - two * A * B - B * B + C * C * C;
    };
    const int exact = poly.operator()<Expansion>().sign();
    EXPECT_EQ(exact, (c > 0) - (c < 0)) << it;
    const int f = poly.operator()<Filtered>().sign();
    if (f == 2) ++undecided;
    else EXPECT_EQ(f, exact) << it;
    // Pure cancellation: exactly zero.
    auto zero = [&]<class N>() {
      const N A(a), B(b), two(2.0);
      return (A + B) * (A - B) - A * A + B * B;
    };
    EXPECT_EQ(zero.operator()<Expansion>().sign(), 0);
    const int fz = zero.operator()<Filtered>().sign();
    EXPECT_TRUE(fz == 0 || fz == 2);
  }
  EXPECT_GT(undecided, 0);  // the filter does hand hard cases to the exact stage
}

TEST(ProbeCylinderTriangle, ExactStageDecidesNearTouching) {
  // Tilted cylinder, triangles moved through the touching position in steps of a few ulps: the
  // decision flips exactly once, at the contact, and agrees with the exact point test of the vertex.
  const Cylinder c{{0.1, 0.2, 0.3}, {3.1, 4.2, 0.3}, 5.0};
  const unsigned long long before = cylinder_exact_fallbacks();
  const Vec3 d = c.c1 - c.c0;
  const Vec3 side = cross(d, Vec3{0, 0, 1}) / norm(d);  // unit, normal to the axis (rounded)
  const Vec3 mid = (c.c0 + c.c1) * 0.5;
  int flips = 0;
  bool last = true;
  for (int k = -40; k <= 40; ++k) {
    const double s = 5.0 + k * 4e-15;
    const Vec3 v = mid + side * s;
    const bool hit = cylinder_triangle_intersect(c, {v, v + Vec3{0, 0, 3}, v + side * 2.0});
    EXPECT_EQ(hit, point_in_cylinder(c, v)) << k;
    if (k > -40 && hit != last) ++flips;
    last = hit;
  }
  EXPECT_EQ(flips, 1);
  EXPECT_GT(cylinder_exact_fallbacks(), before);
}
