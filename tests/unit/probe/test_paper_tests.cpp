// The paper's three levels as written (Li, Zhou & Zheng 2008, §3.2-3.4; issue #28, deliverable 3)
// and where each is incomplete: the box test and the triangle/box test drop contacts (false
// negatives), the three projections never drop one but call clear pairs overlapping (false
// positives, found by a seeded search and checked by the exact test and a sampled distance).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "interfere/probe/paper_tests.h"
#include "sampled_clearance.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

using Tri3 = std::array<Vec3, 3>;

Aabb box(Vec3 lo, Vec3 hi) {
  Aabb b;
  b.lo = lo, b.hi = hi;
  return b;
}

/// Overlap of the paper's projections for every choice it leaves open: the three edges and
/// `diameters` directions of the end circle's diameter.
bool all_choices_overlap(const Cylinder& c, const Tri3& t, int diameters) {
  const Vec3 u = (c.c1 - c.c0) / norm(c.c1 - c.c0);
  const Vec3 h = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 e1 = cross(u, h);
  e1 = e1 / norm(e1);
  const Vec3 e2 = cross(u, e1);
  for (int edge = 0; edge < 3; ++edge) {
    for (int k = 0; k < diameters; ++k) {
      const double phi = M_PI * k / diameters;  // diameters are lines: [0, pi) covers them all
      if (!paper_projections(c, t, edge, e1 * std::cos(phi) + e2 * std::sin(phi)).all()) return false;
    }
  }
  return true;
}

}  // namespace

TEST(PaperLevels, BoxTestAsWritten) {
  const Aabb fat = box({0, 0, 0}, {10, 10, 10});
  // Crossing corners: edges of each meet faces of the other.
  EXPECT_TRUE(paper_box_test(box({5, 5, 5}, {15, 15, 15}), fat));
  EXPECT_TRUE(paper_box_test(fat, box({5, 5, 5}, {15, 15, 15})));
  EXPECT_FALSE(paper_box_test(box({11, 0, 0}, {12, 10, 10}), fat));
  // A rod through the fat box: the rod's edges cross the fat box's faces, not the other way round.
  const Aabb rod = box({-5, 4, 4}, {15, 6, 6});
  EXPECT_TRUE(rod.overlaps(fat));
  EXPECT_TRUE(paper_box_test(rod, fat));
  EXPECT_FALSE(paper_box_test(fat, rod));  // one direction as written: a contact dropped
  // A box inside the other: no edge meets a face either way (the paper's claim "if the boxes
  // intersect, an edge of one meets a face of the other" is false here).
  const Aabb small = box({4, 4, 4}, {6, 6, 6});
  EXPECT_TRUE(small.overlaps(fat));
  EXPECT_FALSE(paper_box_test(small, fat));
  EXPECT_FALSE(paper_box_test(fat, small));
  // Random boxes: never a false contact; missed overlaps occur.
  std::mt19937_64 g(32);
  std::uniform_real_distribution<double> p(0, 10), s(0.5, 6);
  int missed = 0;
  for (int it = 0; it < 4000; ++it) {
    const Vec3 a{p(g), p(g), p(g)}, b{p(g), p(g), p(g)};
    const Aabb A = box(a, a + Vec3{s(g), s(g), s(g)}), B = box(b, b + Vec3{s(g), s(g), s(g)});
    const bool paper = paper_box_test(A, B) || paper_box_test(B, A);
    if (paper) EXPECT_TRUE(A.overlaps(B)) << it;
    missed += A.overlaps(B) && !paper;
  }
  EXPECT_GT(missed, 0);
}

TEST(PaperLevels, TriangleBoxTestAsWritten) {
  const Aabb b = box({0, 0, 0}, {2, 2, 2});
  EXPECT_TRUE(paper_triangle_box_test({Vec3{1, 1, 1}, Vec3{5, 1, 1}, Vec3{5, 3, 1}}, b));  // edge leaves the box
  EXPECT_FALSE(paper_triangle_box_test({Vec3{3, 0, 0}, Vec3{5, 0, 0}, Vec3{3, 2, 0}}, b));  // beside it
  // A triangle inside the box: its edges meet no face (a contact dropped).
  EXPECT_FALSE(paper_triangle_box_test({Vec3{0.5, 0.5, 1}, Vec3{1.5, 0.5, 1}, Vec3{1, 1.5, 1}}, b));
  // A large triangle through the box's middle: the box pierces its interior, its edges are far away
  // (a contact dropped).
  const Tri3 big{Vec3{-20, -20, 1}, Vec3{20, -20, 1}, Vec3{0, 20, 1}};
  EXPECT_FALSE(paper_triangle_box_test(big, b));
  // ... though (1, 1, 1), the box's centre, is on the triangle.
  EXPECT_TRUE(b.contains(Vec3{1, 1, 1}));
}

TEST(PaperLevels, BoxMethodsDecideTheirPrimitives) {
  // paper_segment_meets_face: the area and length methods, checked against the parametric answer.
  const std::array<Vec3, 4> f{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 1, 0}, Vec3{0, 1, 0}};
  EXPECT_TRUE(paper_segment_meets_face({1, 0.5, -1}, {1, 0.5, 1}, f));
  EXPECT_FALSE(paper_segment_meets_face({3, 0.5, -1}, {3, 0.5, 1}, f));     // misses the rectangle
  EXPECT_FALSE(paper_segment_meets_face({1, 0.5, 0.5}, {1, 0.5, 1}, f));    // stops before the plane
  EXPECT_FALSE(paper_segment_meets_face({-1, 0.5, 0}, {3, 0.5, 0}, f));     // in the plane: "parallel"
  std::mt19937_64 g(33);
  std::uniform_real_distribution<double> u(-1, 3);
  for (int it = 0; it < 2000; ++it) {
    const Vec3 p{u(g), u(g), u(g) - 1}, q{u(g), u(g), u(g) - 1};
    if ((p.z > 0) == (q.z > 0) || std::fabs(p.z - q.z) < 1e-3) continue;
    const double s = p.z / (p.z - q.z);
    const Vec3 x = p + (q - p) * s;
    const bool inside = x.x >= 0 && x.x <= 2 && x.y >= 0 && x.y <= 1;
    const double margin = std::min({std::fabs(x.x), std::fabs(x.x - 2), std::fabs(x.y), std::fabs(x.y - 1)});
    if (margin < 1e-6) continue;
    EXPECT_EQ(paper_segment_meets_face(p, q, f), inside) << it;
  }
}

TEST(PaperLevels, ProjectionsNeverMissAContact) {
  std::mt19937_64 g(34);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rnd = [&](double s) { return Vec3{s * u(g), s * u(g), s * u(g)}; };
  int contacts = 0;
  for (int it = 0; it < 3000; ++it) {
    const Cylinder c{rnd(1.0), rnd(1.0), 0.3};
    const Tri3 t{rnd(1.5), rnd(1.5), rnd(1.5)};
    if (!cylinder_triangle_intersect(c, t)) continue;
    ++contacts;
    for (int edge = 0; edge < 3; ++edge) {
      const PaperProjections p = paper_projections(c, t, edge, rnd(1.0));
      EXPECT_TRUE(p.along_axis) << it;
      EXPECT_TRUE(p.along_edge) << it << " edge " << edge;
      EXPECT_TRUE(p.along_diameter) << it;
    }
  }
  EXPECT_GT(contacts, 300);
}

TEST(PaperLevels, ProjectionsSeparateWhatEachProjectionSeparates) {
  // Axis z, r = 1, length 2 from the origin.
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  // Beside the cylinder, parallel to the axis: separated along the axis.
  EXPECT_FALSE(paper_projections(c, {Vec3{2, -1, 0}, Vec3{2, 1, 0}, Vec3{2, 0, 2}}).along_axis);
  // Above the top cap: separated along any diameter.
  EXPECT_FALSE(paper_projections(c, {Vec3{-1, -1, 3}, Vec3{1, -1, 3}, Vec3{0, 1, 3}}).along_diameter);
  // A big triangle whose plane separates (test_cylinder_triangle.cpp's FrameProjectionIsIncomplete):
  // along an edge the plane becomes a line with the cylinder on one side.
  const Cylinder unit_length{{0, 0, 0}, {0, 0, 1}, 1.0};
  const double s = 1 / std::sqrt(2.0);
  const Tri3 t{Vec3{3, -3, 2.1}, Vec3{-3, 3, 2.1}, Vec3{2, 2, 2.1 - 4 * s}};
  for (int edge = 0; edge < 3; ++edge) EXPECT_FALSE(paper_projections(unit_length, t, edge).along_edge) << edge;
  EXPECT_FALSE(three_projection_test(unit_length, t));
}

TEST(PaperLevels, ThreeProjectionsCallClearPairsOverlapping) {
  // Seeded search for the paper's false positives near the top rim (where the end circle and the
  // side meet): a vertex just outside the rim, one over the cap (its projection along the axis
  // falls in the end circle), one farther out. A pair is clear when the exact test says so with a
  // gap of at least 0.02 r; the first false positive is confirmed clear by a dense sampled distance
  // (another method). The paper leaves the edge ("any edge") and the diameter ("any diameter")
  // open: a false positive for the choice edge 0 / the fixed diameter must exist; how many survive
  // every edge, every one of 36 diameters, or both, is counted and printed (docs/probe.md).
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 1.0};
  std::mt19937_64 g(2008);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  auto dir = [&] {
    for (;;) {
      const Vec3 v{u(g), u(g), u(g)};
      const double n = norm(v);
      if (n > 0.1 && n <= 1) return v / n;
    }
  };
  int clear = 0, fixed_choice = 0, every_edge = 0, every_diameter = 0, every_choice = 0;
  Tri3 example{};
  double example_gap = 0;
  for (int it = 0; it < 100000; ++it) {
    const double phi = 2 * M_PI * u01(g);
    const Vec3 rim{std::cos(phi), std::sin(phi), 2};
    const Vec3 v = rim + dir() * (0.02 + 0.08 * u01(g));
    const double rho = 0.95 * std::sqrt(u01(g)), psi = 2 * M_PI * u01(g);
    const Vec3 over{rho * std::cos(psi), rho * std::sin(psi), 2 + 0.02 + 1.5 * u01(g)};
    const Vec3 far = rim * (1 + 2 * u01(g)) + dir() * 2.0;
    const Tri3 t{v, over, far};
    if (cylinder_triangle_intersect(c, t)) continue;
    const double gap = cylinder_triangle_distance(c, t).distance;
    if (gap < 0.02) continue;
    ++clear;
    if (!three_projection_test(c, t, 0)) continue;
    if (fixed_choice++ == 0) example = t, example_gap = gap;
    const bool edges = three_projection_test(c, t, 1) && three_projection_test(c, t, 2);
    every_edge += edges;
    bool diameters = true;
    for (int k = 0; k < 36 && diameters; ++k) {
      const double a = M_PI * k / 36;  // diameters are lines: [0, pi) covers them all
      diameters = paper_projections(c, t, 0, {std::cos(a), std::sin(a), 0}).all();
    }
    every_diameter += diameters;
    every_choice += edges && diameters && all_choices_overlap(c, t, 36);
  }
  std::printf("paper's three projections on %d clear pairs (gap >= 0.02 r): false positives %d for edge 0 and the "
              "fixed diameter, %d for every edge, %d for every one of 36 diameters, %d for every edge and diameter\n",
              clear, fixed_choice, every_edge, every_diameter, every_choice);
  ASSERT_GT(fixed_choice, 0) << "no false positive among " << clear << " clear pairs";
  // The first one: clear by the exact test and by dense surface samples every 0.005 (true <= sampled
  // <= true + h, sampled_clearance.h: sampled - h > 0 proves a gap without the exact test), and all
  // three projections overlap: the paper's false positive.
  TriMesh m;
  m.positions = {example[0], example[1], example[2]};
  m.triangles = {{0, 1, 2}};
  const oracle::Sampled samples = oracle::sample_cylinder(c, 0.005);
  const double sampled = oracle::sampled_distance(samples, m, INFINITY);
  EXPECT_GT(sampled - samples.h, 0);
  EXPECT_NEAR(sampled, example_gap, samples.h);
  EXPECT_FALSE(cylinder_triangle_intersect(c, example));
  const PaperProjections p = paper_projections(c, example, 0);
  EXPECT_TRUE(p.along_axis && p.along_edge && p.along_diameter);
  std::printf("example: gap %.6g, triangle (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g), "
              "cylinder (0,0,0)-(0,0,2) r 1\n",
              example_gap, example[0].x, example[0].y, example[0].z, example[1].x, example[1].y, example[1].z,
              example[2].x, example[2].y, example[2].z);
}

TEST(PaperLevels, PointCheckReportsThePapersFalsePositive) {
  // The first false positive of the seeded search above (printed there), as a one-triangle
  // workpiece and the probe pose whose cylinder is (0,0,0)-(0,0,2), r = 1.
  TriMesh m;
  m.positions = {{-0.41762788177630833, -0.8210775298506976, 2.0431113483579426},
                 {-0.5255325554798489, -0.11186297107474368, 3.2267138360446035},
                 {-1.0452788651563281, -2.71650785719231, 1.850198368577664}};
  m.triangles = {{0, 1, 2}};
  const ProbeShape shape{.radius = 1, .length = 2};
  const ProbePose pose{{0, 0, 0}, {0, 0, -1}};
  const Cylinder c = cylinder_from_tip(pose.tip, pose.axis, shape.length, shape.radius);
  ASSERT_EQ(c.c1.z, 2.0);
  const oracle::Sampled samples = oracle::sample_cylinder(c, 0.005);
  ASSERT_GT(oracle::sampled_distance(samples, m, INFINITY) - samples.h, 0);  // clear (another method)
  const Workpiece w = prepare_workpiece(m, shape);
  const PaperPointCheck pc = paper_point_check(w, shape, pose, 0);
  EXPECT_FALSE(pc.exact);
  EXPECT_EQ(pc.patches_passed, 1u);
  EXPECT_EQ(pc.triangles_passed, 1u);
  EXPECT_EQ(pc.projections_passed, 1u);
  EXPECT_TRUE(pc.collides);
  EXPECT_TRUE(pc.false_positive());
  // The sweep's exact verdict for the same point: clear.
  ProbePath path;
  path.joint_space = false;
  path.poses = {pose};
  path.lines = {2};
  const SweepResult r = sweep(w, path, nullptr, {.probe = shape, .continuous = false});
  EXPECT_FALSE(r.points[0].collides);
  // And a false negative of levels 1-2: a small triangle inside the probe's box, touching the probe.
  TriMesh inside;
  inside.positions = {{-0.2, -0.2, 1}, {0.2, -0.2, 1}, {0, 0.2, 1}};
  inside.triangles = {{0, 1, 2}};
  const PaperPointCheck miss = paper_point_check(prepare_workpiece(inside, shape), shape, pose, 0);
  EXPECT_TRUE(miss.exact);
  EXPECT_FALSE(miss.collides);
  EXPECT_TRUE(miss.false_negative());
}
