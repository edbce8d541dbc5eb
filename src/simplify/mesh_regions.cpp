// Mesh helpers of the simplifier (issue #6, item 5): exact-position welding (the mesh module's
// weld_exact on a copy: faces duplicated along B-Rep boundaries become one topological mesh), splitting back per face id (faces stay
// separable in the output), and regions of a plain mesh split at sharp edges (dihedral-angle
// feature mask) by union-find over the smooth manifold edges.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <utility>
#include <vector>

#include "interfere/mesh/validate.h"
#include "interfere/simplify/qem.h"

namespace interfere {
namespace {
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
}  // namespace

TriMesh weld_positions(const TriMesh& mesh, std::vector<std::uint32_t>* map) {
  TriMesh out = mesh;
  weld_exact(out, map);
  return out;
}

TriMesh split_by_face(const TriMesh& mesh, const std::vector<std::uint32_t>& face_ids) {
  TriMesh out;
  out.triangles.resize(mesh.num_triangles());
  out.positions.reserve(mesh.num_vertices() + mesh.num_vertices() / 8);
  // (vertex, face) -> new index: the first face seen at a vertex in flat arrays, further faces (the
  // vertices on face boundaries) in a hash map. New ids in order of first use.
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint32_t> first_face(nv, kNone), first_id(nv, kNone);
  std::unordered_map<std::uint64_t, std::uint32_t> more;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const std::uint32_t f = face_ids.empty() ? 0 : face_ids[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      std::uint32_t id;
      if (first_id[v] == kNone) {
        first_face[v] = f;
        id = first_id[v] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
      } else if (first_face[v] == f) {
        id = first_id[v];
      } else {
        auto [it, fresh] = more.try_emplace((std::uint64_t{v} << 32) | f, static_cast<std::uint32_t>(out.positions.size()));
        if (fresh) out.positions.push_back(mesh.positions[v]);
        id = it->second;
      }
      out.triangles[t][k] = id;
    }
  }
  return out;
}

std::vector<std::uint32_t> sharp_edge_regions(const TriMesh& input, double angle_deg) {
  const TriMesh mesh = weld_positions(input);
  const std::size_t nt = mesh.num_triangles();
  // Edge -> triangles through sorted (min, max, tri) records.
  struct E {
    std::uint32_t a, b, t;
  };
  std::vector<E> edges;
  edges.reserve(nt * 3);
  for (std::uint32_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edges.push_back({a, b, t});
    }
  std::sort(edges.begin(), edges.end(),
            [](const E& x, const E& y) { return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.t < y.t); });
  std::vector<Vec3> normal(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto c = mesh.corners(t);
    const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
    const double l = norm(n);
    normal[t] = l > 0 ? n / l : Vec3{};
  }
  const double cos_limit = std::cos(angle_deg * std::numbers::pi / 180.0);
  // Union-find over smooth manifold edges.
  std::vector<std::uint32_t> parent(nt);
  for (std::uint32_t t = 0; t < nt; ++t) parent[t] = t;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    if (j - i == 2) {
      const std::uint32_t s = edges[i].t, t = edges[i + 1].t;
      if (dot(normal[s], normal[t]) >= cos_limit) {
        const std::uint32_t rs = find(s), rt = find(t);
        if (rs != rt) parent[std::max(rs, rt)] = std::min(rs, rt);
      }
    }
    i = j;
  }
  std::vector<std::uint32_t> id(nt, kNone), out(nt);
  std::uint32_t next = 0;
  for (std::uint32_t t = 0; t < nt; ++t) {
    const std::uint32_t r = find(t);
    if (id[r] == kNone) id[r] = next++;
    out[t] = id[r];
  }
  return out;
}

}  // namespace interfere
