// Refit: recomputes the triangle boxes and every node box bottom-up after the vertices moved.
//
// Pass 1 recomputes prim_boxes in parallel (prefetching the triangles, which are visited in leaf
// order). Pass 2 uses the layout every builder guarantees (bvh.h): the descendants of an inner node
// x occupy the contiguous index range [x.first, end(x)): the child pair, then the first child's
// descendants, then the second's; a reverse sweep over such a range visits children before parents.
// Large subtrees are split between their two children with tbb::parallel_invoke, smaller ones are
// swept serially. Boxes are min/max of the same inputs, so the result is the same for every thread
// count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <stdexcept>
#include <string>

#include "build_internal.h"
#include "interfere/bvh/bvh.h"

namespace interfere {
namespace {

constexpr std::size_t kSerialNodes = 4096;

struct Refitter {
  Bvh& bvh;

  void node(std::size_t i) const {
    BvhNode& n = bvh.nodes[i];
    AabbF box;
    if (n.is_leaf()) {
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j) box.expand(bvh.prim_boxes[j]);
    } else {
      box = bvh.nodes[n.first].box;
      box.expand(bvh.nodes[n.first + 1].box);
    }
    n.box = box;
  }

  // Refits node x whose descendants are [x.first, end).
  void subtree(std::size_t x, std::size_t end) const {
    const BvhNode& n = bvh.nodes[x];
    if (!n.is_leaf() && end - n.first > kSerialNodes) {
      const std::size_t c0 = n.first, c1 = n.first + 1;
      const std::size_t end0 = bvh.nodes[c1].is_leaf() ? end : bvh.nodes[c1].first;
      tbb::parallel_invoke([&] { subtree(c0, end0); }, [&] { subtree(c1, end); });
    } else if (!n.is_leaf()) {
      for (std::size_t i = end; i-- > n.first;) node(i);
    }
    node(x);
  }
};

}  // namespace

void refit_bvh(Bvh& bvh, const TriMesh& mesh) {
  if (bvh.prims.size() != mesh.num_triangles()) {
    throw std::invalid_argument("refit_bvh: the tree holds " + std::to_string(bvh.prims.size()) +
                                " triangles, the mesh " + std::to_string(mesh.num_triangles()));
  }
  if (bvh.empty()) return;
  bvh.prim_boxes.resize(bvh.prims.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bvh.prims.size(), 1 << 13),
                    [&](const auto& r) {
                      detail::triangle_boxes_gather(
                          mesh, r.begin(), r.end(), [&](std::size_t i) { return bvh.prims[i]; },
                          [&](std::size_t i, const AabbF& box) { bvh.prim_boxes[i] = box; });
                    });
  Refitter{bvh}.subtree(0, bvh.nodes.size());
}

}  // namespace interfere
