// Independent exact oracle for the clash query: the set of intersecting pairs (cross ∪ touch) must
// equal CGAL's exact do_intersect set (Epeck) on every scene, including a mesh against translated and
// rotated copies of itself, where coplanar and touching configurations are everywhere.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <random>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"

namespace interfere {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;

K::Point_3 pt(const Vec3& v) { return {v.x, v.y, v.z}; }

/// CGAL's exact answer, with degenerate triangles handled as segments or points.
bool cgal_intersects(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  auto as_object = [](const std::array<Vec3, 3>& t) -> std::variant<K::Triangle_3, K::Segment_3, K::Point_3> {
    const K::Point_3 p = pt(t[0]), q = pt(t[1]), r = pt(t[2]);
    if (!CGAL::collinear(p, q, r)) return K::Triangle_3(p, q, r);
    if (p == q && q == r) return p;
    // The two extreme points of the collinear triple.
    K::Point_3 lo = p, hi = p;
    for (const K::Point_3& x : {q, r}) {
      if (x < lo) lo = x;
      if (hi < x) hi = x;
    }
    return K::Segment_3(lo, hi);
  };
  const auto oa = as_object(a), ob = as_object(b);
  return std::visit([](const auto& x, const auto& y) { return CGAL::do_intersect(x, y); }, oa, ob);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> cgal_pairs(const TriMesh& a, const TriMesh& b) {
  // CGAL's own boxes for the prefilter (enclosing, so a superset of the meeting pairs), not the
  // library's Aabb, which the engine's broad phase uses (issue #23, item 14).
  auto boxes = [](const TriMesh& m) {
    std::vector<CGAL::Bbox_3> out;
    for (std::uint32_t i = 0; i < m.num_triangles(); ++i) {
      const auto c = m.corners(i);
      out.push_back(pt(c[0]).bbox() + pt(c[1]).bbox() + pt(c[2]).bbox());
    }
    return out;
  };
  const std::vector<CGAL::Bbox_3> box_a = boxes(a), box_b = boxes(b);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t i = 0; i < a.num_triangles(); ++i) {
    for (std::uint32_t j = 0; j < b.num_triangles(); ++j) {
      if (!CGAL::do_overlap(box_a[i], box_b[j])) continue;
      if (cgal_intersects(a.corners(i), b.corners(j))) out.emplace_back(i, j);
    }
  }
  return out;
}

void expect_same_as_cgal(const TriMesh& a, const TriMesh& b, const char* scene) {
  const ClashResult r = clash(make_model(a), make_model(b));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ours;
  for (const TrianglePair& p : r.pairs) ours.emplace_back(p.a, p.b);
  const auto expected = cgal_pairs(a, b);
  EXPECT_EQ(ours, expected) << scene << ": ours " << ours.size() << " pairs, CGAL " << expected.size();
}

TEST(ClashOracle, OverlappingSpheres) {
  SpherePair p = make_overlapping_spheres(4000);
  expect_same_as_cgal(p.a, p.b, "spheres");
}

TEST(ClashOracle, MeshAgainstTranslatedCopies) {
  const TriMesh a = make_sphere({.target_triangles = 600, .bump_amplitude = 0.05});
  for (const Vec3& t : {Vec3{0, 0, 0}, Vec3{0.5, 0, 0}, Vec3{0.25, 0.125, 0}, Vec3{1e-9, 0, 0}, Vec3{2, 0, 0}}) {
    expect_same_as_cgal(a, transformed(a, Transform{.t = t}), "translated sphere");
  }
  const TriMesh box = make_box({0, 0, 0}, {1, 1, 1}, 4);
  for (const Vec3& t : {Vec3{1, 0, 0}, Vec3{0.5, 0.5, 0}, Vec3{0.25, 0, 0}, Vec3{1, 1, 1}, Vec3{0.125, 0.25, 0.5}}) {
    expect_same_as_cgal(box, transformed(box, Transform{.t = t}), "translated box");
  }
}

TEST(ClashOracle, MeshAgainstRotatedCopies) {
  const TriMesh box = make_box({-1, -1, -1}, {1, 1, 1}, 4);
  // Quarter turns are exact in double; the others are generic.
  Transform quarter;
  quarter.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  expect_same_as_cgal(box, transformed(box, quarter), "quarter turn");
  for (double angle : {0.1, 0.7853981633974483, 1.3}) {
    Transform t;
    t.r = {{{std::cos(angle), -std::sin(angle), 0}, {std::sin(angle), std::cos(angle), 0}, {0, 0, 1}}};
    expect_same_as_cgal(box, transformed(box, t), "rotated box");
  }
  const TriMesh s = make_sphere({.target_triangles = 500});
  Transform t;
  t.r = {{{1, 0, 0}, {0, std::cos(0.3), -std::sin(0.3)}, {0, std::sin(0.3), std::cos(0.3)}}};
  expect_same_as_cgal(s, transformed(s, t), "rotated sphere");
}

TEST(ClashOracle, GridSnappedSoupsWithManyDegeneracies) {
  // Coordinates on a 5-point integer grid: coplanar, collinear, touching and degenerate triangles abound.
  std::mt19937_64 rng(2024);
  std::uniform_int_distribution<int> g(0, 4);
  for (int round = 0; round < 20; ++round) {
    TriMesh a, b;
    for (TriMesh* m : {&a, &b}) {
      for (std::uint32_t t = 0; t < 60; ++t) {
        for (int k = 0; k < 3; ++k) m->positions.push_back(Vec3{double(g(rng)), double(g(rng)), double(g(rng))});
        m->triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
      }
    }
    expect_same_as_cgal(a, b, "grid soup");
  }
}

}  // namespace
}  // namespace interfere
