// Independent exact oracle for the simplifier's self-intersection guarantee (issue #6, item 6): the
// intersecting pairs of each result, found by brute force (sweep along x, then CGAL's exact
// do_intersect with Epeck), must equal the engine's self_intersecting_pairs, and each must be a pair
// of triangles left as in the input or, by default, lie inside the input's contact zone: CGAL's exact
// intersection of the two triangles (its bounding box) inside the box of one of the input's own
// intersecting pairs (found the same way) grown by that pair's diagonal.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <set>
#include <tuple>

#include "interfere/mesh/generate.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"
#include "unit/simplify/scenes.h"

namespace interfere {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

K::Triangle_3 tri(const std::array<Vec3, 3>& c) {
  return {{c[0].x, c[0].y, c[0].z}, {c[1].x, c[1].y, c[1].z}, {c[2].x, c[2].y, c[2].z}};
}

bool share_position(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  for (const Vec3& p : a)
    for (const Vec3& q : b)
      if (p == q) return true;
  return false;
}

// Pairs of non-degenerate triangles that intersect without sharing a vertex position, by a sweep
// over the boxes' x extents and CGAL's exact test: the definition self_intersecting_pairs follows.
Pairs cgal_self_pairs(const TriMesh& m) {
  std::vector<std::uint32_t> order(m.num_triangles());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<Aabb> box(m.num_triangles());
  for (std::uint32_t t = 0; t < box.size(); ++t) box[t] = m.triangle_box(t);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return box[a].lo.x < box[b].lo.x; });
  Pairs out;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t a = order[i];
    for (std::size_t j = i + 1; j < order.size() && box[order[j]].lo.x <= box[a].hi.x; ++j) {
      const std::uint32_t b = order[j];
      if (!box[a].overlaps(box[b])) continue;
      const auto ca = m.corners(a), cb = m.corners(b);
      if (share_position(ca, cb)) continue;
      const K::Triangle_3 ta = tri(ca), tb = tri(cb);
      if (ta.is_degenerate() || tb.is_degenerate()) continue;
      if (CGAL::do_intersect(ta, tb)) out.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The bounding box of CGAL's exact intersection of two triangles (a point, a segment, a triangle or
// a polygon), rounded outward.
Aabb cgal_meet(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  const auto x = CGAL::intersection(tri(a), tri(b));
  if (!x) return Aabb{};
  // (CGAL 5.5: a boost::variant of a point, a segment, a triangle or a polygon's points)
  CGAL::Bbox_3 bb;
  if (const auto* p = boost::get<K::Point_3>(&*x)) bb = p->bbox();
  else if (const auto* s = boost::get<K::Segment_3>(&*x)) bb = s->bbox();
  else if (const auto* t = boost::get<K::Triangle_3>(&*x)) bb = t->bbox();
  else
    for (const K::Point_3& q : boost::get<std::vector<K::Point_3>>(*x)) bb += q.bbox();
  return {{bb.xmin(), bb.ymin(), bb.zmin()}, {bb.xmax(), bb.ymax(), bb.zmax()}};
}

std::array<double, 9> corner_key(std::array<Vec3, 3> c) {
  std::sort(c.begin(), c.end(), [](const Vec3& x, const Vec3& y) { return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z); });
  return {c[0].x, c[0].y, c[0].z, c[1].x, c[1].y, c[1].z, c[2].x, c[2].y, c[2].z};
}

// Checks result r of simplifying `input` against the oracle; returns the pairs not both as in the
// input (the inherited ones).
std::size_t expect_no_new_intersection(const TriMesh& input, const SimplifyResult& r, bool inherit, const char* scene) {
  const Pairs pairs = cgal_self_pairs(r.mesh);
  EXPECT_EQ(self_intersecting_pairs(r.mesh), pairs) << scene;
  std::set<std::array<double, 9>> in;
  for (std::size_t t = 0; t < input.num_triangles(); ++t) in.insert(corner_key(input.corners(t)));
  std::vector<Aabb> zone;
  if (inherit)
    for (const auto& [x, y] : cgal_self_pairs(input)) {
      Aabb b = input.triangle_box(x);
      b.expand(input.triangle_box(y));
      const double g = norm(b.extent());
      zone.push_back({b.lo - Vec3{g, g, g}, b.hi + Vec3{g, g, g}});
    }
  std::size_t moved = 0;
  for (const auto& [x, y] : pairs) {
    if (in.count(corner_key(r.mesh.corners(x))) && in.count(corner_key(r.mesh.corners(y)))) continue;
    ++moved;
    const Aabb m = cgal_meet(r.mesh.corners(x), r.mesh.corners(y));
    const bool inside = std::any_of(zone.begin(), zone.end(), [&](const Aabb& z) { return z.contains(m.lo) && z.contains(m.hi); });
    EXPECT_TRUE(inside) << scene << ": pair " << x << ", " << y << " is new and outside the input's contact zone";
  }
  EXPECT_EQ(r.inherited_pairs, moved) << scene;
  return moved;
}

TEST(SimplifyOracle, NoIntersectionOnAMeshWithoutContacts) {
  const TriMesh s = make_sphere({.target_triangles = 20000, .bump_amplitude = 0.05});
  for (double ratio : {0.1, 0.01}) {
    auto r = simplify(s, {.ratio = ratio, .measure_error = false});
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(expect_no_new_intersection(s, *r, true, "bumpy sphere"), 0u);
    EXPECT_TRUE(cgal_self_pairs(r->mesh).empty());
  }
}

TEST(SimplifyOracle, CrossingBodiesKeepTheirContactInsideItsZoneOnly) {
  const TriMesh m = test::crossing_spheres(4000);
  for (bool inherit : {true, false}) {
    auto r = simplify(m, {.target_triangles = 1500, .inherit_input_contacts = inherit, .measure_error = false});
    ASSERT_TRUE(r.has_value());
    const std::size_t moved = expect_no_new_intersection(m, *r, inherit, "crossing spheres");
    if (inherit) EXPECT_GT(moved, 0u);  // the crossing moved with the simplification
  }
}

TEST(SimplifyOracle, ACrackIsInheritedAndNothingElseIntersects) {
  const TriMesh m = test::cracked_sheet();
  for (bool inherit : {true, false}) {
    auto r = simplify(m, {.target_triangles = 20, .inherit_input_contacts = inherit, .measure_error = false});
    ASSERT_TRUE(r.has_value());
    expect_no_new_intersection(m, *r, inherit, "cracked sheet");
    EXPECT_EQ(r->reached, inherit);  // strict, the crack holds the budget
  }
}

}  // namespace
}  // namespace interfere
