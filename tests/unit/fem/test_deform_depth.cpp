// Penetration depth of the FE series (issue #26, item 3; fem/deform.h, SeriesRequest::depth): a
// block moving into another by 0.125 per step. The oracle is the boxes' geometry: a point strictly
// inside the box [lo, hi] lies min over the axes of (p - lo, hi - p) from its surface, 0 otherwise;
// the deepest node, its depth, its FE node and element ids and the per-vertex maps are checked
// against it, never against query/depth.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "interfere/fem/deform.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"

namespace interfere {
namespace {

struct Box {
  Vec3 lo, hi;
};

// Distance of p to the surface of the box when p lies strictly inside it, else 0.
double box_depth(const Vec3& p, const Box& b) {
  const double d = std::min({p.x - b.lo.x, b.hi.x - p.x, p.y - b.lo.y, b.hi.y - p.y, p.z - b.lo.z, b.hi.z - p.z});
  return d > 0 ? d : 0.0;
}

struct Pair {
  GeneratedFem a, b;
  SurfaceResult sa, sb;
  NodalSeries u;
};

constexpr double kV = 0.125;  // B's motion per step, -x

// A = [0,1]^3 (hex8 4x4x4, node ids 1.., element ids 1..64); B = [2, 3] x [0.3, 1.3]^2 at step 0
// (tet4 3x3x3, node ids 5001.., element ids 9001..), moved by -0.125 s in x at step s: the faces
// touch at step 8, cross from step 9 on.
Pair make_pair(std::size_t steps) {
  Pair p;
  p.a = make_fem_box({.type = ElemType::hex8, .nx = 4, .ny = 4, .nz = 4});
  p.b = make_fem_box({.type = ElemType::tet4, .nx = 3, .ny = 3, .nz = 3, .lo = {2, 0.3, 0.3}, .hi = {3, 1.3, 1.3},
                      .first_node_id = 5001, .first_element_id = 9001});
  p.sa = std::move(*extract_surface(p.a.mesh));
  p.sb = std::move(*extract_surface(p.b.mesh));
  p.u.name = "u";
  for (std::size_t s = 0; s < steps; ++s) {
    p.u.times.push_back(static_cast<double>(s));
    p.u.values.emplace_back(p.b.mesh.num_nodes(), Vec3{-kV * static_cast<double>(s), 0, 0});
  }
  return p;
}

Box box_a() { return {{0, 0, 0}, {1, 1, 1}}; }
Box box_b(std::size_t s) {
  const double x0 = 2 - kV * static_cast<double>(s);
  return {{x0, 0.3, 0.3}, {x0 + 1, 1.3, 1.3}};
}

// Node position of B at step s, from the mesh and the motion (not deformed_positions).
Vec3 node_b(const Pair& p, std::uint32_t n, std::size_t s) {
  const Vec3 q = p.b.mesh.nodes[n];
  return {q.x - kV * static_cast<double>(s), q.y, q.z};
}

// Index of the FE node / element with this id, or -1.
std::int64_t index_of(const std::vector<std::int64_t>& ids, std::int64_t id) {
  const auto it = std::find(ids.begin(), ids.end(), id);
  return it == ids.end() ? -1 : it - ids.begin();
}

TEST(FemDeformDepth, DeepestNodeOfEachClashingStepIsTheAnalyticOne) {
  const std::size_t steps = 14;
  Pair p = make_pair(steps);
  const SurfacePart &pa = p.sa.parts[0], &pb = p.sb.parts[0];
  SeriesRequest request{.depth = true};
  std::vector<std::size_t> mapped;
  request.on_depth_maps = [&](const StepSummary& s, const DepthMaps& maps) {
    mapped.push_back(s.step);
    // The per-vertex maps against the boxes: A's surface vertices in B, B's in A.
    ASSERT_EQ(maps.a.depth.size(), pa.mesh.num_vertices());
    ASSERT_EQ(maps.b.depth.size(), pb.mesh.num_vertices());
    for (std::size_t v = 0; v < maps.a.depth.size(); ++v)
      EXPECT_NEAR(maps.a.depth[v], box_depth(p.a.mesh.nodes[pa.vertex_node[v]], box_b(s.step)), 1e-12) << s.step << " a " << v;
    for (std::size_t v = 0; v < maps.b.depth.size(); ++v)
      EXPECT_NEAR(maps.b.depth[v], box_depth(node_b(p, pb.vertex_node[v], s.step), box_a()), 1e-12) << s.step << " b " << v;
  };
  std::vector<std::size_t> seen;
  request.on_step = [&](const StepSummary& s, const ClashResult&) { seen.push_back(s.step); };
  auto r = clash_series({&p.a.mesh, &pa, nullptr}, {&p.b.mesh, &pb, &p.u}, request);
  ASSERT_TRUE(r) << r.error().message();
  ASSERT_EQ(r->steps.size(), steps);
  EXPECT_EQ(r->first_clash_step, 9);
  EXPECT_EQ(mapped, (std::vector<std::size_t>{9, 10, 11, 12, 13}));  // the clashing steps, in order
  EXPECT_EQ(seen.size(), steps);

  double max_depth = -1;
  std::int64_t deepest_step = -1;
  for (const StepSummary& s : r->steps) {
    if (s.verdict != Verdict::clash) {  // clear, and the touching contact at step 8
      EXPECT_FALSE(s.depth_measured) << s.step;
      EXPECT_FALSE(s.has_deepest) << s.step;
      EXPECT_TRUE(s.depth_note.empty()) << s.step;
      continue;
    }
    ASSERT_TRUE(s.depth_measured) << s.step;
    // The oracle's deepest surface node: every surface node of A in B's box and of B in A's.
    double expected = 0;
    for (std::uint32_t n : pa.vertex_node) expected = std::max(expected, box_depth(p.a.mesh.nodes[n], box_b(s.step)));
    for (std::uint32_t n : pb.vertex_node) expected = std::max(expected, box_depth(node_b(p, n, s.step), box_a()));
    ASSERT_GT(expected, 0) << s.step;
    ASSERT_TRUE(s.has_deepest) << s.step;
    EXPECT_NEAR(s.deepest.depth, expected, 1e-12) << s.step;
    // The named node is that deep, belongs to the named part, and its element holds it.
    const FemMesh& mesh = s.deepest.part == 0 ? p.a.mesh : p.b.mesh;
    const std::int64_t n = index_of(mesh.node_ids, s.deepest.node);
    ASSERT_GE(n, 0) << s.step << ": node " << s.deepest.node << " not in part " << s.deepest.part;
    if (s.deepest.part == 0) {
      EXPECT_LT(s.deepest.node, 5001) << s.step;
      EXPECT_NEAR(box_depth(mesh.nodes[static_cast<std::size_t>(n)], box_b(s.step)), expected, 1e-12) << s.step;
      EXPECT_EQ(s.deepest.point, mesh.nodes[static_cast<std::size_t>(n)]) << s.step;
    } else {
      EXPECT_GE(s.deepest.node, 5001) << s.step;
      const Vec3 q = node_b(p, static_cast<std::uint32_t>(n), s.step);
      EXPECT_NEAR(box_depth(q, box_a()), expected, 1e-12) << s.step;
      EXPECT_EQ(s.deepest.point, q) << s.step;
    }
    const std::int64_t e = index_of(mesh.elem_ids, s.deepest.element);
    ASSERT_GE(e, 0) << s.step << ": element " << s.deepest.element << " not in part " << s.deepest.part;
    const std::uint32_t* en = mesh.element_nodes(static_cast<std::size_t>(e));
    EXPECT_NE(std::find(en, en + mesh.element_size(static_cast<std::size_t>(e)), static_cast<std::uint32_t>(n)),
              en + mesh.element_size(static_cast<std::size_t>(e)))
        << s.step << ": element " << s.deepest.element << " lacks node " << s.deepest.node;
    // The true depth of the overlap [x0, 1] x [0.3, 1]^2: the faces x = x0 of B and x = 1 of A
    // reach min(1 - x0, x0, 0.5) deep at their middles; the other faces inside reach at most 0.3.
    const double x0 = box_b(s.step).lo.x;
    const double lower = std::min({1 - x0, x0, 0.5}), upper = std::max(lower, 0.3);
    EXPECT_GE(s.depth, s.deepest.depth - 1e-12) << s.step;  // the vertices are samples
    EXPECT_LE(s.depth, upper + 1e-12) << s.step;            // samples never exceed the truth
    EXPECT_TRUE(s.depth_bounded) << s.step;
    EXPECT_GE(s.depth_bound, lower - 1e-12) << s.step;  // a bound never below the truth
    EXPECT_TRUE(s.depth_note.empty()) << s.step << ": " << s.depth_note;
    if (s.depth > max_depth) max_depth = s.depth, deepest_step = static_cast<std::int64_t>(s.step);
  }
  EXPECT_EQ(r->deepest_step, deepest_step);
}

TEST(FemDeformDepth, OffByDefault) {
  Pair p = make_pair(11);
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &p.u});
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(r->first_clash_step, 9);
  for (const StepSummary& s : r->steps) EXPECT_FALSE(s.depth_measured || s.has_deepest || !s.depth_note.empty());
  EXPECT_EQ(r->deepest_step, -1);
}

TEST(FemDeformDepth, AnOpenPartIsNotMeasuredAndSaysSo) {
  Pair p = make_pair(11);
  // B without its far face (x = 3 at rest): still crossing A from step 9 on, no longer closed.
  SurfacePart open = p.sb.parts[0];
  open.mesh.triangles.clear(), open.tri_element.clear(), open.tri_face.clear();
  const SurfacePart& full = p.sb.parts[0];
  for (std::size_t t = 0; t < full.mesh.triangles.size(); ++t) {
    const auto& tri = full.mesh.triangles[t];
    if (full.mesh.positions[tri[0]].x == 3 && full.mesh.positions[tri[1]].x == 3 && full.mesh.positions[tri[2]].x == 3)
      continue;
    open.mesh.triangles.push_back(tri);
    open.tri_element.push_back(full.tri_element[t]);
    open.tri_face.push_back(full.tri_face[t]);
  }
  ASSERT_LT(open.mesh.triangles.size(), full.mesh.triangles.size());
  SeriesRequest request{.depth = true};
  bool mapped = false;
  request.on_depth_maps = [&](const StepSummary&, const DepthMaps&) { mapped = true; };
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &open, &p.u}, request);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(r->first_clash_step, 9);
  EXPECT_FALSE(mapped);
  EXPECT_EQ(r->deepest_step, -1);
  for (const StepSummary& s : r->steps) {
    EXPECT_FALSE(s.depth_measured) << s.step;
    EXPECT_FALSE(s.has_deepest) << s.step;
    if (s.verdict == Verdict::clash) {
      EXPECT_NE(s.depth_note.find("part B is not closed"), std::string::npos) << s.step << ": " << s.depth_note;
    } else {
      EXPECT_TRUE(s.depth_note.empty()) << s.step;
    }
  }
}

TEST(FemDeformDepth, APartInsideTheOtherHasItsDeepestNode) {
  // B = [1.2, 2.1] x [1.3, 2.2] x [1.1, 2.9] (tet4) inside A = [0, 4]^3 (hex8), no displacement: one
  // step, a containment without crossing; the depth is the deepest node's (no bound).
  const GeneratedFem a = make_fem_box({.type = ElemType::hex8, .nx = 4, .ny = 4, .nz = 4, .hi = {4, 4, 4}});
  const GeneratedFem b = make_fem_box({.type = ElemType::tet4, .nx = 2, .ny = 3, .nz = 2, .lo = {1.2, 1.3, 1.1},
                                       .hi = {2.1, 2.2, 2.9}, .first_node_id = 701, .first_element_id = 801});
  const SurfaceResult sa = *extract_surface(a.mesh), sb = *extract_surface(b.mesh);
  std::size_t maps_seen = 0;
  SeriesRequest request{.depth = true};
  request.on_depth_maps = [&](const StepSummary&, const DepthMaps& maps) {
    ++maps_seen;
    EXPECT_EQ(maps.a.inside, 0u);  // nothing of A lies inside B
    EXPECT_EQ(maps.b.inside, sb.parts[0].mesh.num_vertices());
  };
  auto r = clash_series({&a.mesh, &sa.parts[0], nullptr}, {&b.mesh, &sb.parts[0], nullptr}, request);
  ASSERT_TRUE(r) << r.error().message();
  ASSERT_EQ(r->steps.size(), 1u);
  const StepSummary& s = r->steps[0];
  EXPECT_EQ(s.containment, Containment::b_inside_a);
  ASSERT_EQ(s.verdict, Verdict::clash);
  EXPECT_EQ(maps_seen, 1u);
  const Box outer{{0, 0, 0}, {4, 4, 4}};
  double expected = 0;
  for (std::uint32_t n : sb.parts[0].vertex_node) expected = std::max(expected, box_depth(b.mesh.nodes[n], outer));
  ASSERT_TRUE(s.depth_measured);
  EXPECT_FALSE(s.depth_bounded);
  EXPECT_NEAR(s.depth, expected, 1e-12);
  ASSERT_TRUE(s.has_deepest);
  EXPECT_EQ(s.deepest.part, 1);
  EXPECT_NEAR(s.deepest.depth, expected, 1e-12);
  const std::int64_t n = index_of(b.mesh.node_ids, s.deepest.node);
  ASSERT_GE(n, 0);
  EXPECT_NEAR(box_depth(b.mesh.nodes[static_cast<std::size_t>(n)], outer), expected, 1e-12);
  EXPECT_GE(index_of(b.mesh.elem_ids, s.deepest.element), 0);
  EXPECT_NE(s.depth_note.find("inside"), std::string::npos) << s.depth_note;
  EXPECT_EQ(r->deepest_step, 0);
}

}  // namespace
}  // namespace interfere
