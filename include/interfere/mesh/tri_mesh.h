// TriMesh: positions + indexed triangles. Triangle i is input triangle i (readers keep input order, also
// through welding), so every index reported by a query is an index into the user's file.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/core/transform.h"
#include "interfere/core/vec.h"

namespace interfere {

using Tri = std::array<std::uint32_t, 3>;

struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<Tri> triangles;

  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  std::array<Vec3, 3> corners(std::size_t t) const {
    const Tri& f = triangles[t];
    return {positions[f[0]], positions[f[1]], positions[f[2]]};
  }
  Aabb triangle_box(std::size_t t) const {
    Aabb b;
    for (std::uint32_t v : triangles[t]) b.expand(positions[v]);
    return b;
  }
  Aabb bounds() const {
    Aabb b;
    for (const Vec3& p : positions) b.expand(p);
    return b;
  }
};

/// Returns a copy with every position mapped by `t` (in double).
TriMesh transformed(const TriMesh& mesh, const Transform& t);

/// The triangles `tris` of `mesh` (in that order) with only the vertices they use.
TriMesh submesh(const TriMesh& mesh, const std::vector<std::uint32_t>& tris);

}  // namespace interfere
