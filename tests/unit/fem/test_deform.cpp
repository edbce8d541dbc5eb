// Deformed steps (fem/deform.h): a block moving toward another by t·v per step; the onset step of
// the clash is known analytically. Results named by element and node ids.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "interfere/fem/deform.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"

namespace interfere {
namespace {

struct Pair {
  GeneratedFem a, b;
  SurfaceResult sa, sb;
  NodalSeries u;
};

// A = [0,1]^3 (hex8 4x4x4, element ids 1..), B = [1+gap, 2+gap] x [0.3,1.3] x [0.3,1.3] (tet4; off A's
// node planes so that crossing faces cross inside A's triangles),
// B moving by -v per step in x: B's left face is at x = 1 + gap - s·v·scale.
Pair make_pair_moving(double gap, double v, std::size_t steps, ElemType tb = ElemType::tet4) {
  Pair p;
  p.a = make_fem_box({.type = ElemType::hex8, .nx = 4, .ny = 4, .nz = 4});
  p.b = make_fem_box({.type = tb, .nx = 3, .ny = 3, .nz = 3, .lo = {1 + gap, 0.3, 0.3},
                      .hi = {2 + gap, 1.3, 1.3}, .first_node_id = 5001, .first_element_id = 9001});
  p.sa = std::move(*extract_surface(p.a.mesh));
  p.sb = std::move(*extract_surface(p.b.mesh));
  p.u.name = "u";
  for (std::size_t s = 0; s < steps; ++s) {
    p.u.times.push_back(0.5 * static_cast<double>(s));
    p.u.values.emplace_back(p.b.mesh.num_nodes(), Vec3{-v * static_cast<double>(s), 0, 0});
  }
  return p;
}

TEST(FemDeform, DeformedPositionsAreNodePlusScaledDisplacement) {
  Pair p = make_pair_moving(0.5, 0.125, 3);
  std::vector<Vec3> out;
  deformed_positions(p.sb.parts[0], p.b.mesh, &p.u, 2, 3.0, out);
  ASSERT_EQ(out.size(), p.sb.parts[0].mesh.num_vertices());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Vec3 n = p.b.mesh.nodes[p.sb.parts[0].vertex_node[i]];
    EXPECT_EQ(out[i], (Vec3{n.x - 0.75, n.y, n.z}));
  }
  deformed_positions(p.sb.parts[0], p.b.mesh, nullptr, 0, 3.0, out);
  EXPECT_EQ(out, p.sb.parts[0].mesh.positions);
}

TEST(FemDeform, ClashOnsetStepIsTheAnalyticOne) {
  // gap 1, v = 0.125 (binary-exact): the faces touch at step 8, cross from step 9.
  Pair p = make_pair_moving(1.0, 0.125, 14);
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &p.u},
                        {.keep_first_clash = true, .keep_all = true});
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(r->num_steps, 14u);
  ASSERT_EQ(r->steps.size(), 14u);
  // The verdict model (issue #23, item 13): touching at step 8 is a contact, the clash starts at 9.
  EXPECT_EQ(r->first_contact_step, 8);
  EXPECT_EQ(r->first_clash_step, 9);
  EXPECT_EQ(r->verdict, Verdict::clash);
  EXPECT_EQ(r->worst_step, 9);
  for (const StepSummary& s : r->steps) {
    EXPECT_EQ(s.interference, s.step >= 8) << s.step;
    EXPECT_EQ(s.verdict, s.step < 8 ? Verdict::clear : s.step == 8 ? Verdict::contact : Verdict::clash) << s.step;
    EXPECT_EQ(s.time, 0.5 * static_cast<double>(s.step));
    if (s.step == 8) {
      EXPECT_EQ(s.cross_pairs, 0u);
      EXPECT_GT(s.touch_pairs, 0u);
    }
    if (s.step >= 9) {
      EXPECT_GT(s.cross_pairs, 0u);
      EXPECT_GT(s.max_curve_length, 0.0);
    }
  }
  // Step 9: B = [0.875, 1.875] x [0.3, 1.3]^2 overlaps A in [0.875, 1] x [0.3, 1]^2 (no face on
  // a node plane of the other part, so every intersection is a crossing). The curve: B's faces
  // y = 0.3 and z = 0.3 across A's face x = 1 (2 x 0.7); A's faces y = 1 and z = 1 across B's face
  // x = 0.875 (2 x 0.7) and across B's faces z = 0.3 / y = 0.3 (2 x 0.125).
  EXPECT_NEAR(r->steps[9].total_curve_length, 2 * 0.7 + 2 * 0.7 + 2 * 0.125, 1e-9);
  EXPECT_TRUE(r->first_clash.interference());
  // Every element of A in a region touches x = 1 (its cell is in the last column, ids analytic).
  const RegionIds ids = region_ids(r->results[10].regions.at(0), p.sa.parts[0], p.a.mesh, p.sb.parts[0], p.b.mesh);
  ASSERT_FALSE(ids.elements_a.empty());
  for (std::int64_t id : ids.elements_a) {
    const std::int64_t cell = id - 1;  // 4x4x4 cells, x fastest
    EXPECT_GE(cell % 4, 2) << id;      // cells with x >= 0.5 only (B reaches x = 0.75)
  }
  for (std::int64_t id : ids.elements_b) EXPECT_GE(id, 9001);
  for (std::int64_t id : ids.nodes_b) EXPECT_GE(id, 5001);
  ASSERT_FALSE(ids.nodes_a.empty());
  for (std::int64_t id : ids.nodes_a) {
    const std::size_t n = static_cast<std::size_t>(id - 1);
    EXPECT_GE(p.a.mesh.nodes[n].x, 0.5 - 1e-12);
  }
}

TEST(FemDeform, OnStepSeesEveryCheckedStepsResult) {
  // on_step (issue #25: the viewer keeps each step's regions): called once per checked step, in
  // order, with that step's summary and the same result keep_all keeps.
  Pair p = make_pair_moving(1.0, 0.125, 12);
  std::vector<std::size_t> seen;
  std::vector<std::size_t> region_counts, pair_counts;
  SeriesRequest request{.steps = {2, 8, 9, 11}, .keep_all = true};
  request.on_step = [&](const StepSummary& s, const ClashResult& r) {
    seen.push_back(s.step);
    region_counts.push_back(r.regions.size());
    pair_counts.push_back(r.pairs.size());
    EXPECT_EQ(s.verdict, r.verdict) << s.step;
    EXPECT_EQ(s.regions, r.regions.size()) << s.step;
  };
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &p.u}, request);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(seen, (std::vector<std::size_t>{2, 8, 9, 11}));
  ASSERT_EQ(r->results.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(region_counts[i], r->results[i].regions.size()) << i;
    EXPECT_EQ(pair_counts[i], r->results[i].pairs.size()) << i;
  }
  EXPECT_EQ(pair_counts[0], 0u);  // step 2: apart
  EXPECT_GT(pair_counts[2], 0u);  // step 9: crossing
}

TEST(FemDeform, ScaleAndSelectedStepsAndMismatchedSeries) {
  Pair p = make_pair_moving(1.0, 0.125, 14);
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &p.u},
                        {.scale = 2.0, .steps = {1, 3, 4, 5}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->steps.size(), 4u);
  EXPECT_EQ(r->first_contact_step, 4);  // 1 - 4 * 0.125 * 2 = 0: touching, a contact
  EXPECT_EQ(r->first_clash_step, 5);
  EXPECT_FALSE(r->steps[1].interference);
  EXPECT_TRUE(r->steps[2].interference);

  NodalSeries ua = p.u;
  ua.values.resize(3, std::vector<Vec3>(p.a.mesh.num_nodes()));
  ua.times.resize(3);
  for (auto& step : ua.values) step.assign(p.a.mesh.num_nodes(), Vec3{});
  auto bad = clash_series({&p.a.mesh, &p.sa.parts[0], &ua}, {&p.b.mesh, &p.sb.parts[0], &p.u});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().reason.find("mismatched step counts"), std::string::npos);
  NodalSeries nan = p.u;
  nan.values[3][5].y = std::numeric_limits<double>::quiet_NaN();
  auto bad_value = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &nan});
  ASSERT_FALSE(bad_value);
  EXPECT_NE(bad_value.error().reason.find("step 3: node"), std::string::npos) << bad_value.error().reason;
  auto out_of_range = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &p.u},
                                   {.steps = {14}});
  ASSERT_FALSE(out_of_range);
}

TEST(FemDeform, BondedBodiesAreAContactNotAClash) {
  // Issue #23, item 13: two materials of one conforming mesh (shared nodes and a shared face) touch,
  // their interiors are disjoint: contact. Moved into each other by 0.25 they clash.
  for (ElemType type : {ElemType::hex8, ElemType::tet4, ElemType::tet10}) {
    SCOPED_TRACE(elem_info(type).name);
    GeneratedFem g = make_fem_box({.type = type, .nx = 4, .ny = 2, .nz = 2, .lo = {0, 0, 0}, .hi = {2, 1, 1}});
    FemMesh& m = g.mesh;
    m.groups = {{.name = "left", .id = 1}, {.name = "right", .id = 2}};
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      double x = 0;
      const int c = elem_info(m.elem_types[e]).corners;
      for (int i = 0; i < c; ++i) x += m.nodes[m.element_nodes(e)[i]].x / c;
      m.elem_groups[e] = x < 1 ? 0 : 1;
    }
    auto s = extract_surface(m, {.split = PartSplit::by_group});
    ASSERT_TRUE(s);
    ASSERT_EQ(s->parts.size(), 2u);
    // Step 0: as meshed (bonded); step 1: the right body moved 0.25 into the left one.
    NodalSeries u{.name = "u", .times = {0, 1}, .values = {std::vector<Vec3>(m.num_nodes()), std::vector<Vec3>(m.num_nodes(), Vec3{-0.25, 0, 0})}};
    auto r = clash_series({&m, &s->parts[0], nullptr}, {&m, &s->parts[1], &u}, {.keep_first_clash = true});
    ASSERT_TRUE(r) << r.error().message();
    ASSERT_EQ(r->steps.size(), 2u);
    EXPECT_GT(r->steps[0].touch_pairs, 0u);
    EXPECT_EQ(r->steps[0].cross_pairs, 0u);
    EXPECT_EQ(r->steps[0].verdict, Verdict::contact);
    EXPECT_EQ(r->steps[1].verdict, Verdict::clash);
    EXPECT_EQ(r->first_contact_step, 0);
    EXPECT_EQ(r->first_clash_step, 1);
    EXPECT_EQ(r->verdict, Verdict::clash);
  }
}

TEST(FemDeform, QuadraticPartsThroughMidNodesKeepTheDeformedShape) {
  // A bending displacement u_x = c·(y - 0.5)^2 on tet10 B: only the mid-side nodes carry the
  // curvature between corners; the clash onset differs from a corner-only surface.
  Pair p = make_pair_moving(0.2, 0.0, 1, ElemType::tet10);
  NodalSeries bend{.name = "bend", .times = {0}, .values = {std::vector<Vec3>(p.b.mesh.num_nodes())}};
  for (std::size_t i = 0; i < p.b.mesh.num_nodes(); ++i) {
    const double y = p.b.mesh.nodes[i].y - 0.75;
    bend.values[0][i] = {-0.2 - 0.05 + 0.8 * y * y, 0, 0};  // leftmost point at y=0.75: x = 1 - 0.05
  }
  auto r = clash_series({&p.a.mesh, &p.sa.parts[0], nullptr}, {&p.b.mesh, &p.sb.parts[0], &bend});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->first_clash_step, 0);
}

}  // namespace
}  // namespace interfere
