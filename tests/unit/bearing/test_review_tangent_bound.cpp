// Review of 18a8222 (issue #27, Table 3 with the scars in range): intact_reverse_tangent_bound must be
// a lower bound of s(B, A) = min over the solid B of sd_A on every pose, including extreme and
// degenerate ones, and intact_row_distance must stay bitwise equal to two_sided_cylinder_distance
// wherever A and B overlap (the skip is claimed to change nothing).
//
// Oracle (independent of src/bearing): sd_A by the textbook capped-cylinder formula, evaluated in A's
// own frame (so that a translation of the scene does not enter the oracle's rounding), minimised over
// a dense (height, radius, angle) grid of B's solid and then refined by a compass search that stays
// inside B. Every value it returns is sd_A at a point of B, so it is >= s(B, A): a bound above it is a
// wrong bound, never an artefact of the sampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/part_pair.h"
#include "splitmix.h"

using namespace interfere;
using namespace interfere::bearing;
using interfere::bearing::test::SplitMix;

namespace {

struct Frame {  // an orthonormal frame of A: e0, e1 across the axis, e2 along it; origin A's base
  Vec3 o, e0, e1, e2;
};

Frame frame_of(const Cylinder& a) {
  const Vec3 z = a.axis / norm(a.axis);
  const Vec3 t = std::fabs(z.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 x = cross(z, t);
  x = x / norm(x);
  return {a.base, x, cross(z, x), z};
}

// signed distance to the capped cylinder of radius r, height h along +z from the origin (local coordinates)
double capped_sd(double r, double h, double x, double y, double z) {
  const double dr = std::hypot(x, y) - r;
  const double dz = std::max(-z, z - h);
  if (dr <= 0 && dz <= 0) return std::max(dr, dz);
  const double px = std::max(dr, 0.0), pz = std::max(dz, 0.0);
  return std::sqrt(px * px + pz * pz);
}

// B's point at (t, rho, phi) in A's local frame: B's base, axis and cross directions expressed there
struct BLocal {
  std::array<double, 3> c, ax, u, v;
  double h, R;
};

BLocal b_local(const Frame& f, const Cylinder& b) {
  const auto loc = [&](const Vec3& w) { return std::array<double, 3>{dot(w, f.e0), dot(w, f.e1), dot(w, f.e2)}; };
  const Vec3 z = b.axis / norm(b.axis);
  const Vec3 t = std::fabs(z.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 x = cross(z, t);
  x = x / norm(x);
  const Vec3 y = cross(z, x);
  return {loc(b.base - f.o), loc(z), loc(x), loc(y), b.height, b.radius};
}

double sd_at(const Cylinder& a, const BLocal& b, double t, double rho, double phi) {
  const double cu = rho * std::cos(phi), cv = rho * std::sin(phi);
  double p[3];
  for (int i = 0; i < 3; ++i) p[i] = b.c[i] + b.ax[i] * t + b.u[i] * cu + b.v[i] * cv;
  return capped_sd(a.radius, a.height, p[0], p[1], p[2]);
}

// An upper estimate of s(B, A) (sd_A at points of B): dense grid then compass search inside B.
double dense_reverse(const Cylinder& a, const Cylinder& b) {
  const Frame f = frame_of(a);
  const BLocal bl = b_local(f, b);
  constexpr int nt = 48, nr = 8, np = 96;
  double best = std::numeric_limits<double>::infinity();
  double bt = 0, br = 0, bp = 0;
  for (int i = 0; i <= nt; ++i)
    for (int j = 0; j <= nr; ++j)
      for (int k = 0; k < (j == 0 ? 1 : np); ++k) {
        const double t = bl.h * i / nt, rho = bl.R * j / nr, phi = 2 * M_PI * k / np;
        const double v = sd_at(a, bl, t, rho, phi);
        if (v < best) best = v, bt = t, br = rho, bp = phi;
      }
  double st = bl.h / nt, sr = bl.R / nr, sp = 2 * M_PI / np;
  for (int it = 0; it < 400 && (st > 1e-15 * bl.h || sr > 1e-15 * bl.R); ++it) {
    bool moved = false;
    for (const auto& d : {std::array<double, 3>{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}) {
      const double t = std::clamp(bt + d[0] * st, 0.0, bl.h), rho = std::clamp(br + d[1] * sr, 0.0, bl.R),
                   phi = bp + d[2] * sp;
      const double v = sd_at(a, bl, t, rho, phi);
      if (v < best) best = v, bt = t, br = rho, bp = phi, moved = true;
    }
    if (!moved) st *= 0.5, sr *= 0.5, sp *= 0.5;
  }
  return best;
}

Vec3 unit(const Vec3& v) { return v / norm(v); }

// a unit vector at angle `ang` from `a` (a unit)
Vec3 tilted(const Vec3& a, double ang, double az) {
  const Frame f = frame_of(Cylinder{.base = {}, .axis = a});
  return unit(a * std::cos(ang) + (f.e0 * std::cos(az) + f.e1 * std::sin(az)) * std::sin(ang));
}

void check_pose(const Cylinder& a, const Cylinder& b, const char* what, int it, int& bounded, int& skipped) {
  const double tb = intact_reverse_tangent_bound(a, b);
  ASSERT_FALSE(std::isnan(tb)) << what << " pose " << it;
  if (!std::isfinite(tb)) return;
  ++bounded;
  const double dense = dense_reverse(a, b);
  EXPECT_LE(tb, dense) << what << " pose " << it << " bound " << tb << " dense " << dense;
  const double fwd = cylinder_pair_distance(a, b).distance;
  const double tbt = intact_reverse_tangent_bound(a, b, fwd);
  EXPECT_LE(tbt, dense) << what << " pose " << it << " (target " << fwd << ")";
  if (fwd <= 0) {
    skipped += tbt >= fwd;
    const PairDistance row = intact_row_distance(a, b), two = two_sided_cylinder_distance(a, b);
    EXPECT_EQ(row.distance, two.distance) << what << " pose " << it;
    EXPECT_EQ(row.point_a, two.point_a) << what << " pose " << it;
    EXPECT_EQ(row.point_b, two.point_b) << what << " pose " << it;
  }
}

}  // namespace

// Random radii and heights over three decades, axes from parallel (and antiparallel) to the 60-degree
// limit, poses from far apart through touching to one wholly inside the other.
TEST(ReviewTangentBound, BelowDenseReverseOnRandomPoses) {
  SplitMix g{20261129};
  int bounded = 0, skipped = 0;
  for (int it = 0; it < 600; ++it) {
    Cylinder a, b;
    a.radius = std::exp(g.in(std::log(0.1), std::log(30.0)));
    a.height = std::exp(g.in(std::log(0.05), std::log(80.0)));
    b.radius = std::exp(g.in(std::log(0.1), std::log(30.0)));
    b.height = std::exp(g.in(std::log(0.05), std::log(80.0)));
    a.axis = unit(Vec3{g.in(-1, 1), g.in(-1, 1), g.in(-1, 1)});
    const double ang = std::vector<double>{0.0, 1e-14, 1e-9, 1e-5, 0.01, 0.3, 1.0, M_PI / 3 - 1e-9,
                                           M_PI - 1e-9, M_PI, g.in(0, M_PI / 3)}[it % 11];
    b.axis = tilted(a.axis, ang, g.in(0, 2 * M_PI));
    a.base = Vec3{g.in(-5, 5), g.in(-5, 5), g.in(-5, 5)};
    // B's base about A's axis at a random height, across at a random fraction of r + R
    const Frame f = frame_of(a);
    const double zz = g.in(-0.5, 1.2) * a.height, off = g.in(0, 1.3) * (a.radius + b.radius), az = g.in(0, 2 * M_PI);
    b.base = a.base + a.axis * zz + (f.e0 * std::cos(az) + f.e1 * std::sin(az)) * off - b.axis * g.in(0, b.height);
    check_pose(a, b, "random", it, bounded, skipped);
  }
  EXPECT_GT(bounded, 400);
  EXPECT_GT(skipped, 20);
}

// Table 3-like poses (a roller pressed into a partner, tilt up to 1 degree) translated far from the
// origin and scaled down: the margin is relative to the scene's coordinates.
TEST(ReviewTangentBound, TranslatedAndScaledTable3Poses) {
  SplitMix g{77};
  int bounded = 0, skipped = 0;
  for (const double shift : {0.0, 1e3, 1e6}) {
    for (const double scale : {1.0, 1e-3}) {
      for (int it = 0; it < 60; ++it) {
        const double tilt = g.in(0, 0.0174533), azm = g.in(-M_PI, M_PI), spin = g.in(-M_PI, M_PI);
        const Transform pose = roller_pose({(39.95 + shift) * scale, shift * scale, shift * scale}, tilt, azm, spin);
        Cylinder a = posed_cylinder(10 * scale, -1, 40 * scale, pose);
        Cylinder b;
        b.base = Vec3{shift, shift, -10 + shift} * scale, b.axis = {0, 0, 1}, b.height = 60 * scale, b.radius = 30 * scale;
        check_pose(a, b, "table3", it, bounded, skipped);
        check_pose(b, a, "table3 swapped", it, bounded, skipped);
      }
    }
  }
  EXPECT_GT(bounded, 600);
  EXPECT_GT(skipped, 200);
}

// Degenerate configurations: exactly parallel and antiparallel axes with touching sides, coincident
// cylinders, B wholly inside A and A wholly inside B, |a.b| exactly 0.5, A a thin disc and a needle.
TEST(ReviewTangentBound, DegenerateConfigurations) {
  int bounded = 0, skipped = 0, it = 0;
  const Vec3 z{0, 0, 1};
  const auto cyl = [](Vec3 base, Vec3 axis, double h, double r) {
    Cylinder c;
    c.base = base, c.axis = unit(axis), c.height = h, c.radius = r;
    return c;
  };
  // touching sides, parallel and antiparallel
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({5, 0, 2}, z, 4, 3), "touching parallel", it++, bounded, skipped);
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({5, 0, 8}, -z, 4, 3), "touching antiparallel", it++, bounded, skipped);
  // coincident
  check_pose(cyl({1, 2, 3}, z, 10, 2), cyl({1, 2, 3}, z, 10, 2), "coincident", it++, bounded, skipped);
  check_pose(cyl({1, 2, 3}, z, 10, 2), cyl({1, 2, 13}, -z, 10, 2), "coincident reversed", it++, bounded, skipped);
  // B wholly inside A and A wholly inside B (tilted a little)
  check_pose(cyl({0, 0, 0}, z, 50, 20), cyl({1, 0, 20}, {0.01, 0, 1}, 5, 1), "B inside A", it++, bounded, skipped);
  check_pose(cyl({1, 0, 20}, {0.01, 0, 1}, 5, 1), cyl({0, 0, 0}, z, 50, 20), "A inside B", it++, bounded, skipped);
  // same axis line, B's end in A's middle
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({0, 0, 5}, z, 10, 2), "same axis", it++, bounded, skipped);
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({0, 0, 5}, z, 10, 5), "same axis wider", it++, bounded, skipped);
  // |a.b| exactly 0.5 (60 degrees): cos(60) is not exactly 0.5 in double, so build b.axis = (sqrt(3)/2, 0, 1/2)
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({1, 0, 3}, {std::sqrt(0.75), 0, 0.5}, 6, 1.5), "60 degrees", it++,
             bounded, skipped);
  check_pose(cyl({0, 0, 0}, z, 10, 2), cyl({1, 0, 3}, {-std::sqrt(0.75), 0, -0.5}, 6, 1.5), "120 degrees", it++,
             bounded, skipped);
  // thin disc A and needle A against a fat B
  check_pose(cyl({0, 0, 0}, z, 1e-6, 5), cyl({3, 0, -1}, {0.1, 0, 1}, 2, 4), "disc A", it++, bounded, skipped);
  check_pose(cyl({0, 0, 0}, z, 100, 1e-3), cyl({0.5, 0, 40}, {0.2, 0.1, 1}, 10, 1), "needle A", it++, bounded,
             skipped);
  check_pose(cyl({0, 0, 0}, {1, 1e-15, 0}, 10, 2), cyl({3, 3.9, 0}, {1, 0, 1e-13}, 4, 2), "near parallel x", it++,
             bounded, skipped);
  EXPECT_GE(bounded, 12);
}
