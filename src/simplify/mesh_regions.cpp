// Mesh helpers of the simplifier (issue #6, item 5): exact-position welding (faces duplicated
// along B-Rep boundaries become one topological mesh), splitting back per face id (faces stay
// separable in the output), and regions of a plain mesh split at sharp edges (dihedral-angle
// feature mask) by union-find over the smooth manifold edges.
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "interfere/simplify/qem.h"

namespace interfere {
namespace {
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
}  // namespace

TriMesh weld_positions(const TriMesh& mesh, std::vector<std::uint32_t>* map) {
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint32_t> order(nv);
  for (std::uint32_t i = 0; i < nv; ++i) order[i] = i;
  const auto& p = mesh.positions;
  // A strict total order (ties broken by index): the parallel sort's result is unique.
  tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (p[a].x != p[b].x) return p[a].x < p[b].x;
    if (p[a].y != p[b].y) return p[a].y < p[b].y;
    if (p[a].z != p[b].z) return p[a].z < p[b].z;
    return a < b;
  });
  // Representative: the smallest index of each group; new ids in order of first use.
  std::vector<std::uint32_t> rep(nv);
  for (std::size_t i = 0; i < nv;) {
    std::size_t j = i;
    while (j < nv && p[order[j]] == p[order[i]]) ++j;
    for (std::size_t k = i; k < j; ++k) rep[order[k]] = order[i];
    i = j;
  }
  TriMesh out;
  std::vector<std::uint32_t> id(nv, kNone);
  out.triangles.reserve(mesh.num_triangles());
  for (const Tri& t : mesh.triangles) {
    Tri n;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t r = rep[t[k]];
      if (id[r] == kNone) {
        id[r] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(p[r]);
      }
      n[k] = id[r];
    }
    out.triangles.push_back(n);
  }
  if (map) {
    map->assign(nv, kNone);
    for (std::size_t v = 0; v < nv; ++v) (*map)[v] = id[rep[v]];
  }
  return out;
}

TriMesh split_by_face(const TriMesh& mesh, const std::vector<std::uint32_t>& face_ids) {
  TriMesh out;
  out.triangles.reserve(mesh.num_triangles());
  // (vertex, face) -> new index, through a per-vertex list (few faces per vertex).
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> copies(mesh.num_vertices());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const std::uint32_t f = face_ids.empty() ? 0 : face_ids[t];
    Tri n;
    for (int k = 0; k < 3; ++k) {
      auto& list = copies[mesh.triangles[t][k]];
      std::uint32_t id = kNone;
      for (const auto& [face, idx] : list)
        if (face == f) id = idx;
      if (id == kNone) {
        id = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[mesh.triangles[t][k]]);
        list.emplace_back(f, id);
      }
      n[k] = id;
    }
    out.triangles.push_back(n);
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
