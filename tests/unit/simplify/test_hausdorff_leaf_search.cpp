// The error measurement's own nearest-triangle search (issue #29, src/simplify/piece_bvh.cpp:
// nearest_d2 on the tree's leaf entries, closest_point with the sliver test precomputed) must give
// what the engine's nearest_triangle_d2 gives on the same tree, bit for bit (distance and triangle,
// with and without a stop distance and a seed), and the true nearest distance: checked against a
// brute force written here (every triangle; the plane projection when it falls inside, else the
// nearest of the three edge segments; no BVH, no np/distance.h) on random meshes with slivers,
// needles and degenerate triangles, in the plain tree and the tree of sliver pieces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "../../../src/simplify/distance_internal.h"
#include "interfere/query/distance.h"

namespace interfere {
namespace {

double segment_d2(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double dd = dot(d, d);
  const double s = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  const Vec3 q = a + d * s;
  return dot(p - q, p - q);
}

double brute_triangle_d2(const Vec3& p, const std::array<Vec3, 3>& t) {
  double best = std::min({segment_d2(p, t[0], t[1]), segment_d2(p, t[1], t[2]),
                          segment_d2(p, t[2], t[0])});
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nn = dot(n, n);
  if (nn > 0) {
    const double h = dot(n, p - t[0]);
    const Vec3 q = p - n * (h / nn);
    bool inside = true;
    for (int i = 0; i < 3; ++i)
      inside = inside && dot(n, cross(t[(i + 1) % 3] - t[i], q - t[i])) >= 0;
    if (inside) best = std::min(best, h * h / nn);
  }
  return best;
}

double brute_d2(const TriMesh& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < m.num_triangles(); ++t)
    best = std::min(best, brute_triangle_d2(p, m.corners(t)));
  return best;
}

// Random triangles in the unit cube; every fourth a sliver or needle, some degenerate (a repeated
// corner, three collinear corners).
TriMesh random_mesh(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0, 1), tiny(-1e-7, 1e-7);
  TriMesh m;
  for (int i = 0; i < n; ++i) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)};
    Vec3 c{u(rng), u(rng), u(rng)};
    switch (i % 8) {
      case 1: c = a + (b - a) * u(rng) + Vec3{tiny(rng), tiny(rng), tiny(rng)}; break;  // sliver
      case 3: c = b + Vec3{tiny(rng), tiny(rng), tiny(rng)}; break;                     // needle
      case 5: c = a; break;                                                             // repeated
      case 7: c = a + (b - a) * 0.25; break;                                            // collinear
      default: break;
    }
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

TEST(HausdorffLeafSearch, SameBitsAsTheEngineSearchAndTheBruteForceDistance) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> q(-0.3, 1.3);
  int checked = 0;
  for (int round = 0; round < 12; ++round) {
    const TriMesh m = random_mesh(rng, 20 + 15 * round);
    for (const std::size_t max_pieces : {std::size_t{0}, std::size_t{1} << 20}) {
      const detail::PieceBvh tree = detail::piece_bvh(m, max_pieces);
      ASSERT_EQ(tree.leaf.size(), tree.bvh.prims.size());
      for (int i = 0; i < 200; ++i) {
        // Query points anywhere, and on or next to the mesh (corners, edge points).
        Vec3 p{q(rng), q(rng), q(rng)};
        if (i % 3 == 1) p = m.positions[rng() % m.positions.size()];
        if (i % 3 == 2) {
          const auto c = m.corners(rng() % m.num_triangles());
          p = c[0] + (c[1] - c[0]) * 0.5 + Vec3{1e-9, -2e-9, 0};
        }
        const double exact = brute_d2(m, p);
        const std::uint32_t seed =
            i % 2 ? static_cast<std::uint32_t>(rng() % m.num_triangles()) : detail::kNoSeed;
        for (const double stop : {-1.0, 0.25 * (exact + 1e-3), 4 * exact + 1e-3}) {
          std::uint32_t t_engine = detail::kNoSeed, t_leaf = detail::kNoSeed;
          const double engine =
              nearest_triangle_d2(m, tree.bvh, p, &t_engine, stop, seed, tree.owners());
          const double leaf = detail::nearest_d2(m, tree, p, &t_leaf, stop, seed);
          ASSERT_EQ(leaf, engine) << "round " << round << " query " << i << " stop " << stop;
          ASSERT_EQ(t_leaf, t_engine);
          // The reported triangle is at the reported distance; without a stop it is the nearest
          // (to rounding: a relative 1e-9 of the unit cube), with one it is the nearest or
          // within the stop.
          ASSERT_LT(t_leaf, m.num_triangles());
          EXPECT_NEAR(std::sqrt(brute_triangle_d2(p, m.corners(t_leaf))), std::sqrt(leaf), 1e-9);
          if (stop < 0 || leaf > stop) EXPECT_NEAR(std::sqrt(leaf), std::sqrt(exact), 1e-9);
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 12 * 2 * 200 * 3);
}

}  // namespace
}  // namespace interfere
