// Bounding-volume hierarchy over triangle boxes (issue #2, item 3). A plain struct: builders are
// free functions returning it (after madmann91/bvh v2); traversals live in bvh/traverse.h.
#pragma once
#include <cstdint>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {

/// 32-byte node. Inner node: count == 0, children are nodes[first] and nodes[first + 1].
/// Leaf: prims[first .. first + count) are the triangle indices it holds.
struct BvhNode {
  AabbF box;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32);

/// Layout guaranteed by every builder: nodes[0] is the root; children are stored after their parent
/// (a node's descendants follow it depth-first: its child pair, then the first child's descendants,
/// then the second's), so a reverse sweep visits children before parents. Every node box contains
/// its children's boxes; every leaf box contains its triangles' boxes; every triangle box contains
/// the triangle's double corners (boxes are rounded outward to float).
struct Bvh {
  std::vector<BvhNode> nodes;        ///< nodes[0] is the root (when not empty)
  std::vector<std::uint32_t> prims;  ///< triangle indices referenced by leaves
  std::vector<AabbF> prim_boxes;     ///< prim_boxes[i] is the float box of triangle prims[i]
  bool empty() const { return nodes.empty(); }
};

/// Builders. All five produce the layout above, are deterministic (bit-identical trees for any
/// thread count) and never fail; they differ in speed and tree quality. Measured on make_sphere,
/// 10^6 triangles, 2 cores (numbers in src/bvh/build.cpp): lbvh builds 5-6x faster than binned_sah
/// and its tree-vs-tree queries visit 5-40 % more node pairs, which costs microseconds per query
/// next to tens of milliseconds of build, hence the default.
enum class BvhBuilder {
  /// (a) Incremental insertion as in the paper (issue #2 source, §3): each triangle descends into
  /// the
  /// child whose merged volume grows least; leaves hold one triangle. Triangles are inserted in a
  /// fixed pseudo-random order (input order degenerates to depth O(n) on strip-ordered meshes).
  /// Serial, O(n log n) expected; the reference, not a production builder.
  insertion,
  /// (b) Top-down split of the longest axis at the median: the paper's "optimised" tree.
  median_split,
  /// (c) Binned SAH (Wald 2007), parallel with oneTBB: the best trees (fewest node pairs visited by
  /// tree-vs-tree queries), the slowest top-down build. For trees built once and queried very
  /// often.
  binned_sah,
  /// Default. Linear BVH (Karras 2012): parallel radix sort of 30-bit Morton codes, split at the
  /// highest differing bit; >= 30 M triangles/s on 2 threads at 10^6 triangles.
  lbvh,
  /// The lbvh tree, then `treelet_passes` passes of treelet restructuring (Karras & Aila 2013):
  /// bottom-up, the treelet of up to 7 subtrees below every inner node gets its SAH-optimal
  /// topology (dynamic programming over subsets), in parallel over independent subtrees. Same
  /// leaves and prims as lbvh, never a higher SAH cost (bvh_sah_cost). At 10^6 triangles, one
  /// pass: build about 2.4x lbvh's time (half binned_sah's), SAH cost 57.3 -> 52.5 (binned_sah
  /// 49.5), 11 % / 3 % fewer node-pair tests than lbvh in tree-vs-tree overlap at margin 0 / 0.01
  /// (binned_sah: 23 % / 6 %). Between lbvh and binned_sah, for trees queried often.
  lbvh_treelet,
};

struct BvhBuildOptions {
  BvhBuilder builder = BvhBuilder::lbvh;
  std::uint32_t max_leaf_size = 4;  ///< leaf bound of all builders but insertion (0 counts as 1)
  /// Restructuring passes of lbvh_treelet (ignored by the other builders; 0 gives the lbvh tree).
  /// The first pass costs 1.4x the lbvh build, later ones less (they skip the treelets whose input
  /// did not change), and each gains less: SAH cost 52.5 / 52.0 / 51.9 after 1 / 2 / 3 passes.
  std::uint32_t treelet_passes = 1;
};

/// Per-triangle double boxes rounded outward to float (parallel). boxes[i] is triangle i's box and
/// equals to_float_outward(mesh.triangle_box(i)).
std::vector<AabbF> triangle_boxes(const TriMesh& mesh);

/// Builds a BVH over all triangles of `mesh` (empty Bvh for an empty mesh). Deterministic: the same
/// tree (bit for bit) for any thread count. Each triangle appears exactly once in `prims`.
Bvh build_bvh(const TriMesh& mesh, const BvhBuildOptions& options = {});

/// Recomputes every box (prim_boxes, then nodes bottom-up) after the vertices of `mesh` moved
/// (topology unchanged: the mesh the tree was built from, with new positions). Parallel; the result
/// does not depend on the thread count and equals the boxes a fresh computation gives (the tree
/// structure is kept, so its quality degrades with large deformations: rebuild then). Throws
/// std::invalid_argument when the triangle count differs from the tree's.
void refit_bvh(Bvh& bvh, const TriMesh& mesh);

const char* bvh_builder_name(BvhBuilder b);

/// Surface-area-heuristic cost of a tree (MacDonald & Booth 1990), the figure of merit the SAH
/// builders minimise: (inner_cost * sum of the inner nodes' surface areas + leaf_cost * sum over
/// leaves of surface area * triangle count) / surface area of the root. Serial, in double from the
/// float boxes. 0 for an empty tree or a root of zero area.
double bvh_sah_cost(const Bvh& bvh, double inner_cost = 1.0, double leaf_cost = 1.0);

}  // namespace interfere
