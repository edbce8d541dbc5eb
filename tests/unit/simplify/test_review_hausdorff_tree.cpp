// Review test of 7e4b5a8 (issue #29): one_sided's search tree over `to` now holds at most as many
// pieces as there are samples of `from`, so a coarse mesh measured against a fine sliver-rich one
// (the result -> input direction of a simplification) searches the plain tree. The sampled maximum
// must still be the exact maximum over the documented samples (every used vertex, edge midpoint and
// centroid; distances by a brute force written here: plane projection and edge segments, all
// triangles, no BVH, no np/distance.h), and the bound must still cover every point of `from` (a
// dense barycentric grid on each triangle, brute force). Thread count must not change either.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/mesh/generate.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace interfere {
namespace {

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double dd = dot(d, d);
  const double s = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  return norm(p - (a + d * s));
}

double triangle_distance(const Vec3& p, const std::array<Vec3, 3>& t) {
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nn = dot(n, n);
  if (nn > 0) {
    const Vec3 q = p - n * (dot(p - t[0], n) / nn);
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && dot(cross(t[(k + 1) % 3] - t[k], q - t[k]), n) >= 0;
    if (inside) return std::abs(dot(p - t[0], n)) / std::sqrt(nn);
  }
  return std::min({segment_distance(p, t[0], t[1]), segment_distance(p, t[1], t[2]), segment_distance(p, t[2], t[0])});
}

double brute(const Vec3& p, const TriMesh& to) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t u = 0; u < to.num_triangles(); ++u) best = std::min(best, triangle_distance(p, to.corners(u)));
  return best;
}

/// The exact maximum over one_sided's samples, by brute force.
double sample_max(const TriMesh& from, const TriMesh& to) {
  double m = 0;
  for (std::size_t t = 0; t < from.num_triangles(); ++t) {
    const auto c = from.corners(t);
    for (int k = 0; k < 3; ++k) {
      m = std::max(m, brute(c[k], to));
      m = std::max(m, brute((c[k] + c[(k + 1) % 3]) * 0.5, to));
    }
    m = std::max(m, brute((c[0] + c[1] + c[2]) / 3.0, to));
  }
  return m;
}

/// max over a barycentric grid of spacing ~rho on every triangle of `from` (early out once a point
/// is nearer than the maximum so far: it cannot raise it).
double dense_max(const TriMesh& from, const TriMesh& to, double rho, double start) {
  double mx = start;  // a distance some point of `from` already has (the samples' maximum)
  std::size_t last = 0;
  for (std::size_t t = 0; t < from.num_triangles(); ++t) {
    const auto q = from.corners(t);
    const double l = std::max({norm(q[1] - q[0]), norm(q[2] - q[1]), norm(q[0] - q[2])});
    const int m = std::max(1, static_cast<int>(std::ceil(l / rho)));
    for (int i = 0; i <= m; ++i)
      for (int j = 0; i + j <= m; ++j) {
        const Vec3 p = q[0] + (q[1] - q[0]) * (double(i) / m) + (q[2] - q[0]) * (double(j) / m);
        double best = triangle_distance(p, to.corners(last));
        for (std::size_t u = 0; u < to.num_triangles() && best > mx; ++u)
          if (const double d = triangle_distance(p, to.corners(u)); d < best) best = d, last = u;
        mx = std::max(mx, best);
      }
  }
  return mx;
}

TEST(ReviewHausdorffTree, CoarseAgainstFineSliversPlainTree) {
  for (const auto& [n, ratio] : {std::pair{1200, 0.05}, std::pair{600, 0.03}}) {
    const TriMesh fine = make_fan_prism(n, 1.0, 2.0);
    const auto r = simplify(fine, {.ratio = ratio, .measure_error = false});
    ASSERT_TRUE(r.has_value());
    const TriMesh& coarse = r->mesh;
    SCOPED_TRACE(n);
    const OneSidedDistance d = one_sided(coarse, fine, true);
    // fewer samples than the fine mesh's triangles: the plain tree (the case the commit changed)
    EXPECT_LT(d.samples, fine.num_triangles());
    const double exact = sample_max(coarse, fine);
    EXPECT_NEAR(d.sampled, exact, 1e-12 * (1 + exact));
    const double dm = dense_max(coarse, fine, 0.04, exact);
    EXPECT_GE(d.bound, dm);
    EXPECT_GE(d.bound, d.sampled);
    tbb::task_arena one(1);
    OneSidedDistance serial;
    one.execute([&] { serial = one_sided(coarse, fine, true); });
    EXPECT_EQ(serial.sampled, d.sampled);
    EXPECT_EQ(serial.bound, d.bound);
    std::printf("[ review ] n %d: samples %zu, fine triangles %zu, sampled %.6g (brute %.6g), dense %.6g, bound %.6g\n",
                n, d.samples, fine.num_triangles(), d.sampled, exact, dm, d.bound);
  }
}

}  // namespace
}  // namespace interfere
