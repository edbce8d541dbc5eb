// The exact solvers' bound tree (quadtree.h, BoundTree) and the pruning built on it (scarred.h's
// node bound, raceway_scar_solver.h's concave roller term; issue #27, the target "a scarred roller
// against a scarred raceway at 64^2 vertices, <= 20 us"). What changed there is only which nodes
// are pruned, so the references are full scans without any tree: scarred.h's surface_reference
// (every triangle; the per-triangle minimum itself is checked against bearing_oracle.h's independent
// bracket in test_bearing_scarred.cpp and test_raceway_scar.cpp) must give the same value bit for
// bit, and the concave roller term the maximum over every roller vertex computed here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/raceway_scar.h"
#include "interfere/bearing/raceway_scar_solver.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"
#include "interfere/core/vec.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

using SplitMix = interfere::bearing::test::SplitMix;

Roller scarred(int n, int m, bool raised, std::uint64_t seed, double top_radius = -1) {
  Expected<Roller> r = make_roller({.radius = 10, .top_radius = top_radius, .height = 38, .radial_segments = n,
                                    .height_segments = m});
  EXPECT_TRUE(r.has_value());
  EXPECT_TRUE(apply_scar(*r, {.angle_center_deg = 0, .angle_width_deg = 300, .z_min = 2, .z_max = 36, .depth = 0.04,
                              .roughness = 0.6, .border = 2, .seed = seed, .raised = raised})
                  .has_value());
  return std::move(*r);
}

/// The side cells [i0, i1) x [j0, j1) a bound-tree node covers, from its leaves' triangle ids.
void leaves_below(const BoundTree& t, std::int32_t id, std::vector<std::uint32_t>& tris) {
  const BoundNode& n = t.nodes[static_cast<std::size_t>(id)];
  if (n.child_count == 0) {
    for (std::uint32_t k = 0; k < n.tri_count; ++k) tris.push_back(n.tri_first + k);
    return;
  }
  for (std::int32_t k = 0; k < n.child_count; ++k) leaves_below(t, n.first_child + k, tris);
}

}  // namespace

TEST(BearingBoundTree, EveryTriangleOnceInsideEveryBoxAboveIt) {
  for (const auto& [n, m] : {std::pair{64, 63}, std::pair{24, 7}, std::pair{9, 1}}) {
    const Roller r = scarred(n, m, n == 24, 3);
    const RollerQuadtree q = build_quadtree(r);
    const BoundTree& t = q.bounds;
    ASSERT_FALSE(t.empty());
    std::vector<int> seen(r.mesh.num_triangles(), 0);
    std::vector<std::int32_t> stack{t.side_root, t.bottom_root, t.top_root};
    std::size_t reached = 0;
    while (!stack.empty()) {
      const std::int32_t id = stack.back();
      stack.pop_back();
      ++reached;
      const BoundNode& b = t.nodes[static_cast<std::size_t>(id)];
      std::vector<std::uint32_t> tris;
      leaves_below(t, id, tris);
      ASSERT_GE(b.half_r, 0);
      for (const std::uint32_t tri : tris)
        for (const std::uint32_t v : r.mesh.triangles[tri]) {  // the box holds every vertex below it
          const Vec3 p = r.mesh.positions[v] - b.box_center;
          EXPECT_LE(std::fabs(p.x * b.cos_mid + p.y * b.sin_mid), b.half_r);
          EXPECT_LE(std::fabs(-p.x * b.sin_mid + p.y * b.cos_mid), b.half_t);
          EXPECT_LE(std::fabs(p.z), b.half_z);
        }
      if (b.child_count == 0) {
        EXPECT_LE(b.tri_count, 2u);
        for (std::uint32_t k = 0; k < b.tri_count; ++k) ++seen[b.tri_first + k];
      }
      for (std::int32_t k = 0; k < b.child_count; ++k) stack.push_back(b.first_child + k);
    }
    EXPECT_EQ(reached, t.nodes.size());  // no orphans
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "triangle " << k;
    // column-first: the side root's descendants halve the columns until one is left, and only then
    // the rows; so the nodes covering all m rows are the column halvings (2 n - 1 of them)
    std::vector<std::uint32_t> all;
    leaves_below(t, t.side_root, all);
    EXPECT_EQ(all.size(), 2u * n * m);
    int full_height = 0;
    stack = {t.side_root};
    while (!stack.empty()) {
      const BoundNode& b = t.nodes[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      std::vector<std::uint32_t> tris;
      leaves_below(t, static_cast<std::int32_t>(&b - t.nodes.data()), tris);
      std::vector<int> rows(static_cast<std::size_t>(m), 0);
      for (const std::uint32_t tri : tris) rows[tri / (2u * n)] = 1;
      int covered = 0;
      for (const int x : rows) covered += x;
      if (covered == m) {
        ++full_height;
        for (std::int32_t k = 0; k < b.child_count; ++k) stack.push_back(b.first_child + k);
      }
    }
    EXPECT_EQ(full_height, 2 * n - 1) << n << "x" << m;
  }
}

TEST(BearingBoundTree, ScarredSolverEqualsTheFullScanBitwise) {
  // nearly parallel parts (the bearing's case the tree and the curvature bound are for), tilted
  // ones and crossed ones, cylinders and a frustum as B, pits and raised scars
  SplitMix g{27};
  int cases = 0;
  for (const bool raised : {false, true})
    for (const double top : {-1.0, 11.5}) {
      // a power-of-two grid and an odd one (uneven halvings)
      const Roller r = top < 0 && raised ? scarred(27, 13, raised, 5, top) : scarred(64, 63, raised, 5 + raised, top);
      const RollerQuadtree q = build_quadtree(r);
      for (int k = 0; k < 24; ++k) {
        const Transform pose = roller_pose({g.in(-2, 2), g.in(-2, 2), g.in(-2, 2)}, g.in(0, 0.3), g.in(0, 6.3), g.in(0, 6.3));
        const Vec3 ra = pose.rotate({0, 0, 1}), mid = pose.apply({0, 0, 19});
        const Vec3 t = std::fabs(ra.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 c1 = cross(ra, t), e1 = c1 / norm(c1), e2 = cross(ra, e1);
        const double phi = g.in(0, 6.3);
        const Vec3 out = e1 * std::cos(phi) + e2 * std::sin(phi), side = cross(ra, out);
        // B: a raceway-sized cylinder (R 80) or frustum touching the roller along `out`, its axis
        // parallel to the roller's, tilted by up to 0.1 degrees, 1-20 degrees or crossed (30-90)
        const double tilt = k % 3 == 0 ? g.in(0, 0.1) * kDeg : k % 3 == 1 ? g.in(1, 20) * kDeg : g.in(30, 90) * kDeg;
        Cylinder b;
        b.axis = ra * std::cos(tilt) + side * std::sin(tilt);
        b.height = 50, b.radius = 80;
        if (k % 4 == 3) b.top_radius = 80.5;
        b.base = mid + out * (80 + 10 - g.in(-0.05, 0.1)) - b.axis * 25.0;
        // the cell tree (RollerQuadtree::bounds): bit for bit; the tree of coplanar facet strips
        // (the default since issue #27's 1,024-roller work; test_bearing_facet_strips.cpp) minimises
        // a planar run of cells as one rectangle, the same value to rounding: within 2^-40 of the scale
        set_facet_strips_for_testing(false);
        const MeshPairResult got = ScarredSolver(&r, &q).solve(pose, b);
        set_facet_strips_for_testing(true);
        const MeshPairResult strips = ScarredSolver(&r, &q).solve(pose, b);
        const MeshPairResult ref = surface_reference(r, pose, b);
        EXPECT_EQ(got.distance, ref.distance) << "raised " << raised << " top " << top << " case " << k;
        EXPECT_NEAR(strips.distance, ref.distance, 0x1p-40 * (norm(pose.t - b.center()) + 80 + 25 + 40))
            << "raised " << raised << " top " << top << " case " << k;
        ++cases;
      }
    }
  EXPECT_EQ(cases, 96);
}

TEST(BearingBoundTree, RacewayTermsEqualFullScans) {
  // the pair solver's raceway term against surface_reference over the whole raceway grid, the convex
  // roller term against surface_reference over the roller, and a bore's roller term against the
  // largest rho - (R - raise) over every roller vertex (the roller inside the width); pitted and
  // raised rollers and raceways
  SplitMix g{41};
  for (const bool roller_raised : {false, true})
  for (const bool concave : {false, true})
    for (const bool raised : {false, true}) {
      const Roller rl = scarred(64, 63, roller_raised, 9);
      const RollerQuadtree tree = build_quadtree(rl);
      const double R = concave ? 100.1 : 80;
      const RacewayGeometry geo{.surface = concave ? RacewaySurface::outer : RacewaySurface::inner, .z0 = -25,
                                .width = 50, .radius = R, .top_radius = R};
      Expected<RacewayScar> s = make_raceway_scar(
          geo, {.radial_segments = 256, .height_segments = 31},
          ScarParams{.angle_center_deg = 0, .angle_width_deg = 60, .z_min = 5, .z_max = 45, .depth = 0.05,
                     .roughness = 0.6, .border = 2, .seed = 13, .raised = raised});
      ASSERT_TRUE(s.has_value());
      const RacewayPairRing ring{&*s, Transform::identity()};
      const Transform sp = raceway_surface_pose(ring);
      for (int k = 0; k < 12; ++k) {
        const double phi = g.in(-20, 20) * kDeg, press = g.in(-0.02, 0.08);
        const double tilt = g.in(-0.1, 0.1) * kDeg, az = phi + 0.5 * std::numbers::pi;
        const Vec3 axis{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
        const Vec3 mid = Vec3{std::cos(phi), std::sin(phi), 0} * (R + (concave ? -1 : 1) * (10 - press));
        const Transform pose = roller_pose(mid - axis * 19.0, tilt, az, g.in(0, 6.3));
        const RacewayPairRoller roller{posed_cylinder(10, -1, 38, pose), &rl, &tree, pose};
        const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
        EXPECT_EQ(r.raceway_term, surface_reference(s->surface, sp, raceway_term_roller_solid(roller)).distance)
            << roller_raised << concave << raised << " " << k;
        if (!concave) {
          Cylinder b;
          b.base = sp.t, b.axis = {0, 0, 1}, b.height = 50, b.radius = R + s->raise;
          // (the roller's cylinder in the raceway term is grown by its raise: raceway_term_roller_solid)
          EXPECT_EQ(r.roller_term, surface_reference(rl, pose, b).distance) << raised << " " << k;
        } else {
          double best = -1e300;
          for (const Vec3& v : rl.mesh.positions) {
            const Vec3 x = pose.apply(v);
            ASSERT_GT(x.z, -25);
            ASSERT_LT(x.z, 25);
            best = std::max(best, std::hypot(x.x, x.y) - (R - s->raise));  // every vertex, in the width
          }
          EXPECT_NEAR(r.roller_term, -best, 1e-13 * R) << raised << " " << k;
        }
      }
    }
}
