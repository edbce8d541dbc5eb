// penetration_depth (query/depth.h): the sampled depth and the proven upper bound of crossing
// boxes, against the analytic depth of a point in a box (its smallest distance to the box's faces).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"

namespace interfere {
namespace {

// A rotation by `angle` about the axis (1, 2, 3) / |.|, then a translation.
Transform rotation(double angle, const Vec3& t) {
  const Vec3 u = Vec3{1, 2, 3} * (1 / std::sqrt(14.0));
  const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
  Transform r;
  r.r = {{{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
          {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
          {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}}};
  r.t = t;
  return r;
}

// The analytic depth of p in the box [lo, hi] placed by `pose` (0 outside).
double box_depth(const Vec3& p, const Transform& pose, const Vec3& lo, const Vec3& hi) {
  Vec3 q = p - pose.t;  // local = R^T (p - t)
  q = {pose.r[0][0] * q.x + pose.r[1][0] * q.y + pose.r[2][0] * q.z, pose.r[0][1] * q.x + pose.r[1][1] * q.y + pose.r[2][1] * q.z,
       pose.r[0][2] * q.x + pose.r[1][2] * q.y + pose.r[2][2] * q.z};
  double d = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) d = std::min({d, q[k] - lo[k], hi[k] - q[k]});
  return std::max(d, 0.0);
}

// The largest analytic depth of a dense sampling of the surface of `mesh` in the placed box.
double dense_depth(const TriMesh& mesh, const Transform& pose, const Vec3& lo, const Vec3& hi) {
  double best = 0;
  const int n = 60;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto c = mesh.corners(t);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = double(i) / n, v = double(j) / n;
        best = std::max(best, box_depth(c[0] + (c[1] - c[0]) * u + (c[2] - c[0]) * v, pose, lo, hi));
      }
  }
  return best;
}

TEST(DepthBound, FlatSinkNeedsFewSplits) {
  // A 6 x 6 block sunk 1 deep into the top face of a 10 x 10 x 10 box: the depth is 1 (the sunk
  // bottom face lies 1 below the top face, 2 or more from the sides; the top face's part inside
  // the block lies 1 above the block's bottom). One face of the other part is nearest to whole
  // pieces, so the bound meets the 10 % tolerance within 200 splits (the corner-plus-edge bound
  // alone needs pieces of ~0.17 across, thousands of splits).
  const Model a = make_model(make_box({0, 0, 0}, {10, 10, 10}));
  const Model b = make_model(make_box({2, 2, 9}, {8, 8, 20}));
  const ClashResult r = clash(a, b);
  ASSERT_GT(r.cross_pairs, 0u);
  const PenetrationDepth d = penetration_depth(a, b, r, 200);
  EXPECT_NEAR(d.depth, 1.0, 1e-9);
  EXPECT_GE(d.depth_bound, 1.0 - 1e-9);
  EXPECT_LE(d.depth_bound, 1.1 + 1e-9);
}

TEST(DepthBound, BoundsTheDenseDepthOfRotatedBoxes) {
  for (int k = 0; k < 6; ++k) {
    const Vec3 lo{0, 0, 0}, hi{4, 3, 2};
    const Transform pose = rotation(0.3 + 0.7 * k, {1.5 + 0.2 * k, 1.0, 0.6 + 0.1 * k});
    const TriMesh ma = make_box({0, 0, 0}, {5, 4, 3}, 2);
    TriMesh mb = make_box(lo, hi, 3);
    for (Vec3& p : mb.positions) p = pose.apply(p);
    const Model a = make_model(ma), b = make_model(mb);
    const ClashResult r = clash(a, b);
    if (r.cross_pairs == 0) continue;
    const PenetrationDepth d = penetration_depth(a, b, r, 3000);
    // a's surface in b (analytic), and b's surface in a (a is the box [0, 5] x [0, 4] x [0, 3]).
    const double dense = std::max(dense_depth(ma, pose, lo, hi), dense_depth(mb, Transform{}, {0, 0, 0}, {5, 4, 3}));
    EXPECT_GE(d.depth_bound, dense * (1 - 1e-9)) << k;
    EXPECT_GE(d.depth_bound, d.depth) << k;
  }
}

}  // namespace
}  // namespace interfere
