// The error bound on sliver meshes (issue #23, item 12): a prism over a regular N-gon whose caps
// are fans from one centre vertex (2N long side triangles, 2N spokes) simplified; the bound of the
// input's distance to the result must cover every point (a dense barycentric grid on each input
// triangle, distances by a brute force of its own: projection and edge segments, no BVH, no
// np/distance.h) and stay near it (it was 7000x the sampled distance, from the Lipschitz term of
// 10-long spokes); the convex planar regions it uses are exactly the convex ones. Speed is in
// bench/bench_simplify.cpp (fan_cylinder, polygon_10k, polygon_20k), not here.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "../../../src/simplify/distance_internal.h"
#include "interfere/query/distance.h"
#include "interfere/mesh/generate.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace interfere {
namespace {

TriMesh fan_prism(int n, double r, double h) { return make_fan_prism(n, r, h); }

// Distance from p to the segment ab and to the triangle abc, computed here from scratch.
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
    const Vec3 q = p - n * (dot(p - t[0], n) / nn);  // projection onto the plane
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && dot(cross(t[(k + 1) % 3] - t[k], q - t[k]), n) >= 0;
    if (inside) return std::abs(dot(p - t[0], n)) / std::sqrt(nn);
  }
  return std::min({segment_distance(p, t[0], t[1]), segment_distance(p, t[1], t[2]),
                   segment_distance(p, t[2], t[0])});
}

// The largest distance from dense points of `from` to `to` (brute force, starting from the
// previous point's nearest triangle: once a point is nearer than the maximum so far, it cannot
// raise it), and the points' covering radius. Per triangle, from the corner c0 opposite its
// shortest edge, x(s, t) = c0 + s (e1 + t (e2 - e1)) (e1, e2 the edges from c0) on the grid
// s = i / m, t = j / k: every point of the triangle lies within L / (2 m) + |e2 - e1| / (2 k) of a
// grid point (L its longest edge), so the distance being 1-Lipschitz, the true supremum lies in
// [max, max + radius]. m and k are chosen for a radius of about rho (slivers get few points
// across).
struct Dense {
  double max = 0, radius = 0;
};
Dense dense(const TriMesh& from, const TriMesh& to, double rho) {
  Dense r;
  std::size_t last = 0;
  for (std::size_t t = 0; t < from.num_triangles(); ++t) {
    const auto q = from.corners(t);
    int o = 0;  // corner opposite the shortest edge
    double shortest = std::numeric_limits<double>::infinity(), longest = 0;
    for (int k = 0; k < 3; ++k) {
      const double l = norm(q[(k + 2) % 3] - q[(k + 1) % 3]);
      if (l < shortest) shortest = l, o = k;
      longest = std::max(longest, l);
    }
    const Vec3 c0 = q[o], e1 = q[(o + 1) % 3] - c0, e2 = q[(o + 2) % 3] - c0;
    const int m = std::max(1, int(std::ceil(longest / (2 * rho)))),
              k = std::max(1, int(std::ceil(shortest / (2 * rho))));
    r.radius = std::max(r.radius, longest / (2 * m) + shortest / (2 * k));
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= k; ++j) {
        const Vec3 p = c0 + (e1 + (e2 - e1) * (double(j) / k)) * (double(i) / m);
        double best = triangle_distance(p, to.corners(last));
        for (std::size_t u = 0; u < to.num_triangles() && best > r.max; ++u) {
          const double d = triangle_distance(p, to.corners(u));
          if (d < best) best = d, last = u;
        }
        r.max = std::max(r.max, best);
      }
  }
  return r;
}

TEST(HausdorffSlivers, FanCapBoundCoversEveryPointAndStaysNearIt) {
  for (const auto& [n, h] : {std::pair{512, 2.0}, std::pair{1024, 0.1}}) {
    const TriMesh in = fan_prism(n, 1.0, h);
    const auto r = simplify(in, {.ratio = 0.1, .measure_error = false});
    ASSERT_TRUE(r.has_value());
    const OneSidedDistance d = one_sided(in, r->mesh, true);
    const Dense oracle = dense(in, r->mesh, 0.002);
    SCOPED_TRACE(n);
    EXPECT_GE(d.bound, oracle.max);  // an upper bound of every point's distance
    EXPECT_GE(d.bound, d.sampled);
    // Near the truth: the true supremum is at most oracle.max + oracle.radius; before, the bound of
    // the spokes was their Lipschitz term after two midpoint subdivisions, (1 / 4) / (2 sqrt 3) =
    // 0.072, 20-40x the truth.
    EXPECT_LE(d.bound, 2 * (oracle.max + oracle.radius)) << oracle.max << " + " << oracle.radius;
    tbb::task_arena one(1);
    OneSidedDistance serial;
    one.execute([&] { serial = one_sided(in, r->mesh, true); });
    EXPECT_EQ(serial.bound, d.bound);
    EXPECT_EQ(serial.sampled, d.sampled);
  }
}

// A sliver over a planar face that is NOT convex (an L, a square with a hole, a folded sheet):
// regions must not be taken for convex, or the bound misses the notch. The sliver's corners lie
// on the face, its middle over the notch or the hole.
TEST(HausdorffSlivers, NonConvexPlanarFacesAreNotConvexRegions) {
  // Unit squares (2 triangles each) of a 3 x 3 grid in z = 0, picked by mask.
  const auto squares = [](std::initializer_list<std::pair<int, int>> cells) {
    TriMesh m;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i) m.positions.push_back({double(i), double(j), 0});
    const auto id = [](int i, int j) { return static_cast<std::uint32_t>(j * 4 + i); };
    for (const auto& [i, j] : cells) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
    return m;
  };
  const TriMesh full =
      squares({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {0, 2}, {1, 2}, {2, 2}});
  const TriMesh ell = squares({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {0, 2}});
  const TriMesh ring = squares({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {2, 1}, {0, 2}, {1, 2}, {2, 2}});
  EXPECT_EQ(detail::convex_planar_regions(full).slack.size(), 1u);
  EXPECT_EQ(detail::convex_planar_regions(full).of, std::vector<std::uint32_t>(18, 0));
  for (const TriMesh* m : {&ell, &ring}) {
    const detail::ConvexRegions reg = detail::convex_planar_regions(*m);
    EXPECT_TRUE(reg.slack.empty());
    EXPECT_EQ(std::count(reg.of.begin(), reg.of.end(), detail::ConvexRegions::kNone),
              std::ptrdiff_t(m->num_triangles()));
  }
  // A sliver from corner (2.9, 0.1) to (0.1, 2.9) over the notch of the L (its middle at 1.5, 1.5
  // is 0.5 from it) and over the hole of the ring (0.5 from the hole's border).
  TriMesh sliver;
  sliver.positions = {{2.9, 0.1, 0}, {0.1, 2.9, 0}, {0.1, 2.89, 0}};
  sliver.triangles = {{0, 1, 2}};
  for (const TriMesh* m : {&ell, &ring}) {
    const OneSidedDistance d = one_sided(sliver, *m, true);
    const Dense oracle = dense(sliver, *m, 0.002);
    EXPECT_GT(oracle.max, 0.45);
    EXPECT_GE(d.bound, oracle.max);
  }
  EXPECT_LE(one_sided(sliver, full, true).bound,
            1e-6);  // over the full square: 0 (+ rounding margin)
}

// A planar fan folded onto itself (consistent orientation, but it winds twice around its centre)
// or with a reflex boundary vertex is no convex region either; a fan tilted out of the axes (its
// vertices rounded off the plane) is one, with a slack of the rounding.
TEST(HausdorffSlivers, ConvexRegionsNeedOneConvexWinding) {
  const auto fan = [](int n, double turns, double dent, const Vec3& axis_x, const Vec3& axis_y) {
    TriMesh m;
    m.positions.push_back({0, 0, 0});
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * turns * i / n, r = i == n / 2 ? dent : 1.0;
      m.positions.push_back(axis_x * (r * std::cos(a)) + axis_y * (r * std::sin(a)));
    }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i)
      m.triangles.push_back({0, i + 1, (i + 1) % static_cast<std::uint32_t>(n) + 1});
    return m;
  };
  const Vec3 ex{1, 0, 0}, ey{0, 1, 0};
  EXPECT_EQ(detail::convex_planar_regions(fan(16, 1, 1.0, ex, ey)).slack.size(), 1u);
  EXPECT_TRUE(
      detail::convex_planar_regions(fan(16, 1, 0.5, ex, ey)).slack.empty());  // reflex vertex
  EXPECT_TRUE(detail::convex_planar_regions(fan(31, 2, 1.0, ex, ey)).slack.empty());  // winds twice
  const double s = std::sqrt(0.5);
  const detail::ConvexRegions tilted =
      detail::convex_planar_regions(fan(64, 1, 1.0, Vec3{s, s, 0} * 1.0, Vec3{-0.5, 0.5, s}));
  ASSERT_EQ(tilted.slack.size(), 1u);
  EXPECT_LT(tilted.slack[0], 1e-14);
}

// A convex planar region whose border has a small dent (a vertex moved inwards, turning back by
// 3e-5) still counts, and the dent goes into its slack: a sliver of `from` along the chord over the
// dent has its corners on the region (distance 0) and its middle 1.2e-5 outside it; the bound must
// cover that (dense oracle), which the region's corners alone would not.
TEST(HausdorffSlivers, DentsInAConvexRegionGoIntoItsSlack) {
  const int n = 1024;
  TriMesh to;
  to.positions.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n, r = i == n / 2 ? 1 - 5e-5 : 1.0;
    to.positions.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i)
    to.triangles.push_back({0, i + 1, (i + 1) % static_cast<std::uint32_t>(n) + 1});
  const detail::ConvexRegions reg = detail::convex_planar_regions(to);
  ASSERT_EQ(reg.slack.size(), 1u);
  EXPECT_GT(reg.slack[0], 3e-5);
  EXPECT_LT(reg.slack[0], 4e-5);
  TriMesh from;
  // The chord from vertex n/2 - 1 to n/2 + 2 passes 1.2e-5 outside the dent at n/2, its samples
  // (corners, midpoints, centroid) nearer: only the slack covers the worst point.
  const Vec3 a = to.positions[n / 2], b = to.positions[n / 2 + 3];
  from.positions = {a, b, a + (b - a) * 1e-3 - a * 1e-6};  // a sliver along the chord a b
  from.triangles = {{0, 1, 2}};
  const OneSidedDistance d = one_sided(from, to, true);
  const Dense oracle = dense(from, to, 1e-6);
  EXPECT_GT(oracle.max, 1e-5);
  EXPECT_GT(oracle.max, d.sampled + 1e-7)
      << d.sampled;  // the samples (and the rounding margin) miss it
  EXPECT_GE(d.bound, oracle.max);
  EXPECT_LE(d.bound, oracle.max + oracle.radius + 1e-5);
}

// The search tree over pieces of slivers (piece_bvh.cpp): every point of every triangle lies in a
// box of one of its pieces (random points on the triangles), and the nearest-triangle search on it
// gives the plain tree's search result bit for bit and, to rounding, the distance of a brute force
// over the triangles by triangle_distance above (not np::closest_point_on_triangle, the search's
// own leaf: issue #23, item 14), with or without a stop.
TEST(HausdorffSlivers, PieceTreeCoversTheTrianglesAndSearchesExactly) {
  const TriMesh m = fan_prism(300, 1.0, 3.0);
  const detail::PieceBvh tree = detail::piece_bvh(m, 64 * m.num_triangles());
  ASSERT_FALSE(tree.owner.empty());  // slivers: cut
  EXPECT_GT(tree.bvh.prims.size(), 8 * m.num_triangles());
  std::vector<std::vector<std::size_t>> slots(m.num_triangles());
  for (std::size_t i = 0; i < tree.bvh.prims.size(); ++i)
    slots[tree.owner[tree.bvh.prims[i]]].push_back(i);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    for (int i = 0; i < 50; ++i) {
      double x = u(rng), y = u(rng);
      if (x + y > 1) x = 1 - x, y = 1 - y;
      const Vec3 p = i == 0 ? c[1] : (i == 1 ? c[2] : c[0] + (c[1] - c[0]) * x + (c[2] - c[0]) * y);
      bool in = false;
      for (std::size_t s : slots[t]) {
        const AabbF& b = tree.bvh.prim_boxes[s];
        bool inside = true;
        for (int k = 0; k < 3; ++k) inside = inside && b.lo[k] <= p[k] && p[k] <= b.hi[k];
        in = in || inside;
      }
      ASSERT_TRUE(in) << t;
    }
  }
  const Bvh plain = build_bvh(m);
  constexpr double kTol = 1e-12;  // distances <= 5: both methods' rounding is far below this
  std::uniform_real_distribution<double> w(-1.2, 1.2);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{w(rng), w(rng), i % 3 == 0 ? 0.0 : 1.5 * (w(rng) + 1.2)};
    double brute = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < m.num_triangles(); ++t) brute = std::min(brute, triangle_distance(p, m.corners(t)));
    std::uint32_t tri = 0;
    const double d2 = nearest_triangle_d2(m, tree.bvh, p, &tri, -1, kNoTriangle, tree.owners());
    EXPECT_EQ(d2, nearest_triangle_d2(m, plain, p));
    EXPECT_NEAR(std::sqrt(d2), brute, kTol);
    EXPECT_NEAR(triangle_distance(p, m.corners(tri)), brute, kTol);
    const double stop = d2 * 2, stopped = nearest_triangle_d2(m, tree.bvh, p, &tri, stop,
                                                              kNoTriangle, tree.owners());
    EXPECT_LE(stopped, stop);
    EXPECT_NEAR(triangle_distance(p, m.corners(tri)), std::sqrt(stopped), kTol);
  }
}

}  // namespace
}  // namespace interfere
