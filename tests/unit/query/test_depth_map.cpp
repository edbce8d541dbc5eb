// depth_map / depth_maps (query/depth.h, issue #26 item 3: penetration depth maps), against an
// independent oracle: inside/outside by the generalized winding number (the solid angles of every
// triangle of the other part summed, no BVH, no ray), the depth by brute force over every triangle
// with reference::point_triangle_distance (tests/unit/reference_distance.h, not np/distance.h), and
// analytic depths where the shapes are boxes (a point's smallest distance to the box's faces).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"
#include "unit/reference_distance.h"

namespace interfere {
namespace {

// The winding number of the closed surface `m` around p (about 1 inside an outward surface, 0
// outside): the signed solid angles of its triangles (Van Oosterom and Strackee 1983) over 4 pi.
double winding_number(const TriMesh& m, const Vec3& p) {
  double sum = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    const Vec3 a = c[0] - p, b = c[1] - p, d = c[2] - p;
    const double la = norm(a), lb = norm(b), ld = norm(d);
    const double num = dot(a, cross(b, d));
    const double den = la * lb * ld + dot(a, b) * ld + dot(b, d) * la + dot(d, a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * std::numbers::pi);
}

double brute_distance(const TriMesh& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < m.num_triangles(); ++t) best = std::min(best, reference::point_triangle_distance(p, m.corners(t)));
  return best;
}

// Every vertex of x against the oracle for the closed solid y: the map's depth is the brute-force
// distance where the map says inside, 0 elsewhere; its side agrees with the winding number wherever
// that is well conditioned (the vertex farther than 1e-7 from y's surface); vertices on y's surface
// (brute distance 0) are outside; the summary fields agree with the per-vertex arrays.
void expect_matches_oracle(const DepthMap& map, const TriMesh& x, const TriMesh& y, const char* what) {
  ASSERT_EQ(map.depth.size(), x.num_vertices()) << what;
  ASSERT_EQ(map.side.size(), x.num_vertices()) << what;
  std::size_t inside = 0, compared = 0;
  double max_depth = 0;
  std::uint32_t max_vertex = kNoVertex;
  for (std::uint32_t v = 0; v < x.num_vertices(); ++v) {
    const Vec3& p = x.positions[v];
    const double ref = brute_distance(y, p);
    if (ref > 1e-7) {
      const double w = winding_number(y, p);
      ASSERT_LT(std::fabs(w - std::round(w)), 1e-6) << what << " vertex " << v;
      EXPECT_EQ(map.side[v], std::lround(w) == 1 ? 1 : 0) << what << " vertex " << v << " winding " << w;
      ++compared;
    }
    if (ref == 0) EXPECT_EQ(map.side[v], 0) << what << " vertex " << v << " lies on the surface";
    EXPECT_NE(map.side[v], -1) << what << " vertex " << v;
    if (map.side[v] == 1) {
      EXPECT_NEAR(map.depth[v], ref, 1e-12 * (1 + ref)) << what << " vertex " << v;
      EXPECT_GT(map.depth[v], 0) << what << " vertex " << v;
      ++inside;
      if (map.depth[v] > max_depth) max_depth = map.depth[v], max_vertex = v;
    } else {
      EXPECT_EQ(map.depth[v], 0) << what << " vertex " << v;
    }
  }
  EXPECT_GT(compared, 0u) << what;
  EXPECT_EQ(map.inside, inside) << what;
  EXPECT_EQ(map.undecided, 0u) << what;
  EXPECT_EQ(map.max_depth, max_depth) << what;
  EXPECT_EQ(map.max_vertex, max_vertex) << what;
}

// The analytic depth of p in the box [lo, hi] (0 outside or on it).
double box_depth(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  double d = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) d = std::min({d, p[k] - lo[k], hi[k] - p[k]});
  return std::max(d, 0.0);
}

void expect_box_depths(const DepthMap& map, const TriMesh& x, const Vec3& lo, const Vec3& hi, const char* what) {
  for (std::uint32_t v = 0; v < x.num_vertices(); ++v)
    EXPECT_NEAR(map.depth[v], box_depth(x.positions[v], lo, hi), 1e-12) << what << " vertex " << v;
}

TEST(DepthMap, CubePushedIntoABox) {
  // The unit cube's face x = 1 pushed 0.3 into a box that is wider on y and z: the face's 25
  // vertices lie 0.3 deep (the box's face x = 0.7 is nearest), the 16 on the ring x = 0.75 0.05
  // deep; of the box, the vertices of its face x = 0.7 strictly inside the cube lie 0.3 from the
  // cube's face x = 1, those on the cube's faces y = 0, 1 or z = 0, 1 on its surface (0).
  const Vec3 alo{0, 0, 0}, ahi{1, 1, 1}, blo{0.7, -0.5, -0.5}, bhi{1.7, 1.5, 1.5};
  const Model a = make_model(make_box(alo, ahi, 4)), b = make_model(make_box(blo, bhi, 4));
  const ClashResult r = clash(a, b);
  // (the box's grid lines y, z = 0, 1 lie on the cube's faces: the surfaces only touch, the solids
  // overlap)
  ASSERT_TRUE(r.touching_overlap);
  const DepthMaps m = depth_maps(a, b, r);
  EXPECT_NEAR(m.a.max_depth, 0.3, 1e-12);
  EXPECT_EQ(m.a.inside, 41u);
  EXPECT_NEAR(m.b.max_depth, 0.3, 1e-12);
  EXPECT_EQ(m.b.inside, 1u);  // (0.7, 0.5, 0.5): the face's only grid vertex strictly inside
  ASSERT_NE(m.b.max_vertex, kNoVertex);
  EXPECT_EQ(b.mesh.positions[m.b.max_vertex], (Vec3{0.7, 0.5, 0.5}));
  expect_box_depths(m.a, a.mesh, blo, bhi, "a in b");
  expect_box_depths(m.b, b.mesh, alo, ahi, "b in a");
  expect_matches_oracle(m.a, a.mesh, b.mesh, "a in b");
  expect_matches_oracle(m.b, b.mesh, a.mesh, "b in a");
  // One engine: penetration_depth's maps are these, and its sampled depth is at least their maxima.
  DepthMaps via;
  const PenetrationDepth d = penetration_depth(a, b, r, 0, &via);
  EXPECT_EQ(via.a.depth, m.a.depth);
  EXPECT_EQ(via.b.side, m.b.side);
  EXPECT_GE(d.depth, std::max(m.a.max_depth, m.b.max_depth));
  // One direction at a time, either way round.
  const DepthMap ab = depth_map(a, b, r, DepthOf::a_in_b), ba = depth_map(a, b, r, DepthOf::b_in_a);
  EXPECT_EQ(ab.depth, m.a.depth);
  EXPECT_EQ(ba.depth, m.b.depth);
  const ClashResult rr = clash(b, a);
  EXPECT_EQ(depth_map(b, a, rr, DepthOf::b_in_a).depth, m.a.depth);
}

TEST(DepthMap, SphereSunkIntoABox) {
  // A sphere of radius 0.5 over the unit cube's top face, its south pole (a vertex) 0.3 below it:
  // the deepest vertex is the pole, 0.3 from the top face (0.5 from the sides).
  SphereOptions so;
  so.target_triangles = 4000;
  so.radius = 0.5;
  so.center = {0.5, 0.5, 1.2};
  const Model box = make_model(make_box({0, 0, 0}, {1, 1, 1}, 10)), ball = make_model(make_sphere(so));
  const ClashResult r = clash(ball, box);
  ASSERT_GT(r.cross_pairs, 0u);
  const DepthMaps m = depth_maps(ball, box, r);
  EXPECT_NEAR(m.a.max_depth, 0.3, 1e-12);
  EXPECT_EQ(m.a.max_vertex, ball.mesh.num_vertices() - 1);  // the south pole, last vertex
  EXPECT_GT(m.a.inside, 100u);
  EXPECT_GT(m.b.inside, 10u);
  expect_box_depths(m.a, ball.mesh, {0, 0, 0}, {1, 1, 1}, "ball in box");
  expect_matches_oracle(m.a, ball.mesh, box.mesh, "ball in box");
  expect_matches_oracle(m.b, box.mesh, ball.mesh, "box in ball");
}

TEST(DepthMap, BodyWhollyInsideAnother) {
  // No surface pair: the inner box is one untouched set inside the outer one (containment); every
  // one of its vertices is inside, at its analytic depth; none of the outer box's is.
  const Vec3 lo{0.2, 0.3, 0.4}, hi{0.5, 0.6, 0.9};
  const Model outer = make_model(make_box({0, 0, 0}, {1, 1, 1}, 3)), inner = make_model(make_box(lo, hi, 2));
  const ClashResult r = clash(inner, outer);
  ASSERT_TRUE(r.pairs.empty());
  ASSERT_EQ(r.containment, Containment::a_inside_b);
  const DepthMaps m = depth_maps(inner, outer, r);
  EXPECT_EQ(m.a.inside, inner.mesh.num_vertices());
  EXPECT_NEAR(m.a.max_depth, 0.4, 1e-12);  // the corners (0.5, 0.6, 0.9) etc.: 0.4 from x = 1 / y = 1
  expect_box_depths(m.a, inner.mesh, {0, 0, 0}, {1, 1, 1}, "inner");
  expect_matches_oracle(m.a, inner.mesh, outer.mesh, "inner in outer");
  expect_matches_oracle(m.b, outer.mesh, inner.mesh, "outer in inner");
  EXPECT_EQ(m.b.inside, 0u);
  // penetration_depth keeps its contract (no surface pair: depth 0) but still fills the maps.
  DepthMaps via;
  EXPECT_EQ(penetration_depth(inner, outer, r, 0, &via).depth, 0.0);
  EXPECT_EQ(via.a.depth, m.a.depth);
}

TEST(DepthMap, DisjointAndTouchingBodiesAreAllZero) {
  const Model a = make_model(make_box({0, 0, 0}, {1, 1, 1}, 3));
  for (const double gap : {0.5, 0.0}) {  // apart, then sharing the face x = 1 (different grids)
    const Model b = make_model(make_box({1 + gap, -0.2, 0.1}, {2, 0.9, 1.3}, 4));
    const ClashResult r = clash(a, b);
    if (gap == 0) ASSERT_GT(r.touch_pairs, 0u);
    const DepthMaps m = depth_maps(a, b, r);
    for (const DepthMap* x : {&m.a, &m.b}) {
      EXPECT_EQ(x->inside, 0u) << gap;
      EXPECT_EQ(x->undecided, 0u) << gap;
      EXPECT_EQ(x->max_depth, 0.0) << gap;
      EXPECT_EQ(x->max_vertex, kNoVertex) << gap;
      EXPECT_TRUE(std::all_of(x->depth.begin(), x->depth.end(), [](double d) { return d == 0; })) << gap;
      EXPECT_TRUE(std::all_of(x->side.begin(), x->side.end(), [](signed char s) { return s == 0; })) << gap;
    }
    EXPECT_EQ(m.a.depth.size(), a.mesh.num_vertices());
    EXPECT_EQ(m.b.depth.size(), b.mesh.num_vertices());
    expect_matches_oracle(m.a, a.mesh, b.mesh, "a");
    expect_matches_oracle(m.b, b.mesh, a.mesh, "b");
  }
}

TEST(DepthMap, OpenSolidLeavesVerticesUndecided) {
  // b lost a triangle: it has no inside. a's vertices in b's box are undecided (counted), never a
  // silent 0 with nothing inside and nothing undecided; those beyond the box are outside.
  const Model a = make_model(make_box({0, 0, 0}, {1, 1, 1}, 4));
  TriMesh open = make_box({0.7, -0.5, -0.5}, {1.7, 1.5, 1.5}, 4);
  open.triangles.pop_back();
  const Model b = make_model(open);
  ASSERT_FALSE(b.stats.closed());
  const ClashResult r = clash(a, b);
  const DepthMap m = depth_map(a, b, r, DepthOf::a_in_b);
  EXPECT_EQ(m.inside, 0u);
  EXPECT_EQ(m.undecided, 41u);  // the vertices with x >= 0.7 (x = 0.75 and x = 1)
  for (std::uint32_t v = 0; v < a.mesh.num_vertices(); ++v) {
    EXPECT_EQ(m.side[v], a.mesh.positions[v].x >= 0.7 ? -1 : 0) << v;
    EXPECT_EQ(m.depth[v], 0.0) << v;
  }
  // The closed a is a solid for b's vertices; statistics from the request decide closedness.
  EXPECT_EQ(depth_map(a, b, r, DepthOf::b_in_a).undecided, 0u);
  const MeshStats open_stats;  // (no triangles: not closed)
  DepthMapRequest q;
  q.stats = [&](int side) -> const MeshStats& { return side == 0 ? open_stats : b.stats; };
  EXPECT_GT(depth_map(a, b, r, DepthOf::b_in_a, q).undecided, 0u);
  // A model built without statistics counts as open unless the request says otherwise.
  const Model bare = make_model(make_box({0.7, -0.5, -0.5}, {1.7, 1.5, 1.5}, 4), {}, false);
  EXPECT_EQ(depth_map(a, bare, clash(a, bare), DepthOf::a_in_b).undecided, 41u);
  const MeshStats closed_stats = b.stats.closed() ? b.stats : make_model(make_box({0, 0, 0}, {1, 1, 1})).stats;
  q.stats = [&](int) -> const MeshStats& { return closed_stats; };
  EXPECT_EQ(depth_map(a, bare, clash(a, bare), DepthOf::a_in_b, q).inside, 41u);
}

// A rotation by `angle` about the axis u (unit), then a translation.
Transform rotation(double angle, const Vec3& u, const Vec3& t) {
  const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
  Transform r;
  r.r = {{{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
          {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
          {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}}};
  r.t = t;
  return r;
}

TEST(DepthMap, RandomPosesAgreeWithTheOracle) {
  // Bumpy spheres and boxes at random poses against each other: every vertex of both parts against
  // the winding number and the brute-force distance.
  std::mt19937_64 rng(26003);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t inside_total = 0;
  for (int trial = 0; trial < 8; ++trial) {
    SphereOptions so;
    so.target_triangles = 1500;
    so.radius = 0.6;
    so.bump_amplitude = 0.15;
    so.twist = 0.3 * trial;
    so.center = {0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng)};
    TriMesh x = trial % 2 ? make_box({-0.5, -0.4, -0.3}, {0.5, 0.4, 0.3}, 5) : make_sphere(so);
    Vec3 axis{u(rng), u(rng), u(rng)};
    axis = axis / norm(axis);
    x = transformed(x, rotation(3 * u(rng), axis, {0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng)}));
    so.center = {0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)};
    so.radius = 0.5;
    so.twist = 0.1;
    const TriMesh y = trial % 3 ? make_sphere(so) : make_box({-0.4, -0.45, -0.5}, {0.45, 0.4, 0.35}, 6);
    const Model a = make_model(x), b = make_model(y);
    const ClashResult r = clash(a, b);
    const DepthMaps m = depth_maps(a, b, r);
    const std::string what = "trial " + std::to_string(trial);
    expect_matches_oracle(m.a, a.mesh, b.mesh, (what + " a in b").c_str());
    expect_matches_oracle(m.b, b.mesh, a.mesh, (what + " b in a").c_str());
    inside_total += m.a.inside + m.b.inside;
    if (!r.pairs.empty()) {
      DepthMaps via;
      const PenetrationDepth d = penetration_depth(a, b, r, 0, &via);
      EXPECT_EQ(via.a.depth, m.a.depth) << what;
      EXPECT_EQ(via.b.depth, m.b.depth) << what;
      EXPECT_GE(d.depth, std::max(m.a.max_depth, m.b.max_depth)) << what;
    }
  }
  EXPECT_GT(inside_total, 500u);  // the trials do reach inside
}

}  // namespace
}  // namespace interfere
