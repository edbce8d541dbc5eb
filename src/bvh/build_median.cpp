// (b) Median split: top-down, each node's triangles are split at the object median of the longest
// axis of their centroid bounds (std::nth_element); leaves hold at most max_leaf_size triangles.
// The "optimised" tree: balanced (depth ceil(log2(n / max_leaf_size))) but blind to box
// sizes. Parallel over subtrees (TopDownBuilder); each split is serial, so the root split bounds
// the speed.
#include "build_internal.h"

namespace interfere::detail {
namespace {

struct MedianRule {
  struct Info {};
  PrimRef* refs;
  Bvh* bvh;
  std::size_t max_leaf;

  Split<Info> split(std::size_t b, std::size_t e, const Info&, int, bool) const {
    if (e - b <= max_leaf) return {};
    return {median_split(refs, b, e, longest_axis(centroid_bounds(refs, b, e))), {}, {}};
  }
  AabbF leaf(std::size_t b, std::size_t e) const { return emit_ref_leaf(refs, *bvh, b, e); }
};

}  // namespace

Bvh build_median(const TriMesh& mesh, std::uint32_t max_leaf_size) {
  Bvh bvh;
  const std::size_t n = mesh.num_triangles();
  if (n == 0) return bvh;
  Buffer<PrimRef> refs = make_prim_refs(mesh);
  resize_output(bvh.prims, n);
  resize_output(bvh.prim_boxes, n);
  const MedianRule rule{refs.data(), &bvh, std::max<std::uint32_t>(1, max_leaf_size)};
  TopDownBuilder<MedianRule>(rule).build(n, {}, bvh.nodes);
  return bvh;
}

}  // namespace interfere::detail
