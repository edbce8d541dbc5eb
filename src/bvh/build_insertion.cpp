// (a) Incremental insertion, the reference tree (issue #2 source, §3): triangles are
// inserted one at a time; at every inner node the new triangle descends into the child whose box
// volume grows least when merged with it (ties: smaller surface-area growth, then fewer triangles
// below, which keeps duplicated triangles balanced, then the first child); the leaf it reaches
// becomes an inner node holding the old leaf and the new one. Leaves hold one triangle.
//
// Insertion order: a fixed pseudo-random permutation of the input (splitmix64-driven Fisher-Yates,
// seed 0). Goldsmith & Salmon (1987) already observed that insertion trees depend on the order; in
// input order, meshes that are generated or scanned strip by strip make every triangle land next to
// the previous one and the tree degenerates to depth O(n) (O(n^2) build). The permutation keeps the
// expected depth logarithmic and the result deterministic. Serial by nature.
#include <algorithm>
#include <cstdint>

#include "build_internal.h"

namespace interfere::detail {
namespace {

struct InsNode {
  AabbF box;
  std::int32_t child[2] = {-1, -1};  // inner node: both >= 0
  std::int32_t parent = -1;
  std::uint32_t prim = 0;    // leaf: triangle index
  std::uint32_t leaves = 1;  // triangles below (last tie-break: keeps duplicates balanced)
};

inline AabbF merged(const AabbF& a, const AabbF& b) {
  AabbF m = a;
  m.expand(b);
  return m;
}
inline double volume_d(const AabbF& b) {
  return (static_cast<double>(b.hi[0]) - b.lo[0]) * (static_cast<double>(b.hi[1]) - b.lo[1]) *
         (static_cast<double>(b.hi[2]) - b.lo[2]);
}
inline double half_area_d(const AabbF& b) {
  const double dx = static_cast<double>(b.hi[0]) - b.lo[0];
  const double dy = static_cast<double>(b.hi[1]) - b.lo[1];
  const double dz = static_cast<double>(b.hi[2]) - b.lo[2];
  return dx * dy + dy * dz + dz * dx;
}

std::uint64_t splitmix64(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

Bvh build_insertion(const TriMesh& mesh) {
  Bvh bvh;
  const std::size_t n = mesh.num_triangles();
  if (n == 0) return bvh;
  const Buffer<PrimRef> refs = make_prim_refs(mesh);

  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::uint64_t seed = 0;
  for (std::size_t i = n; i > 1; --i) {
    const std::size_t j = static_cast<std::size_t>(splitmix64(seed) % i);  // bias irrelevant here
    std::swap(order[i - 1], order[j]);
  }

  std::vector<InsNode> t;
  t.reserve(2 * n);
  std::int32_t root = -1;
  for (const std::uint32_t tri : order) {
    const AabbF& box = refs[tri].box;
    const auto leaf = static_cast<std::int32_t>(t.size());
    t.push_back({box, {-1, -1}, -1, tri, 1});
    if (root < 0) {
      root = leaf;
      continue;
    }
    std::int32_t cur = root;
    while (t[cur].child[0] >= 0) {
      t[cur].box.expand(box);
      const AabbF& b0 = t[t[cur].child[0]].box;
      const AabbF& b1 = t[t[cur].child[1]].box;
      const AabbF m0 = merged(b0, box), m1 = merged(b1, box);
      const double dv0 = volume_d(m0) - volume_d(b0), dv1 = volume_d(m1) - volume_d(b1);
      int pick = 0;
      if (dv1 < dv0) {
        pick = 1;
      } else if (dv1 == dv0) {
        const double da0 = half_area_d(m0) - half_area_d(b0),
                     da1 = half_area_d(m1) - half_area_d(b1);
        if (da1 < da0) {
          pick = 1;
        } else if (da1 == da0) {
          pick = t[t[cur].child[1]].leaves < t[t[cur].child[0]].leaves ? 1 : 0;
        }
      }
      ++t[cur].leaves;
      cur = t[cur].child[pick];
    }
    // cur is a leaf: replace it by an inner node holding (old leaf, new leaf).
    const auto inner = static_cast<std::int32_t>(t.size());
    const std::int32_t parent = t[cur].parent;
    t.push_back({merged(t[cur].box, box), {cur, leaf}, parent, 0, 2});
    if (parent < 0) {
      root = inner;
    } else {
      t[parent].child[t[parent].child[0] == cur ? 0 : 1] = inner;
    }
    t[cur].parent = inner;
    t[leaf].parent = inner;
  }

  // Flatten into the depth-first pair layout (explicit stack: the tree may be deep).
  bvh.nodes.resize(2 * n - 1);
  bvh.prims.reserve(n);
  bvh.prim_boxes.reserve(n);
  struct Item {
    std::int32_t src;
    std::uint32_t slot;
  };
  std::vector<Item> stack{{root, 0}};
  std::uint32_t next = 1;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const InsNode& s = t[it.src];
    BvhNode& d = bvh.nodes[it.slot];
    d.box = s.box;
    if (s.child[0] < 0) {
      d.first = static_cast<std::uint32_t>(bvh.prims.size());
      d.count = 1;
      bvh.prims.push_back(s.prim);
      bvh.prim_boxes.push_back(s.box);
    } else {
      d.first = next;
      d.count = 0;
      next += 2;
      // Depth-first: the first child's subtree is laid out before the second's.
      stack.push_back({s.child[1], d.first + 1});
      stack.push_back({s.child[0], d.first});
    }
  }
  return bvh;
}

}  // namespace interfere::detail
