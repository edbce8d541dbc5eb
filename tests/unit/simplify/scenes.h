// Test scenes of the simplifier shared by the unit and the CGAL oracle tests: inputs with
// intersections of their own (issue #6, item 6).
#pragma once
#include <cstdint>
#include <utility>

#include "interfere/mesh/generate.h"

namespace interfere::test {

/// The centre of the second sphere of crossing_spheres (radius 0.8; the first: unit, at the origin).
inline constexpr Vec3 kSecondCentre{0.9, 0.1, 0.05};

/// Two interpenetrating spheres in one mesh, `n` triangles each (about): the input intersects itself
/// along the circle where they cross.
inline TriMesh crossing_spheres(std::size_t n) {
  TriMesh m = make_sphere({.target_triangles = n});
  const TriMesh b = make_sphere({.target_triangles = n, .radius = 0.8, .center = kSecondCentre, .twist = 0.3});
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return m;
}

/// Two flat sheets of 8 x 8 and 13 x 13 cells tessellated apart, overlapping by 1e-6 along x = 1: a
/// crack, as in CAD exports whose face borders were meshed separately. The first 81 vertices are the
/// left sheet's.
inline TriMesh cracked_sheet() {
  TriMesh m;
  for (const auto& [n, x0] : {std::pair{8, 0.0}, std::pair{13, 1.0 - 1e-6}}) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.positions.push_back({x0 + double(i) / n, double(j) / n, 0});
    const auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
  }
  return m;
}

}  // namespace interfere::test
