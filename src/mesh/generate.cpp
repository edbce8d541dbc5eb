#include "interfere/mesh/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

namespace interfere {

TriMesh make_sphere(const SphereOptions& o) {
  // T = 2·lon·(lat-1) with lon = 2·lat  =>  lat ≈ sqrt(T/4).
  const auto lat = static_cast<std::uint32_t>(
      std::max(3.0, std::round(std::sqrt(static_cast<double>(o.target_triangles) / 4.0))));
  const std::uint32_t lon = 2 * lat;
  const double pi = std::numbers::pi;
  TriMesh m;
  m.positions.reserve(static_cast<std::size_t>(lon) * (lat - 1) + 2);
  auto radius_at = [&](double theta, double phi) {
    return o.radius * (1.0 + o.bump_amplitude * std::sin(o.bump_frequency * theta) *
                                 std::sin(o.bump_frequency * phi));
  };
  m.positions.push_back(o.center + Vec3{0, 0, o.radius});  // north pole
  for (std::uint32_t i = 1; i < lat; ++i) {
    const double theta = pi * i / lat;
    for (std::uint32_t j = 0; j < lon; ++j) {
      const double phi = 2 * pi * j / lon + o.twist;
      const double r = radius_at(theta, phi);
      m.positions.push_back(o.center + Vec3{r * std::sin(theta) * std::cos(phi),
                                            r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
    }
  }
  const auto south = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back(o.center + Vec3{0, 0, -o.radius});
  auto ring = [&](std::uint32_t i, std::uint32_t j) { return 1 + (i - 1) * lon + (j % lon); };
  m.triangles.reserve(2 * static_cast<std::size_t>(lon) * (lat - 1));
  for (std::uint32_t j = 0; j < lon; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (std::uint32_t i = 1; i + 1 < lat; ++i) {
    for (std::uint32_t j = 0; j < lon; ++j) {
      const std::uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a, d, b});
    }
  }
  for (std::uint32_t j = 0; j < lon; ++j) m.triangles.push_back({south, ring(lat - 1, j + 1), ring(lat - 1, j)});
  return m;
}

TriMesh make_fan_prism(int n, double r, double h) {
  TriMesh m;
  for (double z : {0.0, h})
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      m.positions.push_back({r * std::cos(a), r * std::sin(a), z});
    }
  const auto un = static_cast<std::uint32_t>(n), c0 = 2 * un, c1 = c0 + 1;
  m.positions.push_back({0, 0, 0});
  m.positions.push_back({0, 0, h});
  for (std::uint32_t i = 0; i < un; ++i) {
    const std::uint32_t j = (i + 1) % un;
    m.triangles.push_back({i, j, un + j});
    m.triangles.push_back({i, un + j, un + i});
    m.triangles.push_back({c0, j, i});
    m.triangles.push_back({c1, un + i, un + j});
  }
  return m;
}

TriMesh make_box(const Vec3& lo, const Vec3& hi, int n) {
  n = std::max(1, n);
  TriMesh m;
  // Six faces, each an n×n grid; shared boundary vertices are merged by exact position afterwards,
  // which is exact here because every face computes a corner from the same lo/hi values.
  auto lerp = [&](int axis, int k) {
    return k == 0 ? lo[axis] : (k == n ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * k / n);
  };
  std::vector<Vec3> pos;
  std::vector<Tri> tris;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = static_cast<std::uint32_t>(pos.size());
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          Vec3 p;
          p[axis] = side ? hi[axis] : lo[axis];
          p[u] = lerp(u, i);
          p[v] = lerp(v, j);
          pos.push_back(p);
        }
      }
      auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(i * (n + 1) + j); };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          // (u, v, axis) is right-handed, so u×v points along +axis: CCW in (u,v) faces +axis.
          if (side) {
            tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
          } else {
            tris.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
            tris.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
          }
        }
      }
    }
  }
  // Merge duplicates along the cube's edges (exact equality of coordinates).
  std::map<std::array<double, 3>, std::uint32_t> index;
  std::vector<std::uint32_t> remap(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const auto [it, inserted] = index.try_emplace({pos[i].x, pos[i].y, pos[i].z},
                                                  static_cast<std::uint32_t>(m.positions.size()));
    if (inserted) m.positions.push_back(pos[i]);
    remap[i] = it->second;
  }
  for (Tri t : tris) m.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return m;
}

SpherePair make_overlapping_spheres(std::size_t triangles_per_part) {
  SpherePair p;
  p.a = make_sphere({.target_triangles = triangles_per_part, .radius = 1.0, .center = {0, 0, 0},
                     .bump_amplitude = 0.01, .bump_frequency = 9, .twist = 0.0});
  p.b = make_sphere({.target_triangles = triangles_per_part, .radius = 1.0, .center = {1.96, 0, 0},
                     .bump_amplitude = 0.01, .bump_frequency = 11, .twist = 0.123});
  return p;
}

}  // namespace interfere
