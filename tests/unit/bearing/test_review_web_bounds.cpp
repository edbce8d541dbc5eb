// Review of 2ee6680 (issue #27, assembly speed): the roller-cage rows of intact rollers apart from
// their web now take a closed form (separated_web: a separating face and its foot in the face, or an
// edge candidate certified by its direction). Attacked outside the commit test's 3-degree poses:
// tilts up to 70 degrees about any axis, shifts of +-4 mm (the roller over the web's ends and
// corners, its axis across faces), and rows pushed to within +-1e-6 / 1e-4 mm of touching. Oracle,
// independent of src/bearing: for a row the solver calls apart, the distance of the two convex solids
// is bracketed by a separating-direction lower bound (any unit v: min over the roller of v.y minus
// max over the web's corners of v.w; maximised by hill climbing from the face normals) and an upper
// bound from web surface points (a 20 x 20 barycentric grid of every posed web triangle, refined by
// a compass search, each point's distance to the solid roller in closed form). A wrong clear (the
// solver apart where the solids overlap) shows as the solver's value above the upper bound; a row
// the solver calls touching or overlapping must have a point common to both solids (within touch:
// min of max(roller's signed distance, web's plane distance) by a random pattern search from the
// solver's witness segment), and its value at most any web point's signed distance to the roller
// (the web's deepest point, eb034ed's closed form). Cylindrical and tapered bearings.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "interfere/bearing/assembly.h"
#include "unit/bearing/assembly_fixture.h"
#include "unit/bearing/splitmix.h"

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Cyl {  // a solid cylinder (r1 < 0) or frustum: radius r at the base, r1 at the top
  Vec3 base, axis;
  double r = 1, h = 1, r1 = -1;
  double top() const { return r1 < 0 ? r : r1; }
};

double seg(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

double cyl_sd(const Cyl& c, const Vec3& p) {  // signed distance: the meridian trapezoid's (rho, z) distance
  const Vec3 w = p - c.base;
  const double z = dot(w, c.axis), rho = norm(w - c.axis * z);
  const double m = std::min({seg(rho, z, 0, 0, c.r, 0), seg(rho, z, c.r, 0, c.top(), c.h), seg(rho, z, c.top(), c.h, 0, c.h)});
  return z > 0 && z < c.h && rho < c.r + (c.top() - c.r) * z / c.h ? -m : m;
}

double lower_at(const Cyl& c, const std::vector<Vec3>& corners, Vec3 v) {
  v = v / norm(v);
  const double cu = std::clamp(dot(v, c.axis), -1.0, 1.0);
  const double sv = std::sqrt(1 - cu * cu);
  const double roller_min = std::min(dot(v, c.base) - c.r * sv, dot(v, c.base + c.axis * c.h) - c.top() * sv);
  double web_max = -kInf;
  for (const Vec3& p : corners) web_max = std::max(web_max, dot(v, p));
  return roller_min - web_max;
}

double lower_bound(const Cyl& c, const std::vector<Vec3>& corners, const std::vector<Vec3>& starts, test::SplitMix& g) {
  double best = -kInf;
  Vec3 bv{1, 0, 0};
  for (const Vec3& s : starts)
    if (norm(s) > 0)
      if (const double l = lower_at(c, corners, s); l > best) best = l, bv = s / norm(s);
  double step = 0.3;
  for (int it = 0; it < 1500 && step > 1e-13; ++it) {
    const Vec3 t = bv + Vec3{g.in(-1, 1), g.in(-1, 1), g.in(-1, 1)} * step;
    if (const double l = lower_at(c, corners, t); l > best) best = l, bv = t / norm(t);
    else if (it % 20 == 19) step *= 0.7;
  }
  return best;
}

double upper_bound(const Cyl& c, const std::vector<std::array<Vec3, 3>>& tris, int n = 20) {
  double best = kInf;
  for (const auto& t : tris) {
    const auto at = [&](double u, double v) { return t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v; };
    double bu = 0, bv = 0, tb = kInf;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        if (const double d = cyl_sd(c, at(double(i) / n, double(j) / n)); d < tb) tb = d, bu = double(i) / n, bv = double(j) / n;
    double s = 1.0 / n;
    for (int moves = 0; s > 1e-15 && moves < 4000; ++moves) {  // (bounded: a valley can take tiny steps forever)
      bool moved = false;
      for (const auto& [du, dv] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}}) {
        const double u = bu + du * s, v = bv + dv * s;
        if (u < 0 || v < 0 || u + v > 1) continue;
        if (const double d = cyl_sd(c, at(u, v)); d < tb) tb = d, bu = u, bv = v, moved = true;
      }
      if (!moved) s *= 0.5;
    }
    best = std::min(best, tb);
  }
  return best;
}

// min over points x of max(sd_roller(x), the web's plane distance max_j n_j.(x - a_j)): <= 0 exactly
// when the solids share a point (both convex). A 3-D pattern search with random directions from the
// given starts (any value found is an upper bound of the minimum).
double common_point(const Cyl& c, const std::vector<std::pair<Vec3, Vec3>>& planes, const std::vector<Vec3>& starts,
                     test::SplitMix& g) {
  const auto f = [&](const Vec3& x) {
    double w = -kInf;
    for (const auto& [a, n] : planes) w = std::max(w, dot(x - a, n));
    return std::max(cyl_sd(c, x), w);
  };
  double best = kInf;
  Vec3 bx;
  for (const Vec3& x : starts)
    if (const double v = f(x); v < best) best = v, bx = x;
  double step = 0.01;
  for (int it = 0; it < 20000 && step > 1e-14; ++it) {
    Vec3 d{g.in(-1, 1), g.in(-1, 1), g.in(-1, 1)};
    const Vec3 x = bx + d * (step / norm(d));
    if (const double v = f(x); v < best) best = v, bx = x;
    else if (it % 30 == 29) step *= 0.7;
  }
  return best;
}

std::array<std::array<double, 3>, 3> rotation(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  return {{{c + k.x * k.x * v, k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s},
           {k.y * k.x * v + k.z * s, c + k.y * k.y * v, k.y * k.z * v - k.x * s},
           {k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v}}};
}

}  // namespace

void web_rows(const char* bearing, double r0, double r1, double h, std::uint64_t seed, int rounds) {
  const std::string extra = R"("frames": 1, "seed": 3, "clearance": 0.05,)";
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, bearing), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  std::vector<Transform> rest;
  for (const AssemblyPart& p : as.parts) rest.push_back(p.rest);
  test::SplitMix rng{seed};
  const auto uniform = [&](double lo, double hi) { return rng.in(lo, hi); };
  int apart = 0, overlapping = 0, near_checked = 0;
  double worst_gap = 0;
  for (int round = 0; round < rounds; ++round) {
    std::vector<Transform> poses = rest;
    for (std::size_t i = 0; i < as.parts.size(); ++i) {
      if (as.parts[i].kind != PartKind::roller) continue;
      const Transform& p0 = rest[i];
      const Vec3 centre = p0.apply({0, 0, 0.5 * h});
      const Vec3 k{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      const auto rot = rotation(k / norm(k), uniform(0, 70) * std::numbers::pi / 180);
      Transform q;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) q.r[r][c] = rot[r][0] * p0.r[0][c] + rot[r][1] * p0.r[1][c] + rot[r][2] * p0.r[2][c];
      const Vec3 off = p0.t - centre;
      q.t = centre + Vec3{uniform(-4, 4), uniform(-4, 4), uniform(-4, 4)} +
            Vec3{rot[0][0] * off.x + rot[0][1] * off.y + rot[0][2] * off.z, rot[1][0] * off.x + rot[1][1] * off.y + rot[1][2] * off.z,
                 rot[2][0] * off.x + rot[2][1] * off.y + rot[2][2] * off.z};
      poses[i] = q;
    }
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_cage) continue;
      const TriMesh& web = as.webs[as.web_offset[as.parts[pair.a].bearing] + pair.feature].mesh;
      const auto check = [&](const std::vector<Transform>& ps, const char* what) -> AssemblyPairResult {
        const AssemblyPairResult r = solve_pair(as, pair, ps, as.spec.clearance);
        Cyl c;
        c.base = ps[pair.a].apply({0, 0, 0}), c.axis = ps[pair.a].rotate({0, 0, 1}), c.r = r0, c.h = h, c.r1 = r1;
        std::vector<Vec3> corners;
        for (const Vec3& p : web.positions) corners.push_back(ps[pair.b].apply(p));
        std::vector<std::array<Vec3, 3>> tris;
        std::vector<Vec3> starts;
        for (const Tri& t : web.triangles) {
          tris.push_back({corners[t[0]], corners[t[1]], corners[t[2]]});
          starts.push_back(cross(corners[t[1]] - corners[t[0]], corners[t[2]] - corners[t[0]]));
        }
        starts.push_back(r.point_b - r.point_a);
        double up = upper_bound(c, tris);
        const double scale = norm(c.base) + 40;
        SCOPED_TRACE(std::string(what) + " " + as.parts[pair.a].id + " web " + std::to_string(pair.feature) + " round " +
                     std::to_string(round));
        EXPECT_TRUE(std::isfinite(r.distance));
        if (r.distance > 0) {
          // apart: the solids' distance; between the two independent bounds
          const double lo = lower_bound(c, corners, starts, rng);
          EXPECT_LE(r.distance, up + 1e-9 * scale) << "above a web point's distance: lower " << lo << " upper " << up;
          EXPECT_GE(r.distance, lo - 1e-9 * scale) << "below a separating bound: upper " << up;
          worst_gap = std::max(worst_gap, up - lo);
        } else {
          // the solver says they touch or overlap: a point common to both solids (within touch): from the witnesses and the points between them
          std::vector<std::pair<Vec3, Vec3>> planes;
          for (const auto& t : tris) {
            const Vec3 nn = cross(t[1] - t[0], t[2] - t[0]);
            planes.emplace_back(t[0], nn / norm(nn));
          }
          std::vector<Vec3> pts;
          for (int q = 0; q <= 10; ++q) pts.push_back(r.point_a + (r.point_b - r.point_a) * (q / 10.0));
          test::SplitMix own{seed ^ 0x5151};
          const double common = common_point(c, planes, pts, own);
          EXPECT_LE(common, 1e-9 * scale) << "solver " << r.distance << " but no common point found (web surface "
                                          << up << ")";
          // S = min(s(roller, web), s(web, roller)) <= s(web, roller) = min over the web of sd_roller <= any
          // web point's sd_roller (eb034ed's closed form for the web's deepest point: not shallower)
          EXPECT_LE(r.distance, up + 1e-9 * scale) << "shallower than a web point's depth in the roller";
        }
        return r;
      };
      const AssemblyPairResult r = check(poses, "random");
      ++(r.distance > 0 ? apart : overlapping);
      if (r.distance > 1e-3) {
        // pushed along the witness direction to within +-1e-6 and +-1e-4 of touching
        const Vec3 v = (r.point_b - r.point_a) / norm(r.point_b - r.point_a);
        for (const double delta : {1e-4, 1e-6, -1e-6, -1e-4}) {
          std::vector<Transform> ps = poses;
          ps[pair.a].t = ps[pair.a].t + v * (r.distance - delta);
          const AssemblyPairResult n = check(ps, "near");
          if (delta > 0) EXPECT_TRUE(n.verdict == Verdict::clearance) << "delta " << delta << " distance " << n.distance;
          else EXPECT_EQ(n.verdict, Verdict::clash) << "delta " << delta << " distance " << n.distance;
          ++near_checked;
        }
      }
    }
  }
  std::printf("[ review webs %s ] apart %d, overlapping %d, near-touch rows %d, largest bracket %.3g\n", std::string(bearing).find("\"cyl\"") != std::string::npos ? "cyl" : "tap", apart, overlapping,
              near_checked, worst_gap);
  EXPECT_GT(apart, 10);
  EXPECT_GT(near_checked, 20);
}

TEST(ReviewWebBounds, ApartRowsLieBetweenIndependentBoundsAtLargeTilts) { web_rows(test::kCylindricalBearing, 10, -1, 20, 2026, 12); }

// the tapered bearing's webs and frustum rollers (radius 8 -> 9.5, length 30; assembly_fixture.h)
TEST(ReviewWebBounds, TaperedRollersAtLargeTilts) { web_rows(test::kTaperedBearing, 8, 9.5, 30, 2027, 8); }

}  // namespace interfere::bearing
