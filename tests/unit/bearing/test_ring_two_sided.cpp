// Two-sided ring pairs (issue #27: s(A, B) = s(B, A)): ring_two_sided.h's S of a roller against an
// outer ring (bore), a cup and a rib block, against a dense reference written here from the
// definitions: fwd = max over the roller's surface of the point's depth in the ring part (the
// smallest distance to the lines of its meridian polygon, the polygon written from the ring's
// parameters), rev = max over the ring part's surfaces of the point's depth in the roller (the
// test's own meridian-trapezoid distance); S = -max(fwd, rev) when they overlap, and the two
// maximisers are on the parts' boundaries (each depth only grows moving into the other part's
// interior... see docs/bearing.md, "Two-sided ring pairs"). Grids of 720 x 80 per surface patch,
// refined twelve times around the best sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

#include "interfere/bearing/ring_two_sided.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Frame {
  Vec3 x, y, z;
};
Frame frame_of(const Vec3& axis) {
  const Vec3 e1 = std::fabs(axis.x) < 0.9 ? cross(axis, Vec3{1, 0, 0}) : cross(axis, Vec3{0, 1, 0});
  const Vec3 x = e1 / norm(e1);
  return {x, cross(axis, x), axis};
}

/// The roller (frustum) as the test sees it.
struct Roller {
  Vec3 base, axis;
  double r0 = 10, r1 = 10, h = 20;
};

/// Depth of p in the roller (> 0 inside): the distance to the nearest edge line of the meridian
/// trapezoid (0 <= z <= h, rho <= r(z)), negative outside (then a lower bound of minus the distance:
/// enough for a maximum that is positive).
double roller_depth(const Roller& r, const Vec3& p) {
  const Vec3 d = p - r.base;
  const double z = dot(d, r.axis), rho = norm(d - r.axis * z);
  const double k = (r.r1 - r.r0) / r.h;
  const double side = (r.r0 + k * z - rho) / std::sqrt(1 + k * k);
  return std::min({side, z, r.h - z});
}

/// Points of the roller's surface, patch 0 side, 1 bottom disk, 2 top disk; (u, v) in [0, 1]^2.
Vec3 roller_surface(const Roller& r, int patch, double u, double v) {
  const Frame f = frame_of(r.axis);
  const double a = 2 * kPi * u;
  const Vec3 radial = f.x * std::cos(a) + f.y * std::sin(a);
  if (patch == 0) return r.base + r.axis * (v * r.h) + radial * (r.r0 + (r.r1 - r.r0) * v);
  return r.base + r.axis * (patch == 1 ? 0.0 : r.h) + radial * ((patch == 1 ? r.r0 : r.r1) * v);
}

/// max of f over a patch parametrised on [u0, u1] x [v0, v1]: a grid, then twelve refinements of a
/// 41 x 41 grid five times finer around the best point each time.
double dense_max(const std::function<Vec3(double, double)>& at, const std::function<double(const Vec3&)>& f, double u0,
                 double u1, double v0, double v1, int nu = 720, int nv = 80) {
  double bu = u0, bv = v0, best = -kInf;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double u = u0 + (u1 - u0) * i / nu, v = v0 + (v1 - v0) * j / nv;
      if (const double val = f(at(u, v)); val > best) best = val, bu = u, bv = v;
    }
  double hu = (u1 - u0) / nu, hv = (v1 - v0) / nv;
  for (int level = 0; level < 12; ++level) {
    const double cu = bu, cv = bv;
    for (int i = -20; i <= 20; ++i)
      for (int j = -20; j <= 20; ++j) {
        const double u = std::clamp(cu + hu * i / 20.0, u0, u1), v = std::clamp(cv + hv * j / 20.0, v0, v1);
        if (const double val = f(at(u, v)); val > best) best = val, bu = u, bv = v;
      }
    hu /= 5, hv /= 5;
  }
  return best;
}

double roller_max(const Roller& r, const std::function<double(const Vec3&)>& f) {
  double best = -kInf;
  for (int patch = 0; patch < 3; ++patch)
    best = std::max(best, dense_max([&](double u, double v) { return roller_surface(r, patch, u, v); }, f, 0, 1, 0, 1));
  return best;
}

/// A ring part as a solid of revolution about (base, axis) whose meridian section is the convex
/// polygon {l_i(rho, z) >= 0}, each l_i an edge's signed distance (free surfaces only), and whose
/// boundary patches are listed for the reverse search.
struct Ring {
  Vec3 base, axis;
  std::vector<std::function<double(double, double)>> edges;
  /// patches: (rho, z) along a boundary edge as functions of v in [0, 1]
  std::vector<std::function<std::pair<double, double>(double)>> patches;
  double depth(const Vec3& p) const {
    const Vec3 d = p - base;
    const double z = dot(d, axis), rho = norm(d - axis * z);
    double m = kInf;
    for (const auto& e : edges) m = std::min(m, e(rho, z));
    return m;
  }
};

/// The reference S: -max(fwd, rev) (or a positive number when they do not overlap). The reverse
/// search runs over the ring's boundary patches within the azimuth window `window` (radians) of
/// the roller's centre (the ring points near the roller).
double reference(const Roller& r, const Ring& ring, double window = 0.6) {
  const double fwd = roller_max(r, [&](const Vec3& p) { return ring.depth(p); });
  const Frame f = frame_of(ring.axis);
  const Vec3 c = r.base + r.axis * (0.5 * r.h) - ring.base;
  const double phi = std::atan2(dot(c, f.y), dot(c, f.x));
  double rev = -kInf;
  for (const auto& patch : ring.patches) {
    const auto at = [&](double u, double v) {
      const auto [rho, z] = patch(v);
      return ring.base + ring.axis * z + (f.x * std::cos(u) + f.y * std::sin(u)) * rho;
    };
    rev = std::max(rev, dense_max(at, [&](const Vec3& q) { return roller_depth(r, q); }, phi - window, phi + window, 0, 1));
  }
  return -std::max(fwd, rev);
}

/// The reference sharpened by the solver's witnesses, each checked here: a roller point (point_a,
/// within rounding of the roller) attains its depth in the ring, a ring point (point_b, within
/// rounding of the ring) its depth in the roller. Either is a genuine lower bound of max(fwd, rev),
/// so S must equal the deepest of them and no sample may be deeper; the sampled search alone
/// stalls at 1e-8 on a few kinked maxima (a roller across the cup's side face).
double witnessed(double ref, const Roller& r, const Ring& ring, const TwoSidedRing& s) {
  double deepest = -ref;
  if (roller_depth(r, s.value.point_a) >= -1e-12) deepest = std::max(deepest, ring.depth(s.value.point_a));
  if (ring.depth(s.value.point_b) >= -1e-12) deepest = std::max(deepest, roller_depth(r, s.value.point_b));
  return -deepest;
}

Cylinder as_cylinder(const Roller& r) {
  Cylinder c;
  c.base = r.base, c.axis = r.axis, c.height = r.h, c.radius = r.r0;
  c.top_radius = r.r1 == r.r0 ? -1 : r.r1;
  return c;
}

Vec3 tilt(const Vec3& axis, double angle, double azimuth) {
  const Frame f = frame_of(axis);
  return axis * std::cos(angle) + (f.x * std::cos(azimuth) + f.y * std::sin(azimuth)) * std::sin(angle);
}

TEST(BearingRingTwoSided, BoreAgainstDenseReference) {
  // outer ring: raceway radius 50, outside 58, width 30, axis +z through the origin (z from -15)
  const double R = 50, out = 58, w = 30;
  Bore bore;
  bore.base = {0, 0, -15}, bore.axis = {0, 0, 1}, bore.radius = R, bore.width = w;
  Ring ring;
  ring.base = bore.base, ring.axis = bore.axis;
  ring.edges = {[&](double rho, double) { return rho - R; }, [&](double rho, double) { return out - rho; },
                [&](double, double z) { return z; }, [&](double, double z) { return w - z; }};
  ring.patches = {[&](double v) { return std::pair{R, v * w}; },             // raceway
                  [&](double v) { return std::pair{R + v * (out - R), 0.0}; },  // side faces
                  [&](double v) { return std::pair{R + v * (out - R), w}; }};
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> uni(0, 1);
  int certified = 0, searched = 0, overlapping = 0;
  double worst = 0;
  for (int i = 0; i < 40; ++i) {
    Roller r;
    r.r0 = r.r1 = 10, r.h = 20;
    const double az = 2 * kPi * uni(rng);
    const Vec3 radial{std::cos(az), std::sin(az), 0};
    // reach beyond the raceway 0..0.4 (some clear), tilts up to 4 degrees, axial positions from
    // inside the width to across a side face (i % 4 == 3)
    const double reach = -0.05 + 0.45 * uni(rng);
    r.axis = tilt({0, 0, 1}, 4 * kPi / 180 * uni(rng), 2 * kPi * uni(rng));
    const double zc = i % 4 == 3 ? (uni(rng) < 0.5 ? -1 : 1) * (15 + 2 * uni(rng)) : -3 + 6 * uni(rng);
    const Vec3 centre = radial * (R + reach - 10) + Vec3{0, 0, zc};
    r.base = centre - r.axis * 10;
    const TwoSidedRing s = two_sided_bore(as_cylinder(r), bore, out);
    const double ref = witnessed(reference(r, ring), r, ring, s);
    SCOPED_TRACE("pose " + std::to_string(i) + " fwd " + std::to_string(s.forward) + " rev " + std::to_string(s.reverse));
    ASSERT_TRUE(std::isfinite(s.value.distance));
    if (!(ref < 0)) {  // apart: positive (the clearance, or a lower bound of it)
      EXPECT_GT(s.value.distance, -1e-9);
      continue;
    }
    ++overlapping;
    (s.certified ? certified : searched)++;
    EXPECT_TRUE(s.exact);
    EXPECT_NEAR(s.value.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
    EXPECT_NEAR(norm(s.value.point_a - s.value.point_b), -s.value.distance, 1e-7);
    worst = std::max(worst, std::fabs(s.value.distance - ref));
  }
  // the hand case of test_assembly_outer_clip.cpp: a roller (radius 10, raceway radius 50.1) lying
  // along +x from x = 35 to 55 with its axis at z = -19, 4 beyond the side face z = -15
  {
    Bore b = bore;
    b.radius = 50.1;
    Ring g = ring;
    g.edges[0] = [](double rho, double) { return rho - 50.1; };
    g.patches = {[&](double v) { return std::pair{50.1, v * w}; },
                 [&](double v) { return std::pair{50.1 + v * (out - 50.1), 0.0}; },
                 [&](double v) { return std::pair{50.1 + v * (out - 50.1), w}; }};
    Roller r;
    r.base = {35, 0, -19}, r.axis = {1, 0, 0};
    const TwoSidedRing s = two_sided_bore(as_cylinder(r), b, out);
    const double ref = reference(r, g, 0.3);
    SCOPED_TRACE("lying roller fwd " + std::to_string(s.forward) + " rev " + std::to_string(s.reverse));
    EXPECT_TRUE(s.exact);
    EXPECT_FALSE(s.certified);
    EXPECT_NEAR(s.value.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
    EXPECT_NEAR(norm(s.value.point_a - s.value.point_b), -s.value.distance, 1e-7);
  }
  std::printf("[ bore ] %d overlapping (%d certified, %d searched), largest |S - reference| %.3g\n", overlapping,
              certified, searched, worst);
  EXPECT_GT(certified, 5);
  EXPECT_GT(searched, 3);
}


TEST(BearingRingTwoSided, CupAgainstDenseReference) {
  // cup: half-angle 20 degrees, radius 40 at z = 0, width 40, outside 75; tapered rollers (8, 9.5,
  // length 30) along its generator, pressed in by up to 0.3, tilted up to 3 degrees, some across a side face
  const double alpha = 20 * kPi / 180, k = std::tan(alpha), w = 40, out = 75;
  Cup cup;
  cup.base = {0, 0, 0}, cup.axis = {0, 0, 1}, cup.radius = 40, cup.top_radius = 40 + k * w, cup.width = w;
  const auto R = [&](double z) { return 40 + k * z; };
  Ring ring;
  ring.base = cup.base, ring.axis = cup.axis;
  ring.edges = {[&](double rho, double z) { return (rho - R(z)) / std::sqrt(1 + k * k); },
                [&](double rho, double) { return out - rho; }, [&](double, double z) { return z; },
                [&](double, double z) { return w - z; }};
  ring.patches = {[&](double v) { return std::pair{R(v * w), v * w}; },
                  [&](double v) { return std::pair{R(0) + v * (out - R(0)), 0.0}; },
                  [&](double v) { return std::pair{R(w) + v * (out - R(w)), w}; }};
  const double beta = std::atan(1.5 / 30), gamma = alpha - beta;
  std::mt19937_64 rng(2027);
  std::uniform_real_distribution<double> uni(0, 1);
  int certified = 0, searched = 0, overlapping = 0;
  double worst = 0;
  for (int i = 0; i < 32; ++i) {
    Roller r;
    r.r0 = 8, r.r1 = 9.5, r.h = 30;
    const double az = 2 * kPi * uni(rng), reach = -0.05 + 0.35 * uni(rng);
    const Vec3 radial{std::cos(az), std::sin(az), 0}, up{0, 0, 1};
    // the small end's outer rim point at z0, `reach` beyond the cone line along its normal
    const double z0 = i % 4 == 3 ? -2 + 4 * uni(rng) : 4 + 4 * uni(rng);
    const Vec3 rim = radial * R(z0) + up * z0 + (radial * std::cos(alpha) - up * std::sin(alpha)) * reach;
    const Vec3 axis = radial * std::sin(gamma) + up * std::cos(gamma);
    const Vec3 base = rim - (radial * std::cos(gamma) - up * std::sin(gamma)) * r.r0;
    // tilt about the mid point
    r.axis = tilt(axis, 3 * kPi / 180 * uni(rng), 2 * kPi * uni(rng));
    r.base = base + axis * (r.h / 2) - r.axis * (r.h / 2);
    const TwoSidedRing s = two_sided_cup(as_cylinder(r), cup, out);
    const double ref = witnessed(reference(r, ring), r, ring, s);
    SCOPED_TRACE("pose " + std::to_string(i) + " fwd " + std::to_string(s.forward) + " rev " + std::to_string(s.reverse));
    ASSERT_TRUE(std::isfinite(s.value.distance));
    if (!(ref < 0)) {
      EXPECT_GT(s.value.distance, -1e-9);
      continue;
    }
    ++overlapping;
    (s.certified ? certified : searched)++;
    EXPECT_TRUE(s.exact);
    EXPECT_NEAR(s.value.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
    EXPECT_NEAR(norm(s.value.point_a - s.value.point_b), -s.value.distance, 1e-7);
    worst = std::max(worst, std::fabs(s.value.distance - ref));
  }
  std::printf("[ cup ] %d overlapping (%d certified, %d searched), largest |S - reference| %.3g\n", overlapping,
              certified, searched, worst);
  EXPECT_GT(certified, 5);
  EXPECT_GT(searched, 3);
}

TEST(BearingRingTwoSided, RibAgainstDenseReference) {
  // rib block: face at z = 0 (normal +z), annulus 30..33, 4 thick; rollers (10, length 20) standing
  // on it with their axes 8 outside the annulus' inner edge, pressed in by up to 0.3, tilted up to 3
  // degrees. rho = 30 is where the rib joins the ring body: not a free surface (ring_two_sided.h)
  const double ri = 30, ro = 33, thick = 4;
  Rib rib;
  rib.center = {0, 0, 0}, rib.normal = {0, 0, 1}, rib.axis = {0, 0, 1}, rib.inner_radius = ri, rib.outer_radius = ro;
  Ring ring;
  ring.base = rib.center, ring.axis = rib.normal;  // z = l, the height above the face
  ring.edges = {[&](double rho, double l) { return rho >= ri ? -l : rho - ri; },
                [&](double rho, double) { return ro - rho; }, [&](double, double l) { return l + thick; }};
  ring.patches = {[&](double v) { return std::pair{ri + v * (ro - ri), 0.0}; },
                  [&](double v) { return std::pair{ro, -v * thick}; }, [&](double v) { return std::pair{ri, -v * thick}; },
                  [&](double v) { return std::pair{ri + v * (ro - ri), -thick}; }};
  std::mt19937_64 rng(127);
  std::uniform_real_distribution<double> uni(0, 1);
  int certified = 0, searched = 0, overlapping = 0;
  double worst = 0;
  for (int i = 0; i < 40; ++i) {
    Roller r;
    r.r0 = r.r1 = 10, r.h = 20;
    const double az = 2 * kPi * uni(rng), reach = -0.05 + 0.35 * uni(rng);
    const Vec3 radial{std::cos(az), std::sin(az), 0};
    r.axis = tilt({0, 0, 1}, 3 * kPi / 180 * uni(rng), 2 * kPi * uni(rng));
    const Vec3 centre = radial * (ri + 8) + Vec3{0, 0, 10 - reach};
    r.base = centre - r.axis * 10;
    // keep the lowest rim point `reach` below the face
    const double nu = r.axis.z, low = r.base.z - 10 * std::sqrt(std::max(0.0, 1 - nu * nu));
    r.base = r.base + Vec3{0, 0, -reach - low};
    const TwoSidedRing s = two_sided_rib(as_cylinder(r), rib, thick);
    const double ref = witnessed(reference(r, ring), r, ring, s);
    SCOPED_TRACE("pose " + std::to_string(i) + " fwd " + std::to_string(s.forward) + " rev " + std::to_string(s.reverse));
    ASSERT_TRUE(std::isfinite(s.value.distance));
    if (!(ref < 0)) {
      EXPECT_GT(s.value.distance, -1e-9);
      continue;
    }
    ++overlapping;
    (s.certified ? certified : searched)++;
    EXPECT_TRUE(s.exact);
    EXPECT_NEAR(s.value.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
    EXPECT_NEAR(norm(s.value.point_a - s.value.point_b), -s.value.distance, 1e-7);
    worst = std::max(worst, std::fabs(s.value.distance - ref));
  }
  std::printf("[ rib ] %d overlapping (%d certified, %d searched), largest |S - reference| %.3g\n", overlapping,
              certified, searched, worst);
  EXPECT_GT(overlapping, 20);
  EXPECT_GT(searched, 3);
}

}  // namespace
}  // namespace interfere::bearing
