// Mesh helpers of the simplifier (issue #6, item 5): exact-position welding (faces duplicated
// along B-Rep boundaries become one topological mesh), splitting back per face id (faces stay
// separable in the output), and regions of a plain mesh split at sharp edges (dihedral-angle
// feature mask) by union-find over the smooth manifold edges.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <utility>
#include <vector>

#include "interfere/simplify/qem.h"
#include "radix_sort.h"

namespace interfere {
namespace {
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
}  // namespace

// Positions are grouped by a 32-bit hash of their bits (-0.0 taken as 0.0, which compares equal),
// sorted stably by hash (parallel radix sort, so indices ascend within a hash), and compared
// exactly within each run of equal hashes: the representative of a group is its smallest index.
TriMesh weld_positions(const TriMesh& mesh, std::vector<std::uint32_t>* map) {
  const std::size_t nv = mesh.num_vertices();
  const auto& p = mesh.positions;
  struct Keyed {
    std::uint32_t hash, index;
  };
  std::vector<Keyed> order(nv), tmp;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 1 << 15), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::uint64_t h = 0x9e3779b97f4a7c15ull;
      for (double c : {p[i].x + 0.0, p[i].y + 0.0, p[i].z + 0.0}) {
        std::uint64_t bits;
        std::memcpy(&bits, &c, 8);
        h = (h ^ bits) * 0xff51afd7ed558ccdull;
        h ^= h >> 32;
      }
      order[i] = {static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(i)};
    }
  });
  radix_sort_u32(order, tmp, [](const Keyed& k) { return k.hash; });
  std::vector<std::uint32_t> rep(nv);
  for (std::size_t i = 0; i < nv;) {
    std::size_t j = i + 1;
    while (j < nv && order[j].hash == order[i].hash) ++j;
    if (j - i <= 16) {  // a collision or a few duplicates: pairwise
      for (std::size_t k = i; k < j; ++k) {
        const std::uint32_t v = order[k].index;
        rep[v] = v;
        for (std::size_t m = i; m < k; ++m)
          if (p[order[m].index] == p[v]) {
            rep[v] = rep[order[m].index];
            break;
          }
      }
    } else {  // many copies of one position: sorted by (position, index)
      std::sort(order.begin() + i, order.begin() + j, [&](const Keyed& a, const Keyed& b) {
        const Vec3 &u = p[a.index], &w = p[b.index];
        if (u.x != w.x) return u.x < w.x;
        if (u.y != w.y) return u.y < w.y;
        if (u.z != w.z) return u.z < w.z;
        return a.index < b.index;
      });
      for (std::size_t k = i; k < j; ++k) {
        const std::uint32_t v = order[k].index;
        rep[v] = k > i && p[order[k - 1].index] == p[v] ? rep[order[k - 1].index] : v;
      }
    }
    i = j;
  }
  TriMesh out;
  std::vector<std::uint32_t> id(nv, kNone);
  out.triangles.resize(mesh.num_triangles());
  out.positions.reserve(nv);
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tr = mesh.triangles[t];
    Tri& n = out.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t r = rep[tr[k]];
      if (id[r] == kNone) {
        id[r] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(p[r]);
      }
      n[k] = id[r];
    }
  }
  if (map) {
    map->assign(nv, kNone);
    for (std::size_t v = 0; v < nv; ++v) (*map)[v] = id[rep[v]];
  }
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
