// §3.2 box test and §3.3 triangle/box test of Li, Zhou & Zheng 2008, as the paper states them
// (issue #28, deliverable 3); what they miss: paper_tests.h and docs/probe.md.
//
// §3.2: the line (x - x1)/a = (y - y1)/b = (z - z1)/c meets the plane Ax + By + Cz + D = 0 at
// parameter t = -(A x1 + B y1 + C z1 + D) / (A a + B b + C c) (the paper prints the denominator as
// "Aa + Bb + Cc + D" and the point as x1 - a t with t's sign flipped, typos that cancel or that no
// reading can use; the parallel case is A a + B b + C c = 0). The point is in the rectangle ABCD
// when S(ABCD) = S(PAB) + S(PBC) + S(PCD) + S(PDA) (area method, Fig. 5a) and on the segment when
// PA + PB = AB (length method, Fig. 5b).
#include <array>
#include <cmath>

#include "interfere/probe/paper_tests.h"

namespace interfere::probe {
namespace {

constexpr double kRel = 1e-9;  // relative tolerance of the area and length equalities (our addition)

double tri_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * norm(cross(b - a, c - a)); }

/// The 12 edges and 6 faces of an axis-aligned box.
std::array<Vec3, 8> corners(const Aabb& b) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
  return c;
}
constexpr int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

}  // namespace

bool paper_segment_meets_face(const Vec3& p, const Vec3& q, const std::array<Vec3, 4>& f) {
  // Plane A x + B y + C z + D = 0 through the face.
  const Vec3 n = cross(f[1] - f[0], f[3] - f[0]);
  const double D = -dot(n, f[0]);
  const Vec3 dir = q - p;  // (a, b, c)
  const double den = dot(n, dir);
  if (den == 0) return false;  // case (1): parallel
  const double t = -(dot(n, p) + D) / den;
  const Vec3 P = p + dir * t;  // case (2): the intersection point
  // Area method: P in the rectangle when the four triangles' areas add up to its area.
  const double S = tri_area(f[0], f[1], f[2]) + tri_area(f[0], f[2], f[3]);
  const double sum = tri_area(P, f[0], f[1]) + tri_area(P, f[1], f[2]) + tri_area(P, f[2], f[3]) + tri_area(P, f[3], f[0]);
  if (sum > S * (1 + kRel)) return false;
  // Length method: P on the segment when PA + PB = AB.
  const double ab = norm(dir);
  return norm(P - p) + norm(P - q) <= ab * (1 + kRel);
}

bool paper_box_test(const Aabb& edges_of, const Aabb& faces_of) {
  const std::array<Vec3, 8> e = corners(edges_of), f = corners(faces_of);
  for (const auto& edge : kEdges) {
    for (const auto& face : kFaces) {
      if (paper_segment_meets_face(e[edge[0]], e[edge[1]], {f[face[0]], f[face[1]], f[face[2]], f[face[3]]}))
        return true;
    }
  }
  return false;
}

Aabb paper_cylinder_box(const Cylinder& c) {
  Aabb b;
  const Vec3 r{c.radius, c.radius, c.radius};
  b.expand(c.c0 - r), b.expand(c.c0 + r), b.expand(c.c1 - r), b.expand(c.c1 + r);
  return b;
}

bool paper_triangle_box_test(const std::array<Vec3, 3>& t, const Aabb& box) {
  const std::array<Vec3, 8> f = corners(box);
  for (int i = 0; i < 3; ++i) {
    for (const auto& face : kFaces) {
      if (paper_segment_meets_face(t[i], t[(i + 1) % 3], {f[face[0]], f[face[1]], f[face[2]], f[face[3]]}))
        return true;
    }
  }
  return false;
}

}  // namespace interfere::probe
