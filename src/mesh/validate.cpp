// weld_exact: hash-partitioned exact welding on the canonical position bits (weld_internal.h); the
// representative of a class is its lowest vertex index, so the result does not depend on the thread
// count. Renumbering in order of first use is one sequential pass over the triangles.
//
// mesh_stats: edges and sorted triangles are bucketed by their smallest vertex (a counting sort,
// CSR layout), each small bucket is sorted on its own; components by union-find.
#include "interfere/mesh/validate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "interfere/core/predicates.h"
#include "weld_internal.h"

namespace interfere {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::uint64_t canonical_bits(double d) {
  const auto b = std::bit_cast<std::uint64_t>(d);
  return b == 0x8000000000000000ull ? 0 : b;  // -0.0 == +0.0
}

/// Counting sort of (bucket, value) pairs into CSR: begin[b]..begin[b+1] holds bucket b's values.
struct Buckets {
  std::vector<std::size_t> begin;
  std::vector<std::uint64_t> values;
};

template <class Emit>
Buckets bucketize(std::size_t num_buckets, const Emit& emit) {
  Buckets b;
  b.begin.assign(num_buckets + 1, 0);
  emit([&](std::uint32_t bucket, std::uint64_t) { ++b.begin[bucket + 1]; });
  std::partial_sum(b.begin.begin(), b.begin.end(), b.begin.begin());
  b.values.resize(b.begin.back());
  std::vector<std::size_t> cursor(b.begin.begin(), b.begin.end() - 1);
  emit([&](std::uint32_t bucket, std::uint64_t v) { b.values[cursor[bucket]++] = v; });
  return b;
}

}  // namespace

std::size_t weld_exact(TriMesh& mesh, std::vector<std::uint32_t>* map) {
  if (map) map->clear();
  const std::size_t nv = mesh.positions.size();
  if (nv > kNone) return 0;
  for (const Tri& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) return 0;
  }
  weld_detail::ScratchBuffer<std::uint32_t> rep(nv);
  const std::vector<Vec3>& pos = mesh.positions;
  weld_detail::representatives<weld_detail::Key64>(
      nv,
      [&](std::size_t i, weld_detail::Key64& k) {
        k = {canonical_bits(pos[i].x), canonical_bits(pos[i].y), canonical_bits(pos[i].z)};
      },
      rep.data());
  std::vector<std::uint32_t> id(nv, kNone);
  std::uint32_t next = 0;
  for (Tri& t : mesh.triangles) {
    for (std::uint32_t& v : t) {
      std::uint32_t& r = id[rep[v]];
      if (r == kNone) r = next++;
      v = r;
    }
  }
  std::vector<Vec3> positions(next);
  for (std::size_t v = 0; v < nv; ++v) {
    if (rep[v] == v && id[v] != kNone) positions[id[v]] = mesh.positions[v];
  }
  mesh.positions = std::move(positions);
  if (map) {
    map->resize(nv);
    for (std::size_t v = 0; v < nv; ++v) (*map)[v] = id[rep[v]];
  }
  return nv - next;
}

MeshStats mesh_stats(const TriMesh& mesh) {
  MeshStats s;
  const std::size_t nv = mesh.positions.size();
  const std::size_t nt = mesh.triangles.size();
  s.vertices = nv;
  s.triangles = nt;
  if (nt == 0) return s;
  const auto& tris = mesh.triangles;
  auto valid = [&](const Tri& t) { return t[0] < nv && t[1] < nv && t[2] < nv; };
  auto repeated = [](const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; };

  // Invalid and degenerate triangles (exact collinearity), in parallel.
  struct Counts {
    std::size_t invalid = 0, degenerate = 0;
  };
  const Counts c = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nt, 1 << 14), Counts{},
      [&](const tbb::blocked_range<std::size_t>& r, Counts acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Tri& t = tris[i];
          if (!valid(t)) {
            ++acc.invalid;
          } else if (repeated(t) ||
                     collinear(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]])) {
            ++acc.degenerate;
          }
        }
        return acc;
      },
      [](Counts a, const Counts& b) {
        a.invalid += b.invalid, a.degenerate += b.degenerate;
        return a;
      });
  s.invalid_triangles = c.invalid;
  s.degenerate_triangles = c.degenerate;

  // Edges bucketed by their smaller vertex; value = (larger vertex << 1) | (1 if directed
  // larger->smaller).
  {
    const Buckets edges = bucketize(nv, [&](const auto& put) {
      for (const Tri& t : tris) {
        if (!valid(t) || repeated(t)) continue;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t a = t[static_cast<std::size_t>(k)],
                              b = t[static_cast<std::size_t>((k + 1) % 3)];
          put(std::min(a, b), (std::uint64_t{std::max(a, b)} << 1) | (a > b ? 1u : 0u));
        }
      }
    });
    struct EdgeCounts {
      std::size_t open = 0, nonmanifold = 0, inconsistent = 0;
    };
    const EdgeCounts e = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, nv, 1 << 12), EdgeCounts{},
        [&](const tbb::blocked_range<std::size_t>& r, EdgeCounts acc) {
          std::vector<std::uint64_t> scratch;
          for (std::size_t v = r.begin(); v != r.end(); ++v) {
            const std::size_t lo = edges.begin[v], hi = edges.begin[v + 1];
            if (lo == hi) continue;
            scratch.assign(edges.values.begin() + static_cast<std::ptrdiff_t>(lo),
                           edges.values.begin() + static_cast<std::ptrdiff_t>(hi));
            std::sort(scratch.begin(), scratch.end());
            for (std::size_t i = 0; i < scratch.size();) {
              std::size_t j = i + 1;
              while (j < scratch.size() && (scratch[j] >> 1) == (scratch[i] >> 1)) ++j;
              const std::size_t uses = j - i;
              if (uses == 1) {
                ++acc.open;
              } else if (uses > 2) {
                ++acc.nonmanifold;
              } else if (scratch[i] == scratch[i + 1]) {
                ++acc.inconsistent;  // both triangles run along the edge in the same direction
              }
              i = j;
            }
          }
          return acc;
        },
        [](EdgeCounts a, const EdgeCounts& b) {
          a.open += b.open, a.nonmanifold += b.nonmanifold, a.inconsistent += b.inconsistent;
          return a;
        });
    s.open_edges = e.open;
    s.nonmanifold_edges = e.nonmanifold;
    s.inconsistent_edges = e.inconsistent;
  }

  // Duplicates: triangles bucketed by their smallest vertex, value = (middle << 32) | largest.
  {
    const Buckets sorted = bucketize(nv, [&](const auto& put) {
      for (const Tri& t : tris) {
        if (!valid(t)) continue;
        Tri u = t;
        std::sort(u.begin(), u.end());
        put(u[0], (std::uint64_t{u[1]} << 32) | u[2]);
      }
    });
    s.duplicate_triangles = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, nv, 1 << 12), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t acc) {
          std::vector<std::uint64_t> scratch;
          for (std::size_t v = r.begin(); v != r.end(); ++v) {
            const std::size_t lo = sorted.begin[v], hi = sorted.begin[v + 1];
            if (hi - lo < 2) continue;
            scratch.assign(sorted.values.begin() + static_cast<std::ptrdiff_t>(lo),
                           sorted.values.begin() + static_cast<std::ptrdiff_t>(hi));
            std::sort(scratch.begin(), scratch.end());
            for (std::size_t i = 1; i < scratch.size(); ++i) acc += scratch[i] == scratch[i - 1];
          }
          return acc;
        },
        std::plus<>());
  }

  // Components: union-find over the vertices of valid triangles (link to the smaller root, path
  // halving).
  {
    std::vector<std::uint32_t> parent(nv);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<std::uint8_t> used(nv, 0);
    auto find = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    auto unite = [&](std::uint32_t a, std::uint32_t b) {
      a = find(a), b = find(b);
      if (a != b) (a < b ? parent[b] : parent[a]) = std::min(a, b);
    };
    for (const Tri& t : tris) {
      if (!valid(t)) continue;
      used[t[0]] = used[t[1]] = used[t[2]] = 1;
      unite(t[0], t[1]);
      unite(t[0], t[2]);
    }
    for (std::size_t v = 0; v < nv; ++v) s.components += used[v] && parent[v] == v;
  }
  return s;
}

std::vector<std::uint32_t> connected_sets(const TriMesh& mesh, const std::vector<char>& keep) {
  const auto nt = static_cast<std::uint32_t>(mesh.num_triangles());
  constexpr std::uint32_t kNone = 0xffffffffu;
  // Union-find over the triangles through the first kept triangle seen at each vertex; each root
  // is the smallest triangle index of its set.
  std::vector<std::uint32_t> parent(nt), at_vertex(mesh.num_vertices(), kNone);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (!keep[t]) continue;
    for (std::uint32_t v : mesh.triangles[t]) {
      if (at_vertex[v] == kNone) {
        at_vertex[v] = t;
        continue;
      }
      const std::uint32_t x = find(t), y = find(at_vertex[v]);
      parent[std::max(x, y)] = std::min(x, y);
    }
  }
  for (std::uint32_t t = 0; t < nt; ++t) parent[t] = find(t);
  return parent;
}

}  // namespace interfere
