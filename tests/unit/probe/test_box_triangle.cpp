// Exact oriented-box / triangle test and distance of the box holder (issue #5, item 2): the face
// split is outward and convex, random pairs agree with an independent separating-axis test (13
// axes on the ideal box, decided only where it is unambiguous), exact degenerate contacts (coplanar
// face, edge on edge, vertex on face/corner, wholly inside) are contacts and the same configurations
// moved by one ulp are not, and the distance matches dense sampling with witnesses that realise it.
// tests/oracle/test_probe_box_cgal.cpp checks every decision against CGAL's exact kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "interfere/core/predicates.h"
#include "interfere/probe/box.h"
#include "unit/probe/random_axes.h"
#include "unit/reference_distance.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

using Tri3 = std::array<Vec3, 3>;

Vec3 rnd(std::mt19937_64& g, double s) {
  std::uniform_real_distribution<double> u(-s, s);
  return {u(g), u(g), u(g)};
}

using test::random_axes;

OrientedBox random_box(std::mt19937_64& g) {
  std::uniform_real_distribution<double> h(0.2, 2.0);
  return make_box(rnd(g, 2), random_axes(g), {h(g), h(g), h(g)});
}

/// Separation along the 13 separating axes of a box and a triangle (box axes, triangle normal,
/// box axis x triangle edge) on the ideal box, in double: > 0 separated, < 0 overlapping.
double sat_separation(const OrientedBox& b, const Tri3& t) {
  std::vector<Vec3> axes(b.axes.begin(), b.axes.end());
  axes.push_back(cross(t[1] - t[0], t[2] - t[0]));
  for (const Vec3& e : b.axes) {
    for (int i = 0; i < 3; ++i) axes.push_back(cross(e, t[(i + 1) % 3] - t[i]));
  }
  double sep = -1e300;
  for (const Vec3& l : axes) {
    const double len = norm(l);
    if (len < 1e-9) continue;
    const double c = dot(b.centre, l);
    double r = 0;
    for (int k = 0; k < 3; ++k) r += b.half[k] * std::fabs(dot(b.axes[k], l));
    double lo = 1e300, hi = -1e300;
    for (const Vec3& v : t) lo = std::min(lo, dot(v, l)), hi = std::max(hi, dot(v, l));
    sep = std::max(sep, std::max(lo - (c + r), (c - r) - hi) / len);
  }
  return sep;
}

/// Distance from p to the ideal box.
double point_box_distance(const OrientedBox& b, const Vec3& p) {
  double s = 0;
  for (int k = 0; k < 3; ++k) {
    const double q = std::fabs(dot(p - b.centre, b.axes[k])) - b.half[k];
    if (q > 0) s += q * q;
  }
  return std::sqrt(s);
}

double up(double x) {
  return std::nextafter(x, INFINITY);
}

/// Axis-aligned box [-1,1] x [-2,2] x [-3,3]: its corners and face planes are exact.
OrientedBox aligned() {
  return make_box({0, 0, 0}, {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}, {1, 2, 3});
}

}  // namespace

TEST(ProbeBoxTriangle, FacesAreOutwardAndConvex) {
  std::mt19937_64 g(11);
  for (int it = 0; it < 300; ++it) {
    OrientedBox b = random_box(g);
    if (it % 2) b = make_box(b.centre, {b.axes[0], b.axes[1], -b.axes[2]}, b.half);  // left-handed
    std::array<int, 8> used{};
    for (int f = 0; f < 12; ++f) {
      const Tri3 t = b.face(f);
      EXPECT_GT(orient3d(t[0], t[1], t[2], b.centre), 0) << it << " " << f;  // centre below: outward
      for (int c = 0; c < 8; ++c) EXPECT_GE(orient3d(t[0], t[1], t[2], b.corners[c]), 0) << it << " " << f;  // convex
      for (auto i : b.faces[f]) ++used[i];
    }
    for (int n : used) EXPECT_GE(n, 3);  // every corner is on 3 faces: 3..6 triangles
    EXPECT_TRUE(point_in_box(b, b.centre));
    for (const Vec3& c : b.corners) EXPECT_TRUE(point_in_box(b, c));
  }
}

TEST(ProbeBoxTriangle, RandomAgainstSeparatingAxes) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, misses = 0, skipped = 0;
  for (int it = 0; it < 4000; ++it) {
    const OrientedBox b = random_box(g);
    Tri3 t;
    if (it % 2) {  // large triangles around the box
      for (Vec3& v : t) v = b.centre + rnd(g, 4);
    } else {  // small triangles near the surface: near contacts
      const Vec3 p = b.centre + b.axes[0] * (b.half[0] * (2 * u(g) - 1)) + b.axes[1] * (b.half[1] * (2 * u(g) - 1)) +
                     b.axes[2] * (b.half[2] * (u(g) < 0.5 ? -1 : 1)) + rnd(g, 0.2);
      for (Vec3& v : t) v = p + rnd(g, 0.3);
    }
    const double sep = sat_separation(b, t);
    const bool got = box_triangle_intersect(b, t);
    if (sep > 1e-9) {
      EXPECT_FALSE(got) << it << " sep " << sep;
      ++misses;
    } else if (sep < -1e-9) {
      EXPECT_TRUE(got) << it << " sep " << sep;
      ++hits;
    } else {
      ++skipped;
    }
    EXPECT_EQ(box_triangle_distance(b, t).distance == 0, got) << it;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
  EXPECT_LT(skipped, 10);
}

TEST(ProbeBoxTriangle, ExactContactsAndOneUlpApart) {
  const OrientedBox b = aligned();
  // Triangle coplanar with the face z = 3, overlapping it; one ulp above: clear.
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{0, 0, 3}, Vec3{5, 0, 3}, Vec3{0, 5, 3}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{0, 0, up(3)}, Vec3{5, 0, up(3)}, Vec3{0, 5, up(3)}}));
  // Coplanar with the face, touching only its edge x = 1 (from outside).
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{1, 0, 3}, Vec3{5, -1, 3}, Vec3{5, 1, 3}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{up(1), 0, 3}, Vec3{5, -1, 3}, Vec3{5, 1, 3}}));
  // Edge through the box edge x = 1, y = 2 at (1, 2, 0), the triangle in x + y >= 3: skew and in
  // the plane z = 0.
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{0, 3, -1}, Vec3{2, 1, 1}, Vec3{3, 3, 5}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{0, up(3), -1}, Vec3{2, up(1), 1}, Vec3{3, up(3), 5}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{0, 3, 0}, Vec3{2, 1, 0}, Vec3{3, 3, 0}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{0, up(3), 0}, Vec3{2, up(1), 0}, Vec3{3, up(3), 0}}));
  // Vertex on a face, on an edge, on a corner; the triangle otherwise outside.
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{1, 0.5, 0.5}, Vec3{4, 0, 0}, Vec3{4, 1, 1}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{up(1), 0.5, 0.5}, Vec3{4, 0, 0}, Vec3{4, 1, 1}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{1, 2, 0.5}, Vec3{4, 5, 0}, Vec3{4, 5, 1}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{1, up(2), 0.5}, Vec3{4, 5, 0}, Vec3{4, 5, 1}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{1, 2, 3}, Vec3{5, 5, 5}, Vec3{5, 6, 7}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{1, 2, up(3)}, Vec3{5, 5, 5}, Vec3{5, 6, 7}}));
  // Wholly inside (also one ulp inside a face), and a big triangle slicing the box with every
  // vertex outside.
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{0, 0, 0}, Vec3{0.5, 0, 0}, Vec3{0, 0.5, 0.5}}));
  const double in = std::nextafter(1.0, 0.0);
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{in, 0, 0}, Vec3{in, 1, 0}, Vec3{in, 0, 1}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{-10, -10, 0.5}, Vec3{10, -10, 0.5}, Vec3{0, 10, 0.5}}));
  // Degenerate triangles: a segment through the box, a point inside, a point outside.
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{-5, 0, 0}, Vec3{5, 0, 0}, Vec3{5, 0, 0}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{0.5, 0.5, 0.5}, Vec3{0.5, 0.5, 0.5}, Vec3{0.5, 0.5, 0.5}}));
  EXPECT_FALSE(box_triangle_intersect(b, {Vec3{up(1), 0, 0}, Vec3{up(1), 0, 0}, Vec3{up(1), 0, 0}}));
  EXPECT_TRUE(box_triangle_intersect(b, {Vec3{1, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 0, 0}}));
}

TEST(ProbeBoxTriangle, OrientedBoxSharedCornerAndFace) {
  std::mt19937_64 g(3);
  for (int it = 0; it < 100; ++it) {
    const OrientedBox b = random_box(g);
    // A triangle with a corner of the box as a vertex, pointing away along the outward diagonal.
    const int c = it % 8;
    Vec3 out{};
    for (int k = 0; k < 3; ++k) out += b.axes[k] * ((c >> k) & 1 ? 1.0 : -1.0);
    const Vec3 p = b.corners[c];
    const Tri3 t{p, p + out * 2 + b.axes[0] * 0.1, p + out * 2 - b.axes[1] * 0.1};
    EXPECT_TRUE(box_triangle_intersect(b, t)) << it;
    // Every boundary triangle touches the box.
    EXPECT_TRUE(box_triangle_intersect(b, b.face(it % 12))) << it;
    // The same triangle moved out by a small step along the diagonal: clear, distance ~ the step.
    const Tri3 moved{t[0] + out * 1e-6, t[1] + out * 1e-6, t[2] + out * 1e-6};
    EXPECT_FALSE(box_triangle_intersect(b, moved)) << it;
    EXPECT_NEAR(box_triangle_distance(b, moved).distance, norm(out) * 1e-6, 1e-12) << it;
  }
}

TEST(ProbeBoxTriangle, DistanceAgainstSampling) {
  std::mt19937_64 g(17);
  int clear = 0;
  for (int it = 0; it < 200; ++it) {
    const OrientedBox b = random_box(g);
    Tri3 t;
    for (Vec3& v : t) v = b.centre + rnd(g, 5);
    const BoxTriangleDistance d = box_triangle_distance(b, t);
    const int n = 80;
    double sampled = 1e300, edge = 0;
    for (int i = 0; i < 3; ++i) edge = std::max(edge, distance(t[i], t[(i + 1) % 3]));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 p = t[0] + (t[1] - t[0]) * (double(i) / n) + (t[2] - t[0]) * (double(j) / n);
        sampled = std::min(sampled, point_box_distance(b, p));
      }
    }
    EXPECT_LE(d.distance, sampled + 1e-9) << it;             // never above an attained value
    EXPECT_GE(d.distance, sampled - edge / n - 1e-9) << it;  // sampling is within edge/n of the minimum
    if (d.distance == 0) {
      EXPECT_TRUE(box_triangle_intersect(b, t));
      continue;
    }
    ++clear;
    // The witnesses realise the distance: one on the box, one on the triangle.
    EXPECT_NEAR(distance(d.on_box, d.on_triangle), d.distance, 1e-12 * (1 + d.distance)) << it;
    EXPECT_LE(point_box_distance(b, d.on_box), 1e-12) << it;
    // (on the triangle by the independent reference: box_triangle_distance's witness comes from
    // np/distance.h's triangle_triangle_closest; issue #23, item 14)
    EXPECT_LE(reference::point_triangle_distance(d.on_triangle, t), 1e-12) << it;
    // Pruning: an upper bound below the distance returns some value >= it.
    EXPECT_GE(box_triangle_distance(b, t, 0.5 * d.distance).distance, 0.5 * d.distance * (1 - 1e-12));
  }
  EXPECT_GT(clear, 50);
}

TEST(ProbeBoxTriangle, GrownAndBoundingCylinderContain) {
  std::mt19937_64 g(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int it = 0; it < 100; ++it) {
    const OrientedBox b = random_box(g);
    const double delta = 0.05 + 0.5 * std::fabs(u(g));
    const OrientedBox big = grown(b, delta);
    const Cylinder around = bounding_cylinder(b);
    for (const Vec3& c : b.corners) EXPECT_TRUE(point_in_cylinder(around, c)) << it;
    const Aabb box = box_aabb(b);
    for (int k = 0; k < 50; ++k) {
      // A point of the box (possibly a corner) plus an offset of length delta.
      Vec3 p = b.centre;
      for (int a = 0; a < 3; ++a) p += b.axes[a] * (b.half[a] * (k < 8 ? ((k >> a) & 1 ? 1 : -1) : u(g)));
      EXPECT_TRUE(box.contains(p)) << it;
      Vec3 dir{u(g), u(g), u(g)};
      dir = dir / norm(dir);
      EXPECT_TRUE(point_in_box(big, p + dir * delta)) << it << " " << k;
    }
  }
}

TEST(ProbeBoxTriangle, HolderBoxFrame) {
  // Probe back centre at the origin, axis -z (pointing down), ref +x: the box spans x in [-2, 2]
  // (width 4), y in [-1, 1] (depth 2 along axis x ref = -z x x = -y), z in [0, 5] (length 5 behind).
  const OrientedBox b = holder_box({0, 0, 0}, {0, 0, -1}, {1, 0, 0}, 4, 2, 5);
  const Aabb a = box_aabb(b);  // padded by 1e-12 x scale
  EXPECT_NEAR(a.lo.x, -2, 1e-11);
  EXPECT_NEAR(a.hi.x, 2, 1e-11);
  EXPECT_NEAR(a.lo.y, -1, 1e-11);
  EXPECT_NEAR(a.hi.y, 1, 1e-11);
  EXPECT_NEAR(a.lo.z, 0, 1e-11);
  EXPECT_NEAR(a.hi.z, 5, 1e-11);
  EXPECT_EQ(b.axes[1], (Vec3{0, -1, 0}));
  // Corner bit 2 set = front face (towards the tip): z = 0.
  EXPECT_NEAR(b.corners[7].z, 0, 1e-12);
  EXPECT_NEAR(b.corners[0].z, 5, 1e-12);
  EXPECT_NEAR(b.corners[1].x, 2, 1e-12);
}
