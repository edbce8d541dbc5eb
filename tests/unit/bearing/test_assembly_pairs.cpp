// Bearing assemblies (issue #27): every pair's solver value against an independent dense reference.
// The reference samples the parts' surfaces on parameter grids (roller side and end disks, raceway
// sides, the web's faces), refines the best sample nine times on grids 10x finer around it, and
// evaluates signed distances written here from their definitions (the distance to a solid cylinder
// or frustum in the meridian half-plane, the radius of a point about a ring axis), with the parts'
// placement taken from the description (spec) and the poses, not from the solvers' descriptors.
// The quantities are those assembly.h documents per pair kind: two-sided S for every pair of an
// intact roller (issue #27; for the ring parts -max(the roller's deepest point in the ring part's
// meridian polygon, the ring part's deepest point in the roller), see ring_two_sided.h); scarred
// rollers' ring rows are one-sided (the reach beyond the bore, below the rib face, the web's
// deepest point in the roller).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- independent geometry ----

struct Solid {  ///< a solid frustum: base centre, unit axis, radii at both ends, height
  Vec3 base, axis;
  double r0 = 1, r1 = 1, h = 1;
};

/// (rho, z) of p about the solid's axis.
std::pair<double, double> meridian(const Solid& s, const Vec3& p) {
  const Vec3 d = p - s.base;
  const double z = dot(d, s.axis);
  return {norm(d - s.axis * z), z};
}

double seg_dist(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  double t = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy);
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

/// Signed distance to the solid: the trapezoid 0 <= rho <= r(z), 0 <= z <= h in the meridian plane.
double sd(const Solid& s, const Vec3& p) {
  const auto [rho, z] = meridian(s, p);
  const double d = std::min({seg_dist(rho, z, 0, 0, s.r0, 0), seg_dist(rho, z, s.r0, 0, s.r1, s.h),
                             seg_dist(rho, z, s.r1, s.h, 0, s.h)});
  const double rz = s.r0 + (s.r1 - s.r0) * z / s.h;
  const bool inside = z > 0 && z < s.h && rho < rz;
  return inside ? -d : d;
}

/// Points of the solid's surface by two parameters in [0, 1]^2, per patch: 0 side, 1 bottom, 2 top.
Vec3 surface(const Solid& s, int patch, double u, double v) {
  const Vec3 e1 = std::fabs(s.axis.x) < 0.9 ? cross(s.axis, Vec3{1, 0, 0}) : cross(s.axis, Vec3{0, 1, 0});
  const Vec3 x = e1 / norm(e1), y = cross(s.axis, x);
  const double a = 2 * kPi * u;
  if (patch == 0) {
    const double z = v * s.h, r = s.r0 + (s.r1 - s.r0) * v;
    return s.base + s.axis * z + (x * std::cos(a) + y * std::sin(a)) * r;
  }
  const double z = patch == 1 ? 0 : s.h, r = (patch == 1 ? s.r0 : s.r1) * v;
  return s.base + s.axis * z + (x * std::cos(a) + y * std::sin(a)) * r;
}

/// min over the patches of f(point(patch, u, v)): a grid of nu x nv, then nine refinements around
/// the best point (u wraps unless `wrap` is false).
double dense_min(int patches, const std::function<Vec3(int, double, double)>& point, const std::function<double(const Vec3&)>& f,
                 int nu = 720, int nv = 60, bool wrap = true) {
  double best = kInf;
  for (int patch = 0; patch < patches; ++patch) {
    double bu = 0, bv = 0, pbest = kInf;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j <= nv; ++j) {
        const double u = (i + 0.0) / nu, v = (j + 0.0) / nv;
        const double val = f(point(patch, u, v));
        if (val < pbest) pbest = val, bu = u, bv = v;
      }
    double hu = 1.0 / nu, hv = 1.0 / nv;
    for (int level = 0; level < 9; ++level) {
      const double cu = bu, cv = bv;
      for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j) {
          double u = cu + hu * i / 20.0;
          if (!wrap) u = std::clamp(u, 0.0, 1.0);
          const double v = std::clamp(cv + hv * j / 20.0, 0.0, 1.0);
          const double val = f(point(patch, u, v));
          if (val < pbest) pbest = val, bu = u, bv = v;
        }
      hu /= 10, hv /= 10;
    }
    best = std::min(best, pbest);
  }
  return best;
}

double solid_min(const Solid& a, const std::function<double(const Vec3&)>& f) {
  return dense_min(3, [&](int p, double u, double v) { return surface(a, p, u, v); }, f);
}

// ---- the parts from the spec and the poses ----

Solid roller_solid(const BearingSpec& b, const Transform& pose) {
  Solid s;
  s.base = pose.apply({0, 0, 0});
  s.axis = pose.rotate({0, 0, 1});
  s.r0 = b.rollers.radius;
  s.r1 = b.type == BearingType::tapered ? b.rollers.top_radius : b.rollers.radius;
  s.h = b.rollers.length;
  return s;
}

struct Fixture {
  Assembly as;
  AssemblyMotion motion;
};

Fixture lively(int frames) {
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(test::kLively, test::both_bearings()), "t.json");
  EXPECT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  EXPECT_TRUE(a) << a.error().message();
  Fixture f{std::move(*a), {}};
  f.motion = generate_motion(f.as, frames, f.as.spec.seed);
  return f;
}

/// min over a scarred roller's mesh (posed) of f: every triangle sampled on a barycentric grid.
double mesh_min(const TriMesh& m, const Transform& pose, const std::function<double(const Vec3&)>& f) {
  double best = kInf;
  constexpr int n = 6;
  for (const Tri& t : m.triangles) {
    const Vec3 a = pose.apply(m.positions[t[0]]), b = pose.apply(m.positions[t[1]]), c = pose.apply(m.positions[t[2]]);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) best = std::min(best, f(a + (b - a) * (i / double(n)) + (c - a) * (j / double(n))));
  }
  return best;
}

/// The exact minimum of the linear height l(p) = (p - c).n over the roller's points whose distance
/// to the ring axis lies in [in, out] (the rib's K): on the roller's end rims (a sinusoid in the
/// angle: its one local minimum, if in the band) or where the band's shells rho = in, out leave the
/// roller (per azimuth the shell's axial line meets the convex roller in an interval: its end).
double rib_reference(const Solid& roller, const Vec3& c, const Vec3& axis, const Vec3& n, double in, double out) {
  const auto golden = [](const std::function<double(double)>& f, double lo, double hi, int it) {
    const double g = (std::sqrt(5.0) - 1) / 2;
    double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
    for (int k = 0; k < it; ++k) {
      if (f1 <= f2) b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
      else a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    }
    return 0.5 * (a + b);
  };
  const auto rho_of = [&](const Vec3& p) { const Vec3 d = p - c; return norm(d - axis * dot(d, axis)); };
  double best = kInf;
  // the rims: the minimum of l over each rim circle, by a dense scan and a golden refinement
  for (int end = 0; end < 2; ++end) {
    const auto rim = [&](double a) { return surface(roller, end == 0 ? 1 : 2, a / (2 * kPi), 1.0); };
    int bi = 0;
    double bv = kInf;
    for (int i = 0; i < 3600; ++i)
      if (const double v = dot(rim(2 * kPi * i / 3600) - c, n); v < bv) bv = v, bi = i;
    const double a = golden([&](double x) { return dot(rim(x) - c, n); }, 2 * kPi * (bi - 1) / 3600, 2 * kPi * (bi + 1) / 3600, 200);
    const double rho = rho_of(rim(a));
    if (rho >= in && rho <= out) best = std::min(best, dot(rim(a) - c, n));
  }
  // the shells
  const Vec3 e1 = std::fabs(axis.x) < 0.9 ? cross(axis, Vec3{1, 0, 0}) : cross(axis, Vec3{0, 1, 0});
  const Vec3 x = e1 / norm(e1), y = cross(axis, x);
  const double s = dot(n, axis) > 0 ? 1.0 : -1.0;  // l = s t along the shell line
  for (double radius : {in, out}) {
    const auto line = [&](double phi, double t) { return c + (x * std::cos(phi) + y * std::sin(phi)) * radius + axis * t; };
    // the lowest l of the line's part inside the roller (kInf when the line misses it)
    const auto low = [&](double phi) {
      const double reach = roller.h + 2 * std::max(roller.r0, roller.r1) + norm(roller.base - c);
      const double tin = golden([&](double t) { return sd(roller, line(phi, t)); }, -reach, reach, 200);
      if (!(sd(roller, line(phi, tin)) < 0)) return kInf;
      double inside = tin, outside = tin - s * reach;  // toward lower l
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (inside + outside);
        (sd(roller, line(phi, mid)) < 0 ? inside : outside) = mid;
      }
      return s * inside;
    };
    int bi = -1;
    double bv = kInf;
    for (int i = 0; i < 1440; ++i)
      if (const double v = low(2 * kPi * i / 1440); v < bv) bv = v, bi = i;
    if (bi < 0) continue;
    // refine on the finite part around the best azimuth
    double lo = 2 * kPi * (bi - 1) / 1440, hi = 2 * kPi * (bi + 1) / 1440;
    for (int level = 0; level < 6; ++level) {
      double bphi = 0.5 * (lo + hi), bl = kInf;
      for (int i = 0; i <= 40; ++i) {
        const double phi = lo + (hi - lo) * i / 40;
        if (const double v = low(phi); v < bl) bl = v, bphi = phi;
      }
      bv = std::min(bv, bl);
      const double w = (hi - lo) / 40;
      lo = bphi - w, hi = bphi + w;
    }
    best = std::min(best, bv);
  }
  return best;
}

/// The reference value of a pair (kInf when the test does not have one).
double reference(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses) {
  const AssemblyPart& pa = as.parts[pair.a];
  const BearingSpec& b = as.spec.bearings[pa.bearing];
  const Solid roller = roller_solid(b, poses[pair.a]);
  const Transform& ring = poses[pair.b];
  const Vec3 axis = ring.rotate({0, 0, 1});
  const auto roller_sd = [&](const Vec3& p) { return sd(roller, p); };
  switch (pair.kind) {
    case AssemblyPairKind::roller_inner:
    case AssemblyPairKind::roller_cone: {
      Solid race;
      if (b.type == BearingType::cylindrical) {
        race.base = ring.apply({0, 0, -0.5 * b.inner_width});
        race.r0 = race.r1 = b.inner_raceway, race.h = b.inner_width;
      } else {
        // the cone from its definition: apex on the axis, half-angle alpha - 2 beta, offset inwards
        const double beta = std::atan((b.rollers.top_radius - b.rollers.radius) / b.rollers.length);
        const double alpha = b.contact_angle_deg * kPi / 180, gamma = alpha - beta, kappa = alpha - 2 * beta;
        const double d1 = b.rollers.radius / std::tan(beta);
        const double apex = -(d1 + 0.5 * b.rollers.length) * std::cos(gamma);
        const double zs = apex + d1 * std::cos(gamma) - b.rollers.radius * std::sin(gamma);
        const double zb = apex + (d1 + b.rollers.length) * std::cos(gamma) + b.rollers.top_radius * std::sin(gamma);
        const double lo = zs - 0.1 * b.rollers.length, hi = zb + 0.1 * b.rollers.length;
        const auto r = [&](double z) { return (z - apex) * std::tan(kappa) - b.cone_clearance / std::cos(kappa); };
        race.base = ring.apply({0, 0, lo});
        race.r0 = r(lo), race.r1 = r(hi), race.h = hi - lo;
      }
      race.axis = axis;
      if (pa.scarred) return mesh_min(*pa.mesh, poses[pair.a], [&](const Vec3& p) { return sd(race, p); });
      const double forward = solid_min(roller, [&](const Vec3& p) { return sd(race, p); });
      // the raceway's surface near the roller: its side over the whole circumference
      const double reverse =
          dense_min(1, [&](int, double u, double v) { return surface(race, 0, u, v); }, roller_sd, 3600, 60);
      return std::min(forward, reverse);
    }
    case AssemblyPairKind::roller_roller: {
      const Solid other = roller_solid(b, poses[pair.b]);
      const AssemblyPart& pb = as.parts[pair.b];
      if (pa.scarred && !pb.scarred) return mesh_min(*pa.mesh, poses[pair.a], [&](const Vec3& p) { return sd(other, p); });
      if (pb.scarred && !pa.scarred) return mesh_min(*pb.mesh, poses[pair.b], roller_sd);
      if (pa.scarred || pb.scarred) return kInf;
      return std::min(solid_min(roller, [&](const Vec3& p) { return sd(other, p); }), solid_min(other, roller_sd));
    }
    case AssemblyPairKind::roller_outer:
    case AssemblyPairKind::roller_cup: {
      // the ring's meridian polygon about its axis (z from the bearing's mid-plane): the raceway line
      // rho = r_at_0 + k z (its signed distance g normal to it), the outside rho = out, the side
      // faces z = lo, hi
      const Vec3 centre = ring.apply({0, 0, 0});
      double lo = -0.5 * b.outer_width, hi = 0.5 * b.outer_width, k = 0, r_at_0 = b.outer_raceway, out = b.outer_radius;
      if (b.type == BearingType::tapered) {
        const double beta = std::atan((b.rollers.top_radius - b.rollers.radius) / b.rollers.length);
        const double alpha = b.contact_angle_deg * kPi / 180, gamma = alpha - beta;
        const double d1 = b.rollers.radius / std::tan(beta);
        const double apex = -(d1 + 0.5 * b.rollers.length) * std::cos(gamma);
        k = std::tan(alpha);
        r_at_0 = -apex * k + b.cup_clearance / std::cos(alpha);
        const double zs = apex + d1 * std::cos(gamma) - b.rollers.radius * std::sin(gamma);
        const double zb = apex + (d1 + b.rollers.length) * std::cos(gamma) + b.rollers.top_radius * std::sin(gamma);
        lo = zs - 0.1 * b.rollers.length, hi = zb + 0.1 * b.rollers.length, out = b.cup_outer;
      }
      const auto g_of = [&](const Vec3& p) {
        const Vec3 d = p - centre;
        const double z = dot(d, axis);
        return (norm(d - axis * z) - r_at_0 - k * z) / std::sqrt(1 + k * k);
      };
      if (pa.scarred) {  // the mesh: the maximum of g over its vertices (one-sided for scarred rollers)
        double best = kInf;
        for (const Vec3& v : pa.mesh->positions) {
          const Vec3 p = poses[pair.a].apply(v);
          const double z = dot(p - centre, axis);
          if (z < lo || z > hi) continue;
          best = std::min(best, -g_of(p));
        }
        return best;
      }
      // two-sided (issue #27): fwd = the roller's deepest point in the polygon, rev = the ring's
      // deepest point in the roller (on its raceway or side faces near the roller)
      const auto ring_depth = [&](const Vec3& p) {
        const Vec3 d = p - centre;
        const double z = dot(d, axis), rho = norm(d - axis * z);
        return std::min({g_of(p), out - rho, z - lo, hi - z});
      };
      const double clear = solid_min(roller, [&](const Vec3& p) { return -g_of(p); });
      if (clear > 0) return clear;  // apart: the clearance to the raceway (the solver's value)
      const double fwd = -solid_min(roller, [&](const Vec3& p) { return -ring_depth(p); });
      const Vec3 e1 = std::fabs(axis.x) < 0.9 ? cross(axis, Vec3{1, 0, 0}) : cross(axis, Vec3{0, 1, 0});
      const Vec3 ex = e1 / norm(e1), ey = cross(axis, ex);
      const Vec3 c = roller.base + roller.axis * (0.5 * roller.h) - centre;
      const double phi = std::atan2(dot(c, ey), dot(c, ex));
      const auto ring_point = [&](int patch, double u, double v) {
        const double a = phi + (u - 0.5) * 0.8;
        const Vec3 radial = ex * std::cos(a) + ey * std::sin(a);
        if (patch == 0) {
          const double z = lo + v * (hi - lo);
          return centre + axis * z + radial * (r_at_0 + k * z);
        }
        const double z = patch == 1 ? lo : hi, r0 = r_at_0 + k * z;
        return centre + axis * z + radial * (r0 + v * (out - r0));
      };
      const double rev = -dense_min(3, ring_point, roller_sd, 720, 60, false);
      return -std::max(fwd, rev);
    }
    case AssemblyPairKind::roller_rib: {
      // (a scarred roller: its intact cylinder; inward scars leave the value the intact one's, see below)
      const double zf = pair.feature == 0 ? -0.5 * b.inner_width + b.rib_width : 0.5 * b.inner_width - b.rib_width;
      const Vec3 c = ring.apply({0, 0, zf});
      const Vec3 n = pair.feature == 0 ? axis : -axis;
      const double in = b.inner_raceway, out = b.inner_raceway + b.rib_height;
      const double one_sided = rib_reference(roller, c, axis, n, in, out);
      if (one_sided > 0 || pa.scarred) return one_sided;
      // two-sided (issue #27): the rib block in <= rho <= out, -width <= l <= 0 (rho = in joins the
      // ring body: not a free surface); fwd = the roller's deepest point in it, rev = its deepest
      // point in the roller (on the block's boundary: face, top, inner and back shells)
      const auto rl = [&](const Vec3& p) {
        const Vec3 d = p - c;
        return std::pair{norm(d - axis * dot(d, axis)), dot(d, n)};
      };
      const auto block_depth = [&](const Vec3& p) {
        const auto [rho, l] = rl(p);
        return rho >= in ? std::min({-l, out - rho, l + b.rib_width}) : rho - in;
      };
      const double fwd = -solid_min(roller, [&](const Vec3& p) { return -block_depth(p); });
      const Vec3 e1 = std::fabs(axis.x) < 0.9 ? cross(axis, Vec3{1, 0, 0}) : cross(axis, Vec3{0, 1, 0});
      const Vec3 ex = e1 / norm(e1), ey = cross(axis, ex);
      const Vec3 rc = roller.base + roller.axis * (0.5 * roller.h) - c;
      const double phi = std::atan2(dot(rc, ey), dot(rc, ex));
      const auto block_point = [&](int patch, double u, double v) {
        const double a = phi + (u - 0.5) * 0.8;
        const Vec3 radial = ex * std::cos(a) + ey * std::sin(a);
        const double rho = patch == 0 || patch == 3 ? in + v * (out - in) : patch == 1 ? out : in;
        const double l = patch == 0 ? 0 : patch == 3 ? -b.rib_width : -v * b.rib_width;
        return c + n * l + radial * rho;
      };
      const double rev = -dense_min(4, block_point, roller_sd, 720, 60, false);
      return -std::max(fwd, rev);
    }
    case AssemblyPairKind::roller_cage: {
      const TriMesh& web = as.webs[as.web_offset[pa.bearing] + pair.feature].mesh;
      double best = kInf;
      // sd_roller is convex and constant along the roller's axis over a web face (a flat valley that
      // misleads grid refinement): a nested golden-section search over each triangle instead
      const auto golden = [](const std::function<double(double)>& f, double lo, double hi) {
        const double g = (std::sqrt(5.0) - 1) / 2;
        double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
        double best = std::min({f(lo), f(hi), f1, f2});
        for (int k = 0; k < 80; ++k) {
          if (f1 <= f2) b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
          else a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
          best = std::min({best, f1, f2});
        }
        return best;
      };
      for (const Tri& t : web.triangles) {
        const Vec3 a = ring.apply(web.positions[t[0]]), e1 = ring.apply(web.positions[t[1]]) - a,
                   e2 = ring.apply(web.positions[t[2]]) - a;
        best = std::min(best, golden([&](double u) {
          return golden([&](double v) { return roller_sd(a + e1 * u + e2 * v); }, 0.0, 1.0 - u);
        }, 0.0, 1.0));
      }
      if (best > 0 || pa.scarred) return best;  // apart (the Euclidean distance), or a scarred roller (one-sided)
      // two-sided (issue #27): the roller's deepest point in the convex web, whose depth is the
      // smallest distance to its face planes (from the posed mesh's triangles)
      const auto web_depth = [&](const Vec3& p) {
        double m = kInf;
        for (const Tri& t : web.triangles) {
          const Vec3 a = ring.apply(web.positions[t[0]]), b1 = ring.apply(web.positions[t[1]]),
                     c1 = ring.apply(web.positions[t[2]]);
          const Vec3 nn = cross(b1 - a, c1 - a);
          m = std::min(m, -dot(p - a, nn) / norm(nn));
        }
        return m;
      };
      const double fwd = -solid_min(roller, [&](const Vec3& p) { return -web_depth(p); });
      return std::min(best, -fwd);
    }
  }
  return kInf;
}

TEST(BearingAssemblyPairs, EverySolverAgainstADenseReference) {
  const Fixture f = lively(2);
  std::map<AssemblyPairKind, int> checked, clashes;
  double worst = 0;
  for (std::size_t frame = 0; frame < f.motion.poses.size(); ++frame)
    for (const AssemblyPair& pair : f.as.pairs) {
      const AssemblyPairResult r = solve_pair(f.as, pair, f.motion.poses[frame], f.as.spec.clearance);
      ASSERT_TRUE(std::isfinite(r.distance));
      const double ref = reference(f.as, pair, f.motion.poses[frame]);
      if (!std::isfinite(ref)) continue;
      SCOPED_TRACE(std::string(assembly_pair_kind_name(pair.kind)) + " " + f.as.parts[pair.a].id + " frame " +
                   std::to_string(frame));
      const bool split = f.as.parts[pair.a].scarred &&
                         (pair.kind == AssemblyPairKind::roller_rib || pair.kind == AssemblyPairKind::roller_cage);
      if (split) {
        // a scarred roller against a rib or web: split into intact ends and the middle's enclosing
        // cylinder, which for inward scars is the intact one: the value is the intact roller's,
        // exact (the ends decide) or flagged as a bound (the middle's)
        EXPECT_NEAR(r.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
        EXPECT_EQ(r.exact, !r.scar);
      } else if (r.scar) {
        // a scarred roller's mesh: the sampled reference is not below the exact minimum
        // (two-sided S <= the forward value <= any sample of it)
        EXPECT_LE(r.distance, ref + 1e-9);
        EXPECT_GE(r.distance, ref - 0.05);
      } else {
        EXPECT_TRUE(r.exact);
        if (r.distance < 0) EXPECT_TRUE(r.two_sided);  // every overlapping intact row (issue #27)
        EXPECT_NEAR(r.distance, ref, 1e-9 * std::max(1.0, std::fabs(ref)));
        worst = std::max(worst, std::fabs(r.distance - ref));
      }
      ++checked[pair.kind];
      if (r.verdict == Verdict::clash) ++clashes[pair.kind];
    }
  RecordProperty("max_abs_difference", std::to_string(worst));
  std::printf("[ assembly ] largest |solver - reference| %.3g over %d kinds\n", worst, static_cast<int>(checked.size()));
  EXPECT_EQ(checked.size(), 7u);  // every pair kind was checked
  // the motion presses parts together: raceway and cage pairs clash in some frames
  EXPECT_GT(clashes[AssemblyPairKind::roller_inner] + clashes[AssemblyPairKind::roller_cone], 0);
  EXPECT_GT(clashes[AssemblyPairKind::roller_cage], 0);
}

TEST(BearingAssemblyPairs, WitnessesAndVerdicts) {
  const Fixture f = lively(2);
  for (const AssemblyPair& pair : f.as.pairs) {
    const AssemblyPairResult r = solve_pair(f.as, pair, f.motion.poses[1], f.as.spec.clearance);
    SCOPED_TRACE(std::string(assembly_pair_kind_name(pair.kind)) + " " + f.as.parts[pair.a].id);
    ASSERT_TRUE(is_finite(r.point_a) && is_finite(r.point_b));
    if (r.exact && r.verdict != Verdict::undecided) {
      const double tol = 1e-9;
      if (r.distance < -tol) EXPECT_EQ(r.verdict, Verdict::clash);
      if (r.distance > tol && r.distance < f.as.spec.clearance) EXPECT_EQ(r.verdict, Verdict::clearance);
      if (r.distance >= f.as.spec.clearance) EXPECT_EQ(r.verdict, Verdict::clear);
      // the witnesses are |distance| apart (the raceway solvers measure radially or along the normal)
      EXPECT_NEAR(norm(r.point_a - r.point_b), std::fabs(r.distance), 1e-6 + 1e-6 * std::fabs(r.distance));
    }
  }
}

}  // namespace
}  // namespace interfere::bearing
