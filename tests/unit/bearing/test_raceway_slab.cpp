// The roller against a ring whose material occupies only the ring's width (raceway.h: bore and
// cup, issue #27): the part of the roller that counts is the roller SOLID restricted to the slab
// 0 <= z <= width, not the roller whose AXIS lies in the slab. Poses where the axis lies wholly
// outside the width while the rim reaches in (a roller lying across the ring's side face, tilted
// rollers overhanging a face) used to come out as 0 ("contact", path apart) or with the wrong
// depth; the reference here is independent of the solver:
//   dual: max over K = roller /\ slab of (rho - k z) = max over the ring azimuth psi of the support
//   function of K in the direction e(psi) - k u, and that support function is, by Lagrange duality
//   for the two slab constraints, min over mu of h_roller(e - k u + mu u) + width * max(0, -mu)
//   (a convex 1-D minimisation; h_roller closed form over the two end circles);
//   sampling: points of the roller's boundary on a dense grid, kept where 0 <= z <= width, never
//   exceed that maximum, and their distance to the ring (a 2-D point-to-region distance in the
//   meridian plane) bounds the reported lower bound of a clear pair from above.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "interfere/bearing/raceway.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kPi = std::numbers::pi;

struct Rng {
  std::mt19937_64 g;
  explicit Rng(unsigned long long seed) : g(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
};

Vec3 unit_perp(const Vec3& u) {
  const Vec3 a = std::fabs(u.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 p = a - u * dot(a, u);
  return p / norm(p);
}

Vec3 tilted(const Vec3& u, double tilt, double az) {
  const Vec3 p1 = unit_perp(u), p2 = cross(u, p1);
  return u * std::cos(tilt) + (p1 * std::cos(az) + p2 * std::sin(az)) * std::sin(tilt);
}

Cylinder roller(const Vec3& center, const Vec3& d, double r0, double r1, double h) {
  Cylinder c;
  c.axis = d / norm(d);
  c.base = center - c.axis * (0.5 * h);
  c.height = h, c.radius = r0, c.top_radius = r1 == r0 ? -1 : r1;
  return c;
}
double r_top(const Cylinder& c) { return c.top_radius < 0 ? c.radius : c.top_radius; }

/// Support function of the roller (relative to `base`) in direction v: over its two end circles.
double support(const Cylinder& c, const Vec3& base, const Vec3& v) {
  const Vec3 vp = v - c.axis * dot(v, c.axis);
  const double s = std::sqrt(dot(vp, vp));
  return std::max(dot(c.base - base, v) + c.radius * s, dot(c.base + c.axis * c.height - base, v) + r_top(c) * s);
}

double ternary_min(const std::function<double(double)>& f, double a, double b) {
  for (int i = 0; i < 120; ++i) {
    const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
    if (f(m1) > f(m2)) a = m1;
    else b = m2;
  }
  return f(0.5 * (a + b));
}

/// The dual reference: max over roller /\ {0 <= z <= w} of rho - k z (K assumed non-empty).
double ref_solid_max(const Cylinder& c, const Vec3& base, const Vec3& u, double w, double k) {
  const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
  const auto hk = [&](double psi) {
    const Vec3 v = e1 * std::cos(psi) + e2 * std::sin(psi) - u * k;
    return ternary_min([&](double mu) { return support(c, base, v + u * mu) + w * std::max(0.0, -mu); }, -1e4, 1e4);
  };
  constexpr int kN = 360;
  std::vector<double> val(kN);
  for (int i = 0; i < kN; ++i) val[i] = hk(2 * kPi * i / kN);
  std::vector<int> order(kN);
  for (int i = 0; i < kN; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return val[a] > val[b]; });
  double best = val[order[0]];
  for (int j = 0; j < 4; ++j) {  // the support function of a convex set: unimodal near each peak
    double a = 2 * kPi * (order[j] - 1) / kN, b = 2 * kPi * (order[j] + 1) / kN;
    for (int i = 0; i < 100; ++i) {
      const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
      if (hk(m1) < hk(m2)) a = m1;
      else b = m2;
    }
    best = std::max(best, hk(0.5 * (a + b)));
  }
  return best;
}

struct Sample {
  double max_in_slab = -1e300;  ///< max of rho - k z over the sampled boundary points in the slab
  double min_ring_dist = 1e300;  ///< min over every sampled point of its distance to the ring
  bool any_in_slab = false;
};
/// Dense sampling of the roller's boundary (lateral grid and end disks); `ring_dist` a point's
/// distance to the ring material.
Sample sample(const Cylinder& c, const Vec3& base, const Vec3& u, double w, double k,
              const std::function<double(double rho, double z)>& ring_dist) {
  Sample s;
  const Vec3 f1 = unit_perp(c.axis), f2 = cross(c.axis, f1);
  const auto visit = [&](const Vec3& p) {
    const Vec3 v = p - base;
    const double z = dot(v, u);
    const Vec3 r = v - u * z;
    const double rho = std::sqrt(dot(r, r));
    s.min_ring_dist = std::min(s.min_ring_dist, ring_dist(rho, z));
    if (z >= 0 && z <= w) s.max_in_slab = std::max(s.max_in_slab, rho - k * z), s.any_in_slab = true;
  };
  constexpr int kA = 240, kT = 80, kR = 12;
  for (int i = 0; i < kA; ++i) {
    const double a = 2 * kPi * i / kA;
    const Vec3 dir = f1 * std::cos(a) + f2 * std::sin(a);
    for (int j = 0; j <= kT; ++j) {
      const double t = c.height * j / kT;
      visit(c.base + c.axis * t + dir * (c.radius + (r_top(c) - c.radius) * t / c.height));
    }
    for (int j = 0; j < kR; ++j) {
      const double f = static_cast<double>(j) / kR;
      visit(c.base + dir * (c.radius * f));
      visit(c.base + c.axis * c.height + dir * (r_top(c) * f));
    }
  }
  return s;
}

/// The roller's axial extent along u (end circles' extreme points).
std::pair<double, double> extent(const Cylinder& c, const Vec3& base, const Vec3& u) {
  const Vec3 pu = u - c.axis * dot(u, c.axis);
  const double spu = std::sqrt(dot(pu, pu));
  const double za = dot(c.base - base, u), zb = za + c.height * dot(c.axis, u);
  return {std::min(za - c.radius * spu, zb - r_top(c) * spu), std::max(za + c.radius * spu, zb + r_top(c) * spu)};
}

/// A random pose near one of the ring's side faces: the axis tilted up to 90 degrees from u, its
/// centre within a rim radius of the face (so that often the axis lies outside the width and the
/// rim inside), radially near the raceway.
Cylinder face_pose(Rng& g, const Vec3& base, const Vec3& u, double w, double R, double r0, double r1, double h,
                   int i) {
  const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
  const double az = g.uniform(0, 2 * kPi);
  const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az), tangent = cross(u, radial);
  const double tilt = i % 3 == 0 ? kPi / 2 : g.uniform(0.2, kPi / 2);
  const double turn = g.uniform(0, 2 * kPi);
  const Vec3 d = u * std::cos(tilt) + (radial * std::cos(turn) + tangent * std::sin(turn)) * std::sin(tilt);
  const double side = i % 2 == 0 ? -1 : 1;
  const double zc = side < 0 ? -g.uniform(0, 0.5 * h + r0) : w + g.uniform(0, 0.5 * h + r0);
  const double rc = R - g.uniform(-h, h);
  return roller(base + u * zc + radial * rc, d, r0, r1, h);
}

}  // namespace

TEST(BearingRacewaySlab, RollerAcrossTheSideFaceHandCase) {
  // A roller lying along x (perpendicular to the bore axis) with its axis 2 below the ring's side
  // face z = 0: the axis lies wholly outside the width, the rim reaches 3 into it. Its far end
  // (x = 48) is beyond the raceway radius 40: a clash. Within the slab (0 <= z <= 3), the end disk
  // x = 48 reaches y^2 = 25 - (z + 2)^2 <= 21, so max rho = sqrt(48^2 + 21) and s = 40 - that
  // (the old axis clip reported 0 here, path apart).
  const Bore bore{{0, 0, 0}, {0, 0, 1}, 40, 30};
  const Cylinder c = roller({38, 0, -2}, {1, 0, 0}, 5, 5, 20);
  const PairDistance pd = roller_bore_distance(c, bore);
  EXPECT_NEAR(pd.distance, 40 - std::sqrt(48.0 * 48 + 21), 1e-12);
  EXPECT_NE(pd.path, AnalyticPath::apart);
  EXPECT_NEAR(pd.point_a.x, 48, 1e-9);
  EXPECT_NEAR(pd.point_a.z, 0, 1e-9);
  // the same roller beside the face with its axis 6 below: the solid misses the slab by 1
  const PairDistance gap = roller_bore_distance(roller({38, 0, -6}, {1, 0, 0}, 5, 5, 20), bore);
  EXPECT_EQ(gap.path, AnalyticPath::apart);
  EXPECT_NEAR(gap.distance, 1, 1e-12);
  // the cup: the same geometry with R(z) = 40 - z / 10; at the face R = 40, and the maximum of
  // g = (rho - 40 + z / 10) / sqrt(1 + 1/100) over the slab part is on the end disk x = 48
  const Cup cup{{0, 0, 0}, {0, 0, 1}, 40, 37, 30};
  const PairDistance pc = roller_cup_distance(c, cup);
  const double kk = -0.1, cb = 1 / std::sqrt(1 + kk * kk);
  // on the end disk x = 48: maximise sqrt(48^2 + y^2) + 0.1 z with y^2 = 25 - (z + 2)^2, z in [0, 3]
  double best = -1e300;
  for (int i = 0; i <= 300000; ++i) {
    const double z = 3.0 * i / 300000;
    best = std::max(best, std::sqrt(48.0 * 48 + 25 - (z + 2) * (z + 2)) + 0.1 * z);
  }
  EXPECT_NEAR(pc.distance, -(best - 40) * cb, 1e-9);
  EXPECT_NE(pc.path, AnalyticPath::apart);
}

/// Random poses across the side faces, bore (k = 0) and cup (k != 0): the solver against the dual
/// reference (exact depth of a clash or contact; exact or a lower bound of a clearance) and the
/// sampling check. Counts make sure the interesting cases occur.
void run_random(bool cup_case, unsigned seed, int n) {
  Rng g(seed);
  int axis_out_rim_in = 0, clash = 0, clear = 0, exact_clear = 0, empty = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 2 * kPi));
    const Vec3 base{g.uniform(-5, 5), g.uniform(-5, 5), g.uniform(-5, 5)};
    const double w = 30, R0 = 40, R1 = cup_case ? R0 - g.uniform(1, 8) : R0;
    const double k = (R1 - R0) / w, cb = 1 / std::sqrt(1 + k * k);
    const double r0 = 5, r1 = i % 4 == 0 ? g.uniform(3, 5) : 5, h = 20;
    const Cylinder c = face_pose(g, base, u, w, R0, r0, r1, h, i);
    const PairDistance pd = cup_case ? roller_cup_distance(c, Cup{base, u, R0, R1, w})
                                     : roller_bore_distance(c, Bore{base, u, R0, w});
    ASSERT_TRUE(std::isfinite(pd.distance)) << i;
    const auto [zmin, zmax] = extent(c, base, u);
    const double za = dot(c.base - base, u), zb = za + c.height * dot(c.axis, u);
    const bool axis_out = std::max(za, zb) < 0 || std::min(za, zb) > w;
    if (zmax < 0 || zmin > w) {  // the solid misses the slab: a non-negative lower bound
      ++empty;
      EXPECT_EQ(pd.path, AnalyticPath::apart) << i;
      EXPECT_GE(pd.distance, 0) << i;
      EXPECT_LE(pd.distance, std::max(-zmax, zmin - w) + 1e-9) << i;
      continue;
    }
    axis_out_rim_in += axis_out;
    const double ref = -(ref_solid_max(c, base, u, w, k) - R0) * cb;  // s over the solid in the slab
    const auto ring_dist = [&](double rho, double z) {  // the meridian region x >= R0 + k z, 0 <= z <= w
      // nearest point of that convex 2-D region: dense search along its boundary (two rays and the
      // segment) is avoided; the half-plane distance clipped by the slab faces is exact enough for
      // an upper bound of the 3-D distance: take the distance to a few boundary points.
      double best = 1e300;
      for (int j = 0; j <= 400; ++j) {
        const double zz = w * j / 400;
        best = std::min(best, std::hypot(std::max(R0 + k * zz - rho, 0.0), z - zz));
      }
      return best;
    };
    const Sample s = sample(c, base, u, w, k, ring_dist);
    // the sampled points of K never exceed the reference maximum, and come close to it
    if (s.any_in_slab) {
      EXPECT_GE(-(s.max_in_slab - R0) * cb, ref - 1e-9) << i;
      EXPECT_LE(-(s.max_in_slab - R0) * cb, ref + 0.5) << i;
    }
    if (ref <= 0) {  // the solids overlap (or touch): the depth is exact
      ++clash;
      EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i << (axis_out ? " axis out" : "");
      EXPECT_NE(pd.path, AnalyticPath::apart) << i;
    } else {  // clear: never reported as touching or overlapping, never above the radial clearance
      ++clear;
      EXPECT_GE(pd.distance, 0) << i;
      EXPECT_LE(pd.distance, ref + 1e-9) << i;
      EXPECT_LE(pd.distance, s.min_ring_dist + 1e-9) << i;  // a lower bound of the distance
      if (pd.path != AnalyticPath::apart) {
        ++exact_clear;
        EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, ref)) << i;
        EXPECT_GT(pd.distance, 0) << i;
      }
    }
  }
  EXPECT_GT(axis_out_rim_in, n / 10);
  EXPECT_GT(clash, n / 10);
  EXPECT_GT(clear, n / 10);
  EXPECT_GT(exact_clear, 0);
  EXPECT_GT(empty, 0);
}

TEST(BearingRacewaySlab, BoreRandomPosesAcrossTheFacesAgainstTheDual) { run_random(false, 2727, 120); }

TEST(BearingRacewaySlab, CupRandomPosesAcrossTheFacesAgainstTheDual) { run_random(true, 2728, 120); }
