// np/distance.h: hand cases for each Voronoi region and for parallel/degenerate segments, and
// random cases checked with the first-order optimality condition of these convex problems (a
// closest pair (p, q) of convex sets P, Q satisfies (p - q) . (x - p) >= 0 for all x in P and (q -
// p) . (y - q) >= 0 for all y in Q; by linearity it suffices to check the corners), plus a sampled
// upper bound.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"
#include "unit/reference_distance.h"

namespace interfere {
namespace {

using Tri = std::array<Vec3, 3>;

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-14) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

const Tri kT{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}};

TEST(NpDistance, ClosestPointOnTriangleRegions) {
  expect_near(closest_point_on_triangle(Vec3{0.5, 0.5, 3}, kT), Vec3{0.5, 0.5, 0});  // face
  expect_near(closest_point_on_triangle(Vec3{-1, -1, 1}, kT), Vec3{0, 0, 0});        // vertex 0
  expect_near(closest_point_on_triangle(Vec3{3, -1, 0}, kT), Vec3{2, 0, 0});         // vertex 1
  expect_near(closest_point_on_triangle(Vec3{-0.5, 4, 0}, kT), Vec3{0, 2, 0});       // vertex 2
  expect_near(closest_point_on_triangle(Vec3{1, -3, 1}, kT), Vec3{1, 0, 0});         // edge 0
  expect_near(closest_point_on_triangle(Vec3{2, 2, -1}, kT), Vec3{1, 1, 0});         // edge 1
  expect_near(closest_point_on_triangle(Vec3{-5, 1, 0}, kT), Vec3{0, 1, 0});         // edge 2
  // Degenerate triangles: collinear and a point.
  const Tri seg{Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{2, 2, 0}};
  expect_near(closest_point_on_triangle(Vec3{0, 2, 5}, seg), Vec3{1, 1, 0});
  const Tri pt{Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{1, 2, 3}};
  expect_near(closest_point_on_triangle(Vec3{0, 0, 0}, pt), Vec3{1, 2, 3});
}

TEST(NpDistance, SegmentSegmentHandCases) {
  // Skew, interior closest points.
  ClosestPoints c =
      segment_segment_closest(Vec3{-1, 0, 0}, Vec3{1, 0, 0}, Vec3{0, -1, 2}, Vec3{0, 1, 2});
  EXPECT_NEAR(c.distance, 2, 1e-15);
  expect_near(c.p, Vec3{0, 0, 0});
  expect_near(c.q, Vec3{0, 0, 2});
  // Endpoint to interior.
  c = segment_segment_closest(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{3, -1, 1}, Vec3{3, 1, 1});
  EXPECT_NEAR(c.distance, std::sqrt(5.0), 1e-15);
  // Parallel, overlapping: distance is the gap; the points are a valid pair.
  c = segment_segment_closest(Vec3{0, 0, 0}, Vec3{4, 0, 0}, Vec3{1, 3, 0}, Vec3{6, 3, 0});
  EXPECT_NEAR(c.distance, 3, 1e-15);
  EXPECT_NEAR(distance(c.p, c.q), 3, 1e-15);
  EXPECT_NEAR(c.p.y, 0, 0);
  EXPECT_NEAR(c.q.y, 3, 0);
  // Parallel, disjoint along the line: endpoint to endpoint.
  c = segment_segment_closest(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{3, 1, 0}, Vec3{5, 1, 0});
  EXPECT_NEAR(c.distance, std::sqrt(5.0), 1e-15);
  expect_near(c.p, Vec3{1, 0, 0});
  expect_near(c.q, Vec3{3, 1, 0});
  // Anti-parallel collinear, overlapping: distance 0.
  c = segment_segment_closest(Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{3, 0, 0}, Vec3{1, 0, 0});
  EXPECT_NEAR(c.distance, 0, 1e-15);
  // Degenerate: point–segment, segment–point, point–point.
  c = segment_segment_closest(Vec3{1, 1, 0}, Vec3{1, 1, 0}, Vec3{0, 0, 0}, Vec3{2, 0, 0});
  EXPECT_NEAR(c.distance, 1, 1e-15);
  expect_near(c.q, Vec3{1, 0, 0});
  c = segment_segment_closest(Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{5, 0, 0}, Vec3{5, 0, 0});
  EXPECT_NEAR(c.distance, 3, 1e-15);
  c = segment_segment_closest(Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{1, 2, 5}, Vec3{1, 2, 5});
  EXPECT_NEAR(c.distance, 2, 1e-15);
}

TEST(NpDistance, TriangleTriangleHandCases) {
  // Parallel planes, overlapping footprints: distance is the gap.
  ClosestPoints c =
      triangle_triangle_closest(kT, Tri{Vec3{0.5, 0.5, 1.5}, Vec3{3, 0.5, 1.5}, Vec3{0.5, 3, 1.5}});
  EXPECT_NEAR(c.distance, 1.5, 1e-15);
  // Edge to edge (skew).
  c = triangle_triangle_closest(kT, Tri{Vec3{1, -1, 1}, Vec3{1, -3, 1}, Vec3{1, -1, 3}});
  EXPECT_NEAR(c.distance, std::sqrt(2.0), 1e-15);
  // Touching at a corner.
  c = triangle_triangle_closest(kT, Tri{Vec3{2, 0, 0}, Vec3{3, 0, 1}, Vec3{3, 1, 0}});
  EXPECT_NEAR(c.distance, 0, 1e-15);
}

bool closest_pair_optimal(const Vec3& p, const Vec3& q, const Vec3* pc, int np, const Vec3* qc,
                          int nq, double tol) {
  const Vec3 r = p - q;
  for (int i = 0; i < np; ++i)
    if (dot(r, pc[i] - p) < -tol) return false;
  for (int i = 0; i < nq; ++i)
    if (dot(-r, qc[i] - q) < -tol) return false;
  return true;
}

Vec3 random_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {u(rng), u(rng), u(rng)};
}

TEST(NpDistance, RandomPointTriangleIsOptimal) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    Tri t{random_point(rng), random_point(rng), random_point(rng)};
    // Degenerate (up to rounding) now and then, with the third corner inside or outside [t0, t1].
    if (i % 10 == 0)
      t[2] = t[0] + (t[1] - t[0]) * (i % 30 == 0 ? 0.3 : (i % 30 == 10 ? 1.7 : -0.6));
    const Vec3 p = random_point(rng) * 2.0;
    const Vec3 q = closest_point_on_triangle(p, t);
    // q in t (barycentric least squares residual) and optimal.
    const Vec3 tc[3] = {t[0], t[1], t[2]};
    ASSERT_TRUE(closest_pair_optimal(q, p, tc, 3, &p, 1, 1e-12)) << i;
    // The optimality test alone accepts points off the triangle: q must lie on t, and the distance
    // must be the independent reference's (unit/reference_distance.h).
    ASSERT_LE(reference::point_triangle_distance(q, t), 1e-12) << i;
    ASSERT_NEAR(distance(p, q), reference::point_triangle_distance(p, t), 1e-12) << i;
    // A few random points of t are never closer.
    for (int k = 0; k < 4; ++k) {
      double s = w(rng), r = w(rng);
      if (s + r > 1) s = 1 - s, r = 1 - r;
      const Vec3 x = t[0] + (t[1] - t[0]) * s + (t[2] - t[0]) * r;
      ASSERT_LE(distance(p, q), distance(p, x) + 1e-12);
    }
  }
}

TEST(NpDistance, RandomSegmentSegmentIsOptimal) {
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p0 = random_point(rng), p1 = random_point(rng);
    Vec3 q0 = random_point(rng), q1 = random_point(rng);
    if (i % 5 == 0) q1 = q0 + (p1 - p0) * 0.7;  // exactly or nearly parallel
    if (i % 7 == 0) q1 = q0;                    // point
    const ClosestPoints c = segment_segment_closest(p0, p1, q0, q1);
    EXPECT_NEAR(c.distance, distance(c.p, c.q), 1e-15);
    const Vec3 pc[2] = {p0, p1}, qc[2] = {q0, q1};
    ASSERT_TRUE(closest_pair_optimal(c.p, c.q, pc, 2, qc, 2, 1e-12)) << i;
    ASSERT_LE(reference::point_segment_distance(c.p, p0, p1), 1e-12) << i;  // on the segments
    ASSERT_LE(reference::point_segment_distance(c.q, q0, q1), 1e-12) << i;
    ASSERT_NEAR(c.distance, reference::segment_segment_distance(p0, p1, q0, q1), 1e-12) << i;
    for (int k = 0; k < 4; ++k) {
      const Vec3 x = p0 + (p1 - p0) * w(rng), y = q0 + (q1 - q0) * w(rng);
      ASSERT_LE(c.distance, distance(x, y) + 1e-12);
    }
  }
}

TEST(NpDistance, RandomTriangleTriangleIsOptimal) {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 10000; ++i) {
    const Tri a{random_point(rng), random_point(rng), random_point(rng)};
    Tri b{random_point(rng), random_point(rng), random_point(rng)};
    for (Vec3& v : b) v += Vec3{0.8, 0, 0};
    if (tri_tri_exact_intersects(a, b)) continue;  // valid for non-intersecting triangles
    ++checked;
    const ClosestPoints c = triangle_triangle_closest(a, b);
    ASSERT_TRUE(closest_pair_optimal(c.p, c.q, a.data(), 3, b.data(), 3, 1e-12)) << i;
    ASSERT_LE(reference::point_triangle_distance(c.p, a), 1e-12) << i;  // on the triangles
    ASSERT_LE(reference::point_triangle_distance(c.q, b), 1e-12) << i;
    ASSERT_NEAR(c.distance, distance(c.p, c.q), 1e-15) << i;
    ASSERT_NEAR(c.distance, reference::triangle_triangle_distance(a, b), 1e-12) << i;
    for (int k = 0; k < 4; ++k) {
      double s = w(rng), r = w(rng);
      if (s + r > 1) s = 1 - s, r = 1 - r;
      const Vec3 x = a[0] + (a[1] - a[0]) * s + (a[2] - a[0]) * r;
      const Vec3 y = b[0] + (b[1] - b[0]) * r + (b[2] - b[0]) * s;
      ASSERT_LE(c.distance, distance(x, y) + 1e-12);
    }
  }
  EXPECT_GT(checked, 3000);
}

}  // namespace
}  // namespace interfere
