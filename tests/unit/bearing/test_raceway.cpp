// The raceway solvers of a roller bearing (raceway.h, issue #27): roller in a cylindrical bore,
// roller end against a rib face, tapered roller against a cone frustum, roller in a conical cup.
// Every solver is compared with independent dense references written here (no call into the
// bearing module's distance code): direct maximisation over a fine angle grid refined by ternary
// search, a dual form (support functions over the ring's azimuth), a parametrisation of the roller's
// boundary by its own angle for the rib, and a grid plus compass search over the roller's boundary
// with an independent point-to-frustum signed distance for the cone. Hundreds of random poses
// (tilts, clearance, touching, overlap) and exact hand cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "interfere/bearing/raceway.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

struct Rng {
  std::mt19937_64 g;
  explicit Rng(unsigned long long seed) : g(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
};

// ---------- independent geometry ----------

Vec3 unit_perp(const Vec3& u) {
  const Vec3 a = std::fabs(u.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 p = a - u * dot(a, u);
  return p / norm(p);
}

/// u rotated by `tilt` toward the azimuth `az` (about an axis perpendicular to u).
Vec3 tilted(const Vec3& u, double tilt, double az) {
  const Vec3 p1 = unit_perp(u), p2 = cross(u, p1);
  const Vec3 w = p1 * std::cos(az) + p2 * std::sin(az);
  return u * std::cos(tilt) + w * std::sin(tilt);
}

double axis_dist(const Vec3& p, const Vec3& base, const Vec3& u) {
  const Vec3 v = p - base;
  const Vec3 r = v - u * dot(v, u);
  return std::sqrt(dot(r, r));
}

Cylinder roller(const Vec3& center, const Vec3& d, double r0, double r1, double h) {
  Cylinder c;
  c.axis = d / norm(d);
  c.base = center - c.axis * (0.5 * h);
  c.height = h, c.radius = r0, c.top_radius = r1 == r0 ? -1 : r1;
  return c;
}

struct Frame {
  Vec3 d, f1, f2;
};
Frame frame_of(const Cylinder& c) {
  const Vec3 f1 = unit_perp(c.axis);
  return {c.axis, f1, cross(c.axis, f1)};
}
double r_top(const Cylinder& c) { return c.top_radius < 0 ? c.radius : c.top_radius; }

/// Ternary search for the maximum of f on [a, b] (unimodal there), 100 steps ((2/3)^100 ~ 2e-18).
double ternary_max(const std::function<double(double)>& f, double a, double b, double* arg) {
  for (int i = 0; i < 100; ++i) {
    const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
    if (f(m1) < f(m2)) a = m1;
    else b = m2;
  }
  *arg = 0.5 * (a + b);
  return f(*arg);
}

/// max of a periodic f over the angle: n samples, the 6 best sampled local maxima refined.
double dense_max_angle(const std::function<double(double)>& f, int n, double* arg = nullptr) {
  std::vector<double> v(n);
  const double step = 2 * kPi / n;
  for (int i = 0; i < n; ++i) v[i] = f(i * step);
  std::vector<int> peaks;
  for (int i = 0; i < n; ++i)
    if (v[i] >= v[(i + n - 1) % n] && v[i] >= v[(i + 1) % n]) peaks.push_back(i);
  std::sort(peaks.begin(), peaks.end(), [&](int a, int b) { return v[a] > v[b]; });
  double best = -1e300, ba = 0;
  for (int i = 0; i < n; ++i)
    if (v[i] > best) best = v[i], ba = i * step;
  for (std::size_t k = 0; k < std::min<std::size_t>(peaks.size(), 6); ++k) {
    double x;
    const double val = ternary_max(f, (peaks[k] - 1) * step, (peaks[k] + 1) * step, &x);
    if (val > best) best = val, ba = x;
  }
  if (arg) *arg = ba;
  return best;
}

/// Where the roller's SOLID lies relative to the slab [0, w] of (base, u): -1 it misses the slab,
/// 1 it lies wholly inside, 0 it crosses a side face (those poses are checked against their own
/// reference in test_raceway_slab.cpp). The axial extent from the end circles' extreme points.
int slab_state(const Cylinder& c, const Vec3& base, const Vec3& u, double w) {
  const Vec3 pu = u - c.axis * dot(u, c.axis);
  const double spu = std::sqrt(dot(pu, pu));
  const double za = dot(c.base - base, u), zb = za + c.height * dot(c.axis, u);
  const double lo = std::min(za - c.radius * spu, zb - r_top(c) * spu);
  const double hi = std::max(za + c.radius * spu, zb + r_top(c) * spu);
  if (hi < 0 || lo > w) return -1;
  return lo >= 0 && hi <= w ? 1 : 0;
}

// ---------- references for the bore and the cup ----------

/// Direct: max over the two end circles of the clipped roller of gfun(point) (2048 angles + ternary).
double ref_rims_max(const Cylinder& c, double t0, double t1, const std::function<double(const Vec3&)>& gfun) {
  const Frame fr = frame_of(c);
  double best = -1e300;
  for (const double t : {t0, t1}) {
    const double r = c.radius + (r_top(c) - c.radius) * t / c.height;
    const Vec3 ctr = c.base + fr.d * t;
    best = std::max(best, dense_max_angle([&](double a) {
      return gfun(ctr + fr.f1 * (r * std::cos(a)) + fr.f2 * (r * std::sin(a)));
    }, 2048));
  }
  return best;
}

/// Dual: max over the ring azimuth psi of the support function of the clipped roller in the
/// direction w = n(psi) - k u (n radial), minus w.base: the max over the roller of rho - k z.
double ref_dual_max(const Cylinder& c, double t0, double t1, const Vec3& base, const Vec3& u, double k) {
  const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
  const auto support = [&](const Vec3& w) {
    double best = -1e300;
    for (const double t : {t0, t1}) {
      const double r = c.radius + (r_top(c) - c.radius) * t / c.height;
      const Vec3 ctr = c.base + c.axis * t;
      const Vec3 wp = w - c.axis * dot(w, c.axis);
      best = std::max(best, dot(ctr - base, w) + r * std::sqrt(dot(wp, wp)));
    }
    return best;
  };
  return dense_max_angle([&](double psi) { return support(e1 * std::cos(psi) + e2 * std::sin(psi) - u * k); }, 4096);
}

// ---------- bore ----------

TEST(BearingRaceway, BoreHandCases) {
  Bore bore{{0, 0, 0}, {0, 0, 1}, 40, 30};
  ASSERT_TRUE(validate_bore(bore).ok());
  // coaxial roller: s = R - r
  PairDistance pd = roller_bore_distance(roller({0, 0, 15}, {0, 0, 1}, 5, 5, 20), bore);
  EXPECT_NEAR(pd.distance, 35, 1e-12);
  EXPECT_EQ(pd.path, AnalyticPath::bore);
  // parallel, offset e: s = R - r - e
  for (const double e : {1.0, 30.0, 34.9, 35.0, 35.2}) {
    pd = roller_bore_distance(roller({e, 0, 15}, {0, 0, 1}, 5, 5, 20), bore);
    EXPECT_NEAR(pd.distance, 40 - 5 - e, 1e-12) << e;
    EXPECT_NEAR(axis_dist(pd.point_b, bore.base, bore.axis), 40, 1e-12);
  }
  // tilted by g in the xz plane about its centre (e, 0, 15): the farthest point is the +x rim point
  // of the top circle: x = e + (h/2) sin g + r cos g
  for (const double g : {0.5, 2.0, 5.0}) {
    const double e = 34;
    pd = roller_bore_distance(roller({e, 0, 15}, {std::sin(g * kDeg), 0, std::cos(g * kDeg)}, 5, 5, 20), bore);
    EXPECT_NEAR(pd.distance, 40 - (e + 10 * std::sin(g * kDeg) + 5 * std::cos(g * kDeg)), 1e-12) << g;
  }
  // tapered roller, parallel axes: the larger end circle decides
  pd = roller_bore_distance(roller({30, 0, 15}, {0, 0, 1}, 6, 4, 20), bore);
  EXPECT_NEAR(pd.distance, 4, 1e-12);
  // roller beside the ring (axis wholly outside the width): the axial gap
  pd = roller_bore_distance(roller({30, 0, 45}, {0, 0, 1}, 5, 5, 20), bore);
  EXPECT_EQ(pd.path, AnalyticPath::apart);
  EXPECT_NEAR(pd.distance, 5, 1e-12);
  // roller axis perpendicular to the bore axis (degenerate projection: a segment)
  pd = roller_bore_distance(roller({0, 0, 15}, {1, 0, 0}, 5, 5, 20), bore);
  EXPECT_NEAR(pd.distance, 40 - std::hypot(10.0, 5.0), 1e-12);
}

TEST(BearingRaceway, BoreRandomPosesAgainstDenseReferences) {
  Rng g(2701);
  int n = 0, overlap = 0, clear = 0, crossing = 0, touching = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 2 * kPi));
    Bore bore{{g.uniform(-5, 5), g.uniform(-5, 5), g.uniform(-5, 5)}, u, 40, 30};
    const double r0 = 5, r1 = i % 3 == 0 ? g.uniform(3.5, 5) : 5, h = 20;
    const double gap = i % 10 == 0 ? g.uniform(-1e-9, 1e-9) : g.uniform(-0.5, 0.5);
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az);
    const double zc = i % 7 == 0 ? g.uniform(-5, 35) : g.uniform(12, 18);  // some overhang the faces
    const Vec3 d = tilted(u, g.uniform(0, 5) * kDeg, g.uniform(0, 2 * kPi));
    Cylinder c = roller(bore.base + u * zc + radial * (40 - r0 - gap), d, r0, r1, h);
    if (i % 10 == 0)  // touching: move the roller radially by the computed clearance (twice)
      for (int k = 0; k < 2; ++k) c.base = c.base + radial * roller_bore_distance(c, bore).distance;
    const PairDistance pd = roller_bore_distance(c, bore);
    ASSERT_TRUE(std::isfinite(pd.distance));
    const int state = slab_state(c, bore.base, bore.axis, bore.width);
    if (state == -1) {
      EXPECT_EQ(pd.path, AnalyticPath::apart);
      EXPECT_GE(pd.distance, 0);
      continue;
    }
    if (state == 0) {  // across a side face: test_raceway_slab.cpp
      ++crossing;
      continue;
    }
    ++n;
    const double t0 = 0, t1 = h;
    const double direct = 40 - ref_rims_max(c, t0, t1, [&](const Vec3& p) { return axis_dist(p, bore.base, u); });
    const double dual = 40 - ref_dual_max(c, t0, t1, bore.base, u, 0);
    EXPECT_NEAR(direct, dual, 1e-9) << i;
    EXPECT_NEAR(pd.distance, direct, 1e-9 * std::max(1.0, std::fabs(direct))) << i;
    // witnesses: point_a on the clipped roller's end circles at the reported depth, point_b on the bore
    EXPECT_NEAR(40 - axis_dist(pd.point_a, bore.base, u), pd.distance, 1e-9) << i;
    EXPECT_NEAR(axis_dist(pd.point_b, bore.base, u), 40, 1e-9) << i;
    EXPECT_NEAR(norm(pd.point_b - pd.point_a), std::fabs(pd.distance), 1e-9) << i;
    overlap += pd.distance < -1e-6, clear += pd.distance > 1e-6, touching += std::fabs(pd.distance) < 1e-6;
  }
  EXPECT_GT(n, 330);
  EXPECT_GT(overlap, 50);
  EXPECT_GT(clear, 50);
  EXPECT_GT(crossing, 10);
  EXPECT_GT(touching, 5);
  // the interior of the roller never exceeds the end circles (the extreme-point argument)
  Rng h(5);
  for (int i = 0; i < 50; ++i) {
    const Bore bore{{0, 0, 0}, {0, 0, 1}, 40, 30};
    const Cylinder c = roller({34, 0, 15}, tilted({0, 0, 1}, h.uniform(0, 0.1), h.uniform(0, 7)), 5, 4, 20);
    const PairDistance pd = roller_bore_distance(c, bore);
    const Frame fr = frame_of(c);
    for (int k = 0; k < 200; ++k) {
      const double t = h.uniform(0, 20), a = h.uniform(0, 2 * kPi);
      const double r = (5 + (4 - 5) * t / 20) * std::sqrt(h.uniform(0, 1));
      const Vec3 p = c.base + fr.d * t + fr.f1 * (r * std::cos(a)) + fr.f2 * (r * std::sin(a));
      EXPECT_GE(40 - axis_dist(p, bore.base, bore.axis), pd.distance - 1e-12);
    }
  }
}

// ---------- cup ----------

TEST(BearingRaceway, CupReducesToBoreAndHandCase) {
  Rng g(77);
  for (int i = 0; i < 100; ++i) {
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 7));
    const Cup cup{{1, 2, 3}, u, 40, 40, 30};
    const Bore bore{{1, 2, 3}, u, 40, 30};
    const Vec3 e1 = unit_perp(u);
    const Cylinder c = roller(Vec3{1, 2, 3} + u * 15 + e1 * (35 + g.uniform(-0.5, 0.5)),
                              tilted(u, g.uniform(0, 4) * kDeg, g.uniform(0, 7)), 5, i % 2 ? 5 : 4, 20);
    EXPECT_NEAR(roller_cup_distance(c, cup).distance, roller_bore_distance(c, bore).distance, 1e-12) << i;
  }
  // roller lying along the cup's generator at distance delta inside it: s = delta
  const double R0 = 40, R1 = 34, w = 30;
  const Cup cup{{0, 0, 0}, {0, 0, 1}, R0, R1, w};
  const double L = std::hypot(R1 - R0, w);
  const Vec3 gdir{(R1 - R0) / L, 0, w / L}, nout{w / L, 0, -(R1 - R0) / L};  // generator, outward normal
  for (const double delta : {0.3, 0.0, -0.2}) {
    const Vec3 mid = Vec3{0.5 * (R0 + R1), 0, 0.5 * w} - nout * (5 + delta);
    const PairDistance pd = roller_cup_distance(roller(mid, gdir, 5, 5, 20), cup);
    EXPECT_NEAR(pd.distance, delta, 1e-12);
    EXPECT_EQ(pd.path, AnalyticPath::cup);
  }
}

TEST(BearingRaceway, CupRandomPosesAgainstDenseReferences) {
  Rng g(4242);
  int n = 0, overlap = 0, clear = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 2 * kPi));
    const double R0 = g.uniform(38, 42), R1 = R0 - g.uniform(2, 10), w = 30;
    const Cup cup{{g.uniform(-5, 5), g.uniform(-5, 5), g.uniform(-5, 5)}, u, R0, R1, w};
    const double k = (R1 - R0) / w;
    const double r0 = 5.5, r1 = g.uniform(4, 5.5), h = 20;
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az);
    const double zc = i % 8 == 0 ? g.uniform(-5, 35) : g.uniform(12, 18);
    const double L = std::hypot(R1 - R0, w);
    const Vec3 gen = (radial * (R1 - R0) + u * w) / L, nout = (radial * w - u * (R1 - R0)) / L;
    const double gap = i % 10 == 0 ? g.uniform(-1e-9, 1e-9) : g.uniform(-0.5, 0.5);
    const Vec3 on_cone = cup.base + u * zc + radial * (R0 + k * zc);
    const Vec3 d = tilted(gen, g.uniform(0, 4) * kDeg, g.uniform(0, 2 * kPi));
    const Cylinder c = roller(on_cone - nout * (0.5 * (r0 + r1) + gap), d, r0, r1, h);
    const PairDistance pd = roller_cup_distance(c, cup);
    ASSERT_TRUE(std::isfinite(pd.distance));
    if (slab_state(c, cup.base, u, w) != 1) continue;  // across a face: test_raceway_slab.cpp
    const double t0 = 0, t1 = h;
    ++n;
    const double cb = 1 / std::sqrt(1 + k * k);
    const auto gfun = [&](const Vec3& p) {
      return (axis_dist(p, cup.base, u) - R0 - k * dot(p - cup.base, u)) * cb;
    };
    const double direct = -ref_rims_max(c, t0, t1, gfun);
    const double dual = -(ref_dual_max(c, t0, t1, cup.base, u, k) - R0) * cb;
    EXPECT_NEAR(direct, dual, 1e-9) << i;
    EXPECT_NEAR(pd.distance, direct, 1e-9 * std::max(1.0, std::fabs(direct))) << i;
    EXPECT_NEAR(-gfun(pd.point_a), pd.distance, 1e-9) << i;
    // point_b lies on the cone surface
    EXPECT_NEAR(gfun(pd.point_b), 0, 1e-9) << i;
    overlap += pd.distance < -1e-6, clear += pd.distance > 1e-6;
  }
  EXPECT_GT(n, 250);
  EXPECT_GT(overlap, 40);
  EXPECT_GT(clear, 40);
}

// ---------- rib ----------

double oracle_frustum_sd(const Cylinder& c, const Vec3& p);  // below (cone-cone)

/// min of l over the roller's boundary points with ri <= rho <= ro, parametrised by the roller's own
/// angle: for each angle, the ray of each end disk and the lateral generator are segments along
/// which rho is convex and l linear; the feasible parts are found by ternary search of rho's minimum
/// and bisection of the crossings, and l is taken at their ends.
double ref_rib(const Cylinder& c, const Rib& rib, bool* any) {
  const Frame fr = frame_of(c);
  const double h = c.height, r0 = c.radius, r1 = r_top(c);
  const auto l = [&](const Vec3& p) { return dot(p - rib.center, rib.normal); };
  const auto rho = [&](const Vec3& p) { return axis_dist(p, rib.center, rib.axis); };
  const double ri = rib.inner_radius, ro = rib.outer_radius;
  const auto seg_min = [&](const Vec3& A, const Vec3& B) {
    const auto P = [&](double s) { return A + (B - A) * s; };
    double a = 0, b = 1;
    for (int i = 0; i < 100; ++i) {
      const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
      if (rho(P(m1)) > rho(P(m2))) a = m1;
      else b = m2;
    }
    const double sm = 0.5 * (a + b);
    const double rm = rho(P(sm));
    if (rm > ro) return 1e300;
    const auto crossing = [&](double from, double to, double level) {  // rho(from) <= level < rho(to)
      for (int i = 0; i < 100; ++i) {
        const double m = 0.5 * (from + to);
        if (rho(P(m)) <= level) from = m;
        else to = m;
      }
      return from;
    };
    const double s1 = rho(P(0)) <= ro ? 0.0 : crossing(sm, 0, ro);
    const double s2 = rho(P(1)) <= ro ? 1.0 : crossing(sm, 1, ro);
    std::vector<double> ends;
    if (rm >= ri) {
      ends = {s1, s2};
    } else {  // rho < ri on (s3, s4) around sm: outside
      const auto inner = [&](double from, double to) {  // rho(from) < ri <= rho(to)
        for (int i = 0; i < 100; ++i) {
          const double m = 0.5 * (from + to);
          if (rho(P(m)) < ri) from = m;
          else to = m;
        }
        return to;
      };
      if (rho(P(s1)) >= ri) ends.push_back(s1), ends.push_back(inner(sm, s1));
      if (rho(P(s2)) >= ri) ends.push_back(s2), ends.push_back(inner(sm, s2));
    }
    double best = 1e300;
    for (const double s : ends) {
      const double rr = rho(P(s));
      if (rr >= ri - 1e-9 && rr <= ro + 1e-9) best = std::min(best, l(P(s)));
    }
    return best;
  };
  // the three segment families (bottom-disk rays, top-disk rays, generators) separately: each is
  // continuous in the angle where finite (+inf where it misses the shell)
  double v = 1e300;
  for (int fam = 0; fam < 3; ++fam) {
    const auto F = [&](double a) {
      const Vec3 dir = fr.f1 * std::cos(a) + fr.f2 * std::sin(a);
      const Vec3 b = c.base, t = c.base + fr.d * h;
      if (fam == 0) return seg_min(b, b + dir * r0);
      if (fam == 1) return seg_min(t, t + dir * r1);
      return seg_min(b + dir * r0, t + dir * r1);
    };
    v = std::min(v, -dense_max_angle([&](double a) { return -F(a); }, 512));
    // the minimum can sit at the edge of the feasible angles (e.g. the end circle crossing
    // rho = ri): bisect every feasible/infeasible pair of neighbouring samples to the edge and take
    // F there (on the feasible side)
    constexpr int kN = 512;
    std::vector<double> fv(kN);
    for (int i = 0; i < kN; ++i) fv[i] = F(2 * kPi * i / kN);
    for (int i = 0; i < kN; ++i) {
      const int j = (i + 1) % kN;
      if ((fv[i] < 1e299) == (fv[j] < 1e299)) continue;
      double in = 2 * kPi * i / kN, out = 2 * kPi * (i + 1) / kN;
      if (!(fv[i] < 1e299)) std::swap(in, out);
      for (int k = 0; k < 100; ++k) {
        const double m = 0.5 * (in + out);
        if (F(m) < 1e299) in = m;
        else out = m;
      }
      v = std::min(v, F(in));
    }
  }
  *any = v < 1e299;
  return v;
}

TEST(BearingRaceway, RibHandCases) {
  const Rib rib{{0, 0, 0}, {0, 0, 1}, 30, 36, {0, 0, 1}};
  ASSERT_TRUE(validate_rib(rib).ok());
  // roller end parallel to the face, wholly over the annulus: s = gap
  PairDistance pd = roller_rib_distance(roller({33, 0, 10.25}, {0, 0, 1}, 2.5, 2.5, 20), rib);
  EXPECT_NEAR(pd.distance, 0.25, 1e-12);
  EXPECT_EQ(pd.path, AnalyticPath::rib);
  // tilted by g about the y axis so that its -x side dips, end circle over the annulus: the lowest
  // point of the bottom circle: 0.25 - r sin g... base centre at height 0.25
  for (const double gdeg : {0.5, 1.0, 3.0}) {
    const double gg = gdeg * kDeg;
    const Vec3 d{std::sin(gg), 0, std::cos(gg)};
    Cylinder c;
    c.base = {33, 0, 0.25}, c.axis = d, c.height = 20, c.radius = 2.5;
    pd = roller_rib_distance(c, rib);
    EXPECT_NEAR(pd.distance, 0.25 - 2.5 * std::sin(gg), 1e-12) << gdeg;
  }
  // partly outside: centre at rho 35 (the end disk reaches rho 37.5 > 36), tilted so that the +x side
  // dips (the end disk is the plane z = 0.25 - (x - 35) tan g): the deepest point over the annulus
  // is where the end disk crosses rho = ro at y = 0: height = 0.25 - (ro - 35) tan g
  for (const double gdeg : {0.5, 1.0, 3.0}) {
    const double gg = gdeg * kDeg;
    Cylinder c;
    c.base = {35, 0, 0.25}, c.axis = {std::sin(gg), 0, std::cos(gg)}, c.height = 20, c.radius = 2.5;
    pd = roller_rib_distance(c, rib);
    EXPECT_NEAR(pd.distance, 0.25 - 1.0 * std::tan(gg), 1e-11) << gdeg;
  }
  // a roller wholly beyond the outer radius: apart, a positive lower bound
  pd = roller_rib_distance(roller({45, 0, -5}, {0, 0, 1}, 2.5, 2.5, 20), rib);
  EXPECT_EQ(pd.path, AnalyticPath::apart);
  EXPECT_NEAR(pd.distance, 45 - 2.5 - 36, 1e-12);
}

TEST(BearingRaceway, RibRandomPosesAgainstDenseReference) {
  Rng g(999);
  int n = 0, overlap = 0, clear = 0, partial = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 2 * kPi));
    const bool outer = i % 2 == 1;  // an outer ring's rib (annulus above the rollers' axis)
    Rib rib;
    rib.center = {g.uniform(-5, 5), g.uniform(-5, 5), g.uniform(-5, 5)};
    rib.axis = u, rib.normal = i % 4 == 3 ? u * -1.0 : u;
    rib.inner_radius = outer ? 37 : 25, rib.outer_radius = outer ? 50 : 36;
    const double sign = dot(rib.normal, u);
    const double r0 = 5, r1 = i % 3 == 0 ? g.uniform(4, 5) : 5, h = 20;
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az);
    const double gap = i % 10 == 0 ? g.uniform(-1e-9, 1e-9) : g.uniform(-0.4, 0.4);
    const double pitch = i % 25 == 0 ? 60 : 34;  // a few wholly outside the annulus
    const Vec3 d = tilted(rib.normal, g.uniform(0, 4) * kDeg, g.uniform(0, 2 * kPi));
    Cylinder c;
    c.base = rib.center + radial * pitch + rib.normal * gap, c.axis = d, c.height = h, c.radius = r0;
    c.top_radius = r1 == r0 ? -1 : r1;
    (void)sign;
    const PairDistance pd = roller_rib_distance(c, rib);
    ASSERT_TRUE(std::isfinite(pd.distance));
    bool any = false;
    const double ref = ref_rib(c, rib, &any);
    if (!any) {
      EXPECT_EQ(pd.path, AnalyticPath::apart) << i;
      EXPECT_GT(pd.distance, 0) << i;
      continue;
    }
    ++n;
    EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i;
    // witnesses: point_a at height distance above the plane and over the annulus; point_b on the face
    EXPECT_NEAR(dot(pd.point_a - rib.center, rib.normal), pd.distance, 1e-9) << i;
    EXPECT_LE(oracle_frustum_sd(c, pd.point_a), 1e-9) << i;  // point_a in the roller
    EXPECT_NEAR(dot(pd.point_b - rib.center, rib.normal), 0, 1e-9) << i;
    const double rb = axis_dist(pd.point_b, rib.center, u);
    EXPECT_GE(rb, rib.inner_radius - 1e-9);
    EXPECT_LE(rb, rib.outer_radius + 1e-9);
    overlap += pd.distance < -1e-6, clear += pd.distance > 1e-6;
    // partly outside: the roller's deepest end-circle point is not over the annulus
    partial += std::fabs(pd.distance - (std::min(dot(c.base - rib.center, rib.normal),
                                                 dot(c.top_center() - rib.center, rib.normal)) -
                                        r0 * std::sqrt(std::max(0.0, 1 - dot(d, rib.normal) * dot(d, rib.normal))))) > 1e-6;
  }
  EXPECT_GT(n, 250);
  EXPECT_GT(overlap, 40);
  EXPECT_GT(clear, 40);
  EXPECT_GT(partial, 20);
}

// The assembly's rib poses (issue #27, speed), the ring far from the origin as in a 32-bearing
// scene, both end orientations, both face normals, small and large tilts with a tangential part:
//   lean > 0: the roller tilted outward, its lowest rim point beyond the rib's outer radius: the
//     minimum lies where the end disk crosses rho = ro, found in closed form with a KKT certificate
//     (raceway_rib.cpp, outer_shell_closed_form);
//   lean < 0: tilted inward, its lowest rim point often inside ri: the azimuth search of the ri
//     curve, the ro curve skipped when its closed-form lower bound is above (outer_curve_lower_bound).
void rib_tilt_cases(std::uint32_t seed, double lean, double pitch_lo, double pitch_hi, int* at_ro, int* at_ri) {
  Rng g(seed);
  for (int i = 0; i < 120; ++i) {
    const Vec3 u = tilted({1, 0, 0}, g.uniform(0, 0.2), g.uniform(0, 2 * kPi));
    Rib rib;
    rib.center = {9300 + g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)};
    rib.axis = u, rib.normal = i % 2 == 1 ? u * -1.0 : u;
    rib.inner_radius = 110, rib.outer_radius = 114;
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az), tangent = cross(u, radial);
    const double tilt = (i % 3 == 0 ? g.uniform(0.005, 0.1) : g.uniform(0.1, 3)) * kDeg;
    Vec3 d = rib.normal * std::cos(tilt) + radial * (lean * std::sin(tilt) * 0.9) +
             tangent * std::sin(tilt) * g.uniform(-0.4, 0.4);
    d = d / norm(d);
    Cylinder c;
    c.radius = 10, c.height = 38;
    const Vec3 near = rib.center + radial * g.uniform(pitch_lo, pitch_hi) + rib.normal * g.uniform(-0.5, 0.5);
    if (i % 4 < 2) {
      c.base = near, c.axis = d;  // the base faces the rib
    } else {
      c.base = near + d * c.height, c.axis = d * -1.0;  // the top faces it
    }
    const PairDistance pd = roller_rib_distance(c, rib);
    bool any = false;
    const double ref = ref_rib(c, rib, &any);
    ASSERT_TRUE(any) << i;
    EXPECT_EQ(pd.path, AnalyticPath::rib) << i;
    EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i;
    EXPECT_NEAR(dot(pd.point_a - rib.center, rib.normal), pd.distance, 1e-9) << i;
    EXPECT_LE(oracle_frustum_sd(c, pd.point_a), 1e-9) << i;
    EXPECT_NEAR(dot(pd.point_b - rib.center, rib.normal), 0, 1e-9) << i;
    const double rho = axis_dist(pd.point_a, rib.center, u);
    *at_ro += std::fabs(rho - rib.outer_radius) < 1e-9;
    *at_ri += std::fabs(rho - rib.inner_radius) < 1e-9;
  }
}

TEST(BearingRaceway, RibOutwardTiltAgainstDenseReference) {
  int at_ro = 0, at_ri = 0;
  rib_tilt_cases(2711, 1, 119.8, 122, &at_ro, &at_ri);
  EXPECT_GT(at_ro, 100);  // the minimum on rho = ro in (nearly) all of them
}

TEST(BearingRaceway, RibInwardTiltAgainstDenseReference) {
  int at_ro = 0, at_ri = 0;
  rib_tilt_cases(2712, -1, 119, 120.2, &at_ro, &at_ri);  // the inner rim point near ri
  EXPECT_GT(at_ri, 40);  // the lowest rim point inside ri: the minimum on rho = ri
}

// ---------- cone-cone ----------

double seg_dist2d(double px, double pz, double ax, double az, double bx, double bz) {
  const double dx = bx - ax, dz = bz - az;
  const double L2 = dx * dx + dz * dz;
  double t = L2 > 0 ? ((px - ax) * dx + (pz - az) * dz) / L2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - ax - t * dx, pz - az - t * dz);
}

/// Signed distance to a solid frustum: its meridian section, the symmetric trapezoid, as a convex
/// polygon: inside by edge half-planes, the distance to the nearest edge segment.
double oracle_frustum_sd(const Cylinder& c, const Vec3& p) {
  const Vec3 v = p - c.base;
  const double z = dot(v, c.axis);
  const Vec3 rv = v - c.axis * z;
  const double x = std::sqrt(dot(rv, rv));
  const double R0 = c.radius, R1 = r_top(c), h = c.height;
  const double vx[4] = {R0, R1, -R1, -R0}, vz[4] = {0, h, h, 0};
  bool inside = true;
  double dmin = 1e300;
  for (int k = 0; k < 4; ++k) {
    const int m = (k + 1) % 4;
    // counter-clockwise: (R0,0) -> (R1,h) -> (-R1,h) -> (-R0,0); inside is to the left
    const double cr = (vx[m] - vx[k]) * (z - vz[k]) - (vz[m] - vz[k]) * (x - vx[k]);
    if (cr < 0) inside = false;
    dmin = std::min(dmin, seg_dist2d(x, z, vx[k], vz[k], vx[m], vz[m]));
  }
  return inside ? -dmin : dmin;
}

/// min over the boundary of A of sd_B: grids over the lateral surface and both end disks, then a
/// compass search (periodic angle, clamped radial/axial parameter) from the best grid points.
double ref_cone(const Cylinder& a, const Cylinder& b) {
  const Frame fr = frame_of(a);
  const double h = a.height, r0 = a.radius, r1 = r_top(a);
  // surfaces: 0 lateral (t, phi), 1 bottom disk (s, phi), 2 top disk (s, phi); parameter in [0, 1]
  const auto point = [&](int surf, double q, double phi) {
    const Vec3 dir = fr.f1 * std::cos(phi) + fr.f2 * std::sin(phi);
    if (surf == 0) return a.base + fr.d * (q * h) + dir * (r0 + (r1 - r0) * q);
    if (surf == 1) return a.base + dir * (q * r0);
    return a.base + fr.d * h + dir * (q * r1);
  };
  const auto f = [&](int surf, double q, double phi) { return oracle_frustum_sd(b, point(surf, q, phi)); };
  struct Start {
    double v;
    int surf;
    double q, phi;
  };
  std::vector<Start> starts;
  constexpr int nq = 48, nphi = 256;
  for (int surf = 0; surf < 3; ++surf)
    for (int i = 0; i <= nq; ++i)
      for (int j = 0; j < nphi; ++j) {
        const double q = double(i) / nq, phi = 2 * kPi * j / nphi;
        starts.push_back({f(surf, q, phi), surf, q, phi});
      }
  std::partial_sort(starts.begin(), starts.begin() + 6, starts.end(), [](const Start& x, const Start& y) { return x.v < y.v; });
  double best = starts[0].v;
  for (int k = 0; k < 6; ++k) {
    Start s = starts[k];
    double sq = 1.0 / nq, sp = 2 * kPi / nphi;
    while (sq > 1e-15 || sp > 1e-15) {
      bool moved = false;
      const double cand[4][2] = {{s.q + sq, s.phi}, {s.q - sq, s.phi}, {s.q, s.phi + sp}, {s.q, s.phi - sp}};
      const double cand2[4][2] = {{s.q + sq, s.phi + sp}, {s.q - sq, s.phi - sp}, {s.q + sq, s.phi - sp}, {s.q - sq, s.phi + sp}};
      for (const auto* cs : {cand, cand2})
        for (int m = 0; m < 4; ++m) {
          const double q = std::clamp(cs[m][0], 0.0, 1.0);
          const double v = f(s.surf, q, cs[m][1]);
          if (v < s.v) s.v = v, s.q = q, s.phi = cs[m][1], moved = true;
        }
      if (!moved) sq *= 0.5, sp *= 0.5;
    }
    best = std::min(best, s.v);
  }
  return best;
}

TEST(BearingRaceway, FrustumSignedDistanceMatchesOracle) {
  Rng g(3);
  for (int i = 0; i < 2000; ++i) {
    const Cylinder c = roller({g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)},
                              tilted({0, 0, 1}, g.uniform(0, 3), g.uniform(0, 7)), g.uniform(1, 30), g.uniform(0, 30), g.uniform(1, 40));
    const Vec3 p{g.uniform(-40, 40), g.uniform(-40, 40), g.uniform(-40, 40)};
    EXPECT_NEAR(point_frustum_signed_distance(c, p), oracle_frustum_sd(c, p), 1e-12) << i;
    const Vec3 q = nearest_on_frustum_boundary(c, p);
    EXPECT_NEAR(oracle_frustum_sd(c, q), 0, 1e-12) << i;
    EXPECT_NEAR(norm(q - p), std::fabs(oracle_frustum_sd(c, p)), 1e-12) << i;
  }
}

TEST(BearingRaceway, ConeHandCases) {
  // B: cone frustum R0 = 30 at z = 0 to R1 = 25 at z = 30. A: a cylinder parallel to B's generator
  // in the meridian plane y = 0, at distance r + delta from the generator line: s = delta.
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
  const double L = std::hypot(5.0, 30.0);
  const Vec3 gdir{-5 / L, 0, 30 / L}, nout{30 / L, 0, 5 / L};
  for (const double delta : {0.5, 1e-3, 0.0, -0.1, -0.4}) {
    const Vec3 mid = Vec3{27.5, 0, 15} + nout * (4 + delta);
    const PairDistance pd = cone_pair_distance(roller(mid, gdir, 4, 4, 20), b);
    EXPECT_NEAR(pd.distance, delta, 1e-12) << delta;
    EXPECT_EQ(pd.path, AnalyticPath::cone) << delta;
  }
  // untapered B: the standard solver
  Cylinder bc = b;
  bc.top_radius = -1;
  const Cylinder a = roller({37, 0, 15}, {0, 0, 1}, 4, 4, 20);
  EXPECT_EQ(cone_pair_distance(a, bc).distance, cylinder_pair_distance(a, bc).distance);
  // A above B's top face, coaxial: s = the axial gap (the general path)
  const PairDistance pd = cone_pair_distance(roller({0, 0, 40.5}, {0, 0, 1}, 4, 3, 20), b);
  EXPECT_NEAR(pd.distance, 0.5, 1e-9);
}

TEST(BearingRaceway, ConeRandomPosesAgainstDenseReference) {
  Rng g(31337);
  int overlap = 0, clear = 0, certified = 0;
  constexpr int kPoses = 200;
  for (int i = 0; i < kPoses; ++i) {
    Cylinder b;  // the cone: a frustum of half angle ~6-15 degrees
    const Vec3 u = tilted({0, 0, 1}, g.uniform(0, 0.3), g.uniform(0, 2 * kPi));
    b.base = {g.uniform(-5, 5), g.uniform(-5, 5), g.uniform(-5, 5)}, b.axis = u, b.height = 30;
    b.radius = g.uniform(28, 32), b.top_radius = b.radius - g.uniform(3, 8);
    const double R0 = b.radius, R1 = b.top_radius, hb = b.height;
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 e1 = unit_perp(u), e2 = cross(u, e1);
    const Vec3 radial = e1 * std::cos(az) + e2 * std::sin(az);
    const double L = std::hypot(R1 - R0, hb);
    const Vec3 gen = (radial * (R1 - R0) + u * hb) / L, nout = (radial * hb - u * (R1 - R0)) / L;
    const double zc = g.uniform(11, 19);
    const Vec3 on_cone = b.base + u * zc + radial * (R0 + (R1 - R0) * zc / hb);
    const double r0 = 4.5, r1 = i % 4 == 0 ? 4.5 : g.uniform(3.5, 4.5), h = 18;
    const double gap = i % 10 == 0 ? g.uniform(-1e-9, 1e-9) : g.uniform(-0.4, 0.4);
    Cylinder a;
    if (i % 3 == 2) {
      // line contact: the roller's generator facing B parallel to B's generator at distance gap
      // (the roller narrows from r0 to r1: its axis is turned by its half angle alpha toward B, so
      // that its generator base + r0 m -> top + r1 m is parallel to gen; m = the roller's radial
      // direction toward B in the meridian plane)
      const double alpha = std::atan((r0 - r1) / h);
      const Vec3 d = gen * std::cos(alpha) - nout * std::sin(alpha);
      const Vec3 m = (nout * std::cos(alpha) + gen * std::sin(alpha)) * -1.0;
      a = roller(on_cone + nout * gap - m * (0.5 * (r0 + r1)), d, r0, r1, h);
    } else {
      const Vec3 d = tilted(gen, g.uniform(0, 4) * kDeg, g.uniform(0, 2 * kPi));
      a = roller(on_cone + nout * (0.5 * (r0 + r1) + gap), d, r0, r1, h);
    }
    const PairDistance pd = cone_pair_distance(a, b);
    if (i % 3 == 2) {
      EXPECT_NEAR(pd.distance, gap, 1e-12) << i;  // exact by construction
      EXPECT_EQ(pd.path, AnalyticPath::cone) << i;
    }
    ASSERT_TRUE(std::isfinite(pd.distance));
    const double ref = ref_cone(a, b);
    EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i << " path " << analytic_path_name(pd.path);
    EXPECT_LE(pd.distance, ref + 1e-12) << i;  // the reference is a value reached by a point of A
    EXPECT_NEAR(oracle_frustum_sd(b, pd.point_a), pd.distance, 1e-9) << i;
    EXPECT_NEAR(oracle_frustum_sd(b, pd.point_b), 0, 1e-9) << i;
    overlap += pd.distance < -1e-6, clear += pd.distance > 1e-6, certified += pd.path == AnalyticPath::cone;
  }
  EXPECT_GT(overlap, 30);
  EXPECT_GT(clear, 30);
  EXPECT_GT(certified, kPoses * 9 / 10);
}

TEST(BearingRaceway, ConeEndFaceAgainstDenseReference) {
  // a roller standing on the cone's top face (B's end face, not its cone surface, is nearest): the
  // lateral certificate cannot hold; the end-face dual or the nested golden-section path runs
  Rng g(11);
  Cylinder b;
  b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
  int general = 0;
  for (int i = 0; i < 12; ++i) {
    const double gap = g.uniform(-0.4, 0.4);
    const Vec3 d = tilted({0, 0, 1}, g.uniform(0, 3) * kDeg, g.uniform(0, 2 * kPi));
    const Cylinder a = roller(Vec3{g.uniform(-15, 15), g.uniform(-15, 15), 30 + gap + 9}, d, 4.5, 3.8, 18);
    const PairDistance pd = cone_pair_distance(a, b);
    const double ref = ref_cone(a, b);
    EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i;
    EXPECT_NEAR(oracle_frustum_sd(b, pd.point_a), pd.distance, 1e-9) << i;
    general += pd.path == AnalyticPath::general;
  }
  std::printf("cone on the top face: %d of 12 poses by the nested (general) path\n", general);
}

/// The nested golden-section minimum of the test's own frustum signed distance over the solid A
/// (cartesian parameters of A's disks: sd_B is convex and partial minimisation keeps convexity).
double ref_nested(const Cylinder& a, const Cylinder& b) {
  const Frame fr = frame_of(a);
  const auto golden = [](const std::function<double(double)>& f, double lo, double hi) {
    const double gr = (std::sqrt(5.0) - 1) / 2;
    double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo), f1 = f(x1), f2 = f(x2);
    double best = std::min({f(lo), f(hi), f1, f2});
    for (int i = 0; i < 70; ++i) {
      if (f1 <= f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - gr * (hi - lo), f1 = f(x1);
      else lo = x1, x1 = x2, f1 = f2, x2 = lo + gr * (hi - lo), f2 = f(x2);
      best = std::min({best, f1, f2});
    }
    return best;
  };
  const auto over_y = [&](double t, double x, double r) {
    const double ym = std::sqrt(std::max(0.0, r * r - x * x));
    return golden([&](double y) { return oracle_frustum_sd(b, a.base + fr.d * t + fr.f1 * x + fr.f2 * y); }, -ym, ym);
  };
  const auto over_x = [&](double t) {
    const double r = a.radius + (r_top(a) - a.radius) * t / a.height;
    return golden([&](double x) { return over_y(t, x, r); }, -r, r);
  };
  return golden(over_x, 0, a.height);
}

TEST(BearingRaceway, ConeReverseRingIntoRoller) {
  // s(cone ring, roller): the ring's deepest point inside the roller (the other side of the pair's
  // two-sided value); the ring is large, the roller's infinite cone reaches into it beyond the
  // roller's ends, so the lateral certificate fails: the end-face dual or the nested path runs
  Rng g(8080);
  int general = 0;
  for (int i = 0; i < 16; ++i) {
    Cylinder b;
    b.base = {0, 0, 0}, b.axis = {0, 0, 1}, b.height = 30, b.radius = 30, b.top_radius = 25;
    const double az = g.uniform(0, 2 * kPi);
    const Vec3 radial{std::cos(az), std::sin(az), 0}, u{0, 0, 1};
    const double L = std::hypot(5.0, 30.0);
    const Vec3 gen = (radial * -5.0 + u * 30.0) / L, nout = (radial * 30.0 + u * 5.0) / L;
    const double zc = g.uniform(12, 18);
    const Vec3 on_cone = u * zc + radial * (30 - 5 * zc / 30);
    const Cylinder a = roller(on_cone + nout * (4.1 + g.uniform(-0.4, 0.0)), tilted(gen, g.uniform(0, 3) * kDeg, g.uniform(0, 7)), 4.5, i % 2 ? 3.7 : 4.5, 18);
    const PairDistance pd = cone_pair_distance(b, a);  // an untapered roller too (i even)
    const double ref = ref_nested(b, a);
    EXPECT_NEAR(pd.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref))) << i << " " << analytic_path_name(pd.path);
    EXPECT_NEAR(oracle_frustum_sd(a, pd.point_a), pd.distance, 1e-9) << i;
    EXPECT_LE(oracle_frustum_sd(b, pd.point_a), 1e-9) << i;  // point_a in the ring
    general += pd.path == AnalyticPath::general;
  }
  std::printf("ring into roller: %d of 16 poses by the nested (general) path\n", general);
}

TEST(BearingRaceway, DegenerateConfigurationsAreFinite) {
  // exactly coaxial, parallel, perpendicular, pointed (top radius 0) rollers; rollers through the
  // ring axis; a roller end parallel to the rib face; coaxial cone pairs
  const Bore bore{{0, 0, 0}, {0, 0, 1}, 40, 30};
  const Cup cup{{0, 0, 0}, {0, 0, 1}, 40, 34, 30};
  const Rib rib{{0, 0, 0}, {0, 0, 1}, 30, 36, {0, 0, 1}};
  Cylinder cone;
  cone.base = {0, 0, 0}, cone.axis = {0, 0, 1}, cone.height = 30, cone.radius = 30, cone.top_radius = 25;
  const Vec3 dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, tilted({0, 0, 1}, 1e-300, 0), tilted({0, 0, 1}, 1e-9, 1)};
  const Vec3 centres[] = {{0, 0, 15}, {34, 0, 15}, {0, 0, 0}, {0, 0, 45}, {30, 0, 31}, {0, 34, 10.000001}};
  for (const Vec3& d : dirs)
    for (const Vec3& c : centres)
      for (const double r1 : {5.0, 0.0, 3.0}) {
        const Cylinder r = roller(c, d, 5, r1, 20);
        for (const PairDistance& pd : {roller_bore_distance(r, bore), roller_cup_distance(r, cup),
                                       roller_rib_distance(r, rib), cone_pair_distance(r, cone)}) {
          EXPECT_TRUE(std::isfinite(pd.distance)) << c.x << " " << c.y << " " << c.z << " " << r1;
          EXPECT_TRUE(std::isfinite(pd.point_a.x + pd.point_a.y + pd.point_a.z));
          EXPECT_TRUE(std::isfinite(pd.point_b.x + pd.point_b.y + pd.point_b.z));
        }
      }
  // a coaxial pointed roller in the bore: its base circle decides, s = R - r
  EXPECT_NEAR(roller_bore_distance(roller({0, 0, 15}, {0, 0, 1}, 5, 0, 20), bore).distance, 35, 1e-12);
}

TEST(BearingRaceway, ValidationNamesTheParameter) {
  Bore bore{{0, 0, 0}, {0, 0, 2}, 40, 30};
  Status s = validate_bore(bore, "bearing 1 outer ring");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("bearing 1 outer ring.axis"), std::string::npos) << s.error().message();
  bore.axis = {0, 0, 1}, bore.width = -1;
  EXPECT_FALSE(validate_bore(bore).ok());
  Cup cup{{0, 0, 0}, {0, 0, 1}, 40, 0, 30};
  EXPECT_FALSE(validate_cup(cup).ok());
  Rib rib{{0, 0, 0}, {1, 0, 0}, 30, 36, {0, 0, 1}};
  EXPECT_FALSE(validate_rib(rib).ok());
  rib.normal = {0, 0, 1}, rib.outer_radius = 20;
  s = validate_rib(rib);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("outer_radius"), std::string::npos);
  Cylinder c;
  c.height = 0;
  EXPECT_FALSE(validate_roller(c).ok());
  c.height = 1, c.radius = std::nan("");
  EXPECT_FALSE(validate_roller(c).ok());
  c.radius = 1;
  EXPECT_TRUE(validate_roller(c).ok());
}

}  // namespace
