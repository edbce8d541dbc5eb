// Exact oracle for the box holder's box-triangle test (probe/box.h): the solid is the convex hull
// of the 8 corner doubles, so T meets it iff some convex combination of the corners equals some
// convex combination of T's vertices: a linear feasibility problem (11 weights >= 0, 3 coordinate
// equations and 2 sums), solved exactly by CGAL's QP solver on the input doubles (Gmpzf). An
// independent route: no faces, no orientation predicates, no triangle-triangle test. Inputs make
// degenerate contacts frequent: triangle vertices snapped to corners, to points computed on faces
// and edges (rounded, so within an ulp of the surface on either side), moved by a few ulps, and
// degenerate triangles (segments, points).
#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "interfere/probe/box.h"
#include "unit/probe/random_axes.h"

namespace interfere::probe {
namespace {

using Tri = std::array<Vec3, 3>;

bool lp_intersects(const OrientedBox& b, const Tri& t) {
  CGAL::Quadratic_program<double> lp(CGAL::EQUAL, true, 0, false, 0);  // A x = b, x >= 0
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) lp.set_a(i, k, b.corners[i][k]);
    lp.set_a(i, 3, 1);
  }
  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 3; ++k) lp.set_a(8 + j, k, -t[j][k]);
    lp.set_a(8 + j, 4, 1);
  }
  for (int k = 0; k < 3; ++k) lp.set_b(k, 0);
  lp.set_b(3, 1);
  lp.set_b(4, 1);
  return !CGAL::solve_linear_program(lp, CGAL::Gmpzf()).is_infeasible();
}

std::string describe(const OrientedBox& b, const Tri& t) {
  std::ostringstream s;
  s.precision(17);
  s << "corners:";
  for (const Vec3& c : b.corners) s << " (" << c.x << ", " << c.y << ", " << c.z << ")";
  s << "\ntriangle:";
  for (const Vec3& v : t) s << " (" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

using test::random_axes;

Vec3 nudge(const Vec3& v, std::mt19937_64& g) {
  Vec3 r = v;
  for (int k = 0; k < 3; ++k) {
    for (int n = static_cast<int>(g() % 5) - 2; n != 0; n += n > 0 ? -1 : 1) {
      r[k] = std::nextafter(r[k], n > 0 ? INFINITY : -INFINITY);
    }
  }
  return r;
}

}  // namespace

TEST(ProbeBoxOracle, BoxTriangleMatchesExactLinearProgram) {
  std::mt19937_64 g(2024);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, misses = 0;
  for (int it = 0; it < 1500; ++it) {
    const OrientedBox b =
        make_box({100 * u(g), -50 * u(g), 30 * u(g)}, random_axes(g), {0.5 + 3 * u(g), 0.5 + 3 * u(g), 0.5 + 3 * u(g)});
    // A point on the surface (computed: within rounding of it), a corner, or an edge point.
    auto surface = [&]() {
      const int kind = static_cast<int>(g() % 3);
      if (kind == 0) return b.corners[g() % 8];
      const Tri f = b.face(static_cast<int>(g() % 12));
      double s = u(g), r = u(g);
      if (kind == 2) r = 0;  // on an edge of the face triangle
      if (s + r > 1) s = 1 - s, r = 1 - r;
      return f[0] + (f[1] - f[0]) * s + (f[2] - f[0]) * r;
    };
    Tri t;
    switch (it % 5) {
      case 0:  // random triangles around the box
        for (Vec3& v : t) v = b.centre + Vec3{8 * u(g) - 4, 8 * u(g) - 4, 8 * u(g) - 4};
        break;
      case 1: {  // one vertex on the surface, the others random (outward or through)
        t[0] = nudge(surface(), g);
        for (int i = 1; i < 3; ++i) t[i] = t[0] + Vec3{6 * u(g) - 3, 6 * u(g) - 3, 6 * u(g) - 3};
        break;
      }
      case 2:  // every vertex on the surface (coplanar with a face, along edges, ...)
        for (Vec3& v : t) v = nudge(surface(), g);
        break;
      case 3: {  // a triangle in a face's plane (spanned by face corners), moved along its normal
        const Tri f = b.face(static_cast<int>(g() % 12));
        const double a = 2 * u(g) - 0.5, c = 2 * u(g) - 0.5;
        t = {f[0] + (f[1] - f[0]) * a, f[0] + (f[2] - f[0]) * c, f[1] + (f[2] - f[1]) * u(g) * 3};
        for (Vec3& v : t) v = nudge(v, g);
        break;
      }
      default: {  // degenerate: a segment or a point near the surface
        t[0] = nudge(surface(), g);
        t[1] = g() % 2 ? t[0] : t[0] + Vec3{2 * u(g) - 1, 2 * u(g) - 1, 2 * u(g) - 1};
        t[2] = t[1];
        break;
      }
    }
    const bool expect = lp_intersects(b, t);
    EXPECT_EQ(box_triangle_intersect(b, t), expect) << it << "\n" << describe(b, t);
    EXPECT_EQ(point_in_box(b, t[0]), lp_intersects(b, {t[0], t[0], t[0]})) << it << "\n" << describe(b, t);
    (expect ? hits : misses)++;
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 300);
}

}  // namespace interfere::probe
