// Dense references for the scarred rollers' two-sided rows (issue #27; test_scarred_two_sided_*.cpp),
// written here independently of the solvers: random poses around the rest poses, the closest point
// on a triangle and between segments (Ericson 2005, §5.1.5 and §5.1.9, re-derived here), the
// distance of two disjoint triangles (the smallest of the 6 corner-triangle and 9 edge-edge
// distances), ray parity against a closed mesh (Moller-Trumbore crossings), and the distance from a
// point to a mesh by every triangle.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "interfere/bearing/assembly.h"
#include "unit/bearing/assembly_fixture.h"
#include "unit/bearing/splitmix.h"

namespace interfere::bearing::test {

/// One frame of `bearing` with every roller scarred (350 degrees wide, 0.08 deep; raised or inward).
inline Assembly scarred_assembly(const std::string& bearing, bool raised) {
  const std::string extra =
      std::string(R"("frames": 1, "seed": 3, "clearance": 0.05, "scar": {"fraction": 1, "angle_width_deg": 350, "depth": 0.08, "seed": 9)") +
      (raised ? R"(, "raised": true)" : "") + "},";
  Expected<AssemblySpec> s = parse_assembly(assembly_json(extra, bearing), "t.json");
  EXPECT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  EXPECT_TRUE(built) << built.error().message();
  return std::move(*built);
}

inline std::array<std::array<double, 3>, 3> rot_about(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  return {{{c + k.x * k.x * v, k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s},
           {k.y * k.x * v + k.z * s, c + k.y * k.y * v, k.y * k.z * v - k.x * s},
           {k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v}}};
}

/// Every roller of `as` moved from its rest pose: tilted up to `tilt_deg` about an axis across it,
/// spun, shifted radially (from the ring axis) by [r0, r1], along its axis by +-`axial`,
/// tangentially by +-`tangential`.
inline std::vector<Transform> random_poses(const Assembly& as, SplitMix& rng, double tilt_deg, double r0, double r1,
                                           double axial, double tangential) {
  std::vector<Transform> poses;
  for (const AssemblyPart& p : as.parts) poses.push_back(p.rest);
  for (std::size_t i = 0; i < as.parts.size(); ++i) {
    if (as.parts[i].kind != PartKind::roller) continue;
    const BearingSpec& b = as.spec.bearings[as.parts[i].bearing];
    const Vec3 ring_axis = as.geometry[as.parts[i].bearing].frame.rotate({0, 0, 1});
    const Vec3 centre = as.geometry[as.parts[i].bearing].frame.t;
    const Transform& p0 = as.parts[i].rest;
    const Vec3 u = p0.rotate({0, 0, 1}), mid = p0.apply({0, 0, 0.5 * b.rollers.length});
    Vec3 radial = (mid - centre) - ring_axis * dot(mid - centre, ring_axis);
    radial = radial / norm(radial);
    const Vec3 t = cross(ring_axis, radial);
    const double a = rng.in(0, 2 * std::numbers::pi);
    const auto tilt = rot_about(t * std::cos(a) + radial * std::sin(a), rng.in(0, tilt_deg) * std::numbers::pi / 180);
    const auto spin = rot_about(u, rng.in(0, 2 * std::numbers::pi));
    std::array<std::array<double, 3>, 3> rot{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) rot[r][c] = tilt[r][0] * spin[0][c] + tilt[r][1] * spin[1][c] + tilt[r][2] * spin[2][c];
    const Vec3 shift = radial * rng.in(r0, r1) + u * rng.in(-axial, axial) + t * rng.in(-tangential, tangential);
    Transform q;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) q.r[r][c] = rot[r][0] * p0.r[0][c] + rot[r][1] * p0.r[1][c] + rot[r][2] * p0.r[2][c];
    const Vec3 off = p0.t - mid;
    q.t = mid + shift + Vec3{rot[0][0] * off.x + rot[0][1] * off.y + rot[0][2] * off.z,
                             rot[1][0] * off.x + rot[1][1] * off.y + rot[1][2] * off.z,
                             rot[2][0] * off.x + rot[2][1] * off.y + rot[2][2] * off.z};
    poses[i] = q;
  }
  return poses;
}

/// The posed corners of a mesh.
inline std::vector<Vec3> posed_positions(const TriMesh& m, const Transform& pose) {
  std::vector<Vec3> out;
  out.reserve(m.positions.size());
  for (const Vec3& v : m.positions) out.push_back(pose.apply(v));
  return out;
}

/// Closest point of triangle abc to p: the minimum of a convex quadratic over the triangle, found by
/// the region of p (vertex, edge or face), each region's closed form.
inline Vec3 ref_closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double den = 1 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

/// Squared distance of segments p1q1 and p2q2 (clamped parameters of the infinite lines' closest points).
inline double ref_segment_d2(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return dot(r, r);
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), den = a * e - b * b;
      s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  const Vec3 w = (p1 + d1 * s) - (p2 + d2 * t);
  return dot(w, w);
}

/// Distance of two triangles that do not intersect.
inline double ref_triangle_distance(const std::array<Vec3, 3>& x, const std::array<Vec3, 3>& y) {
  double d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const Vec3 px = ref_closest_on_triangle(x[i], y[0], y[1], y[2]);
    d2 = std::min(d2, dot(px - x[i], px - x[i]));
    const Vec3 py = ref_closest_on_triangle(y[i], x[0], x[1], x[2]);
    d2 = std::min(d2, dot(py - y[i], py - y[i]));
    for (int j = 0; j < 3; ++j) d2 = std::min(d2, ref_segment_d2(x[i], x[(i + 1) % 3], y[j], y[(j + 1) % 3]));
  }
  return std::sqrt(d2);
}

/// Distance from p to the surface of a posed mesh (every triangle).
inline double ref_point_mesh_distance(const Vec3& p, const std::vector<Vec3>& pos, const TriMesh& m) {
  double d2 = std::numeric_limits<double>::infinity();
  for (const Tri& t : m.triangles) {
    const Vec3 c = ref_closest_on_triangle(p, pos[t[0]], pos[t[1]], pos[t[2]]);
    d2 = std::min(d2, dot(c - p, c - p));
  }
  return std::sqrt(d2);
}

/// Ray parity of p against a closed posed mesh along an oblique direction `dir` (Moller-Trumbore):
/// true inside.
inline bool ref_inside(const Vec3& p, const std::vector<Vec3>& pos, const TriMesh& m,
                       const Vec3& dir = {0.5773, 0.6112, 0.5413}) {
  const Vec3 d = dir / norm(dir);
  int crossings = 0;
  for (const Tri& t : m.triangles) {
    const Vec3 a = pos[t[0]], e1 = pos[t[1]] - a, e2 = pos[t[2]] - a;
    const Vec3 h = cross(d, e2);
    const double det = dot(e1, h);
    if (det == 0) continue;
    const double f = 1 / det;
    const Vec3 s = p - a;
    const double u = f * dot(s, h);
    if (u < 0 || u > 1) continue;
    const Vec3 q = cross(s, e1);
    const double v = f * dot(d, q);
    if (v < 0 || u + v > 1) continue;
    if (f * dot(e2, q) > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

/// Distance of two posed closed meshes whose surfaces do not meet: the smallest triangle-triangle
/// distance over all pairs (pairs whose bounding spheres are farther than the best found skipped).
inline double ref_mesh_distance(const TriMesh& ma, const std::vector<Vec3>& pa, const TriMesh& mb, const std::vector<Vec3>& pb) {
  struct Sphere {
    Vec3 c;
    double r;
  };
  const auto spheres = [](const TriMesh& m, const std::vector<Vec3>& p) {
    std::vector<Sphere> s;
    for (const Tri& t : m.triangles) {
      const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3.0;
      s.push_back({c, std::max({norm(p[t[0]] - c), norm(p[t[1]] - c), norm(p[t[2]] - c)})});
    }
    return s;
  };
  const std::vector<Sphere> sa = spheres(ma, pa), sb = spheres(mb, pb);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ma.triangles.size(); ++i)
    for (std::size_t j = 0; j < mb.triangles.size(); ++j) {
      if (norm(sa[i].c - sb[j].c) - sa[i].r - sb[j].r > best) continue;
      const Tri& x = ma.triangles[i];
      const Tri& y = mb.triangles[j];
      best = std::min(best, ref_triangle_distance({pa[x[0]], pa[x[1]], pa[x[2]]}, {pb[y[0]], pb[y[1]], pb[y[2]]}));
    }
  return best;
}

inline double relative_difference(double a, double b) {
  const double m = std::max(std::fabs(a), std::fabs(b));
  return m == 0 ? 0 : std::fabs(a - b) / m;
}

}  // namespace interfere::bearing::test
