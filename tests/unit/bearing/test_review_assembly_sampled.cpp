// Review (issue #27, helper H6): the assembly rows that this session's speed-ups and certificates
// touch (roller-inner by intact_row_distance, the scarred solver's leaf records and cut, the scarred
// rib rows' two-sided flag, the cage web's skips) against an oracle written here, of a different
// method: the roller's surface sampled point by point (the scarred roller's mesh: vertices and a
// barycentric grid of every triangle; an intact roller's side and end disks on a grid refined
// around its best point) and each point's exact distance to the partner solid in its meridian
// half-plane (raceway cylinder, the other roller's intact cylinder, the rib block's rectangle).
// Every sample is a point of the roller (a scarred mesh lies in the solids its rows measure: the
// intact end cylinders hold the mesh's inscribed ends), so its distance is at least the solids'
// distance: a row reporting a clearance d > 0 must have no sample nearer than d (less rounding);
// a clear row must have none nearer than the clearance. Rows that claim the Euclidean distance
// (exact, two_sided, d > 0) of an intact roller must also be reached by the refined samples.
// Adversarial motions: axes parallel to rounding (tilt 0, 1e-12 deg) and at 1.5 degrees, rollers
// pushed into the ribs (axial play 4) and against each other (pocket play 4), a heavy load, a
// bearing at 1e6 mm on a skew axis, a raised scar and scars across the angle 0 / 2 pi.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <array>

#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

/// The distance from (rho, z) to the rectangle [r0, r1] x [z0, z1] of a meridian half-plane (0 inside).
double rect_distance(double rho, double z, double r0, double r1, double z0, double z1) {
  const double dr = std::max({r0 - rho, rho - r1, 0.0}), dz = std::max({z0 - z, z - z1, 0.0});
  return std::hypot(dr, dz);
}

/// (rho, z) of x about the line through o with unit direction u: rho from |w|^2 - z^2 would cancel
/// near the axis, so from the component across u directly.
void meridian(const Vec3& x, const Vec3& o, const Vec3& u, double& rho, double& z) {
  const Vec3 w = x - o;
  z = dot(w, u);
  rho = norm(w - u * z);
}

struct Partner {
  enum Kind { cylinder, rib } kind = cylinder;
  Vec3 o, u;  // cylinder: base and axis; rib: face centre and the normal out of the rib
  double r0 = 0, r1 = 0, z0 = 0, z1 = 0;
  double distance(const Vec3& x) const {
    double rho, z;
    meridian(x, o, u, rho, z);
    return rect_distance(rho, z, r0, r1, z0, z1);
  }
};

/// The roller's surface, sampled; `f` gets every sample.
void sample_roller(const AssemblyPart& part, const BearingSpec& b, const Transform& pose,
                   const std::function<void(const Vec3&)>& f) {
  if (part.scarred) {
    const TriMesh& m = *part.mesh;
    std::vector<Vec3> p(m.positions.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = pose.apply(m.positions[i]);
    for (const Vec3& x : p) f(x);
    constexpr int k = 4;
    for (const Tri& t : m.triangles)
      for (int i = 0; i <= k; ++i)
        for (int j = 0; i + j <= k; ++j)
          f(p[t[0]] + (p[t[1]] - p[t[0]]) * (double(i) / k) + (p[t[2]] - p[t[0]]) * (double(j) / k));
    return;
  }
  const double R = b.rollers.radius, L = b.rollers.length;
  const auto at = [&](double z, double r, double a) { return pose.apply({r * std::cos(a), r * std::sin(a), z}); };
  const auto patch = [&](const std::function<Vec3(double, double)>& g) {
    for (int i = 0; i < 720; ++i)
      for (int j = 0; j <= 40; ++j) f(g(i / 720.0, j / 40.0));
  };
  patch([&](double u, double v) { return at(v * L, R, 2 * kPi * u); });
  patch([&](double u, double v) { return at(0, v * R, 2 * kPi * u); });
  patch([&](double u, double v) { return at(L, v * R, 2 * kPi * u); });
}

/// An intact roller's smallest distance to the partner: the grid, then refined (10 levels of 41 x 41,
/// five times finer each) around the best point of each of its three patches.
double refined_intact(const BearingSpec& b, const Transform& pose, const Partner& q) {
  const double R = b.rollers.radius, L = b.rollers.length;
  const auto at = [&](double z, double r, double a) { return pose.apply({r * std::cos(a), r * std::sin(a), z}); };
  double best = kInf;
  const std::function<Vec3(double, double)> patches[3] = {
      [&](double u, double v) { return at(v * L, R, 2 * kPi * u); },
      [&](double u, double v) { return at(0, v * R, 2 * kPi * u); },
      [&](double u, double v) { return at(L, v * R, 2 * kPi * u); }};
  for (const auto& g : patches) {
    double bu = 0, bv = 0, pb = kInf;
    for (int i = 0; i < 720; ++i)
      for (int j = 0; j <= 40; ++j)
        if (const double d = q.distance(g(i / 720.0, j / 40.0)); d < pb) pb = d, bu = i / 720.0, bv = j / 40.0;
    double hu = 1 / 720.0, hv = 1 / 40.0;
    for (int level = 0; level < 10; ++level) {
      const double cu = bu, cv = bv;
      for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j) {
          const double u = cu + hu * i / 20.0, v = std::clamp(cv + hv * j / 20.0, 0.0, 1.0);
          if (const double d = q.distance(g(u, v)); d < pb) pb = d, bu = u, bv = v;
        }
      hu /= 5, hv /= 5;
    }
    best = std::min(best, pb);
  }
  return best;
}

/// The two-sided depth of an overlapping rib or web row, sampled (ring_two_sided.h: S = -max(fwd,
/// rev), fwd = max over the roller of the depth in the partner, rev = max over the partner of the
/// depth in the roller). The roller A' (a scarred roller's rows: its intact end cylinders [0, z0],
/// [z1, L] and the mesh between; an intact roller: its cylinder): fwd from its end pieces' surfaces and
/// its mesh's points; rev from a grid of partner points, each point's depth in A' bounded below by
/// its depth in an end piece (a ball in the piece is in A'). Both samples are at most the true
/// values, so a row claiming S = v needs max(fwd, rev) <= -v (less rounding).
double sampled_depth(const AssemblyPart& part, const BearingSpec& b, const ScarParams& scar, const Transform& pose,
                     const std::function<double(const Vec3&)>& depth_in_partner,
                     const std::function<void(const std::function<void(const Vec3&)>&)>& partner_points) {
  const double R = b.rollers.radius, L = b.rollers.length;
  double z0 = L, z1 = L;  // intact: one piece [0, L]
  if (part.scarred) {
    const double lo = scar.z_min < 0 ? 0.25 * L : scar.z_min, hi = scar.z_max < 0 ? 0.75 * L : scar.z_max;
    z0 = std::clamp(lo, 0.0, L), z1 = std::clamp(hi, z0, L);
  }
  const auto at = [&](double z, double r, double a) { return pose.apply({r * std::cos(a), r * std::sin(a), z}); };
  double fwd = 0;
  const auto piece = [&](double za, double zb) {
    if (!(zb > za)) return;
    for (int i = 0; i < 720; ++i) {
      const double a = 2 * kPi * i / 720;
      for (int j = 0; j <= 60; ++j) fwd = std::max(fwd, depth_in_partner(at(za + (zb - za) * j / 60.0, R, a)));
      for (int j = 0; j <= 40; ++j) {
        fwd = std::max(fwd, depth_in_partner(at(za, R * j / 40.0, a)));
        fwd = std::max(fwd, depth_in_partner(at(zb, R * j / 40.0, a)));
      }
    }
  };
  piece(0, z0);
  piece(z1, L);
  if (part.scarred)
    sample_roller(part, b, pose, [&](const Vec3& x) {
      const double z = dot(x - pose.t, pose.rotate({0, 0, 1}));
      if (z >= z0 && z <= z1) fwd = std::max(fwd, depth_in_partner(x));
    });
  double rev = 0;
  const Vec3 u = pose.rotate({0, 0, 1});
  partner_points([&](const Vec3& q) {
    double rho, z;
    meridian(q, pose.t, u, rho, z);
    for (const auto& [za, zb] : {std::pair{0.0, z0}, std::pair{z1, L}})
      if (zb > za && rho <= R && z >= za && z <= zb) rev = std::max(rev, std::min({R - rho, z - za, zb - z}));
  });
  return std::max(fwd, rev);
}

struct Tally {
  int rows = 0, apart = 0, euclid = 0, clear = 0, overlap_two_sided = 0;
  int annulus = 0, annulus_nearer = 0, annulus_clear_within = 0;  // rib rows measured over the annulus
  double worst_gap = 0;
  double depth_gap = 0;  // the overlapping two-sided rows' largest (-row - sampled depth)
  int scarred_overlap = 0;  // their largest (row - sampled Euclidean distance)
};

void check_scene(const std::string& text, int frames, Tally& tally) {
  SCOPED_TRACE(text.substr(0, 400));
  const Expected<AssemblySpec> spec = parse_assembly(text, "review");
  ASSERT_TRUE(spec.has_value()) << spec.error().message();
  const Expected<Assembly> as = build_assembly(*spec);
  ASSERT_TRUE(as.has_value()) << as.error().message();
  const AssemblyMotion motion = generate_motion(*as, frames, spec->seed);
  for (int f = 0; f < frames; ++f)
    for (const AssemblyPair& pair : as->pairs) {
      const AssemblyPart& ra = as->parts[pair.a];
      const AssemblyPart& pb = as->parts[pair.b];
      const BearingSpec& b = as->spec.bearings[ra.bearing];
      const Transform& pose_a = motion.poses[f][pair.a];
      const Transform& pose_b = motion.poses[f][pair.b];
      Partner q;
      if (pair.kind == AssemblyPairKind::roller_inner) {
        const Cylinder& race = as->geometry[ra.bearing].raceway;
        q.o = pose_b.apply(race.base), q.u = pose_b.rotate(race.axis);
        q.r1 = race.radius, q.z1 = race.height;
      } else if (pair.kind == AssemblyPairKind::roller_roller && !pb.scarred) {
        q.o = pose_b.t, q.u = pose_b.rotate({0, 0, 1});
        q.r1 = b.rollers.radius, q.z1 = b.rollers.length;
      } else if (pair.kind == AssemblyPairKind::roller_rib) {
        const double zf = pair.feature == 0 ? -0.5 * b.inner_width + b.rib_width : 0.5 * b.inner_width - b.rib_width;
        q.o = pose_b.apply({0, 0, zf});
        q.u = pair.feature == 0 ? pose_b.rotate({0, 0, 1}) : pose_b.rotate({0, 0, -1});
        q.kind = Partner::rib;
        q.r0 = b.inner_raceway, q.r1 = b.inner_raceway + b.rib_height, q.z0 = -b.rib_width, q.z1 = 0;
      } else if (pair.kind != AssemblyPairKind::roller_cage) {
        continue;
      }
      if (b.rollers.top_radius >= 0 && b.rollers.top_radius != b.rollers.radius) continue;
      const AssemblyPairResult r = solve_pair(*as, pair, motion.poses[f], spec->clearance);
      ++tally.rows;
      if (r.distance <= 0 && r.exact && r.two_sided &&
          (pair.kind == AssemblyPairKind::roller_rib || pair.kind == AssemblyPairKind::roller_cage)) {
        ++tally.overlap_two_sided;
        std::function<double(const Vec3&)> depth;
        std::function<void(const std::function<void(const Vec3&)>&)> points;
        std::array<Vec3, 6> n;
        std::array<double, 6> d;
        if (pair.kind == AssemblyPairKind::roller_rib) {
          depth = [&](const Vec3& x) {  // the rib block's free edges: face, top, back (rho = r_i joins the ring)
            double rho, l;
            meridian(x, q.o, q.u, rho, l);
            return rho < q.r0 ? -kInf : std::min({-l, q.r1 - rho, l - q.z0});
          };
          points = [&](const std::function<void(const Vec3&)>& g) {  // the block near the roller
            const Vec3 e1 = pose_b.rotate({1, 0, 0}), e2 = pose_b.rotate({0, 1, 0});
            const Vec3 c = pose_a.apply({0, 0, 0.5 * b.rollers.length});
            const double a0 = std::atan2(dot(c - q.o, e2), dot(c - q.o, e1));
            for (int i = -150; i <= 150; ++i)
              for (int j = 0; j <= 40; ++j)
                for (int k = 0; k <= 30; ++k) {
                  const double a = a0 + i * 0.12 / 150, rho = q.r0 + (q.r1 - q.r0) * j / 40.0, l = q.z0 * k / 30.0;
                  g(q.o + (e1 * std::cos(a) + e2 * std::sin(a)) * rho + q.u * l);
                }
          };
        } else {
          const CageWeb& w = as->geometry[ra.bearing].webs[static_cast<std::size_t>(pair.feature)];
          for (int j = 0; j < 6; ++j) n[j] = pose_b.rotate(w.normals[j]), d[j] = w.offsets[j] + dot(n[j], pose_b.t);
          depth = [&](const Vec3& x) {  // a convex hexahedron: the nearest face plane
            double v = kInf;
            for (int j = 0; j < 6; ++j) v = std::min(v, d[j] - dot(n[j], x));
            return v;
          };
          points = [&](const std::function<void(const Vec3&)>& g) {  // trilinear grid of the corners
            std::array<Vec3, 8> c;
            for (int i = 0; i < 8; ++i) c[i] = pose_b.apply(w.corners[i]);
            constexpr int m = 40;
            for (int i = 0; i <= m; ++i)
              for (int j = 0; j <= m; ++j)
                for (int k = 0; k <= m; ++k) {
                  const double x = double(i) / m, y = double(j) / m, z = double(k) / m;
                  g(c[0] * ((1 - x) * (1 - y) * (1 - z)) + c[1] * (x * (1 - y) * (1 - z)) + c[2] * (x * y * (1 - z)) +
                    c[3] * ((1 - x) * y * (1 - z)) + c[4] * ((1 - x) * (1 - y) * z) + c[5] * (x * (1 - y) * z) +
                    c[6] * (x * y * z) + c[7] * ((1 - x) * y * z));
                }
          };
        }
        const double deepest = sampled_depth(ra, b, as->spec.scar, pose_a, depth, points);
        tally.depth_gap = std::max(tally.depth_gap, -r.distance - deepest);  // (the samples reach the row: small)
        tally.scarred_overlap += ra.scarred ? 1 : 0;
        EXPECT_LE(deepest, -r.distance + 1e-9 * (1 + std::fabs(r.distance)))
            << assembly_pair_kind_name(pair.kind) << (ra.scarred ? " scarred" : "") << " frame " << f << ": row "
            << r.distance << " (two-sided) but a sampled depth " << deepest;
      }
      if (pair.kind == AssemblyPairKind::roller_cage || !(r.distance > 0)) continue;
      ++tally.apart;
      // nearest: the Euclidean distance of the samples; lowest: for the rib, the smallest height over
      // the face plane of the samples over the annulus (the rib rows' clearance: "over the annulus",
      // assembly.h, where not two-sided)
      double nearest = kInf, lowest = kInf;
      sample_roller(ra, b, pose_a, [&](const Vec3& x) {
        nearest = std::min(nearest, q.distance(x));
        if (q.kind == Partner::rib) {
          double rho, l;
          meridian(x, q.o, q.u, rho, l);
          if (rho >= q.r0 && rho <= q.r1) lowest = std::min(lowest, l);
        }
      });
      const double scale = 1 + std::max({std::fabs(pose_a.t.x), std::fabs(pose_a.t.y), std::fabs(pose_a.t.z)}) +
                           b.rollers.length + q.r1;
      const double slack = 1e-12 * scale;
      const std::string what = std::string(assembly_pair_kind_name(pair.kind)) + (ra.scarred ? " scarred" : "") +
                               " frame " + std::to_string(f) + " pair " + std::to_string(&pair - as->pairs.data());
      // no sampled point of the roller nearer than the row's clearance (the rib's, where not
      // two-sided: none lower over the annulus)
      const bool annulus = q.kind == Partner::rib && !r.two_sided;
      if (annulus) {
        ++tally.annulus;
        EXPECT_GE(lowest, r.distance - slack) << what << ": row " << r.distance << " lowest " << lowest;
        if (nearest < r.distance - slack) ++tally.annulus_nearer, tally.worst_gap = std::max(tally.worst_gap, r.distance - nearest);
        if (nearest <= spec->clearance && r.verdict == Verdict::clear) ++tally.annulus_clear_within;
      }
      if (!annulus) {
        EXPECT_GE(nearest, r.distance - slack) << what << ": row " << r.distance << " sample " << nearest
                                             << " solver " << assembly_solver_name(r.solver) << " exact " << r.exact
                                             << " two_sided " << r.two_sided;
      }
      if (r.verdict == Verdict::clear) {  // (rib rows over the annulus too: their verdict is the
        ++tally.clear;                      // Euclidean distance's bracket, rib_euclid_bound.h)
        EXPECT_GT(nearest, spec->clearance) << what;
      }
      if (r.exact && r.two_sided && !ra.scarred) {  // the Euclidean distance: reached by the samples
        ++tally.euclid;
        const double refined = refined_intact(b, pose_a, q);
        EXPECT_LE(refined, r.distance + 1e-9 * (1 + r.distance) + slack) << what << ": row " << r.distance
                                                                          << " refined " << refined;
      }
    }
}

void report(const Tally& t) {
  std::printf("rows %d, overlapping two-sided rib/web %d, apart %d (clear %d), Euclidean intact %d; rib over the annulus %d: %d nearer by the samples "
              "(by up to %.3g), %d clear within the clearance; overlapping: %d scarred, sampled depth short by <= %.3g\n",
              t.rows, t.overlap_two_sided, t.apart, t.clear, t.euclid, t.annulus, t.annulus_nearer, t.worst_gap, t.annulus_clear_within,
              t.scarred_overlap, t.depth_gap);
}

std::string bearing(const std::string& position, const std::string& axis) {
  return R"({"id": "b", "type": "cylindrical", "position": )" + position + R"(, "axis": )" + axis + R"(,
      "inner_ring": {"bore_radius": 95, "raceway_radius": 110, "width": 50, "rib": {"height": 4, "width": 5}},
      "outer_ring": {"raceway_radius": 130.1, "outer_radius": 145, "width": 50},
      "rollers": {"count": 32, "radius": 10, "length": 38, "pitch_radius": 120.05},
      "cage": {"pocket_clearance": 0.3, "web_thickness": 8}})";
}

std::string scene(double tilt, double load, double axial, double pocket, const std::string& scar,
                  const std::string& position = "[0, 0, 0]", const std::string& axis = "[1, 0, 0]") {
  char motion[400];
  std::snprintf(motion, sizeof motion,
                R"("seed": 3, "clearance": 0.05, "motion": {"inner_deg_per_frame": 11, "max_tilt_deg": %.17g,
                "load": {"displacement": %.17g}, "pocket_play": %.17g, "axial_play": %.17g},)",
                tilt, load, pocket, axial);
  return std::string("{") + motion + R"("scar": )" + scar + R"(, "bearings": [)" + bearing(position, axis) + "]}";
}

constexpr const char* kWrapScar = R"({"fraction": 0.5, "angle_width_deg": 350, "seed": 5})";
constexpr const char* kZeroScar = R"({"fraction": 0.5, "angle_center_deg": 0, "angle_width_deg": 40, "depth": 0.05, "seed": 9})";
constexpr const char* kRaisedScar = R"({"fraction": 0.5, "angle_width_deg": 120, "depth": 0.03, "raised": true, "seed": 2})";

TEST(ReviewAssemblySampled, NoRowNearerThanItsRollersSamplesParallelAxes) {
  Tally t;
  check_scene(scene(0, 0.08, 1.02, 1.2, kWrapScar), 2, t);
  check_scene(scene(1e-12, 0.3, 4, 1.2, kZeroScar), 2, t);
  report(t);
  EXPECT_GT(t.euclid, 20);
}

TEST(ReviewAssemblySampled, NoRowNearerThanItsRollersSamplesTiltsAndPlay) {
  Tally t;
  check_scene(scene(1.5, 0.6, 4, 4, kWrapScar), 2, t);
  check_scene(scene(0.05, 0.08, 1.02, 1.2, kRaisedScar), 2, t);
  report(t);
  EXPECT_GT(t.euclid, 20);
}

TEST(ReviewAssemblySampled, NoRowNearerThanItsRollersSamplesFarAndSkew) {
  Tally t;
  check_scene(scene(0.05, 0.3, 4, 1.2, kZeroScar, "[1000000, -1000000, 1000000]", "[1, 1, 1]"), 2, t);
  check_scene(scene(1e-9, 0.08, 1.02, 4, kRaisedScar, "[1000000, 0, 0]", "[0, 0, 1]"), 2, t);
  report(t);
  EXPECT_GT(t.euclid, 20);
}

}  // namespace
}  // namespace interfere::bearing
