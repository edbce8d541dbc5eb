// weld_exact and mesh_stats on hand-built meshes with known answers, plus a randomized weld check
// against a std::map reference and thread-count independence.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/validate.h"

namespace interfere {
namespace {

TriMesh tetrahedron() {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};  // outward
  return m;
}

TriMesh concat(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const auto off = static_cast<std::uint32_t>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  return m;
}

/// Every triangle as its own three vertices (what an STL file gives).
TriMesh soup(const TriMesh& m) {
  TriMesh s;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    const auto v = static_cast<std::uint32_t>(s.positions.size());
    s.positions.insert(s.positions.end(), c.begin(), c.end());
    s.triangles.push_back({v, v + 1, v + 2});
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// weld_exact

TEST(Weld, SoupOfAClosedMeshWeldsBackKeepingOrder) {
  const TriMesh box = make_box({0, 0, 0}, {1, 2, 3}, 3);
  TriMesh s = soup(box);
  const std::size_t before = s.num_vertices();
  const std::size_t removed = weld_exact(s);
  EXPECT_EQ(s.num_vertices(), box.num_vertices());
  EXPECT_EQ(removed, before - box.num_vertices());
  ASSERT_EQ(s.num_triangles(), box.num_triangles());
  for (std::size_t t = 0; t < box.num_triangles(); ++t) EXPECT_EQ(s.corners(t), box.corners(t));
  // Numbered in order of first use.
  std::uint32_t next = 0;
  for (const Tri& t : s.triangles) {
    for (std::uint32_t v : t) {
      EXPECT_LE(v, next);
      if (v == next) ++next;
    }
  }
  EXPECT_TRUE(mesh_stats(s).closed());
}

TEST(Weld, SignedZeroIsOneVertexAndUnusedVerticesGo) {
  TriMesh m;
  m.positions = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, -0.0}, {1, 1, 0}, {1, 0, 0}};
  m.triangles = {{1, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(weld_exact(m), 3u);  // vertex 0 unused, 4 == 1, 6 == 2
  EXPECT_EQ(m.positions, (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 3, 1}}));
}

TEST(Weld, NearlyEqualPositionsStayApart) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {std::nextafter(0.0, 1.0), 0, 0}};
  m.triangles = {{0, 1, 2}, {3, 1, 2}};
  EXPECT_EQ(weld_exact(m), 0u);
  EXPECT_EQ(m.num_vertices(), 4u);
}

TEST(Weld, InvalidIndexLeavesTheMeshUnchanged) {
  TriMesh m = tetrahedron();
  m.triangles.push_back({0, 1, 7});
  const TriMesh before = m;
  EXPECT_EQ(weld_exact(m), 0u);
  EXPECT_EQ(m.positions, before.positions);
  EXPECT_EQ(m.triangles, before.triangles);
}

TEST(Weld, RandomSoupMatchesAMapReferenceForAnyThreadCount) {
  // 90k corners drawn from 5k distinct points (several chunks and hash partitions), signed zeros;
  // then 18k corners (the serial table of small inputs).
  for (const int triangles : {30000, 6000}) {
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<int> pick(0, 4999);
    std::uniform_int_distribution<int> coord(-3, 3);
    std::vector<Vec3> pool(5000);
    for (Vec3& p : pool) p = {coord(rng) * 0.1, coord(rng) * 0.25, static_cast<double>(pick(rng))};
    pool[17] = {0.0, 0.0, 0.0};
    TriMesh m;
    for (int t = 0; t < triangles; ++t) {
      const auto v = static_cast<std::uint32_t>(m.positions.size());
      for (int k = 0; k < 3; ++k) {
        Vec3 p = pool[static_cast<std::size_t>(pick(rng))];
        if (p.x == 0 && (t + k) % 2) p.x = -0.0;
        m.positions.push_back(p);
      }
      m.triangles.push_back({v, v + 1, v + 2});
    }
    // Reference: std::map on values (== treats -0 and +0 alike), numbering in order of first use.
    std::map<std::array<double, 3>, std::uint32_t> ids;
    std::vector<Tri> expected;
    for (const Tri& t : m.triangles) {
      Tri e;
      for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& p = m.positions[t[k]];
        e[k] = ids.try_emplace({p.x + 0.0, p.y + 0.0, p.z + 0.0},
                               static_cast<std::uint32_t>(ids.size()))
                   .first->second;
      }
      expected.push_back(e);
    }
    for (int threads : {1, 2, 4}) {
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism,
                             static_cast<std::size_t>(threads));
      TriMesh w = m;
      EXPECT_EQ(weld_exact(w), m.num_vertices() - ids.size());
      EXPECT_EQ(w.triangles, expected);
      for (std::size_t t = 0; t < w.num_triangles(); ++t) {
        const auto a = w.corners(t), b = m.corners(t);
        for (std::size_t k = 0; k < 3; ++k)
          EXPECT_TRUE(a[k].x == b[k].x && a[k].y == b[k].y && a[k].z == b[k].z);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// mesh_stats

TEST(Stats, ClosedTetrahedron) {
  const MeshStats s = mesh_stats(tetrahedron());
  EXPECT_EQ(s.vertices, 4u);
  EXPECT_EQ(s.triangles, 4u);
  EXPECT_EQ(s.degenerate_triangles, 0u);
  EXPECT_EQ(s.duplicate_triangles, 0u);
  EXPECT_EQ(s.open_edges, 0u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_EQ(s.inconsistent_edges, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.invalid_triangles, 0u);
  EXPECT_TRUE(s.closed());
}

TEST(Stats, GeneratedClosedMeshes) {
  for (const TriMesh& m :
       {make_box({-1, -1, -1}, {1, 2, 3}, 4), make_sphere({.target_triangles = 5000}),
        make_sphere({.target_triangles = 800, .bump_amplitude = 0.1})}) {
    const MeshStats s = mesh_stats(m);
    EXPECT_TRUE(s.closed());
    EXPECT_EQ(s.components, 1u);
    EXPECT_EQ(s.degenerate_triangles, 0u);
    EXPECT_EQ(s.duplicate_triangles, 0u);
    // Euler: V - E + F = 2 with E = 3F/2 for a closed genus-0 manifold.
    EXPECT_EQ(static_cast<long>(s.vertices) - static_cast<long>(3 * s.triangles / 2) +
                  static_cast<long>(s.triangles),
              2);
  }
}

TEST(Stats, OpenSquare) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.open_edges, 4u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_EQ(s.inconsistent_edges, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_FALSE(s.closed());
}

TEST(Stats, FinMakesANonManifoldEdge) {
  TriMesh m = tetrahedron();
  m.positions.push_back({1, 1, -1});
  m.triangles.push_back({0, 1, 4});  // third triangle on edge (0,1)
  const MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.nonmanifold_edges, 1u);
  EXPECT_EQ(s.open_edges, 2u);  // (1,4) and (4,0)
  EXPECT_EQ(s.components, 1u);
  EXPECT_FALSE(s.closed());
}

TEST(Stats, FlippedTriangleGivesInconsistentEdges) {
  TriMesh m = tetrahedron();
  std::swap(m.triangles[2][1], m.triangles[2][2]);
  const MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.inconsistent_edges, 3u);
  EXPECT_EQ(s.open_edges, 0u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_FALSE(s.closed());
}

TEST(Stats, DuplicatesInAnyOrientation) {
  TriMesh m = tetrahedron();
  m.triangles.push_back({2, 1, 0});  // same set as {0, 2, 1}, same orientation, rotated
  m.triangles.push_back({0, 1, 2});  // same set, opposite orientation
  const MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.duplicate_triangles, 2u);
  EXPECT_EQ(s.nonmanifold_edges, 3u);  // each edge of the triangle is now used 4 times
  EXPECT_EQ(s.degenerate_triangles, 0u);
}

TEST(Stats, DegenerateTriangles) {
  TriMesh m;
  m.positions = {{0, 0, 0},
                 {1, 0, 0},
                 {2, 0, 0},
                 {0, 1, 0},
                 {0.1, 0.2, 0.3},
                 {0.2, 0.4, 0.6},
                 {0.2, 0.4, std::nextafter(0.6, 1.0)}};
  m.triangles = {
      {0, 1, 2},  // collinear, distinct indices
      {0, 0, 3},  // repeated index
      {0, 1, 3},  // fine
      {0, 4, 5},  // collinear in exact arithmetic: 0.2,0.4,0.6 = 2·(0.1,0.2,0.3) exactly in binary
      {0, 4, 6}};  // one ulp off that line: not degenerate
  const MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.degenerate_triangles, 3u);
}

TEST(Stats, ComponentsAndInvalidTriangles) {
  TriMesh m = concat(make_box({0, 0, 0}, {1, 1, 1}), make_box({3, 0, 0}, {4, 1, 1}));
  m = concat(m, tetrahedron());
  m.positions.push_back({7, 7, 7});  // unreferenced: not a component
  MeshStats s = mesh_stats(m);
  EXPECT_EQ(s.components, 3u);
  EXPECT_TRUE(s.closed());
  m.triangles.push_back({0, 1, 1000});
  s = mesh_stats(m);
  EXPECT_EQ(s.invalid_triangles, 1u);
  EXPECT_EQ(s.components, 3u);
  EXPECT_TRUE(s.closed());  // the invalid triangle is left out of the edge counts
}

TEST(Stats, UnweldedSoupIsAllOpen) {
  const TriMesh s = soup(tetrahedron());
  const MeshStats st = mesh_stats(s);
  EXPECT_EQ(st.open_edges, 12u);
  EXPECT_EQ(st.components, 4u);
  EXPECT_EQ(st.degenerate_triangles, 0u);
}

TEST(Stats, EmptyMesh) {
  const MeshStats s = mesh_stats(TriMesh{});
  EXPECT_EQ(s.triangles, 0u);
  EXPECT_FALSE(s.closed());
}

}  // namespace
}  // namespace interfere
