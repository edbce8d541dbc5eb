#include "interfere/mesh/tri_mesh.h"

#include <unordered_map>
#include <utility>

namespace interfere {

TriMesh transformed(const TriMesh& mesh, const Transform& t) {
  TriMesh out;
  out.triangles = mesh.triangles;
  // A mirroring pose (det R < 0) turns every triangle's winding around: swap two corners so that an
  // outward-oriented solid stays outward (its signed volume keeps its sign; issue #23, item 8).
  if (t.determinant_sign() < 0)
    for (Tri& f : out.triangles) std::swap(f[1], f[2]);
  out.positions.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) out.positions.push_back(t.apply(p));
  return out;
}

TriMesh submesh(const TriMesh& mesh, const std::vector<std::uint32_t>& tris) {
  TriMesh out;
  std::unordered_map<std::uint32_t, std::uint32_t> remap;
  out.triangles.reserve(tris.size());
  for (std::uint32_t t : tris) {
    Tri f{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      const auto [it, inserted] = remap.try_emplace(v, static_cast<std::uint32_t>(out.positions.size()));
      if (inserted) out.positions.push_back(mesh.positions[v]);
      f[k] = it->second;
    }
    out.triangles.push_back(f);
  }
  return out;
}

}  // namespace interfere
