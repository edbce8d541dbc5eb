// Imported scars from a point cloud (issue #27): per side vertex, the inverse-distance-weighted
// mean (Shepard 1968, weights 1/d^2) of the radial deviations of the measured points within a
// window on the unrolled nominal surface; the reader of "x y z" text files and of meshes (their
// vertices).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "scar_number.h"
#include "interfere/bearing/scar_import.h"
#include "interfere/mesh/io.h"

namespace interfere::bearing {
using detail::scar_number;

Expected<VertexHeights> scar_from_points(const std::vector<Vec3>& points,
                                         const RollerParams& roller,
                                         const PointScarOptions& options,
                                         const std::string& source) {
  if (Status s = validate(roller); !s) return s.error();
  if (points.empty()) return Error{.file = source, .reason = "the scar point cloud has no point"};
  const int n = roller.radial_segments, m = roller.height_segments;
  const double rmax = std::max(roller.radius, roller.top()), h = roller.height;
  const double col = 2 * std::numbers::pi / n, dz = h / m;
  if (!(std::isfinite(options.window) && options.window >= 0))
    return Error{
        .file = source,
        .reason = "the point window must be >= 0 (0 = automatic), got " + scar_number(options.window)};
  const double w = options.window > 0 ? options.window : std::hypot(rmax * col, dz);
  const double exact = 1e-12 * (rmax + h);
  // each point: angle, z, deviation; bucketed by grid column and ring for the window search
  struct P {
    double phi, z, dev;
  };
  std::vector<P> ps;
  ps.reserve(points.size());
  const int nbz = m + 1;
  std::vector<std::vector<std::uint32_t>> bucket(static_cast<std::size_t>(n) * nbz);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3& p = points[k];
    const auto where = [&] {
      return "point " + std::to_string(k) + " (" + scar_number(p.x) + ", " + scar_number(p.y) + ", " + scar_number(p.z) +
             ")";
    };
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      return Error{.file = source, .reason = where() + ": a coordinate is not finite"};
    if (p.z < -w || p.z > h + w) continue;  // beyond every vertex's window
    const double rho = std::hypot(p.x, p.y);
    const double r = roller.radius_at(std::clamp(p.z, 0.0, h));
    if (!(rho > 0))
      return Error{.file = source,
                   .reason = where() + ": on the roller's axis (its angle is undefined)"};
    double phi = std::atan2(p.y, p.x);
    if (phi < 0) phi += 2 * std::numbers::pi;
    ps.push_back({phi, p.z, rho - r});
    const int bi = std::clamp(static_cast<int>(phi / col), 0, n - 1);
    const int bj = std::clamp(static_cast<int>(std::floor(p.z / dz + 0.5)), 0, m);
    bucket[static_cast<std::size_t>(bj) * n + bi].push_back(
        static_cast<std::uint32_t>(ps.size() - 1));
  }
  VertexHeights out;
  out.n = n, out.m = m, out.source = source;
  const std::size_t nv = static_cast<std::size_t>(n) * (m + 1);
  out.height.assign(nv, 0.0);
  out.covered.assign(nv, 0);
  const int reach_z = static_cast<int>(std::ceil(w / dz)) + 1;
  for (int j = 0; j <= m; ++j) {
    const double zv = j == m ? h : h * j / m;
    const double rv = roller.radius_at(zv);
    // columns within the window at this ring's radius (the whole ring when it spans it)
    const double reach_angle = w / rv;
    const double reach_cols = std::ceil(reach_angle / col) + 1;
    const bool all_columns = 2 * reach_cols + 1 >= n;
    const int reach_i = all_columns ? 0 : static_cast<int>(reach_cols);
    for (int i = 0; i < n; ++i) {
      const double phv = col * i;
      double wsum = 0, vsum = 0, esum = 0;
      int exact_count = 0;
      for (int bj = std::max(0, j - reach_z); bj <= std::min(m, j + reach_z); ++bj) {
        // each bucket column once: all of them, or i - reach_i .. i + reach_i (fewer than n)
        const int lo = all_columns ? 0 : i - reach_i, hi = all_columns ? n - 1 : i + reach_i;
        for (int c = lo; c <= hi; ++c) {
          const int bi = (c % n + n) % n;
          for (const std::uint32_t q : bucket[static_cast<std::size_t>(bj) * n + bi]) {
            const P& p = ps[q];
            const double da = std::remainder(p.phi - phv, 2 * std::numbers::pi);
            const double d = std::hypot(rv * da, p.z - zv);
            if (d > w) continue;
            if (d <= exact) {
              esum += p.dev, ++exact_count;
            } else {
              const double wt = 1.0 / (d * d);
              wsum += wt, vsum += wt * p.dev;
            }
          }
        }
      }
      const std::size_t v = static_cast<std::size_t>(j) * n + i;
      if (exact_count > 0) {
        out.height[v] = esum / exact_count, out.covered[v] = 1;
      } else if (wsum > 0) {
        out.height[v] = vsum / wsum, out.covered[v] = 1;
      }
      if (out.covered[v] && !(rv + out.height[v] > 0))
        return Error{.file = source,
                     .reason = "vertex (" + std::to_string(i) + ", " + std::to_string(j) +
                               ") at angle " + scar_number(360.0 * i / n) + " deg, z " + scar_number(zv) +
                               ": the points' deviation " + scar_number(out.height[v]) +
                               " would take the surface to or through the axis (radius " + scar_number(rv) +
                               ")"};
    }
  }
  if (out.covered_count() == 0)
    return Error{
        .file = source,
        .reason = "no point lies within the window (" + scar_number(w) +
                  " mm) of a vertex of the roller: are the "
                  "points in the roller's body frame (axis +z from the bottom end centre)?"};
  return out;
}

Expected<std::vector<Vec3>> read_scar_points(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".stl" || ext == ".ply" || ext == ".obj" || ext == ".off") {
    Expected<TriMesh> mesh = read_mesh(path);
    if (!mesh) return mesh.error();
    return std::move(mesh->positions);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path, .reason = "cannot open the scar point file"};
  std::vector<Vec3> pts;
  std::string line;
  std::int64_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ss(line);
    std::string tok;
    double v[3];
    int count = 0;
    while (ss >> tok) {
      if (count == 3)
        return Error{.file = path, .line = line_no, .reason = "expected 3 numbers x y z, got more"};
      char* end = nullptr;
      errno = 0;
      const double d = std::strtod(tok.c_str(), &end);
      if (end != tok.c_str() + tok.size() || !std::isfinite(d) || errno == ERANGE)
        return Error{.file = path,
                     .line = line_no,
                     .reason = "field " + std::to_string(count + 1) + ": '" + tok +
                               "' is not a finite number"};
      v[count++] = d;
    }
    if (count != 3)
      return Error{.file = path,
                   .line = line_no,
                   .reason = "expected 3 numbers x y z, got " + std::to_string(count)};
    pts.push_back({v[0], v[1], v[2]});
  }
  if (in.bad()) return Error{.file = path, .reason = "cannot read the scar point file"};
  if (pts.empty()) return Error{.file = path, .reason = "the scar point file has no point"};
  return pts;
}

}  // namespace interfere::bearing
