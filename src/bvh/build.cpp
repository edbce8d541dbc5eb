// Builder dispatch and names (one algorithm per file: build_insertion/median/sah/lbvh.cpp, the
// treelet restructuring of lbvh_treelet in build_treelet.cpp; the shared top-down framework and
// memory helpers are in build_internal.h).
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
//
// lbvh_treelet (same mesh; the VM's second core was busy with other jobs, so minima of 9-27 runs
// on 1 thread; SAH cost = bvh_sah_cost):
//   build, 1 thread         lbvh 48 ms, then +1 / 2 / 3 passes 116 / 172 / 206 ms, binned_sah
//                           247 ms (one 2-thread run while the core was partly free: lbvh 36,
//                           2 passes 119, binned_sah 160 ms)
//   SAH cost                lbvh 57.3, after 1 / 2 / 3 passes 52.5 / 52.0 / 51.9, binned_sah 49.5
//   node-pair box tests, margin 0 / 0.01: lbvh 11.0k / 88.6k, 1 pass 9.7k / 86.1k, 3 passes
//                           9.6k / 85.8k, binned_sah 8.4k / 83.4k (the leaves are lbvh's, hence
//                           its 10.0k / 329k triangle-box tests; binned_sah 9.1k / 318k)
//   serial overlap time at margin 0 / 0.01 (min of 15): lbvh 48 / 1590 us, 1 pass 46 / 1530 us,
//                           binned_sah 39 / 1410 us.
// One pass closes two thirds of the inner-node SAH gap to binned_sah at half its build time, but
// the default stays lbvh: that pass costs 1.4x the whole lbvh build (estimated 14 M tri/s on 2
// threads instead of 36 M, far below the 30 M target) for 3-6 % faster tree-vs-tree queries.
// lbvh_treelet is for trees queried many times that cannot afford binned_sah's build.
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
    case BvhBuilder::lbvh_treelet: {
      Bvh bvh = detail::build_lbvh(mesh, options.max_leaf_size);
      detail::optimize_treelets(bvh, options.treelet_passes);
      return bvh;
    }
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
    case BvhBuilder::lbvh_treelet:
      return "lbvh_treelet";
  }
  return "unknown";
}

}  // namespace interfere
