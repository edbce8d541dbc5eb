// BVH benchmarks (issue #2, items 3 and 7): build with each builder and refit, at 1e5 and 1e6
// triangles (make_sphere), on 1 and 2 threads; tree-vs-tree overlap of
// make_overlapping_spheres(1e6) serial and parallel. Throughput counters are triangles per second
// (items_processed); build rows also report the tree's SAH cost (bvh_sah_cost), overlap rows the
// box tests of the serial traversal (node pairs, and triangle boxes in leaf pairs). Targets:
// default build >= 30 M tri/s and refit >= 100 M tri/s on 2 threads at 1e6.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common.h"
#include "interfere/bvh/bvh.h"
#include "interfere/bvh/traverse.h"
#include "interfere/mesh/generate.h"

namespace interfere {
namespace {

const TriMesh& sphere_mesh(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<TriMesh>> cache;
  auto& slot = cache[n];
  if (!slot)
    slot = std::make_unique<TriMesh>(make_sphere({.target_triangles = n, .bump_amplitude = 0.01}));
  return *slot;
}

struct TreePair {
  SpherePair mesh;
  Bvh a, b;
};
const TreePair& tree_pair(std::size_t n, BvhBuilder builder) {
  static std::map<std::pair<std::size_t, BvhBuilder>, std::unique_ptr<TreePair>> cache;
  auto& slot = cache[{n, builder}];
  if (!slot) {
    slot = std::make_unique<TreePair>();
    slot->mesh = make_overlapping_spheres(n);
    slot->a = build_bvh(slot->mesh.a, {.builder = builder});
    slot->b = build_bvh(slot->mesh.b, {.builder = builder});
  }
  return *slot;
}

void bm_build(benchmark::State& state, BvhBuilder builder, std::size_t n, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const TriMesh& mesh = sphere_mesh(n);
  for (auto _ : state) {
    Bvh bvh = build_bvh(mesh, {.builder = builder});
    benchmark::DoNotOptimize(bvh.nodes.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.num_triangles()));
  const Bvh bvh = build_bvh(mesh, {.builder = builder});  // for the counters, untimed
  state.counters["nodes"] = static_cast<double>(bvh.nodes.size());
  state.counters["sah"] = bvh_sah_cost(bvh);
}

void bm_refit(benchmark::State& state, BvhBuilder builder, std::size_t n, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const TriMesh& mesh = sphere_mesh(n);
  Bvh bvh = build_bvh(mesh, {.builder = builder});
  TriMesh moved = mesh;
  for (Vec3& p : moved.positions) p = p * 1.01 + Vec3{0.003, -0.002, 0.001};
  bool flip = false;
  for (auto _ : state) {
    refit_bvh(bvh, flip ? mesh : moved);  // alternate so every iteration changes the boxes
    flip = !flip;
    benchmark::DoNotOptimize(bvh.nodes.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.num_triangles()));
}

// Box tests of the serial traversal (detail::overlap_from, counted): node pairs tested, and
// triangle-box tests in leaf pairs.
struct BoxTests {
  std::size_t nodes = 0, prims = 0;
};
BoxTests count_box_tests(const Bvh& a, const Bvh& b, float margin) {
  BoxTests c;
  ++c.nodes;
  if (a.empty() || b.empty() || !boxes_overlap(a.nodes[0].box, b.nodes[0].box, margin)) return c;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [ia, ib] = stack.back();
    stack.pop_back();
    const BvhNode& na = a.nodes[ia];
    const BvhNode& nb = b.nodes[ib];
    if (na.is_leaf() && nb.is_leaf()) {
      for (std::uint32_t i = na.first; i < na.first + na.count; ++i) {
        ++c.prims;
        if (!boxes_overlap(a.prim_boxes[i], nb.box, margin)) continue;
        c.prims += nb.count;
      }
    } else if (detail::descend_a(na, nb)) {
      for (std::uint32_t k : {na.first + 1, na.first}) {
        ++c.nodes;
        if (boxes_overlap(a.nodes[k].box, nb.box, margin)) stack.push_back({k, ib});
      }
    } else {
      for (std::uint32_t k : {nb.first + 1, nb.first}) {
        ++c.nodes;
        if (boxes_overlap(na.box, b.nodes[k].box, margin)) stack.push_back({ia, k});
      }
    }
  }
  return c;
}

// threads == 0: the serial for_each_overlap; otherwise collide_parallel on that many threads.
void bm_overlap(benchmark::State& state, BvhBuilder builder, std::size_t n, float margin,
                int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::max(threads, 1));
  const TreePair& p = tree_pair(n, builder);
  std::size_t pairs = 0;
  for (auto _ : state) {
    if (threads == 0) {  // serial traversal
      pairs = 0;
      for_each_overlap(p.a, p.b, margin, [&](std::uint32_t, std::uint32_t) { ++pairs; });
    } else {
      const auto out = collide_parallel<std::pair<std::uint32_t, std::uint32_t>>(
          p.a, p.b, {.margin = margin}, [](std::uint32_t i, std::uint32_t j, auto& v) {
            v.push_back({i, j});
          });
      pairs = out.size();
    }
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  const BoxTests tests = count_box_tests(p.a, p.b, margin);
  state.counters["node_tests"] = static_cast<double>(tests.nodes);
  state.counters["prim_tests"] = static_cast<double>(tests.prims);
}

std::string label(std::size_t n) {
  return n == 100000 ? "1e5" : n == 1000000 ? "1e6" : std::to_string(n);
}

[[maybe_unused]] const bool registered = [] {
  for (std::size_t n : {std::size_t{100000}, std::size_t{1000000}}) {
    for (BvhBuilder b : {BvhBuilder::lbvh, BvhBuilder::lbvh_treelet, BvhBuilder::binned_sah,
                         BvhBuilder::median_split, BvhBuilder::insertion}) {
      for (int t : {1, 2}) {
        if (b == BvhBuilder::insertion && t != 1) continue;  // serial by nature
        const std::string name = "Bvh/Build/" + std::string(bvh_builder_name(b)) + "/" + label(n) +
                                 "/threads:" + std::to_string(t);
        // The targets are judged on the default builder at 1e6: repeated, the report takes the
        // median (single runs of ~30 ms swing by a third on this shared VM).
        const bool judged = n == 1000000 && b == BvhBuildOptions{}.builder;
        benchmark::RegisterBenchmark(name.c_str(),
                                     [b, n, t](benchmark::State& s) { bm_build(s, b, n, t); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Repetitions(judged ? bench::target_repetitions() : 1);
      }
    }
    for (int t : {1, 2}) {
      const std::string name = "Bvh/Refit/" + label(n) + "/threads:" + std::to_string(t);
      benchmark::RegisterBenchmark(
          name.c_str(),
          [n, t](benchmark::State& s) { bm_refit(s, BvhBuildOptions{}.builder, n, t); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Repetitions(n == 1000000 ? bench::target_repetitions() : 1);
    }
  }
  for (BvhBuilder b : {BvhBuilder::lbvh, BvhBuilder::lbvh_treelet, BvhBuilder::binned_sah,
                       BvhBuilder::median_split}) {
    for (float m : {0.0f, 0.01f}) {
      for (int t : {0, 1, 2}) {
        const std::string name = "Bvh/Overlap/" + std::string(bvh_builder_name(b)) +
                                 "/1e6/margin:" + (m == 0 ? "0" : "0.01") +
                                 (t == 0 ? "/serial" : "/parallel/threads:" + std::to_string(t));
        benchmark::RegisterBenchmark(
            name.c_str(), [b, m, t](benchmark::State& s) { bm_overlap(s, b, 1000000, m, t); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace interfere
