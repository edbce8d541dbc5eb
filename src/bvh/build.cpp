// Builder dispatch and names (one algorithm per file: build_insertion/median/sah/lbvh.cpp; the
// shared top-down framework and memory helpers are in build_internal.h).
//
// Choice of the default (BvhBuildOptions::builder = lbvh), from bench/bench_bvh.cpp and a node-pair
// counter, make_sphere / make_overlapping_spheres at 10^6 triangles, 2-vCPU AMD EPYC VM (shared;
// runs at raised scheduling priority, medians of 5):
//   build, 1 / 2 threads    lbvh 44.7 / 27.4 ms (22 / 36 M tri/s)   binned_sah 250 / 153 ms
//                           median_split 212 / 111 ms               insertion 1970 ms (serial)
//   refit, 1 / 2 threads    13.7 / 7.5 ms (73 / 134 M tri/s)
//   node-pair box tests of the tree-vs-tree overlap at margin 0 / 0.002 / 0.01 / 0.05:
//                           binned_sah 8.4k / 16k / 83k / 2.23M     lbvh 11.0k / 23k / 89k / 2.37M
//                           median_split 12.9k / 22k / 89k / 1.89M
//   serial overlap time at margin 0 / 0.01: lbvh 0.061 / 1.65 ms, binned_sah 0.052 / 1.56 ms.
// The SAH tree is the best, but its lead is microseconds per query against 100+ ms more build (and
// the narrow phase of the reported pairs costs far more than either); the lead comes from its
// lowest levels (median splits below 16 triangles lose most of it), where every node costs a
// binning pass, so no cheap LBVH/SAH hybrid keeps it. binned_sah stays for trees built once and
// queried very often. Leaves: every builder but insertion makes leaves of up to max_leaf_size
// triangles; the SAH's ray-tracing leaf-termination test was dropped because its smaller leaves
// measured slower for tree-vs-tree queries (1.0 M nodes instead of 0.61 M, 2.5x the node tests at
// margin 0.05).
#include "build_internal.h"
#include "interfere/bvh/bvh.h"

namespace interfere {

Bvh build_bvh(const TriMesh& mesh, const BvhBuildOptions& options) {
  switch (options.builder) {
    case BvhBuilder::insertion:
      return detail::build_insertion(mesh);
    case BvhBuilder::median_split:
      return detail::build_median(mesh, options.max_leaf_size);
    case BvhBuilder::lbvh:
      return detail::build_lbvh(mesh, options.max_leaf_size);
    case BvhBuilder::binned_sah:
      break;
  }
  return detail::build_sah(mesh, options.max_leaf_size);
}

const char* bvh_builder_name(BvhBuilder b) {
  switch (b) {
    case BvhBuilder::insertion:
      return "insertion";
    case BvhBuilder::median_split:
      return "median_split";
    case BvhBuilder::binned_sah:
      return "binned_sah";
    case BvhBuilder::lbvh:
      return "lbvh";
  }
  return "unknown";
}

}  // namespace interfere
