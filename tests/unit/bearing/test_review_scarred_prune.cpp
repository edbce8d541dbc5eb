// Review of 18a8222 (issue #27): node_lower_bound now returns the max of its two cheap terms when they
// already reach the pruning cut, and descend prefetches. Claimed: the same pruning decisions, so the
// branch and bound gives exactly the exhaustive surface_reference's value. Attacked with long warm
// sequences (temporal coherence + hints: the cut is tight from the first node on, where the early
// return fires most), random and extreme poses (deep penetration, far apart, the partner's end cap
// against the roller, nearly parallel and crossed axes), inward and raised scars, cylinder and frustum
// partners; and checked against an independent upper bound: min over the posed mesh's vertices of a
// textbook capped-cylinder signed distance (every vertex lies on the surface, so the surface minimum
// can never be above it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"
#include "splitmix.h"

using namespace interfere;
using namespace interfere::bearing;
using interfere::bearing::test::SplitMix;

namespace {

Roller make_scarred(double r0, double r1, std::uint64_t seed, bool raised, double width) {
  Expected<Roller> r = make_roller({.radius = r0, .top_radius = r1, .height = 40, .radial_segments = 48, .height_segments = 39});
  EXPECT_TRUE(r.has_value());
  ScarParams s{.angle_center_deg = 30, .angle_width_deg = width, .z_min = 2, .z_max = 38, .depth = 0.2,
               .roughness = 0.7, .border = 1, .seed = seed, .raised = raised};
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

// textbook signed distance to an untapered capped cylinder
double capped_sd(const Cylinder& c, const Vec3& p) {
  const Vec3 w = p - c.base;
  const double z = dot(w, c.axis);
  const double rho = norm(w - c.axis * z);
  const double dr = rho - c.radius, dz = std::max(-z, z - c.height);
  if (dr <= 0 && dz <= 0) return std::max(dr, dz);
  const double px = std::max(dr, 0.0), pz = std::max(dz, 0.0);
  return std::sqrt(px * px + pz * pz);
}

double vertex_upper(const Roller& r, const Transform& pose, const Cylinder& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& v : r.mesh.positions) best = std::min(best, capped_sd(b, pose.apply(v)));
  return best;
}

Vec3 unit(const Vec3& v) { return v / norm(v); }

Cylinder partner_near(SplitMix& g, const Transform& pose, double roller_r, bool tapered) {
  // B's axis within ~70 degrees of the roller's, its side about the roller's side, any depth
  const Vec3 ra{pose.r[0][2], pose.r[1][2], pose.r[2][2]};
  Cylinder b;
  b.axis = unit(ra + Vec3{g.in(-1, 1), g.in(-1, 1), g.in(-1, 1)} * g.in(0, 1.5));
  b.radius = g.in(3, 40);
  if (tapered) b.top_radius = b.radius * g.in(0.6, 1.4);
  b.height = g.in(5, 80);
  const Vec3 c = pose.apply(Vec3{0, 0, g.in(-5, 45)});
  Vec3 across = cross(b.axis, Vec3{g.in(-1, 1), g.in(-1, 1), g.in(-1, 1)});
  across = unit(across);
  const double dist = (roller_r + b.radius) * g.in(0.7, 1.1);
  b.base = c + across * dist - b.axis * g.in(-0.2, 1.2) * b.height;
  return b;
}

}  // namespace

TEST(ReviewScarredPrune, WarmSequencesEqualTheExhaustiveReference) {
  struct Case {
    double r0, r1;
    bool raised;
    double width;
    bool tapered_b;
  };
  const Case cases[] = {{10, -1, false, 120, false}, {10, -1, true, 359, false}, {10, -1, false, 359, true},
                        {8, 11, true, 200, true}, {9, 7, false, 90, false}};
  SplitMix g{424242};
  int compared = 0, vertex_checked = 0, penetrating = 0;
  for (const Case& cs : cases) {
    const Roller roller = make_scarred(cs.r0, cs.r1, 5 + compared, cs.raised, cs.width);
    const RollerQuadtree tree = build_quadtree(roller);
    for (int seq = 0; seq < 6; ++seq) {
      ScarredSolver warm(&roller, &tree);
      Vec3 pivot{g.in(-50, 50), g.in(-50, 50), g.in(-50, 50)};
      double tilt = g.in(0, 0.3), az = g.in(-M_PI, M_PI), spin = g.in(-M_PI, M_PI);
      Transform pose = roller_pose(pivot, tilt, az, spin);
      Cylinder b = partner_near(g, pose, cs.r0, cs.tapered_b);
      for (int f = 0; f < 25; ++f) {
        // small motion most frames, a jump now and then (the previous triangle then far off)
        const bool jump = f % 9 == 8;
        tilt = std::clamp(tilt + g.in(-0.01, 0.01) * (jump ? 30 : 1), 0.0, 1.2);
        az += g.in(-0.05, 0.05) * (jump ? 20 : 1), spin += g.in(-0.1, 0.1) * (jump ? 20 : 1);
        pose = roller_pose(pivot, tilt, az, spin);
        if (jump) b = partner_near(g, pose, cs.r0, cs.tapered_b);
        const MeshPairResult ref = surface_reference(roller, pose, b);
        // the claim reviewed here is the cell tree's (RollerQuadtree::bounds): bit for bit. The tree of
        // coplanar facet strips (issue #27, later; test_bearing_facet_strips.cpp) gives the same value
        // to rounding, checked below within 2^-40 of the scale
        set_facet_strips_for_testing(false);
        const MeshPairResult w = (f % 2) ? warm.solve(pose, b, pose.apply(Vec3{cs.r0, 0, 20})) : warm.solve(pose, b);
        ScarredSolver cold(&roller, &tree);
        const MeshPairResult c = cold.solve(pose, b);
        set_facet_strips_for_testing(true);
        {
          const MeshPairResult sc = ScarredSolver(&roller, &tree).solve(pose, b, pose.apply(Vec3{cs.r0, 0, 20}));
          EXPECT_NEAR(sc.distance, ref.distance, 0x1p-40 * (norm(pose.t - b.center()) + b.height + 2 * b.radius + 80))
              << "strips, case r0=" << cs.r0 << " seq " << seq << " frame " << f;
        }
        ASSERT_EQ(w.distance, ref.distance) << "case r0=" << cs.r0 << " seq " << seq << " frame " << f;
        ASSERT_EQ(c.distance, ref.distance) << "case r0=" << cs.r0 << " seq " << seq << " frame " << f;
        EXPECT_EQ(c.point_a, ref.point_a) << "seq " << seq << " frame " << f;
        EXPECT_LE(c.evaluated, roller.mesh.num_triangles());
        penetrating += ref.distance < 0;
        ++compared;
        if (!b.tapered()) {
          const double vu = vertex_upper(roller, pose, b);
          EXPECT_LE(c.distance, vu + 1e-9 * (1 + std::fabs(vu))) << "seq " << seq << " frame " << f;
          ++vertex_checked;
        }
      }
    }
  }
  EXPECT_EQ(compared, 5 * 6 * 25);
  EXPECT_GT(vertex_checked, 300);
  EXPECT_GT(penetrating, 100);
}

// Extreme partners: a huge partner nearly coaxial, a tiny one inside the roller, one far away, one
// whose end cap faces the roller's side, and the whole scene far from the origin.
TEST(ReviewScarredPrune, ExtremePartnersEqualTheReference) {
  const Roller roller = make_scarred(10, -1, 99, true, 300);
  const RollerQuadtree tree = build_quadtree(roller);
  const auto cyl = [](Vec3 base, Vec3 axis, double h, double r) {
    Cylinder c;
    c.base = base, c.axis = unit(axis), c.height = h, c.radius = r;
    return c;
  };
  for (const double shift : {0.0, 1e4, 1e7}) {
    const Transform pose = roller_pose({shift, -shift, shift}, 0.01, 0.3, 1.1);
    const Vec3 o = pose.t;
    const Cylinder bs[] = {
        cyl(o + Vec3{0.5, 0, -100}, {1e-9, 0, 1}, 300, 9.9),     // nearly coaxial, almost the roller's size
        cyl(o + Vec3{0.5, 0, -100}, {1e-9, 0, 1}, 300, 1000),    // huge, containing the roller
        cyl(o + Vec3{1, 1, 15}, {0.3, 0.1, 1}, 2, 0.5),          // tiny, inside the roller
        cyl(o + Vec3{1e3, 0, 0}, {0, 1, 0}, 10, 5),              // far away
        cyl(o + Vec3{10.1, 0, 20}, {1, 0, 0}, 20, 6),            // end cap against the side
        cyl(o + Vec3{19.95, 0, -10}, {0, 0, 1}, 60, 10),         // side by side, touching
    };
    int k = 0;
    for (const Cylinder& b : bs) {
      const MeshPairResult ref = surface_reference(roller, pose, b);
      ScarredSolver cold(&roller, &tree);
      const MeshPairResult c = cold.solve(pose, b);
      EXPECT_EQ(c.distance, ref.distance) << "shift " << shift << " partner " << k;
      const MeshPairResult again = cold.solve(pose, b, b.base);  // warm, with a poor hint
      EXPECT_EQ(again.distance, ref.distance) << "shift " << shift << " partner " << k;
      const double vu = vertex_upper(roller, pose, b);
      EXPECT_LE(c.distance, vu + 1e-9 * (1 + std::fabs(vu) + shift)) << "shift " << shift << " partner " << k;
      ++k;
    }
  }
}
