// Scarred rollers against the rib and the cage web, two-sided (issue #27; src/bearing/
// scarred_rib_two_sided.h, scarred_web_two_sided.h; the web's test and reference below). A
// scarred roller's rib row measures A' = its intact end cylinders [0, z0] and [z1, L] and the scarred
// mesh between them (the end pieces decide when the row is exact). Rows flagged `two_sided` must
// equal, against a reference written here from the description:
//   overlapping: S = -max(fwd, rev) with
//     fwd = max over A' of the depth in the rib block {r_i <= rho <= r_o, -T <= l <= 0} (its meridian
//           rectangle's free edges: the face, the top and the back; rho = r_i joins the ring body),
//           by a dense grid refined around its best point on each end piece's side and end disk,
//           and the middle mesh's vertices and barycentric grids;
//     rev = max over the rib block of the depth in A', by a grid of rib points near the roller
//           (their depth in the end cylinder, whose ball stays in the end piece: asserted);
//   apart: the Euclidean distance of A' to the rib block, by the same dense search of the distance
//          to the meridian rectangle over A''s surface.
// The sampled fwd and rev are lower estimates of the true ones and the sampled distance an upper
// one. Asserted: the sampled rev never exceeds the row's depth (the ball argument); the row equals
// the reference to 1e-9 relative; no row is `clear` while a sampled point of A' lies in the rib or
// nearer than the clearance. The poses (tilts to 1.5 degrees, pushed up to 0.6 mm past the free
// axial play into either rib) also give rows the certificate must refuse: a witness on the rib's
// top edge, where the depth is not the reach below the face (counted; the sampled S there is
// shallower than the row: the row is not S).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>

#include "interfere/bearing/assembly.h"
#include "unit/bearing/scarred_reference.h"

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

/// The rib block of one rib in meridian coordinates: rho from the ring axis, l the height above the face.
struct RibRef {
  Vec3 centre, axis, normal;
  double ri = 0, ro = 0, thick = 0;
  void meridian(const Vec3& x, double& rho, double& l) const {
    const Vec3 w = x - centre;
    l = dot(w, normal);
    rho = norm(w - axis * dot(w, axis));
  }
  /// depth in the block (the smallest distance to the free edges' lines); < 0 outside
  double depth(const Vec3& x) const {
    double rho, l;
    meridian(x, rho, l);
    const double d = std::min({-l, ro - rho, thick + l});
    return rho < ri ? std::min(d, rho - ri) : d;
  }
  /// the distance to the block (its meridian rectangle [ri, ro] x [-thick, 0]), 0 inside
  double distance(const Vec3& x) const {
    double rho, l;
    meridian(x, rho, l);
    const double dr = std::max({ri - rho, rho - ro, 0.0}), dl = std::max({-thick - l, l, 0.0});
    return std::hypot(dr, dl);
  }
};

RibRef rib_of(const Assembly& as, const AssemblyPair& pair, const Transform& ring_pose) {
  const BearingSpec& b = as.spec.bearings[as.parts[pair.a].bearing];
  RibRef rib;
  rib.axis = ring_pose.rotate({0, 0, 1});
  const double h = 0.5 * b.inner_width - b.rib_width;  // the faces look inward, toward the rollers
  rib.centre = ring_pose.apply({0, 0, pair.feature == 0 ? -h : h});
  rib.normal = pair.feature == 0 ? rib.axis : rib.axis * -1.0;
  rib.ri = b.inner_raceway, rib.ro = b.inner_raceway + b.rib_height, rib.thick = b.rib_width;
  return rib;
}

/// The scarred roller as the rib rows see it: intact end cylinders [0, z0], [z1, L], the mesh between.
struct RollerRef {
  Vec3 base, axis, e1, e2;
  double R = 0, L = 0, z0 = 0, z1 = 0;
  Vec3 at(double z, double r, double angle) const {
    return base + axis * z + (e1 * std::cos(angle) + e2 * std::sin(angle)) * r;
  }
  double z_of(const Vec3& x) const { return dot(x - base, axis); }
  /// depth of q in the intact cylinder
  double cylinder_depth(const Vec3& q) const {
    const Vec3 w = q - base;
    const double z = dot(w, axis);
    return std::min({R - norm(w - axis * z), z, L - z});
  }
};

RollerRef roller_of(const Assembly& as, const AssemblyPair& pair, const Transform& pose) {
  const BearingSpec& b = as.spec.bearings[as.parts[pair.a].bearing];
  RollerRef r;
  r.base = pose.apply({0, 0, 0});
  r.axis = pose.rotate({0, 0, 1});
  r.e1 = pose.rotate({1, 0, 0}), r.e2 = pose.rotate({0, 1, 0});
  r.R = b.rollers.radius, r.L = b.rollers.length;
  const double lo = as.spec.scar.z_min < 0 ? 0.25 * r.L : as.spec.scar.z_min;
  const double hi = as.spec.scar.z_max < 0 ? 0.75 * r.L : as.spec.scar.z_max;
  r.z0 = std::clamp(lo, 0.0, r.L), r.z1 = std::clamp(hi, r.z0, r.L);
  return r;
}

/// The largest f over a patch (u, v) in [0, 1]^2: a grid, then twelve 41 x 41 grids, each five times
/// finer, around the best point.
double patch_max(const std::function<Vec3(double, double)>& at, const std::function<double(const Vec3&)>& f,
                 int nu = 360, int nv = 40, bool wrap = true) {
  double bu = 0, bv = 0, best = -kInf;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j)
      if (const double val = f(at(double(i) / nu, double(j) / nv)); val > best) best = val, bu = double(i) / nu, bv = double(j) / nv;
  double hu = 1.0 / nu, hv = 1.0 / nv;
  for (int level = 0; level < 12; ++level) {
    const double cu = bu, cv = bv;
    for (int i = -20; i <= 20; ++i)
      for (int j = -20; j <= 20; ++j) {
        // the angle wraps (wrap); the other coordinate is clamped
        const double uu = cu + hu * i / 20.0;
        const double u = wrap ? uu - std::floor(uu) : std::clamp(uu, 0.0, 1.0), v = std::clamp(cv + hv * j / 20.0, 0.0, 1.0);
        if (const double val = f(at(u, v)); val > best) best = val, bu = u, bv = v;
      }
    hu /= 5, hv /= 5;
  }
  return best;
}

/// The largest f over A''s surface: each end piece's side and end disk (dense, refined) and the
/// middle mesh (vertices and an 8-step barycentric grid of every side triangle, the parts between z0
/// and z1).
double roller_max(const RollerRef& r, const TriMesh& mesh, const std::vector<Vec3>& pos,
                  const std::function<double(const Vec3&)>& f) {
  double best = -kInf;
  const double a = 2 * kPi;
  if (r.z0 > 0) {
    best = std::max(best, patch_max([&](double u, double v) { return r.at(v * r.z0, r.R, a * u); }, f));
    best = std::max(best, patch_max([&](double u, double v) { return r.at(0, v * r.R, a * u); }, f));
  }
  if (r.z1 < r.L) {
    best = std::max(best, patch_max([&](double u, double v) { return r.at(r.z1 + v * (r.L - r.z1), r.R, a * u); }, f));
    best = std::max(best, patch_max([&](double u, double v) { return r.at(r.L, v * r.R, a * u); }, f));
  }
  const auto sample = [&](const Vec3& x) {
    if (const double z = r.z_of(x); z >= r.z0 && z <= r.z1) best = std::max(best, f(x));
  };
  constexpr int kGrid = 8;
  for (const Tri& t : mesh.triangles)
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; i + j <= kGrid; ++j)
        sample(pos[t[0]] + (pos[t[1]] - pos[t[0]]) * (double(i) / kGrid) + (pos[t[2]] - pos[t[0]]) * (double(j) / kGrid));
  return best;
}

/// Overlapping exact rows against the reference S = -max(fwd, rev): a certified row must equal it to
/// 1e-9 relative; a refused one is counted, and as not S when the reference is off it by > 1e-6.
struct OverlapStats {
  int overlapping = 0, certified = 0, refused = 0, refused_not_s = 0;
  double worst = 0, rev_ratio_max = 0;
  void record(const AssemblyPairResult& r, double fwd, double rev) {
    const double depth = -r.distance;
    if (depth > 0) rev_ratio_max = std::max(rev_ratio_max, rev / depth);
    const double ref = -std::max(fwd, rev);
    if (!r.two_sided) {
      ++refused;
      if (std::fabs(ref - r.distance) > 1e-6 * depth) ++refused_not_s;
      return;
    }
    ++certified;
    const double diff = test::relative_difference(ref, r.distance);
    worst = std::max(worst, diff);
    EXPECT_LE(diff, 1e-9) << "row " << r.distance << ", reference " << ref << " (fwd " << fwd << ", rev " << rev << ")";
  }
};

struct RibStats : OverlapStats {
  int apart_certified = 0, apart_refused = 0, bound = 0;
  double worst_apart = 0;
};

void check_rib_rows(const Assembly& as, test::SplitMix& rng, int rounds, RibStats& st) {
  for (int round = 0; round < rounds; ++round) {
    const std::vector<Transform> poses = test::random_poses(as, rng, 1.5, -0.04, 0.04, 1.6, 0.3);
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_rib || !as.parts[pair.a].scarred) continue;
      SCOPED_TRACE(as.parts[pair.a].id + " rib " + std::to_string(pair.feature) + " round " + std::to_string(round));
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      const RibRef rib = rib_of(as, pair, poses[pair.b]);
      const RollerRef roller = roller_of(as, pair, poses[pair.a]);
      const TriMesh& mesh = *as.parts[pair.a].mesh;
      const std::vector<Vec3> pos = test::posed_positions(mesh, poses[pair.a]);
      const double scale = rib.ro + norm(roller.base) + roller.L;
      // (each dense search only where a check needs it)
      const bool clear = r.verdict == Verdict::clear;
      const double fwd = r.distance <= 0 || clear ? roller_max(roller, mesh, pos, [&](const Vec3& x) { return rib.depth(x); }) : -kInf;
      const double near = r.distance > 0 || clear ? -roller_max(roller, mesh, pos, [&](const Vec3& x) { return -rib.distance(x); }) : kInf;
      // never a wrong clear: a sampled point of A' in the rib, or nearer than the clearance
      if (fwd > 1e-9 || near < as.spec.clearance) EXPECT_NE(r.verdict, Verdict::clear) << "fwd " << fwd << ", nearest " << near;
      if (!r.exact) {
        ++st.bound;
        EXPECT_FALSE(r.two_sided);
        continue;
      }
      if (r.distance > 0) {
        if (!r.two_sided) {
          ++st.apart_refused;
          continue;
        }
        ++st.apart_certified;
        const double diff = test::relative_difference(near, r.distance);
        st.worst_apart = std::max(st.worst_apart, diff);
        EXPECT_LE(diff, 1e-9) << "row " << r.distance << ", the Euclidean distance " << near;
        continue;
      }
      ++st.overlapping;
      const double depth = -r.distance;
      // rev: rib points near the roller's end (azimuth window of the roller, rho over the annulus,
      // l from the face down to a little past the row's depth), their depth in A'
      double rev = 0;
      const Vec3 m = roller.base + roller.axis * (0.5 * roller.L) - rib.centre;
      const Vec3 radial0 = (m - rib.axis * dot(m, rib.axis)) / norm(m - rib.axis * dot(m, rib.axis));
      const Vec3 tangent = cross(rib.axis, radial0);
      for (int ia = -30; ia <= 30; ++ia) {
        const double phi = ia * (16.0 / 30) * kPi / 180;
        const Vec3 radial = radial0 * std::cos(phi) + tangent * std::sin(phi);
        for (int ir = 0; ir <= 40; ++ir) {
          const double rho = rib.ri + (rib.ro - rib.ri) * ir / 40.0;
          for (int il = 0; il <= 8; ++il) {
            const double l = -(2 * depth + 1e-3) * il / 8.0;
            const Vec3 q = rib.centre + radial * rho + rib.normal * l;
            const double t = roller.cylinder_depth(q);
            if (!(t > 0)) continue;
            const double z = roller.z_of(q);
            ASSERT_TRUE(z + t <= roller.z0 || z - t >= roller.z1) << "a rib point's ball reaches the scar window";
            rev = std::max(rev, t);
          }
        }
      }
      EXPECT_LE(rev, depth + 1e-12 * scale) << "the rib reaches deeper into the roller than the row says";
      st.record(r, fwd, rev);
    }
  }
}

TEST(BearingScarredRibTwoSided, RowsAgainstADenseReference) {
  RibStats st;
  for (const bool raised : {false, true}) {
    const Assembly as = test::scarred_assembly(test::kCylindricalBearing, raised);
    test::SplitMix rng{raised ? 43u : 41u};
    check_rib_rows(as, rng, 10, st);
  }
  std::printf("rib: %d overlapping exact rows: %d certified (largest relative difference %.3g, sampled rev / depth <= "
              "%.4f), %d refused (%d of them off the reference by more than 1e-6: not S); apart: %d certified (largest "
              "relative difference %.3g), %d refused; %d bounds\n",
              st.overlapping, st.certified, st.worst, st.rev_ratio_max, st.refused, st.refused_not_s,
              st.apart_certified, st.worst_apart, st.apart_refused, st.bound);
  EXPECT_GT(st.certified, 10);
  EXPECT_GT(st.refused_not_s, 0);
  EXPECT_GT(st.apart_certified, 10);
}


// Scarred rollers against a cage web (src/bearing/scarred_web_two_sided.h): the web W is the posed
// web mesh (a convex hexahedron; its depth the smallest distance to its 12 triangles' planes). Rows
// flagged `two_sided` that overlap must equal S = -max(fwd, rev) of A' and W:
//   fwd = max over A' of the depth in W (roller_max above);
//   rev = max over W of the depth in A': each web triangle by a refined grid of the depth in the end
//         cylinders (pieces of A', cut faces counted: a lower estimate), and a coarse grid of the web
//         points in the scar window inside the mesh (ray parity) at their distance to the mesh.
// Poses push the rollers tangentially into the webs (tilts to 1 degree); inward scars (the
// certificate's usual case) and raised ones (the grown roller reaches deeper: most are refused).
/// The largest value of a concave f over the triangle a + e1 u + e2 v (u, v >= 0, u + v <= 1): golden-section
/// searches nested over u and v (an affine map; the partial maximum of a concave function is concave).
template <class F>
double triangle_max(const Vec3& a, const Vec3& e1, const Vec3& e2, const F& f) {
  const auto golden = [](const auto& g, double lo, double hi) {
    const double r = 0.5 * (std::sqrt(5.0) - 1);
    double a = lo, b = hi, x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = g(x1), f2 = g(x2);
    for (int it = 0; it < 90; ++it) {
      if (f1 < f2) a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = g(x2);
      else b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = g(x1);
    }
    return std::max({f1, f2, g(lo), g(hi)});
  };
  return golden([&](double u) { return golden([&](double v) { return f(a + e1 * u + e2 * v); }, 0.0, 1.0 - u); }, 0.0, 1.0);
}

struct WebStats : OverlapStats {
  int apart = 0, bound = 0;
};

void check_web_rows(const Assembly& as, test::SplitMix& rng, int rounds, WebStats& st) {
  for (int round = 0; round < rounds; ++round) {
    const std::vector<Transform> poses = test::random_poses(as, rng, 1.0, -0.04, 0.04, 0.5, 0.7);
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_cage || !as.parts[pair.a].scarred) continue;
      SCOPED_TRACE(as.parts[pair.a].id + " web " + std::to_string(pair.feature) + " round " + std::to_string(round));
      const AssemblyPairResult r = solve_pair(as, pair, poses, as.spec.clearance);
      const RollerRef roller = roller_of(as, pair, poses[pair.a]);
      const TriMesh& mesh = *as.parts[pair.a].mesh;
      const std::vector<Vec3> pos = test::posed_positions(mesh, poses[pair.a]);
      const TriMesh& web = as.webs[as.web_offset[as.parts[pair.a].bearing] + pair.feature].mesh;
      const std::vector<Vec3> wpos = test::posed_positions(web, poses[pair.b]);
      const auto web_depth = [&](const Vec3& x) {
        double d = kInf;
        for (const Tri& t : web.triangles) {
          const Vec3 n = cross(wpos[t[1]] - wpos[t[0]], wpos[t[2]] - wpos[t[0]]);
          d = std::min(d, dot(n, wpos[t[0]] - x) / norm(n));
        }
        return d;
      };
      if (r.distance > 0 || !r.exact) {
        r.exact ? ++st.apart : ++st.bound;
        if (r.verdict == Verdict::clear) {  // never a wrong clear: no sampled point of A' in the web
          const double fwd = roller_max(roller, mesh, pos, web_depth);
          EXPECT_LE(fwd, 0) << "a point of the roller lies in the web, verdict clear";
        }
        continue;
      }
      ++st.overlapping;
      const double depth = -r.distance;
      const double fwd = roller_max(roller, mesh, pos, web_depth);
      // rev: the depth in the end pieces (refined), and in the mesh's window (coarse)
      // (each piece's depth is concave: maximised over a web triangle by a nested golden-section search)
      const auto depth_e0 = [&](const Vec3& q) {
        const Vec3 w = q - roller.base;
        const double z = dot(w, roller.axis);
        return std::min({roller.R - norm(w - roller.axis * z), z, roller.z0 - z});
      };
      const auto depth_e1 = [&](const Vec3& q) {
        const Vec3 w = q - roller.base;
        const double z = dot(w, roller.axis);
        return std::min({roller.R - norm(w - roller.axis * z), z - roller.z1, roller.L - z});
      };
      double rev = -kInf;
      for (const Tri& t : web.triangles) {
        const Vec3 a = wpos[t[0]], e1 = wpos[t[1]] - a, e2 = wpos[t[2]] - a;
        const auto at = [&](double u, double v) { return a + e1 * u + e2 * (v * (1 - u)); };
        rev = std::max({rev, triangle_max(a, e1, e2, depth_e0), triangle_max(a, e1, e2, depth_e1)});
        constexpr int kCoarse = 40;
        for (int i = 0; i <= kCoarse; ++i)
          for (int j = 0; j <= kCoarse; ++j) {
            const Vec3 q = at(double(i) / kCoarse, double(j) / kCoarse);
            const double z = roller.z_of(q);
            if (!(z > roller.z0 && z < roller.z1) || roller.cylinder_depth(q) + as.parts[pair.a].roller->raise <= 0) continue;
            if (test::ref_inside(q, pos, mesh)) rev = std::max(rev, test::ref_point_mesh_distance(q, pos, mesh));
          }
      }
      const double scale = norm(roller.base) + roller.L + roller.R;
      if (r.two_sided) EXPECT_LE(rev, depth + 1e-12 * scale) << "the web reaches deeper into the roller than the row says";
      st.record(r, fwd, rev);
    }
  }
}

TEST(BearingScarredWebTwoSided, RowsAgainstADenseReference) {
  for (const bool raised : {false, true}) {
    WebStats st;
    const Assembly as = test::scarred_assembly(test::kCylindricalBearing, raised);
    test::SplitMix rng{raised ? 53u : 51u};
    check_web_rows(as, rng, raised ? 3 : 8, st);
    std::printf("web (%s scars): %d overlapping exact rows: %d certified (largest relative difference %.3g, sampled "
                "rev / depth <= %.4f), %d refused (%d of them off the reference by more than 1e-6: not S); %d apart, %d bounds\n",
                raised ? "raised" : "inward", st.overlapping, st.certified, st.worst, st.rev_ratio_max, st.refused,
                st.refused_not_s, st.apart, st.bound);
    if (!raised) {
      EXPECT_GT(st.certified, 10);
      EXPECT_GT(st.refused_not_s, 0);
    }
  }
}
}  // namespace
}  // namespace interfere::bearing
