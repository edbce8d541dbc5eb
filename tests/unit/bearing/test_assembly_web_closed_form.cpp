// Cage webs in closed form (issue #27, speed; assembly_pairs.cpp separated_web and
// deepest_closed_form): the roller-cage rows of rollers moved at random around their pockets (tilted
// up to 3 degrees about any axis across the roller, shifted along the axis past either end of the
// web, toward and away from the webs, radially), against a dense reference written here from the
// definitions: the web's deepest point in the roller (or, apart, their distance) by a nested
// golden-section search of the roller's signed distance over each web triangle of the posed mesh,
// and the roller's deepest point in the web (its depth: the smallest distance to the face planes of
// the posed mesh's triangles) by the larger of a grid over the roller's surface refined nine times
// and a nested golden-section search over the solid roller (the depth is concave). (The surface grid
// alone misses the maximum by up to 0.02 mm in some of these poses: the old solver and the new give
// the deeper value, their witness on the roller's surface at exactly that depth.) Cylindrical
// and tapered rollers, intact and scarred (inward scars: the value is the intact roller's, one-sided
// for the overlapping rows), the poses both apart (the separating face's foot inside the face, or
// past the web's end face: the edge candidate) and overlapping (one face, or the pocket and end
// faces together).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "unit/bearing/assembly_fixture.h"
#include "unit/bearing/splitmix.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Solid {  ///< a solid frustum: base centre, unit axis, radii at both ends, height
  Vec3 base, axis;
  double r0 = 1, r1 = 1, h = 1;
};

double seg_dist(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

/// Signed distance to the solid: the trapezoid 0 <= rho <= r(z), 0 <= z <= h of the meridian plane.
double sd(const Solid& s, const Vec3& p) {
  const Vec3 d = p - s.base;
  const double z = dot(d, s.axis), rho = norm(d - s.axis * z);
  const double m = std::min({seg_dist(rho, z, 0, 0, s.r0, 0), seg_dist(rho, z, s.r0, 0, s.r1, s.h),
                             seg_dist(rho, z, s.r1, s.h, 0, s.h)});
  return z > 0 && z < s.h && rho < s.r0 + (s.r1 - s.r0) * z / s.h ? -m : m;
}

Vec3 surface(const Solid& s, int patch, double u, double v) {
  const Vec3 e1 = std::fabs(s.axis.x) < 0.9 ? cross(s.axis, Vec3{1, 0, 0}) : cross(s.axis, Vec3{0, 1, 0});
  const Vec3 x = e1 / norm(e1), y = cross(s.axis, x);
  const double a = 2 * kPi * u;
  if (patch == 0) return s.base + s.axis * (v * s.h) + (x * std::cos(a) + y * std::sin(a)) * (s.r0 + (s.r1 - s.r0) * v);
  const double z = patch == 1 ? 0 : s.h, r = (patch == 1 ? s.r0 : s.r1) * v;
  return s.base + s.axis * z + (x * std::cos(a) + y * std::sin(a)) * r;
}

/// min of f over the solid's surface: a 720 x 60 grid per patch, nine 10x refinements.
double surface_min(const Solid& s, const std::function<double(const Vec3&)>& f) {
  double best = kInf;
  for (int patch = 0; patch < 3; ++patch) {
    double bu = 0, bv = 0, pbest = kInf;
    for (int i = 0; i < 720; ++i)
      for (int j = 0; j <= 60; ++j)
        if (const double val = f(surface(s, patch, i / 720.0, j / 60.0)); val < pbest) pbest = val, bu = i / 720.0, bv = j / 60.0;
    double hu = 1.0 / 720, hv = 1.0 / 60;
    for (int level = 0; level < 9; ++level, hu /= 10, hv /= 10) {
      const double cu = bu, cv = bv;
      for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j) {
          const double u = cu + hu * i / 20.0, v = std::clamp(cv + hv * j / 20.0, 0.0, 1.0);
          if (const double val = f(surface(s, patch, u, v)); val < pbest) pbest = val, bu = u, bv = v;
        }
    }
    best = std::min(best, pbest);
  }
  return best;
}

double golden(const std::function<double(double)>& f, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
  double best = std::min({f(lo), f(hi), f1, f2});
  for (int k = 0; k < 80; ++k) {
    if (f1 <= f2) b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    else a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    best = std::min({best, f1, f2});
  }
  return best;
}

/// The reference of a roller-cage row (assembly.h): rev = min over the web's triangles of the
/// roller's signed distance; apart or scarred: rev; else -max(fwd, -rev).
double reference(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses) {
  const AssemblyPart& pa = as.parts[pair.a];
  const BearingSpec& b = as.spec.bearings[pa.bearing];
  Solid roller;
  roller.base = poses[pair.a].apply({0, 0, 0}), roller.axis = poses[pair.a].rotate({0, 0, 1});
  roller.r0 = b.rollers.radius, roller.r1 = b.type == BearingType::tapered ? b.rollers.top_radius : b.rollers.radius;
  roller.h = b.rollers.length;
  const TriMesh& web = as.webs[as.web_offset[pa.bearing] + pair.feature].mesh;
  const Transform& ring = poses[pair.b];
  double rev = kInf;
  for (const Tri& t : web.triangles) {
    const Vec3 a = ring.apply(web.positions[t[0]]), e1 = ring.apply(web.positions[t[1]]) - a,
               e2 = ring.apply(web.positions[t[2]]) - a;
    rev = std::min(rev, golden([&](double u) {
      return golden([&](double v) { return sd(roller, a + e1 * u + e2 * v); }, 0.0, 1.0 - u);
    }, 0.0, 1.0));
  }
  if (rev > 0 || pa.scarred) return rev;
  // the web's depth of a point: the smallest distance to the planes of the posed mesh's triangles
  std::vector<std::pair<Vec3, Vec3>> planes;  // (a point, the unit outward normal)
  for (const Tri& t : web.triangles) {
    const Vec3 a = ring.apply(web.positions[t[0]]), b1 = ring.apply(web.positions[t[1]]), c1 = ring.apply(web.positions[t[2]]);
    const Vec3 nn = cross(b1 - a, c1 - a);
    planes.emplace_back(a, nn / norm(nn));
  }
  const auto web_depth = [&](const Vec3& p) {
    double m = kInf;
    for (const auto& [a, nn] : planes) m = std::min(m, -dot(p - a, nn));
    return m;
  };
  // fwd = max over the solid roller of the depth (concave): its surface sampled densely, and a
  // nested golden-section search over the solid (axial position, then x and y across the disk:
  // partial maxima of a concave function over a convex set are concave); the larger of the two
  const double sampled = -surface_min(roller, [&](const Vec3& p) { return -web_depth(p); });
  const Vec3 t1 = std::fabs(roller.axis.x) < 0.9 ? cross(roller.axis, Vec3{1, 0, 0}) : cross(roller.axis, Vec3{0, 1, 0});
  const Vec3 ex = t1 / norm(t1), ey = cross(roller.axis, ex);
  const double nested = -golden([&](double z) {
    const double rz = roller.r0 + (roller.r1 - roller.r0) * z / roller.h;
    const Vec3 c = roller.base + roller.axis * z;
    return golden([&](double x) {
      const double yh = std::sqrt(std::max(0.0, rz * rz - x * x));
      return golden([&](double y) { return -web_depth(c + ex * x + ey * y); }, -yh, yh);
    }, -rz, rz);
  }, 0.0, roller.h);
  return std::min(rev, -std::max(sampled, nested));
}

/// A rotation by `angle` about the unit axis k (Rodrigues).
std::array<std::array<double, 3>, 3> rotation(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  return {{{c + k.x * k.x * v, k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s},
           {k.y * k.x * v + k.z * s, c + k.y * k.y * v, k.y * k.z * v - k.x * s},
           {k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v}}};
}

TEST(BearingAssemblyWebClosedForm, RandomPocketPosesAgainstADenseReference) {
  const std::string extra =
      R"("frames": 1, "seed": 3, "clearance": 0.05, "scar": {"fraction": 0.3, "angle_width_deg": 350, "depth": 0.05, "seed": 5},)";
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, test::both_bearings()), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  std::vector<Transform> rest;
  for (const AssemblyPart& p : as.parts) rest.push_back(p.rest);
  test::SplitMix rng{27};
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  int apart = 0, overlapping = 0, checked = 0;
  double worst = 0;
  for (int round = 0; round < 3; ++round) {
    std::vector<Transform> poses = rest;
    for (std::size_t i = 0; i < as.parts.size(); ++i) {
      if (as.parts[i].kind != PartKind::roller) continue;
      const BearingSpec& b = as.spec.bearings[as.parts[i].bearing];
      const Transform& p0 = rest[i];
      const Vec3 u = p0.rotate({0, 0, 1}), centre = p0.apply({0, 0, 0.5 * b.rollers.length});
      const Vec3 bearing_axis = as.geometry[as.parts[i].bearing].frame.rotate({0, 0, 1});
      const Vec3 tangent = cross(bearing_axis, centre - as.geometry[as.parts[i].bearing].frame.t);
      const Vec3 t = tangent / norm(tangent);
      const Vec3 radial = cross(t, u) / norm(cross(t, u));
      // a tilt about a random axis across the roller (up to 3 degrees), then shifts along the axis
      // (past the web's ends), toward the webs (into them or clear of them) and radially
      const double a = uniform(0, 2 * kPi);
      const Vec3 k = t * std::cos(a) + radial * std::sin(a);
      const auto rot = rotation(k / norm(k), uniform(0, 3) * kPi / 180);
      const Vec3 shift = u * uniform(-3, 3) + t * uniform(-1.5, 1.5) + radial * uniform(-1, 1);
      Transform q;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) q.r[r][c] = rot[r][0] * p0.r[0][c] + rot[r][1] * p0.r[1][c] + rot[r][2] * p0.r[2][c];
      const Vec3 off = p0.t - centre;
      q.t = centre + shift + Vec3{rot[0][0] * off.x + rot[0][1] * off.y + rot[0][2] * off.z,
                                  rot[1][0] * off.x + rot[1][1] * off.y + rot[1][2] * off.z,
                                  rot[2][0] * off.x + rot[2][1] * off.y + rot[2][2] * off.z};
      poses[i] = q;
    }
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_cage) continue;
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      const double ref = reference(as, pair, poses);
      SCOPED_TRACE(as.parts[pair.a].id + " web " + std::to_string(pair.feature) + " round " + std::to_string(round));
      ASSERT_TRUE(std::isfinite(r.distance) && std::isfinite(ref));
      EXPECT_NEAR(r.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
      worst = std::max(worst, std::fabs(r.distance - ref));
      if (!as.parts[pair.a].scarred) {
        EXPECT_TRUE(r.exact);
        EXPECT_TRUE(r.two_sided);
        // the witnesses are |distance| apart
        EXPECT_NEAR(norm(r.point_a - r.point_b), std::fabs(r.distance), 1e-6 + 1e-6 * std::fabs(r.distance));
      }
      ++checked;
      ++(r.distance > 0 ? apart : overlapping);
    }
  }
  std::printf("[ webs ] %d rows (%d apart, %d overlapping), largest |solver - reference| %.3g\n", checked, apart,
              overlapping, worst);
  EXPECT_GT(apart, 20);
  EXPECT_GT(overlapping, 20);
}

}  // namespace
}  // namespace interfere::bearing
