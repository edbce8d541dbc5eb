// Adversarial review of issue #27's speed and exactness changes of 2026-11-30 (helper HR): poses
// where the new skips' certificates are nearly tight, far from the origin, tiny and huge, nearly and
// exactly parallel; the rows' determinism over threads and frame order; two scarred rollers' bracket
// [L, U*] (scarred_two_sided.h (3)) for crossing, coaxial end-to-end and far-away rollers against an
// independent oracle (scarred_reference.h: closest points on every triangle, ray parity).
//  * ReviewSpeedSkips.EndPathSkipKeepsCertifiedRows: analytic.cpp's cylinder_pair_distance no
//    longer solves the end-path ellipse when its point lies beyond B's slab for certain; wherever
//    min_axis_distance (unchanged, public) certifies, cylinder_pair_distance must return its value
//    and point bit for bit. Poses put A's end circle's extreme height within 1e-13 .. 1e-5 (of the
//    scale) of B's end plane, the skip's own boundary.
//  * ReviewSpeedSkips.TangentBoundKeepsTheReverse: intact_row_distance (tangent bound, margin 1e-13
//    of the scale) equals two_sided_cylinder_distance bit for bit for overlapping nearly parallel,
//    exactly parallel and antiparallel cylinders, translated to 1e4 and 1e7, scaled by 1e-3 and 1e3;
//    the bound is never above the reverse value the solver computes. (Rows whose forward value is
//    > 0 skip the reverse by design and agree to rounding only: part_pair.h.)
//  * ReviewSpeedSkips.AdversarialScenesAnyThreadsAndFrameOrder: scenes the benchmark does not hold
//    (bearings 9.8 m from the origin on oblique axes, raised scars, tilt 27.7 deg near Eq. (1)'s
//    limit, bearings scaled by 1e-3 far away): solve_pair, run_assembly on 1 and 2 threads and on
//    the frames reversed give the same rows bit for bit (the scarred solver keeps the previous
//    triangle between frames: a different history must not change a row).
//  * ReviewSpeedSkips.ScarredSolverHistoryAndHintOnVertexLines: the scarred solver's new evaluation
//    order (previous triangle, hinted cell, its partner across a vertex line; the holder rule) must
//    not change a result: B beside a scarred roller on its facets' vertex lines (exact ties of two
//    columns) and between, fresh, after other poses, with and without a hint, bit for bit.
//  * ReviewSpeedSkips.RibEuclidBoundNaNIsNeverClear: a rib row with a NaN in its roller or rib that
//    said clear or clearance becomes undecided (26b27f7), with and without a raise; no NaN bound.
//  * ReviewTwoScarredBracket.CrossingCoaxialAndFarRollers (cylindrical and tapered): a clash is certified by a point of one
//    surface deeper than the tolerance in the other's mesh (the oracle's sd there), a contact has no
//    vertex of either mesh deeper than the tolerance in the other, L <= U*, both orders bitwise.
//  * ReviewTwoScarredBracket.DenseAllScarredAssembly: an assembly whose motion presses scarred
//    neighbours together (37 rollers, 0.38 mm apart at rest): exact rows equal the brute-force
//    distance with no vertex inside the other roller, bracket clashes have a witness deeper than tol.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/scarred.h"
#include "unit/bearing/scarred_pair_parts.h"
#include "unit/bearing/scarred_reference.h"
#include "../../../src/bearing/rib_euclid_bound.h"
#include "unit/bearing/splitmix.h"

namespace interfere::bearing {
namespace {

Vec3 unit(const Vec3& v) { return v / norm(v); }

/// A unit vector across u (deterministic from the rng).
Vec3 across(const Vec3& u, test::SplitMix& rng) {
  const Vec3 q{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)};
  return unit(q - u * dot(q, u));
}

TEST(ReviewSpeedSkips, EndPathSkipKeepsCertifiedRows) {
  test::SplitMix rng{2711};
  long certified = 0, near_boundary = 0;
  for (int it = 0; it < 60000; ++it) {
    const double far = it % 3 == 0 ? 0 : it % 3 == 1 ? 1e4 : 1e7;
    const double s = it % 5 == 0 ? 1e-3 : it % 5 == 1 ? 1e3 : 1;
    const Vec3 u = unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)});
    const int mode = it % 4;
    const double ang = mode == 0 ? 0 : mode == 1 ? 1e-9 * rng.in(0, 1) : mode == 2 ? 1e-4 * rng.in(0, 1) : rng.in(0, 0.6);
    Vec3 d = unit(u * std::cos(ang) + across(u, rng) * std::sin(ang));
    if (it % 8 >= 4) d = d * -1.0;
    Cylinder b;
    b.base = Vec3{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)} * far;
    b.axis = u, b.height = s * rng.in(1, 50), b.radius = s * rng.in(0.5, 20);
    Cylinder a;
    a.axis = d, a.height = s * rng.in(1, 50), a.radius = s * rng.in(0.5, 20);
    // A's end circle beside B, its extreme height about B's end plane: centre height hh + reach + e
    const double reach = a.radius * norm(cross(d, u));  // r |sin| (the circle's extent along u)
    const double scale = 1 + far + a.height + a.radius + b.height + b.radius;
    const double e = (rng.in(0, 1) < 0.5 ? -1 : 1) * scale * std::pow(10.0, rng.in(-13, -5));
    const bool top = rng.in(0, 1) < 0.5;
    const Vec3 side = across(u, rng) * ((a.radius + b.radius) * rng.in(0.3, 1.5));
    const Vec3 endc = b.center() + u * ((top ? 1 : -1) * (0.5 * b.height + reach + e)) + side;
    // the end whose centre is endc: A extends away from B's slab or into it
    a.base = rng.in(0, 1) < 0.5 ? endc : endc - a.axis * a.height;
    const Vec3 bc = b.center();
    const RadialMin rm = min_axis_distance(a, bc, b.axis);
    const double z = dot(rm.point - bc, b.axis), dr = rm.rho - b.radius, dz = std::fabs(z) - 0.5 * b.height;
    if (std::fabs(dz) < 1e-6 * scale) ++near_boundary;
    if (!(rm.rho > 0 && (dr >= 0 ? dz <= 0 : dz <= dr))) continue;
    ++certified;
    const PairDistance pd = cylinder_pair_distance(a, b);
    ASSERT_EQ(pd.distance, dr) << "it " << it;
    ASSERT_EQ(pd.point_a.x, rm.point.x) << "it " << it;
    ASSERT_EQ(pd.point_a.y, rm.point.y) << "it " << it;
    ASSERT_EQ(pd.point_a.z, rm.point.z) << "it " << it;
  }
  std::printf("[ end-path skip ] %ld certified rows identical (%ld minimisers within 1e-6 of the scale of B's end plane)\n",
              certified, near_boundary);
  EXPECT_GT(certified, 1000);
  EXPECT_GT(near_boundary, 1000);
}

TEST(ReviewSpeedSkips, TangentBoundKeepsTheReverse) {
  test::SplitMix rng{977};
  long skipped = 0, total = 0, apart = 0;
  double tightest = 1e300;  // smallest (reverse - bound) / margin among the skips
  for (int it = 0; it < 20000; ++it) {
    const double far = it % 3 == 0 ? 0 : it % 3 == 1 ? 1e4 : 1e7;
    const double s = it % 5 == 0 ? 1e-3 : it % 5 == 1 ? 1e3 : 1;
    const Vec3 u = unit({rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)});
    const int mode = it % 4;
    const double ang = mode == 0 ? 0 : mode == 1 ? 1e-9 * rng.in(0, 1) : mode == 2 ? 1e-5 * rng.in(0, 1) : 0.02 * rng.in(0, 1);
    Vec3 d = unit(u * std::cos(ang) + across(u, rng) * std::sin(ang));
    if (it % 8 >= 4) d = d * -1.0;
    Cylinder a, b;
    a.radius = s * 10, b.radius = s * (it % 2 ? 10 : rng.in(5, 15));
    a.height = s * 38, b.height = s * (it % 2 ? 38 : rng.in(10, 60));
    b.axis = u, a.axis = d;
    b.base = Vec3{rng.in(-1, 1), rng.in(-1, 1), rng.in(-1, 1)} * far;
    // overlapping side by side (radial overlap from 1e-9 to 1 of the radius), A's middle near B's
    const double overlap = (a.radius + b.radius) * std::pow(10.0, rng.in(-9, -0.3));
    const Vec3 mid = b.center() + across(u, rng) * (a.radius + b.radius - overlap) + u * (s * rng.in(-5, 5));
    a.base = mid - a.axis * (0.5 * a.height);
    const PairDistance row = intact_row_distance(a, b), ref = two_sided_cylinder_distance(a, b);
    const PairDistance fwd = cylinder_pair_distance(a, b);
    ++total;
    if (fwd.distance > 0) {
      // (apart by the forward value: the reverse is skipped by design, the value then equal to
      // rounding only, part_pair.h; at 1e7 with radii of 1e-2 the two directions' values differ in
      // sign: 3.7e-10 and -2.3e-10, far inside the touch tolerance 2^-36 of the scale)
      const double scale = 1 + far + a.height + b.height + a.radius + b.radius;
      ASSERT_LE(std::fabs(row.distance - ref.distance), 1e-15 * scale) << "it " << it;
      ++apart;
      continue;
    }
    ASSERT_EQ(row.distance, ref.distance) << "it " << it;
    ASSERT_EQ(row.point_a.x, ref.point_a.x) << "it " << it;
    ASSERT_EQ(row.point_b.z, ref.point_b.z) << "it " << it;
    ASSERT_EQ(row.path, ref.path) << "it " << it;
    const double bound = intact_reverse_tangent_bound(a, b, fwd.distance);
    if (bound >= fwd.distance) {
      ++skipped;
      const double rev = cylinder_pair_distance(b, a).distance;
      ASSERT_LE(bound, rev) << "it " << it;
      // the margin's share left: (rev - bound) / margin, margin = 1e-13 of cylinder_two_sided.cpp's
      // scale (1 means the envelope before the margin is at the reverse value)
      const double scale = 1 + std::max({std::fabs(a.base.x), std::fabs(a.base.y), std::fabs(a.base.z), std::fabs(b.base.x),
                                         std::fabs(b.base.y), std::fabs(b.base.z)}) +
                           a.height + b.height + a.radius + b.radius;
      tightest = std::min(tightest, (rev - bound) / (1e-13 * scale));
    }
  }
  std::printf("[ tangent bound ] %ld rows (%ld apart by rounding), %ld skipped by the tangent bound, least (reverse - bound) / margin %.4g\n",
              total, apart, skipped, tightest);
  EXPECT_GT(skipped, 1000);
  // measured 0.997: the envelope's rounding (a few ulps of the scale) uses < 1 % of the margin
  EXPECT_GT(tightest, 0.5);
}

TEST(ReviewSpeedSkips, ScarredSolverHistoryAndHintOnVertexLines) {
  // a26ed4c/8d47157 (scarred.cpp): the leaves evaluated first (the previous triangle's, the hinted
  // cell's and its partner across the vertex line the best point lies on) and the holder rule
  // change the order of the descent; ties keep the lowest entry, so the result must not depend on
  // it. An intact cylinder B parallel beside a scarred roller, in the direction of a vertex line of
  // its facets (two columns tie exactly there) and between two, on the scar's side and away from
  // it, apart and overlapping, rest and 9.8 m away: the same distance, point and triangle, fresh,
  // after other poses (another previous triangle), with a hint and without.
  for (const bool raised : {false, true}) {
    const Assembly as = test::scarred_assembly(test::kCylindricalBearing, raised);
    std::size_t ia = 0;
    while (as.parts[ia].kind != PartKind::roller || !as.parts[ia].scarred) ++ia;
    const AssemblyPart& part = as.parts[ia];
    const Roller& roller = *part.roller;
    const int n = roller.n();
    const double R = as.spec.bearings[0].rollers.radius, h = as.spec.bearings[0].rollers.length;
    int compared = 0;
    for (const bool far : {false, true}) {
      Transform pose = part.rest;
      if (far) pose.t = pose.t + Vec3{9800.0, 7000.5, -6000.25};
      for (int k = 0; k < 16; ++k) {
        const double angle = 2 * std::numbers::pi * ((k / 2) * (n / 8) + (k % 2 ? 0.5 : 0.0)) / n;  // vertex lines and between
        for (const double gap : {0.3, 0.0, -0.05}) {
          Cylinder b;
          b.radius = 7, b.height = 30;
          b.axis = pose.rotate({0, 0, 1});
          b.base = pose.apply({(R + 7 + gap) * std::cos(angle), (R + 7 + gap) * std::sin(angle), 0.5 * (h - 30)});
          const Vec3 hint = pose.apply({R * std::cos(angle), R * std::sin(angle), 0.5 * h});
          ScarredSolver fresh(&roller, part.tree.get());
          const MeshPairResult ref = fresh.solve(pose, b);
          ScarredSolver warm(&roller, part.tree.get());
          std::vector<MeshPairResult> got;
          got.push_back(ScarredSolver(&roller, part.tree.get()).solve(pose, b, hint));
          for (int other = 0; other < 4; ++other) {  // another pose first: its triangle is the previous one
            Cylinder c = b;
            const double a2 = angle + std::numbers::pi * (other + 1) / 2.5;
            c.base = pose.apply({(R + 7.2) * std::cos(a2), (R + 7.2) * std::sin(a2), 0.5 * (h - 30) + other});
            warm.solve(pose, c);
            got.push_back(warm.solve(pose, b));
            warm.solve(pose, c);
            got.push_back(warm.solve(pose, b, hint));
          }
          got.push_back(warm.solve(pose, b));  // the same pose twice
          for (const MeshPairResult& g : got) {
            ++compared;
            ASSERT_EQ(g.distance, ref.distance) << "k " << k << " gap " << gap << (far ? " far" : "");
            ASSERT_EQ(g.triangle, ref.triangle) << "k " << k << " gap " << gap << (far ? " far" : "");
            ASSERT_EQ(g.point_a.x, ref.point_a.x);
            ASSERT_EQ(g.point_a.y, ref.point_a.y);
            ASSERT_EQ(g.point_a.z, ref.point_a.z);
            ASSERT_EQ(g.point_b.x, ref.point_b.x);
          }
        }
      }
    }
    std::printf("[ scarred solver ] %s: %d solves with other histories and hints identical to the fresh ones\n",
                raised ? "raised" : "inward", compared);
  }
}

TEST(ReviewSpeedSkips, RibEuclidBoundNaNIsNeverClear) {
  // 26b27f7: a NaN lower bound is taken as -inf (distance_verdict reads NaN as clear). A rib row
  // whose roller or rib carries a NaN (a degenerate pose) and whose value said clear or clearance
  // must come out undecided, never clear; the bound itself is never NaN.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Rib face;
  face.center = {0, 0, 0}, face.axis = {0, 0, 1}, face.normal = {0, 0, 1};
  face.inner_radius = 110, face.outer_radius = 114;
  Cylinder roller;
  roller.base = {120.05, 0, 1}, roller.axis = {0, 0, 1}, roller.radius = 10, roller.height = 38;
  const double clearance = 0.05, tol = 1e-9;
  for (int which = 0; which < 6; ++which) {
    Cylinder c = roller;
    Rib f = face;
    if (which == 0) c.base.x = nan;
    if (which == 1) c.axis = {nan, 0, 1};
    if (which == 2) c.radius = nan;
    if (which == 3) f.center.z = nan;
    if (which == 4) f.normal = {0, nan, 1};
    if (which == 5) f.outer_radius = nan;
    for (int level = 0; level < 3; ++level) {
      const double lower = detail::rib_euclid_lower(c, f, 5, level);
      EXPECT_FALSE(std::isnan(lower)) << "case " << which << " level " << level;
    }
    for (const Verdict v : {Verdict::clear, Verdict::clearance}) {
      AssemblyPairResult row;
      row.distance = v == Verdict::clear ? 1.0 : 0.01, row.verdict = v, row.exact = true, row.two_sided = false;
      row.path = AnalyticPath::side;
      detail::rib_euclid_row(row, c, 0, f, 5, clearance, tol, true);
      EXPECT_EQ(row.verdict, Verdict::undecided) << "case " << which;
      AssemblyPairResult raised = row;
      raised.verdict = v;
      detail::rib_euclid_row(raised, c, 0.03, f, 5, clearance, tol, false);
      EXPECT_EQ(raised.verdict, Verdict::undecided) << "case " << which << " (grown by a raise)";
    }
  }
  // (and the same row without a NaN keeps its clear verdict: 1 mm over the face, E = 1)
  AssemblyPairResult row;
  row.distance = 1.0, row.verdict = Verdict::clear, row.exact = true, row.two_sided = false;
  detail::rib_euclid_row(row, roller, 0, face, 5, clearance, tol, true);
  EXPECT_EQ(row.verdict, Verdict::clear);
}

// ---- scenes ----

std::string cylindrical(int i, const std::string& position, const std::string& axis, double s) {
  char b[900];
  std::snprintf(b, sizeof b,
                R"({"id": "b%d", "type": "cylindrical", "position": %s, "axis": %s,
      "inner_ring": {"bore_radius": %.17g, "raceway_radius": %.17g, "width": %.17g, "rib": {"height": %.17g, "width": %.17g}},
      "outer_ring": {"raceway_radius": %.17g, "outer_radius": %.17g, "width": %.17g},
      "rollers": {"count": 32, "radius": %.17g, "length": %.17g, "pitch_radius": %.17g},
      "cage": {"pocket_clearance": %.17g, "web_thickness": %.17g}})",
                i, position.c_str(), axis.c_str(), 95 * s, 110 * s, 50 * s, 4 * s, 5 * s, 130.1 * s, 145 * s, 50 * s, 10 * s,
                38 * s, 120.05 * s, 0.3 * s, 8 * s);
  return b;
}

std::string scene(const std::string& bearings, double s, double tilt, double load, bool raised) {
  char m[600];
  std::snprintf(m, sizeof m,
                R"({"seed": 9, "clearance": %.17g, "motion": {"max_tilt_deg": %.17g, "load": {"displacement": %.17g},
      "pocket_play": 2, "axial_play": 2}, "scar": {"fraction": 0.5, "angle_width_deg": 350, "depth": %.17g, "seed": 5%s},
      "bearings": [)",
                0.05 * s, tilt, load * s, 0.05 * s, raised ? R"(, "raised": true)" : "");
  return m + bearings + "]}";
}

bool same(const AssemblyPairResult& x, const AssemblyPairResult& y) {
  return std::memcmp(&x.distance, &y.distance, sizeof(double)) == 0 && x.point_a.x == y.point_a.x &&
         x.point_a.y == y.point_a.y && x.point_a.z == y.point_a.z && x.point_b.x == y.point_b.x &&
         x.point_b.y == y.point_b.y && x.point_b.z == y.point_b.z && x.solver == y.solver && x.path == y.path &&
         x.scar == y.scar && x.exact == y.exact && x.two_sided == y.two_sided && x.verdict == y.verdict &&
         x.scar_part == y.scar_part;
}

TEST(ReviewSpeedSkips, AdversarialScenesAnyThreadsAndFrameOrder) {
  struct Case {
    const char* name;
    std::string text;
  };
  const std::string far = cylindrical(0, "[9800, 7000.5, -6000.25]", "[0.6, 0.8, 1e-7]", 1) + "," +
                          cylindrical(1, "[9500, 7000.5, -6000.25]", "[1, 1e-9, 0]", 1);
  const std::string tilted = cylindrical(0, "[5000, 0, 0]", "[1, 0, 0]", 1) + "," + cylindrical(1, "[5300, 0, 0]", "[1, 0, 0]", 1);
  const std::string tiny = cylindrical(0, "[9000, -9000, 5000]", "[1, 0, 0]", 1e-3) + "," +
                           cylindrical(1, "[9000.3, -9000, 5000]", "[1, 0, 0]", 1e-3);
  const Case cases[] = {{"far oblique raised, tilt 3, load 0.6", scene(far, 1, 3, 0.6, true)},
                        {"tilt 27.7 (Eq. (1) limit 27.76), load 0.6, raised", scene(tilted, 1, 27.7, 0.6, true)},
                        {"scaled 1e-3, 12.7 m away, tilt 1", scene(tiny, 1e-3, 1, 0.3, false)}};
  constexpr int kFrames = 3;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Expected<AssemblySpec> spec = parse_assembly(c.text, "review.json");
    ASSERT_TRUE(spec) << spec.error().message();
    const Expected<Assembly> as = build_assembly(*spec);
    ASSERT_TRUE(as) << as.error().message();
    const AssemblyMotion motion = generate_motion(*as, kFrames, spec->seed);
    const std::size_t np = as->pairs.size();
    std::vector<AssemblyPairResult> single(kFrames * np);
    for (int f = 0; f < kFrames; ++f)
      for (std::size_t p = 0; p < np; ++p) single[f * np + p] = solve_pair(*as, as->pairs[p], motion.poses[f], spec->clearance);
    AssemblyMotion reversed = motion;
    std::reverse(reversed.poses.begin(), reversed.poses.end());
    int scarred_rows = 0;
    for (const int threads : {1, 2}) {
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
      const AssemblyResult res = run_assembly(*as, motion), rev = run_assembly(*as, reversed);
      ASSERT_EQ(res.rows.size(), single.size());
      ASSERT_EQ(rev.rows.size(), single.size());
      for (std::size_t i = 0; i < single.size(); ++i) {
        ASSERT_TRUE(same(res.rows[i].result, single[i])) << "threads " << threads << " row " << i;
        const std::size_t f = i / np, p = i % np;
        ASSERT_TRUE(same(rev.rows[(kFrames - 1 - f) * np + p].result, single[i])) << "reversed, threads " << threads << " row " << i;
        if (threads == 1 && single[i].scar) ++scarred_rows;
      }
    }
    std::printf("[ scenes ] %s: %zu rows (%d scarred) the same on 1 and 2 threads, frames reversed, and by solve_pair\n", c.name,
                single.size(), scarred_rows);
    EXPECT_GT(scarred_rows, 0);
  }
}

// ---- two scarred rollers (scarred_two_sided.h (3)) ----

/// sd of p to a posed closed mesh by every triangle's closest point and ray parity in three
/// directions (majority).
double oracle_sd(const Vec3& p, const std::vector<Vec3>& pos, const TriMesh& m) {
  const double d = test::ref_point_mesh_distance(p, pos, m);
  const int in = test::ref_inside(p, pos, m) + test::ref_inside(p, pos, m, {-0.31, 0.72, 0.62}) +
                 test::ref_inside(p, pos, m, {0.83, -0.22, 0.51});
  return in >= 2 ? -d : d;
}

Transform translated(Transform t, const Vec3& by) {
  t.t = t.t + by;
  return t;
}

TEST(ReviewTwoScarredBracket, CrossingCoaxialAndFarRollers) {
  int clash = 0, contact = 0, other = 0;
  for (const char* bearing : {test::kCylindricalBearing, test::kTaperedBearing})
  for (const bool raised : {false, true}) {
    const Assembly as = test::scarred_assembly(bearing, raised);
    const BearingSpec& b = as.spec.bearings[0];
    const double R = b.rollers.radius, h = b.rollers.length;
    std::size_t ia = 0;
    while (as.parts[ia].kind != PartKind::roller) ++ia;
    const Transform pa0 = as.parts[ia].rest;
    const Vec3 ua = pa0.rotate({0, 0, 1}), ma = pa0.apply({0, 0, 0.5 * h});
    const Vec3 x = unit(ma - as.geometry[0].frame.t - ua * dot(ma - as.geometry[0].frame.t, ua));  // radial
    // B: the same roller's mesh (another part of the same bearing: its own scar) posed from A's pose
    std::size_t ib = ia + 1;
    while (as.parts[ib].kind != PartKind::roller) ++ib;
    const double tol0 = 0x1p-36 * (norm(ma) + 100);  // about touch_tolerance's size, for the gaps
    struct Pose {
      const char* what;
      Transform b;
    };
    std::vector<Pose> poses;
    for (const double gap : {-0.3, -0.02, -3 * tol0, -0.5 * tol0, 0.0}) {
      // coaxial end to end: B's bottom cap on A's top cap (coplanar at gap 0), turned about the axis
      Transform t = pa0;
      const auto spin = test::rot_about(ua, 0.37);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) t.r[r][c] = spin[r][0] * pa0.r[0][c] + spin[r][1] * pa0.r[1][c] + spin[r][2] * pa0.r[2][c];
      t.t = pa0.apply({0, 0, h + gap});
      poses.push_back({"coaxial", t});
      // crossing at 90 and 30 degrees about the line of centres (x), centres 2R + gap apart
      for (const double angle : {0.5 * std::numbers::pi, std::numbers::pi / 6}) {
        const auto rot = test::rot_about(x, angle);
        Transform c = pa0;
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) c.r[r][k] = rot[r][0] * pa0.r[0][k] + rot[r][1] * pa0.r[1][k] + rot[r][2] * pa0.r[2][k];
        const Vec3 mb = ma + x * (2 * R + gap);
        c.t = mb - c.rotate({0, 0, 0.5 * h});
        poses.push_back({"crossing", c});
      }
    }
    const Vec3 away{9800.0, -7000.5, 6000.25};
    for (const Pose& pose : poses)
      for (const bool moved : {false, true}) {
        const Transform ta = moved ? translated(pa0, away) : pa0, tb = moved ? translated(pose.b, away) : pose.b;
        SCOPED_TRACE(std::string(raised ? "raised " : "inward ") + pose.what + (moved ? " far" : ""));
        const ScenePart A = test::scene_part(as, ia, ta), B = test::scene_part(as, ib, tb);
        const PartPairResult r = decide_part_pair(A, B, as.spec.clearance), q = decide_part_pair(B, A, as.spec.clearance);
        EXPECT_EQ(r.distance, q.distance);
        EXPECT_EQ(r.distance_lower, q.distance_lower);
        EXPECT_EQ(r.verdict, q.verdict);
        EXPECT_LE(r.distance_lower, r.distance);
        const double tol = touch_tolerance(A.cylinder, B.cylinder);
        const std::vector<Vec3> qa = test::posed_positions(A.mesh->mesh, ta), qb = test::posed_positions(B.mesh->mesh, tb);
        if (r.verdict == Verdict::clash) {
          ++clash;
          if (r.solver != PartPairSolver::bound) continue;  // (a containment clash: another test's)
          // U* < -tol: its witness is a point of one surface deeper than tol in the other's mesh
          const bool on_b = r.reverse != r.swapped;  // the witness on the part given second (B)
          const Vec3 w = r.reverse ? r.point_b : r.point_a;
          const double sd = on_b ? oracle_sd(w, qa, A.mesh->mesh) : oracle_sd(w, qb, B.mesh->mesh);
          EXPECT_LT(sd, -tol) << "clash witness depth " << sd << " (row U* " << r.distance << ")";
        } else if (r.verdict == Verdict::contact) {
          ++contact;
          // no vertex of either mesh deeper than tol inside the other
          const auto deepest = [&](const std::vector<Vec3>& p, const std::vector<Vec3>& o, const TriMesh& om, const Cylinder& oc) {
            double worst = 0;
            for (const Vec3& v : p) {
              const double z = dot(v - oc.base, oc.axis), rho = norm(cross(v - oc.base, oc.axis));
              if (std::max({rho - oc.max_radius() - 1, -z, z - oc.height}) > 0) continue;  // (outside: sd > 0)
              worst = std::min(worst, oracle_sd(v, o, om));
            }
            return worst;
          };
          const double da = deepest(qa, qb, B.mesh->mesh, B.cylinder), db = deepest(qb, qa, A.mesh->mesh, A.cylinder);
          EXPECT_GE(std::min(da, db), -tol - 1e-12 * (norm(ta.t) + 100)) << "a contact row with a vertex " << std::min(da, db) << " deep";
        } else {
          ++other;
        }
      }
  }
  std::printf("[ two scarred ] %d clash, %d contact, %d other rows checked\n", clash, contact, other);
  EXPECT_GT(clash, 10);
}

TEST(ReviewTwoScarredBracket, DenseAllScarredAssembly) {
  // 37 rollers of radius 10 on a pitch radius of 120.05 (0.38 mm between neighbours at rest), every
  // one scarred, pocket play 4, tilt 3 deg, load 0.6: the motion presses scarred neighbours together
  // (at a930634 these rows were `undecided` with a negative lower bound). Exact rows (the meshes
  // apart) against the brute-force distance of every triangle pair with no vertex of either mesh
  // inside the other (two-ray parity); clashes by the bracket: a witness deeper than tol in the other
  // mesh by the oracle's sd.
  for (const bool raised : {false, true}) {
    const std::string bearing =
        R"({"id": "b0", "type": "cylindrical", "position": [0, 0, 0], "axis": [1, 0, 0],
        "inner_ring": {"bore_radius": 95, "raceway_radius": 110, "width": 50, "rib": {"height": 4, "width": 5}},
        "outer_ring": {"raceway_radius": 130.1, "outer_radius": 145, "width": 50},
        "rollers": {"count": 37, "radius": 10, "length": 38, "pitch_radius": 120.05},
        "cage": {"pocket_clearance": 0.05, "web_thickness": 0.2}})";
    const std::string text = std::string(R"({"seed": 3, "clearance": 0.05, "motion": {"max_tilt_deg": 3,
        "load": {"displacement": 0.6}, "pocket_play": 4, "axial_play": 0}, "scar": {"fraction": 1,
        "angle_width_deg": 350, "seed": 5)") + (raised ? R"(, "depth": 0.03, "raised": true)" : "") + R"(}, "bearings": [)" +
                             bearing + "]}";
    const Expected<AssemblySpec> spec = parse_assembly(text, "dense.json");
    ASSERT_TRUE(spec) << spec.error().message();
    const Expected<Assembly> as = build_assembly(*spec);
    ASSERT_TRUE(as) << as.error().message();
    const AssemblyMotion motion = generate_motion(*as, 6, spec->seed);
    int exact = 0, clash = 0, rows = 0;
    for (std::size_t f = 0; f < motion.poses.size(); ++f)
      for (const AssemblyPair& pair : as->pairs) {
        if (pair.kind != AssemblyPairKind::roller_roller || !as->parts[pair.a].scarred || !as->parts[pair.b].scarred) continue;
        ++rows;
        const std::vector<Transform>& poses = motion.poses[f];
        const AssemblyPairResult r = solve_pair(*as, pair, poses, spec->clearance);
        if (r.distance > 0.2) continue;  // (clear by far)
        const TriMesh &ma = *as->parts[pair.a].mesh, &mb = *as->parts[pair.b].mesh;
        const std::vector<Vec3> qa = test::posed_positions(ma, poses[pair.a]), qb = test::posed_positions(mb, poses[pair.b]);
        const double tol = touch_tolerance(posed_cylinder(10, -1, 38, poses[pair.a]), posed_cylinder(10, -1, 38, poses[pair.b]));
        SCOPED_TRACE(std::string(raised ? "raised" : "inward") + " frame " + std::to_string(f) + " " + as->parts[pair.a].id);
        if (r.exact) {
          ++exact;
          int inside = 0;
          const auto count = [&](const std::vector<Vec3>& p, const std::vector<Vec3>& o, const TriMesh& om, const Transform& opose) {
            const Cylinder oc = posed_cylinder(10.5, -1, 38, opose);  // (holds the other solid: raise <= 0.03)
            for (const Vec3& v : p) {
              const double z = dot(v - oc.base, oc.axis), rho = norm(cross(v - oc.base, oc.axis));
              if (rho > oc.radius || z < -0.5 || z > oc.height + 0.5) continue;  // (outside the other)
              inside += test::ref_inside(v, o, om) && test::ref_inside(v, o, om, {-0.31, 0.72, 0.62});
            }
          };
          count(qa, qb, mb, poses[pair.b]);
          count(qb, qa, ma, poses[pair.a]);
          EXPECT_EQ(inside, 0) << "an exact (apart) row with a vertex inside the other roller";
          const double ref = test::ref_mesh_distance(ma, qa, mb, qb);
          EXPECT_NEAR(r.distance, ref, 1e-9 * std::fabs(ref) + 1e-13) << verdict_name(r.verdict);
        } else if (r.verdict == Verdict::clash && r.solver == AssemblySolver::bound) {
          ++clash;
          const double sd = std::min(oracle_sd(r.point_a, qb, mb), oracle_sd(r.point_b, qa, ma));
          EXPECT_LT(sd, -tol) << "clash witness depth " << sd << " (row " << r.distance << ")";
          EXPECT_NEAR(sd, r.distance, 1e-9);
        }
      }
    std::printf("[ dense all scarred ] %s: %d two-scarred rows, %d exact (apart) checked, %d clashes by the bracket checked\n",
                raised ? "raised" : "inward", rows, exact, clash);
    EXPECT_GT(exact + clash, 0);
  }
}

}  // namespace
}  // namespace interfere::bearing
