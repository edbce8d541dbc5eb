// The scarred solver's tree of coplanar facet strips (quadtree.h, FacetStrips; scarred.h; issue #27,
// the 1,024-roller target): a planar run of intact cells of one column is minimised as one rectangle
// (two triangles), the scar's cells and the caps as before, and an end cap is skipped when the
// gradient of sd_B at the side's best point shows it cannot go lower (within 2^-44 of the scale).
// The reference is independent of the solver: sd_B written from its definition (the distance to the
// solid cylinder in its (radial, axial) half-plane, inside the larger of the two face depths) and,
// for every triangle of the mesh, a nested golden-section search over its barycentric coordinates
// (sd_B is convex), after a 1-Lipschitz vertex bound that skips triangles which cannot reach the
// best value. Scarred rollers: pits and raised scars, windows touching the mesh borders (angle
// across 0, z from 0 to the full height), an imported map; B beside the roller with parallel axes
// (ties along the generator), tilted, pressed, apart, past an end, crossing, and a large ring.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scar_import.h"
#include "interfere/bearing/scarred.h"
#include "interfere/core/vec.h"
#include "unit/bearing/splitmix.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
using SplitMix = interfere::bearing::test::SplitMix;

/// sd_B from its definition.
double ref_sd(const Cylinder& b, const Vec3& p) {
  const Vec3 d = p - b.center();
  const double z = dot(d, b.axis);
  const double rho = norm(d - b.axis * z);
  const double dr = rho - b.radius, dz = std::fabs(z) - 0.5 * b.height;
  if (dr <= 0 && dz <= 0) return std::max(dr, dz);
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
}

template <class F>
double golden(F&& f, double lo, double hi, int iters) {
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int k = 0; k < iters; ++k) {
    if (fc <= fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
    }
  }
  return std::min({fc, fd, f(lo), f(hi)});
}

/// min over the posed mesh of sd_B: every triangle not excluded by the vertex bound, by a nested
/// golden-section search over (s, t), p = a + s (b - a) + t (c - a), t in [0, 1 - s].
double reference(const Roller& r, const Transform& pose, const Cylinder& b) {
  std::vector<Vec3> p(r.mesh.positions.size());
  std::vector<double> v(p.size());
  double best = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = pose.apply(r.mesh.positions[i]), v[i] = ref_sd(b, p[i]), best = std::min(best, v[i]);
  for (const Tri& t : r.mesh.triangles) {
    const Vec3 &a = p[t[0]], &bb = p[t[1]], &c = p[t[2]];
    const double edge = std::max({norm(bb - a), norm(c - a), norm(c - bb)});
    if (std::min({v[t[0]], v[t[1]], v[t[2]]}) - edge > best) continue;  // sd_B is 1-Lipschitz
    const auto inner = [&](double s) {
      return golden([&](double tt) { return ref_sd(b, a + (bb - a) * s + (c - a) * tt); }, 0.0, 1.0 - s, 70);
    };
    best = std::min(best, golden(inner, 0.0, 1.0, 70));
  }
  return best;
}

Roller roller_with(int n, int m, const ScarParams& s) {
  Expected<Roller> r = make_roller({.radius = 10, .height = 38, .radial_segments = n, .height_segments = m});
  EXPECT_TRUE(r.has_value());
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

/// B beside the roller's side at gap `gap` in the body direction `phi` (parallel axes), shifted along
/// the axis by `shift`, tilted by `tilt` about the line joining the axes; radius `rb`.
Cylinder beside(double phi, double gap, double shift, double tilt, double rb, double hb) {
  const Vec3 dir{std::cos(phi), std::sin(phi), 0};
  const Vec3 side{-std::sin(phi), std::cos(phi), 0};
  const Vec3 axis = Vec3{0, 0, 1} * std::cos(tilt) + side * std::sin(tilt);
  const Vec3 center = dir * (10 + rb + gap) + Vec3{0, 0, 19 + shift};
  Cylinder b;
  b.axis = axis, b.radius = rb, b.height = hb, b.base = center - axis * (0.5 * hb);
  return b;
}

struct Case {
  Transform pose;
  Cylinder b;
};

/// Poses: the roller posed by a random rigid motion, B placed in its body frame then moved along.
std::vector<Case> cases(SplitMix& rng, double scar_angle_deg) {
  std::vector<Case> out;
  const double phi0 = scar_angle_deg * kDeg;
  const struct {
    double gap, shift, tilt_deg, rb, hb;
  } specs[] = {
      {0.5, 0, 0, 10, 38},       // neighbour apart, parallel: ties along the generator
      {0.2, 0.9, 0, 10, 38},     // apart, one end overhanging
      {-0.02, 0, 0, 10, 38},     // pressed, parallel
      {0.0, 0.3, 0.05, 10, 38},  // touching, nearly parallel
      {0.1, -0.6, 1, 10, 38},    // tilted 1 degree
      {-0.01, 0, 3, 10, 38},     // tilted 3 degrees, pressed
      {0.02, 0, 0.05, 110, 50},  // a ring beside the roller (an inner raceway)
      {0.3, 21, 0, 10, 38},      // past the roller's end: the caps and the rim
      {-0.5, 0, 60, 4, 30},      // crossing
  };
  for (const auto& s : specs) {
    const double phi = phi0 + (rng.uniform() - 0.5) * 12 * kDeg;
    const Cylinder local = beside(phi, s.gap, s.shift, s.tilt_deg * kDeg, s.rb, s.hb);
    const Transform pose = roller_pose({rng.uniform() * 100, rng.uniform() * 100 - 50, rng.uniform() * 20},
                                       rng.uniform() * 0.5, rng.uniform() * 6.3, rng.uniform() * 6.3);
    Cylinder b = local;
    b.base = pose.apply(local.base);
    const Vec3 ax = pose.apply(local.axis) - pose.apply(Vec3{0, 0, 0});
    b.axis = ax / norm(ax);
    out.push_back({pose, b});
  }
  // the caps hold the minimum: B end-on under the bottom cap (apart), B across the top cap (pressed)
  const auto place = [&](Vec3 base, Vec3 axis, double rb, double hb) {
    const Transform pose = roller_pose({rng.uniform() * 100, rng.uniform() * 100 - 50, rng.uniform() * 20},
                                       rng.uniform() * 0.5, rng.uniform() * 6.3, rng.uniform() * 6.3);
    Cylinder b;
    b.radius = rb, b.height = hb, b.base = pose.apply(base);
    const Vec3 ax = pose.apply(axis) - pose.apply(Vec3{0, 0, 0});
    b.axis = ax / norm(ax);
    out.push_back({pose, b});
  };
  place({3, 1, -10.2}, {0, 0, 1}, 4, 10);
  place({-15, 2, 38 + 3 - 0.05}, {1, 0, 0}, 3, 30);
  place({1, -2, -8 - 0.01 * rng.uniform()}, Vec3{0.03, 0, 1} / norm(Vec3{0.03, 0, 1}), 9.5, 8);
  return out;
}

double scale_of(const Transform& pose, const Cylinder& b) {
  return norm(pose.t - b.center()) + b.radius + 0.5 * b.height + 38;
}

/// The solver (strips, cold and warm, with and without a hint) against the reference; the cell tree
/// (set_facet_strips_for_testing(false)) against the strips within 2^-40 of the scale.
void check_roller(const Roller& r, double scar_angle_deg, std::uint64_t seed, const char* what) {
  const RollerQuadtree tree = build_quadtree(r);
  SplitMix rng{seed};
  ScarredSolver warm(&r, &tree);
  for (const Case& c : cases(rng, scar_angle_deg)) {
    const double ref = reference(r, c.pose, c.b);
    const double sc = scale_of(c.pose, c.b);
    ScarredSolver cold(&r, &tree);
    const MeshPairResult a = cold.solve(c.pose, c.b);
    const Vec3 hint = c.pose.apply(Vec3{10, 0, 19});
    const MeshPairResult h = ScarredSolver(&r, &tree).solve(c.pose, c.b, hint);
    const MeshPairResult w = warm.solve(c.pose, c.b);
    set_facet_strips_for_testing(false);
    const MeshPairResult old = ScarredSolver(&r, &tree).solve(c.pose, c.b);
    set_facet_strips_for_testing(true);
    for (const MeshPairResult* x : {&a, &h, &w}) {
      EXPECT_NEAR(x->distance, ref, 1e-9 * sc) << what;
      EXPECT_NEAR(x->distance, old.distance, 0x1p-40 * sc) << what;
      // the witness is a point of the mesh with that value
      EXPECT_NEAR(ref_sd(c.b, x->point_a), x->distance, 1e-9 * sc) << what;
      EXPECT_LT(x->triangle, r.mesh.triangles.size()) << what;
    }
    // the same call twice: the same result bit for bit (no hidden state besides `previous`)
    const MeshPairResult a2 = ScarredSolver(&r, &tree).solve(c.pose, c.b);
    EXPECT_EQ(a2.distance, a.distance);
    EXPECT_EQ(a2.point_a.x, a.point_a.x);
    EXPECT_EQ(a2.triangle, a.triangle);
  }
}

}  // namespace

TEST(BearingFacetStrips, EveryCellOnceAndStripsOnlyWherePlanar) {
  for (const bool raised : {false, true}) {
    const Roller r = roller_with(32, 32, {.angle_center_deg = 0, .angle_width_deg = 90, .z_min = 0, .z_max = 20,
                                          .depth = 0.04, .border = 2, .seed = 7, .raised = raised});
    const RollerQuadtree q = build_quadtree(r);
    const FacetStrips& fs = q.strips;
    ASSERT_FALSE(fs.empty());
    const int n = r.n(), m = r.m();
    std::vector<int> cover(static_cast<std::size_t>(n) * m, 0), caps(2 * static_cast<std::size_t>(n), 0);
    int strips = 0;
    std::vector<std::int32_t> stack{fs.tree.side_root, fs.tree.bottom_root, fs.tree.top_root};
    while (!stack.empty()) {
      const BoundNode& node = fs.tree.nodes[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      for (std::int32_t k = 0; k < node.child_count; ++k) stack.push_back(node.first_child + k);
      // the box contains the vertices of every entry below it
      {
        std::vector<std::int32_t> below{static_cast<std::int32_t>(&node - fs.tree.nodes.data())};
        while (!below.empty()) {
          const BoundNode& d = fs.tree.nodes[static_cast<std::size_t>(below.back())];
          below.pop_back();
          for (std::int32_t k = 0; k < d.child_count; ++k) below.push_back(d.first_child + k);
          for (std::uint32_t e = d.tri_first; d.child_count == 0 && e < d.tri_first + d.tri_count; ++e)
            for (const std::uint32_t v : fs.corners[e]) {
              const Vec3 q = r.mesh.positions[v] - node.box_center;
              EXPECT_LE(std::fabs(q.x * node.cos_mid + q.y * node.sin_mid), node.half_r);
              EXPECT_LE(std::fabs(-q.x * node.sin_mid + q.y * node.cos_mid), node.half_t);
              EXPECT_LE(std::fabs(q.z), node.half_z);
            }
        }
      }
      if (node.child_count > 0) continue;
      for (std::uint32_t e = node.tri_first; e < node.tri_first + node.tri_count; ++e) {
        const std::uint32_t t = fs.mesh_triangle[e];
        if (t == FacetStrips::kStrip) {
          const auto [i, j0, j1] = fs.strip_cells[e];
          ASSERT_GE(j1 - j0, 2);
          ++strips;
          // planar: every vertex of both columns of the run keeps its (x, y) (intact, or one
          // displacement down the column); one z per row
          for (int j = j0; j <= j1; ++j) {
            for (const int c : {i, i + 1}) {
              EXPECT_EQ(r.mesh.positions[r.side_vertex(c, j)].x, r.mesh.positions[r.side_vertex(c, j0)].x);
              EXPECT_EQ(r.mesh.positions[r.side_vertex(c, j)].y, r.mesh.positions[r.side_vertex(c, j0)].y);
            }
            EXPECT_EQ(r.mesh.positions[r.side_vertex(i, j)].z, r.mesh.positions[r.side_vertex(i + 1, j)].z);
          }
          if (e % 2 == 0)
            for (int j = j0; j < j1; ++j) ++cover[static_cast<std::size_t>(j) * n + i];
        } else if (t < static_cast<std::uint32_t>(2 * n * m)) {
          if (t % 2 == 0) ++cover[t / 2];
          EXPECT_EQ(fs.corners[e][0], r.mesh.triangles[t][0]);
        } else {
          ++caps[t - static_cast<std::uint32_t>(2 * n * m)];
        }
      }
    }
    for (const int c : cover) EXPECT_EQ(c, 1);
    for (const int c : caps) EXPECT_EQ(c, 1);
    EXPECT_GE(strips, 2 * (n - 12));  // the columns outside the 90 degree window are single strips
    for (std::uint32_t t = 0; t < r.mesh.triangles.size(); ++t) EXPECT_GE(fs.leaf_of_triangle[t], 0);
  }
}

TEST(BearingFacetStrips, InwardScarsAgainstDenseReference) {
  // a window inside the side, one touching z = 0 and crossing angle 0, one covering the full height
  const ScarParams windows[] = {
      {.angle_center_deg = 0, .angle_width_deg = 40, .z_min = 10, .z_max = 30, .depth = 0.05, .seed = 3},
      {.angle_center_deg = 350, .angle_width_deg = 60, .z_min = 0, .z_max = 15, .depth = 0.05, .seed = 4},
      {.angle_center_deg = 180, .angle_width_deg = 350, .z_min = 0, .z_max = 38, .depth = 0.03, .seed = 5},
  };
  std::uint64_t seed = 11;
  for (const ScarParams& s : windows) {
    const Roller r = roller_with(32, 32, s);
    check_roller(r, s.angle_center_deg, seed++, "inward");
  }
}

TEST(BearingFacetStrips, RaisedScarsAgainstDenseReference) {
  const ScarParams windows[] = {
      {.angle_center_deg = 10, .angle_width_deg = 50, .z_min = 5, .z_max = 38, .depth = 0.04, .seed = 6, .raised = true},
      {.angle_center_deg = 0, .angle_width_deg = 120, .z_min = 12, .z_max = 26, .depth = 0.02, .seed = 8, .raised = true},
  };
  std::uint64_t seed = 21;
  for (const ScarParams& s : windows) {
    const Roller r = roller_with(24, 16, s);
    check_roller(r, s.angle_center_deg, seed++, "raised");
  }
}

TEST(BearingFacetStrips, ImportedMapAgainstDenseReference) {
  // a CSV height map (scar_import.h): a bump and a pit, angle -30..30, z 4..34
  std::ostringstream csv;
  csv.precision(17);
  csv << "z\\angle_deg";
  for (int a = -30; a <= 30; a += 5) csv << ", " << a;
  csv << "\n";
  for (int z = 4; z <= 34; z += 2) {
    csv << z;
    for (int a = -30; a <= 30; a += 5)
      csv << "," << 0.03 * std::exp(-((a - 8) * (a - 8)) / 60.0 - (z - 14) * (z - 14) / 20.0) -
                        0.04 * std::exp(-((a + 10) * (a + 10)) / 80.0 - (z - 26) * (z - 26) / 30.0);
    csv << "\n";
  }
  const auto map = parse_scar_csv(csv.str(), "strips.csv");
  ASSERT_TRUE(map.has_value()) << map.error().message();
  Expected<Roller> r = make_roller({.radius = 10, .height = 38, .radial_segments = 32, .height_segments = 32});
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(apply_height_map(*r, *map).has_value());
  check_roller(*r, 0, 31, "imported");
}

TEST(BearingFacetStrips, IntactRollerTiesAlongTheGenerator) {
  // no scar: every column is one strip; B exactly parallel beside a vertex column and beside a
  // column's middle (the minimum is a whole generator segment: a tie)
  Expected<Roller> r = make_roller({.radius = 10, .height = 38, .radial_segments = 32, .height_segments = 32});
  ASSERT_TRUE(r.has_value());
  const RollerQuadtree tree = build_quadtree(*r);
  for (const double phi : {0.0, std::numbers::pi / 32, 2 * std::numbers::pi / 32 * 5}) {
    for (const double gap : {0.4, 0.0, -0.03}) {
      const Cylinder b = beside(phi, gap, 0, 0, 10, 38);
      const double ref = reference(*r, Transform::identity(), b);
      ScarredSolver s(&*r, &tree);
      const MeshPairResult a = s.solve(Transform::identity(), b);
      EXPECT_NEAR(a.distance, ref, 1e-9 * 80);
      EXPECT_LE(a.evaluated, 12u);  // a few strips, not the column's 64 triangles
    }
  }
}
