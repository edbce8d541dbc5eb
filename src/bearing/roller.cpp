// Parametric rollers (Jia & Zheng 2019, §2.1, "bearing.parameters"); tapered rollers beyond the
// paper. Regular (angle x height) grid, outward triangles, fans on the end caps.
#include "interfere/bearing/roller.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace interfere::bearing {
namespace {
Error param_error(const std::string& prefix, const char* name, const std::string& what, double got) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", got);
  return Error{.reason = prefix + "." + name + " must be " + what + ", got " + buf};
}
}  // namespace

Status validate(const RollerParams& p, const std::string& prefix) {
  // lengths up to 1e9 (any unit): far beyond any bearing, and far from overflow in the solvers
  if (!(p.radius > 0 && p.radius <= 1e9)) return param_error(prefix, "radius", "> 0 (and <= 1e9)", p.radius);
  if (!(std::isfinite(p.top_radius) && (p.top_radius < 0 || (p.top_radius > 0 && p.top_radius <= 1e9))))
    return param_error(prefix, "top_radius", "> 0 and <= 1e9 (or negative for 'same as radius')", p.top_radius);
  if (!(p.height > 0 && p.height <= 1e9)) return param_error(prefix, "height", "> 0 (and <= 1e9)", p.height);
  if (p.radial_segments < 3 || p.radial_segments > 1 << 14)
    return param_error(prefix, "radial_segments", "in [3, 16384]", p.radial_segments);
  if (p.height_segments < 1 || p.height_segments > 1 << 14)
    return param_error(prefix, "height_segments", "in [1, 16384]", p.height_segments);
  return {};
}

double Roller::angle(int i) const { return 2.0 * std::numbers::pi * i / n(); }
double Roller::z(int j) const { return j == m() ? params.height : params.height * j / m(); }

void Roller::update_positions() {
  const int nn = n(), mm = m();
  raise = 0;
  for (const double d : displacement) raise = std::max(raise, -d);
  for (int j = 0; j <= mm; ++j) {
    const double zz = z(j);
    const double rr = params.radius_at(zz);
    for (int i = 0; i < nn; ++i) {
      const double a = angle(i);
      const double r = rr - displacement[side_vertex(i, j)];
      mesh.positions[side_vertex(i, j)] = {r * std::cos(a), r * std::sin(a), zz};
    }
  }
  mesh.positions[static_cast<std::size_t>(nn) * (mm + 1)] = {0, 0, 0};
  mesh.positions[static_cast<std::size_t>(nn) * (mm + 1) + 1] = {0, 0, params.height};
}

Expected<Roller> make_roller(const RollerParams& p) {
  if (Status s = validate(p); !s) return s.error();
  Roller r;
  r.params = p;
  const int n = p.radial_segments, m = p.height_segments;
  const std::size_t nv = static_cast<std::size_t>(n) * (m + 1);
  r.mesh.positions.resize(nv + 2);
  r.displacement.assign(nv, 0.0);
  r.scar.assign(nv, 0);
  r.update_positions();
  r.mesh.triangles.resize(static_cast<std::size_t>(2) * n * m + 2 * n);
  const auto v = [&](int i, int j) { return r.side_vertex(i, j); };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v00 = v(i, j), v10 = v(i + 1, j), v11 = v(i + 1, j + 1), v01 = v(i, j + 1);
      r.mesh.triangles[r.side_triangle(i, j)] = {v00, v10, v11};
      r.mesh.triangles[r.side_triangle(i, j) + 1] = {v00, v11, v01};
    }
  }
  const auto cb = static_cast<std::uint32_t>(nv), ct = static_cast<std::uint32_t>(nv + 1);
  for (int i = 0; i < n; ++i) {
    r.mesh.triangles[r.bottom_triangle(i)] = {cb, v(i + 1, 0), v(i, 0)};
    r.mesh.triangles[r.top_triangle(i)] = {ct, v(i, m), v(i + 1, m)};
  }
  return r;
}

Transform roller_pose(const Vec3& pivot, double tilt, double azimuth, double spin) {
  // Rodrigues rotation about k = (-sin az, cos az, 0) by tilt, times Rz(spin).
  const double kx = -std::sin(azimuth), ky = std::cos(azimuth);
  const double c = std::cos(tilt), s = std::sin(tilt), t = 1 - c;
  const double rt[3][3] = {{t * kx * kx + c, t * kx * ky, s * ky},
                           {t * kx * ky, t * ky * ky + c, -s * kx},
                           {-s * ky, s * kx, c}};
  const double cs = std::cos(spin), ss = std::sin(spin);
  Transform out;
  for (int r = 0; r < 3; ++r) {
    out.r[r][0] = rt[r][0] * cs + rt[r][1] * ss;
    out.r[r][1] = -rt[r][0] * ss + rt[r][1] * cs;
    out.r[r][2] = rt[r][2];
  }
  out.t = pivot;
  return out;
}

}  // namespace interfere::bearing
