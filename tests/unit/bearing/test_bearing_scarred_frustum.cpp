// The scarred solver against an intact cone frustum B (issue #27, deliverable 2: scars on tapered
// rollers; scarred.h). Oracle, independent of the bearing module's distance code: the signed
// distance to the frustum as a generic convex polygon (the symmetric meridian trapezoid, four edges
// walked in a loop: outside the distance to the nearest edge point, inside minus the distance to the
// nearest edge line) with a subgradient, and a best-first subdivision of every posed triangle of
// the scarred mesh (dense samples refined around the minimum: each cell's centroid value is an upper
// bound; the lower bound is the convexity bound sd(c) + min over the corners of g . (v - c), and the
// same for the convex minorants of sd_B: the lateral tangent-plane distance (rho - R(z)) / sqrt(1 +
// k^2), -z and z - h). The solver's value must lie in that bracket, refined to 1e-9.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

#include "interfere/bearing/scar.h"
#include "interfere/bearing/scarred.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

struct SdGrad {
  double value = 0;
  Vec3 grad;
};

/// sd to the frustum c (radius c.radius at the base, c.top() at the top) by a generic convex
/// polygon walk in p's meridian plane.
SdGrad frustum_oracle(const Cylinder& c, const Vec3& p) {
  const Vec3 w = p - c.base;
  const double z = dot(w, c.axis);
  const Vec3 q = w - c.axis * z;
  const double x = norm(q);
  const Vec3 radial = x > 0 ? q / x : Vec3{1, 0, 0};
  // counter-clockwise polygon in (x, z)
  const std::array<std::array<double, 2>, 4> v = {{{-c.radius, 0}, {c.radius, 0}, {c.top(), c.height}, {-c.top(), c.height}}};
  bool inside = true;
  double best_out = 1e300, best_in = 1e300;
  double gx = 0, gz = 0, ix = 0, iz = 0;
  for (int e = 0; e < 4; ++e) {
    const auto& a = v[static_cast<std::size_t>(e)];
    const auto& b = v[static_cast<std::size_t>((e + 1) % 4)];
    const double ex = b[0] - a[0], ez = b[1] - a[1], l = std::hypot(ex, ez);
    const double nx = ez / l, nz = -ex / l;  // outward normal of a counter-clockwise polygon
    const double line = (x - a[0]) * nx + (z - a[1]) * nz;
    if (line > 0) inside = false;
    if (-line < best_in) best_in = -line, ix = nx, iz = nz;
    const double t = std::clamp(((x - a[0]) * ex + (z - a[1]) * ez) / (l * l), 0.0, 1.0);
    const double dx = x - (a[0] + t * ex), dz = z - (a[1] + t * ez), d = std::hypot(dx, dz);
    if (d < best_out) best_out = d, gx = d > 0 ? dx / d : nx, gz = d > 0 ? dz / d : nz;
  }
  if (inside) return {-best_in, radial * ix + c.axis * iz};
  return {best_out, radial * gx + c.axis * gz};
}

struct Bracket {
  double lower = 0, upper = 0;
};

Bracket frustum_min_bracket(const std::vector<std::array<Vec3, 3>>& triangles, const Cylinder& b, double tol,
                            std::size_t budget = 6'000'000) {
  struct Cell {
    std::array<Vec3, 3> v;
    double lower;
    bool operator<(const Cell& o) const { return lower > o.lower; }
  };
  const double k = (b.top() - b.radius) / b.height, nk = std::sqrt(1 + k * k);
  Bracket out;
  out.upper = 1e300;
  std::size_t evaluations = 0;
  std::priority_queue<Cell> open;
  const auto push = [&](const std::array<Vec3, 3>& v) {
    const Vec3 c = (v[0] + v[1] + v[2]) / 3.0;
    const SdGrad s = frustum_oracle(b, c);
    ++evaluations;
    out.upper = std::min(out.upper, s.value);
    const auto bound = [&](double value, const Vec3& g) {
      double lin = 0;
      for (const Vec3& x : v) lin = std::min(lin, dot(g, x - c));
      return value + lin;
    };
    const Vec3 w = c - b.base;
    const double z = dot(w, b.axis);
    const Vec3 q = w - b.axis * z;
    const double rho = norm(q);
    const Vec3 radial = rho > 0 ? q / rho : Vec3{0, 0, 0};
    const double lateral = (rho - b.radius - k * z) / nk;
    open.push({v, std::max({bound(s.value, s.grad), bound(lateral, (radial - b.axis * k) / nk), bound(-z, b.axis * -1.0),
                            bound(z - b.height, b.axis)})});
  };
  for (const auto& t : triangles) {
    for (const Vec3& x : t) out.upper = std::min(out.upper, frustum_oracle(b, x).value);
    push(t);
  }
  while (!open.empty()) {
    const Cell cell = open.top();
    if (cell.lower >= out.upper - tol || evaluations >= budget) break;
    open.pop();
    const auto& v = cell.v;
    int e0 = 0;
    for (int e = 1; e < 3; ++e)
      if (norm(v[(e + 1) % 3] - v[e]) > norm(v[(e0 + 1) % 3] - v[e0])) e0 = e;
    const Vec3& p0 = v[e0];
    const Vec3& p1 = v[(e0 + 1) % 3];
    const Vec3& p2 = v[(e0 + 2) % 3];
    const Vec3 m = (p0 + p1) * 0.5;
    out.upper = std::min(out.upper, frustum_oracle(b, m).value);
    push({p0, m, p2});
    push({m, p1, p2});
  }
  out.lower = open.empty() ? out.upper : std::min(open.top().lower, out.upper);
  return out;
}

Roller scarred_tapered(std::uint64_t seed, bool raised, double r0 = 8, double r1 = 10, int n = 32, int m = 31) {
  Expected<Roller> r = make_roller({.radius = r0, .top_radius = r1, .height = 30, .radial_segments = n, .height_segments = m});
  EXPECT_TRUE(r.has_value());
  ScarParams s{.angle_center_deg = 0, .angle_width_deg = 120, .z_min = 4, .z_max = 26, .depth = 0.06,
               .roughness = 0.6, .border = 2, .seed = seed, .raised = raised};
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

std::vector<std::array<Vec3, 3>> posed_triangles(const Roller& r, const Transform& pose) {
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const auto c = r.mesh.corners(t);
    out.push_back({pose.apply(c[0]), pose.apply(c[1]), pose.apply(c[2])});
  }
  return out;
}

/// A deterministic generator (splitmix64) for the poses.
struct Rng {
  std::uint64_t s;
  double uniform() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  }
  double in(double a, double b) { return a + (b - a) * uniform(); }
};

double check(const Roller& a, const RollerQuadtree& tree, const Transform& pose, const Cylinder& b, const char* what,
             int trial) {
  const MeshPairResult ref = surface_reference(a, pose, b);
  ScarredSolver solver(&a, &tree);
  const MeshPairResult fast = solver.solve(pose, b);
  const double scale = std::max(b.height, b.max_radius()) + norm(pose.t);
  EXPECT_NEAR(fast.distance, ref.distance, 1e-12 * scale) << what << " " << trial;
  const Bracket br = frustum_min_bracket(posed_triangles(a, pose), b, 1e-9 * scale);
  EXPECT_LE(br.upper - br.lower, 1e-9 * scale) << what << " " << trial;
  EXPECT_GE(fast.distance, br.lower - 1e-12 * scale) << what << " " << trial;
  EXPECT_LE(fast.distance, br.upper + 1e-12 * scale) << what << " " << trial;
  // the witnesses: point_a on A's surface at that value, point_b on B's boundary
  EXPECT_NEAR(frustum_oracle(b, fast.point_a).value, fast.distance, 1e-9 * scale) << what << " " << trial;
  EXPECT_NEAR(frustum_oracle(b, fast.point_b).value, 0, 1e-9 * scale) << what << " " << trial;
  return fast.distance;
}

}  // namespace

TEST(BearingScarredFrustum, TriangleMinimaMatchTheOracle) {
  // single triangles everywhere around a frustum: beside it, past its ends, crossing its axis, inside
  Cylinder b;
  b.base = {1, -2, 3}, b.axis = Vec3{0.2, 0.1, 1} / norm(Vec3{0.2, 0.1, 1}), b.height = 30, b.radius = 8,
  b.top_radius = 12;
  Rng rng{7};
  for (int trial = 0; trial < 150; ++trial) {
    const Vec3 c = b.base + Vec3{rng.in(-25, 25), rng.in(-25, 25), rng.in(-15, 45)};
    const double size = trial % 3 == 0 ? 0.2 : trial % 3 == 1 ? 3.0 : 15.0;
    std::array<Vec3, 3> t;
    for (Vec3& v : t) v = c + Vec3{rng.in(-size, size), rng.in(-size, size), rng.in(-size, size)};
    const TriangleMin tm = triangle_min_signed_distance(b, t[0], t[1], t[2]);
    const Bracket br = frustum_min_bracket({t}, b, 1e-10);
    ASSERT_LE(br.upper - br.lower, 1e-9) << trial;
    EXPECT_GE(tm.value, br.lower - 1e-11) << trial;
    EXPECT_LE(tm.value, br.upper + 1e-11) << trial;
    EXPECT_NEAR(frustum_oracle(b, tm.point).value, tm.value, 1e-10) << trial;
  }
}

TEST(BearingScarredFrustum, ScarredTaperedRollerAgainstATaperedNeighbour) {
  // a scarred tapered roller beside an intact tapered roller (a tapered bearing's neighbours): pressed
  // into it, touching, apart; the scar inward and raised
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 8, b.top_radius = 10;
  Rng rng{11};
  for (int trial = 0; trial < 8; ++trial) {
    const Roller a = scarred_tapered(100 + trial, trial % 2 == 1);
    const RollerQuadtree tree = build_quadtree(a);
    const double gap = trial < 3 ? -0.3 : trial < 5 ? 0.0 : 0.4;
    const double tilt = rng.in(-0.03, 0.03), spin = rng.in(0, 2 * std::numbers::pi);
    // the scar (angle 0 in A's frame) faces B: spin so that A's +x points to -x
    const Transform pose = roller_pose({20 + gap + rng.in(-0.05, 0.05), rng.in(-0.5, 0.5), rng.in(-1, 1)}, tilt,
                                       0.5 * std::numbers::pi, std::numbers::pi + 0.3 * (spin - std::numbers::pi) / 3);
    const double s = check(a, tree, pose, b, "neighbour", trial);
    if (trial < 3) EXPECT_LT(s, -0.1) << trial;  // pressed in
    if (trial >= 5) EXPECT_GT(s, 0.1) << trial;  // apart
  }
}

TEST(BearingScarredFrustum, ScarredTaperedRollerAgainstAConeRaceway) {
  // a tapered bearing's cone (a large frustum) with a scarred tapered roller on it, its axis along
  // the cone's generator (line contact of the intact roller, broken by the scar and a small tilt)
  Cylinder cone;
  cone.base = {0, 0, -15}, cone.axis = {0, 0, 1}, cone.height = 30, cone.radius = 40, cone.top_radius = 46;
  const double k = 6.0 / 30;
  Rng rng{5};
  for (int trial = 0; trial < 8; ++trial) {
    const Roller a = scarred_tapered(300 + trial, trial % 2 == 0);
    const RollerQuadtree tree = build_quadtree(a);
    // the roller's bottom at z = -15 on the cone generator's outside; lean = the cone's half angle
    // plus the roller's own (its generator toward the cone parallel to the cone's)
    const double lean = std::atan(k) + std::atan((10.0 - 8.0) / 30) * -1 + rng.in(-0.01, 0.01);
    const double press = trial < 4 ? rng.in(0.02, 0.2) : rng.in(-0.3, 0.0);
    const double phi = rng.in(-0.2, 0.2);
    const Vec3 radial{std::cos(phi), std::sin(phi), 0};
    const Vec3 bottom = radial * (40 + 8 / std::cos(lean) - press) + Vec3{0, 0, -15 + rng.in(-0.2, 0.2)};
    // tilt toward +radial (azimuth phi): the roller leans outward with the cone
    const Transform pose = roller_pose(bottom, lean, phi, std::numbers::pi + rng.in(-0.4, 0.4));
    const double s = check(a, tree, pose, cone, "cone", trial);
    if (trial < 4) EXPECT_LT(s, 0) << trial;  // pressed into the cone
  }
}

TEST(BearingScarredFrustum, DeepAndCrossingPosesAndACylindricalA) {
  // a scarred roller pushed deep into the frustum (inside sd), crossing its end, and a scarred
  // cylindrical roller against a frustum
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 9, b.top_radius = 6;
  Rng rng{3};
  for (int trial = 0; trial < 6; ++trial) {
    const bool cylindrical = trial >= 3;
    Roller a = cylindrical ? scarred_tapered(500 + trial, false, 8, 8) : scarred_tapered(500 + trial, trial == 1);
    const RollerQuadtree tree = build_quadtree(a);
    const Vec3 at{rng.in(5, 14), rng.in(-3, 3), rng.in(-20, 20)};
    const Transform pose = roller_pose(at, rng.in(0, 0.6), rng.in(0, 6.28), rng.in(0, 6.28));
    const double s = check(a, tree, pose, b, cylindrical ? "cylindrical" : "deep", trial);
    EXPECT_LT(s, 0) << trial;  // (every pose overlaps)
  }
}
