// roller_rib_distance's inner case in closed form (issue #27, speed; raceway_rib.cpp,
// inner_shell_closed_form): the roller's end facing the rib leans toward the ring axis, its lowest
// rim point inside the rib's inner radius ri; the minimum of l over K = roller ∩ {ri <= rho <= ro}
// is then where the rim crosses rho = ri, certified by arcs of the circle rho = ri. The reference is
// written here, in long double, without the bearing module (reference_rib below: the roller's own
// angle, not the ring's azimuth; every sampled minimum and every edge of the feasible angles refined,
// so both rim crossings are taken: the previous azimuth search settled on the higher of the two on 3
// of 94,716 rows of the 1,024-roller scene, by up to 7.8e-5). Poses: the ring far from the origin (as in the 32-bearing
// scene), both face normals, either end facing, tilts 1e-5..5 degrees leaning inward (and some
// outward and sideways), the inner rim point from 3 mm inside ri to 0.3 mm outside, gaps from
// overlapping to clear, two roller sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "interfere/bearing/raceway.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

using LD = long double;

struct P3 {
  LD x, y, z;
};
P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
P3 operator*(P3 a, LD s) { return {a.x * s, a.y * s, a.z * s}; }
LD dotl(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
P3 crossl(P3 a, P3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
P3 lift(const Vec3& v) { return {v.x, v.y, v.z}; }

/// min of l over the roller's boundary points with ri <= rho <= ro (a point of K), parametrised by
/// the roller's own angle t: for each t, the radius of each end disk and the lateral generator are
/// segments along which rho is convex and l linear, so the segment's part in the shell is at most two
/// intervals whose ends (rho's minimum by ternary search, the crossings of ro and ri by bisection)
/// carry the minimum of l. F(t), the least over the three segments, is then searched over t: 720
/// samples, every sampled local minimum refined by ternary search over its two neighbouring steps, and
/// every step whose ends are one feasible and one not bisected to the edge of the feasible angles
/// (where the rim crosses ri or ro: the inner case's minimum). +inf when no point lies in the shell.
LD reference_rib(const Cylinder& c, const Rib& rib) {
  const P3 base = lift(c.base), d = lift(c.axis), center = lift(rib.center), n = lift(rib.normal), u = lift(rib.axis);
  const P3 t0 = std::fabs(c.axis.x) < 0.6 ? P3{1, 0, 0} : P3{0, 1, 0};
  P3 f1 = crossl(d, t0);
  f1 = f1 * (1 / std::sqrt(dotl(f1, f1)));
  const P3 f2 = crossl(d, f1);
  const LD r = c.radius, h = c.height, ri = rib.inner_radius, ro = rib.outer_radius;
  const auto rho = [&](const P3& x) {
    const P3 v = x - center, w = v - u * dotl(v, u);
    return std::sqrt(dotl(w, w));
  };
  const auto l = [&](const P3& x) { return dotl(x - center, n); };
  const LD kInfL = INFINITY;
  const auto seg_min = [&](const P3& A, const P3& B) {
    const auto at = [&](LD s) { return A + (B - A) * s; };
    LD a = 0, b = 1;
    for (int i = 0; i < 80; ++i) {
      const LD m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
      if (rho(at(m1)) > rho(at(m2))) a = m1;
      else b = m2;
    }
    const LD sm = (a + b) / 2, rm = rho(at(sm));
    if (rm > ro) return kInfL;
    const auto edge = [&](LD in, LD out, LD level, bool below) {  // the crossing of rho = level
      for (int i = 0; i < 80; ++i) {
        const LD m = (in + out) / 2;
        ((rho(at(m)) <= level) == below ? in : out) = m;
      }
      return in;
    };
    const LD s1 = rho(at(0)) <= ro ? 0 : edge(sm, 0, ro, true), s2 = rho(at(1)) <= ro ? 1 : edge(sm, 1, ro, true);
    LD best = kInfL;
    const auto take = [&](LD s) {
      const LD rr = rho(at(s));
      if (rr >= ri && rr <= ro) best = std::min(best, l(at(s)));
    };
    if (rm >= ri) {
      take(s1), take(s2);
    } else {  // rho < ri around sm: the feasible parts end where rho reaches ri
      if (rho(at(s1)) >= ri) take(s1), take(edge(s1, sm, ri, false));
      if (rho(at(s2)) >= ri) take(s2), take(edge(s2, sm, ri, false));
    }
    return best;
  };
  LD best = kInfL;
  for (int fam = 0; fam < 3; ++fam) {
    const auto F = [&](LD t) {
      const P3 dir = f1 * std::cos(t) + f2 * std::sin(t);
      const P3 top = base + d * h;
      if (fam == 0) return seg_min(base, base + dir * r);
      if (fam == 1) return seg_min(top, top + dir * r);
      return seg_min(base + dir * r, top + dir * r);
    };
    constexpr int kN = 720;
    constexpr LD kStep = 2 * std::numbers::pi_v<LD> / kN;
    std::array<LD, kN> fv;
    for (int i = 0; i < kN; ++i) fv[i] = F(kStep * i), best = std::min(best, fv[i]);
    for (int i = 0; i < kN; ++i) {
      const int prev = (i + kN - 1) % kN, next = (i + 1) % kN;
      if (fv[i] < kInfL && fv[i] <= fv[prev] && fv[i] <= fv[next]) {  // a sampled local minimum
        LD a = kStep * (i - 1), b = kStep * (i + 1);
        for (int k = 0; k < 80; ++k) {
          const LD m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
          if (F(m1) > F(m2)) a = m1;
          else b = m2;
        }
        best = std::min(best, F((a + b) / 2));
      }
      if ((fv[i] < kInfL) != (fv[next] < kInfL)) {  // the edge of the feasible angles
        LD in = kStep * i, out = kStep * (i + 1);
        if (!(fv[i] < kInfL)) std::swap(in, out);
        for (int k = 0; k < 80; ++k) {
          const LD m = (in + out) / 2;
          (F(m) < kInfL ? in : out) = m;
        }
        best = std::min(best, F(in));
      }
    }
  }
  return best;
}

Vec3 unit_perp(const Vec3& u) {
  const Vec3 a = std::fabs(u.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 p = a - u * dot(a, u);
  return p / norm(p);
}

double rho_of(const Vec3& p, const Rib& rib) {
  const Vec3 v = p - rib.center;
  const Vec3 w = v - rib.axis * dot(v, rib.axis);
  return norm(w);
}

struct Counts {
  int poses = 0, at_ri = 0, overlapping = 0;
  double worst = 0;
};

void run_cases(unsigned seed, double radius, double length, double ri, double ro, int count, Counts* out) {
  std::mt19937_64 g(seed);
  const auto U = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); };
  constexpr double kDeg = std::numbers::pi / 180;
  for (int i = 0; i < count; ++i) {
    Rib rib;
    Vec3 u{1, 0, 0};
    if (i % 5 == 4) {  // a ring axis off the coordinate axes
      u = Vec3{1, U(-0.2, 0.2), U(-0.2, 0.2)};
      u = u / norm(u);
    }
    rib.axis = u;
    rib.normal = i % 2 == 1 ? u * -1.0 : u;
    rib.center = Vec3{9300 + U(-1, 1), U(-1, 1), U(-1, 1)};
    rib.inner_radius = ri, rib.outer_radius = ro;
    const double az = U(0, 2 * std::numbers::pi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az), tangent = cross(u, radial);
    const int band = i % 4;  // tilt ranges: tiny, small, the motion's, large
    const double tilt = (band == 0 ? U(1e-5, 1e-3) : band == 1 ? U(1e-3, 0.1) : band == 2 ? U(0.1, 3) : U(3, 5)) * kDeg;
    const double lean = i % 7 == 6 ? 1.0 : -1.0;  // mostly inward (the case under test), some outward
    const double side = i % 3 == 0 ? U(-1, 1) : U(-0.3, 0.3);
    Vec3 d = rib.normal * std::cos(tilt) + (radial * (lean * std::sqrt(std::max(0.0, 1 - side * side))) + tangent * side) * std::sin(tilt);
    d = d / norm(d);
    Cylinder c;
    c.radius = radius, c.height = length;
    // the end centre: its inner rim point from 3 mm inside ri to 0.3 mm outside; the gap to the face
    // from -0.3 (overlapping) to 0.5
    const Vec3 near = rib.center + radial * (ri + radius + U(-3, 0.3)) + rib.normal * U(-0.3, 0.5);
    if (i % 4 < 2) {
      c.base = near, c.axis = d;
    } else {
      c.base = near + d * length, c.axis = d * -1.0;
    }
    const PairDistance pd = roller_rib_distance(c, rib);
    const LD ref = reference_rib(c, rib);
    if (!(ref < INFINITY)) continue;  // no roller point over the annulus (the apart bound)
    ++out->poses;
    const double tol = 1e-9 * std::max(1.0, std::fabs(static_cast<double>(ref)));
    EXPECT_NEAR(pd.distance, static_cast<double>(ref), tol) << "pose " << i << " seed " << seed;
    out->worst = std::max(out->worst, std::fabs(pd.distance - static_cast<double>(ref)));
    // the witness: a roller point over the annulus at the reported height
    const double rho = rho_of(pd.point_a, rib);
    EXPECT_GE(rho, ri - 1e-9) << i;
    EXPECT_LE(rho, ro + 1e-9) << i;
    EXPECT_NEAR(dot(pd.point_a - rib.center, rib.normal), pd.distance, 1e-9) << i;
    const Vec3 v = pd.point_a - c.base;
    const double along = dot(v, c.axis), across = norm(v - c.axis * along);
    EXPECT_GE(along, -1e-9) << i;
    EXPECT_LE(along, length + 1e-9) << i;
    EXPECT_LE(across, radius + 1e-9) << i;
    out->at_ri += std::fabs(rho - ri) < 1e-9;
    out->overlapping += pd.distance < 0;
  }
}

TEST(BearingRaceway, RibInnerCaseClosedFormAgainstDenseReference) {
  Counts a, b;
  run_cases(27101, 10, 38, 110, 114, 96, &a);   // the 1,024-roller scene's rib
  run_cases(27102, 6, 20, 60, 61.5, 64, &b);    // a smaller bearing, a thin rib
  std::printf("[ rib inner ] %d + %d poses, %d + %d with the minimum on rho = ri, %d + %d overlapping, "
              "largest |solver - reference| %.3g\n",
              a.poses, b.poses, a.at_ri, b.at_ri, a.overlapping, b.overlapping, std::max(a.worst, b.worst));
  EXPECT_GT(a.poses, 80);
  EXPECT_GT(b.poses, 50);
  EXPECT_GT(a.at_ri, 40);  // the inner case is exercised
  EXPECT_GT(b.at_ri, 25);
  EXPECT_GT(a.overlapping + b.overlapping, 20);
}

// Three rib rows of the 1,024-roller scene (tilt 0.05 degrees, frame 2; the poses as solved, to the
// last bit) where the previous azimuth search returned the higher of the two rim crossings (by
// 8.6e-6, 7.8e-5 and 2.1e-5: clearances too large). Roller base, axis, radius, length; rib centre,
// normal, axis, ri, ro.
TEST(BearingRaceway, RibInnerCaseSceneRowsAgainstDenseReference) {
  const double rows[3][19] = {
      {-18.777860036577785, -77.983257779263496, -91.272255101487957, 0.99999999999732836, 1.5015753549630668e-06, 1.7574563150494571e-06, 10, 38, -20, -0.080000000000000002, 1.4695761589768237e-17, 1, 0, 0, 1, 0, 0, 110, 114},
      {5380.0183995282268, -78.020227017689493, -91.24111967094359, 0.99999999978205834, 1.3568405894390896e-05, 1.5867635782107709e-05, 10, 38, 5380, -0.080000000000000002, 1.4695761589768237e-17, 1, 0, 0, 1, 0, 0, 110, 114},
      {8381.9861845344112, -77.608369296093059, -91.591034345410847, 0.99999999998383005, -3.6763516488237298e-06, -4.3387182746819188e-06, 10, 38, 8420, -0.080000000000000002, 1.4695761589768237e-17, -1, -0, -0, 1, 0, 0, 110, 114},
  };
  for (const auto& q : rows) {
    Cylinder c;
    c.base = {q[0], q[1], q[2]}, c.axis = {q[3], q[4], q[5]}, c.radius = q[6], c.height = q[7];
    Rib rib;
    rib.center = {q[8], q[9], q[10]}, rib.normal = {q[11], q[12], q[13]}, rib.axis = {q[14], q[15], q[16]};
    rib.inner_radius = q[17], rib.outer_radius = q[18];
    const PairDistance pd = roller_rib_distance(c, rib);
    const LD ref = reference_rib(c, rib);
    EXPECT_NEAR(pd.distance, static_cast<double>(ref), 1e-11);
    EXPECT_NEAR(rho_of(pd.point_a, rib), q[17], 1e-9);
  }
}

}  // namespace
