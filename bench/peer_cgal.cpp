// Peer: CGAL 5.5 on the same sphere pairs, the textbook exact pipeline. Its own translation unit so
// that CGAL headers stay local.
//   Peer/cgal/box_intersection_d/<n>  from the meshes in memory: one box per triangle, the two-set
//       box_intersection_d sweep (Zomorodian & Edelsbrunner 2000), then CGAL::do_intersect on each
//       box pair with Exact_predicates_inexact_constructions_kernel, collecting every pair.
//   Exact/<scene>/cgal  the same pipeline on the exactness scenes of common.h.
// Single-threaded (CGAL's sweep is serial). The counters compare CGAL's pair list with the engine's
// exact one: both decide exactly, so `missing` and `extra` must be 0.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <CGAL/version.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"

namespace interfere::bench {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;

std::vector<Box> triangle_boxes_cgal(const TriMesh& m) {
  std::vector<Box> boxes;
  boxes.reserve(m.num_triangles());
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const Aabb b = m.triangle_box(t);  // min/max of doubles: exact
    boxes.emplace_back(CGAL::Bbox_3(b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z),
                       static_cast<std::uint32_t>(t));
  }
  return boxes;
}

K::Triangle_3 cgal_triangle(const TriMesh& m, std::uint32_t t) {
  const auto c = m.corners(t);
  return {K::Point_3(c[0].x, c[0].y, c[0].z), K::Point_3(c[1].x, c[1].y, c[1].z),
          K::Point_3(c[2].x, c[2].y, c[2].z)};
}

/// Box sweep + do_intersect on each box pair: every intersecting (triangle of A, triangle of B)
/// pair, sorted.
PairList cgal_pairs(const TriMesh& a, const TriMesh& b, std::size_t& candidates) {
  PairList pairs;
  candidates = 0;
  std::vector<Box> boxes_a = triangle_boxes_cgal(a), boxes_b = triangle_boxes_cgal(b);
  CGAL::box_intersection_d(
      boxes_a.begin(), boxes_a.end(), boxes_b.begin(), boxes_b.end(),
      [&](const Box& ba, const Box& bb) {
        ++candidates;
        if (CGAL::do_intersect(cgal_triangle(a, ba.info()), cgal_triangle(b, bb.info()))) {
          pairs.emplace_back(ba.info(), bb.info());
        }
      });
  std::sort(pairs.begin(), pairs.end());  // the engine's output is sorted too
  return pairs;
}

void report(benchmark::State& state, const TriMesh& a, const TriMesh& b, const PairList& pairs,
            std::size_t candidates, const PairList& reference) {
  state.SetItemsProcessed(
      static_cast<std::int64_t>(state.iterations() * (a.num_triangles() + b.num_triangles())));
  set_diff_counters(state, pairs, reference, a, b);
  state.counters["candidates"] = static_cast<double>(candidates);
  state.counters["tris_a"] = static_cast<double>(a.num_triangles());
  state.counters["tris_b"] = static_cast<double>(b.num_triangles());
}

void bm_cgal(benchmark::State& state, std::size_t n) {
  const SpherePair& p = sphere_pair(n);
  PairList pairs;
  std::size_t candidates = 0;
  for (auto _ : state) {
    pairs = cgal_pairs(p.a, p.b, candidates);
    benchmark::DoNotOptimize(pairs.data());
  }
  report(state, p.a, p.b, pairs, candidates, reference_pairs(n));
}

void bm_cgal_exact(benchmark::State& state, const std::string& scene) {
  const ExactScene& sc = exact_scene(scene);
  PairList pairs;
  std::size_t candidates = 0;
  for (auto _ : state) {
    pairs = cgal_pairs(sc.a, sc.b, candidates);
    benchmark::DoNotOptimize(pairs.data());
  }
  report(state, sc.a, sc.b, pairs, candidates, exact_scene_reference(scene));
}

#define INTERFERE_STR2(x) #x
#define INTERFERE_STR(x) INTERFERE_STR2(x)

[[maybe_unused]] const bool registered = [] {
  benchmark::AddCustomContext("cgal_version", INTERFERE_STR(CGAL_VERSION));
  const std::size_t peer_max = env_size("INTERFERE_BENCH_PEER_MAX", 1000000);
  for (std::size_t n : table_sizes()) {
    if (n > peer_max) continue;
    benchmark::RegisterBenchmark(("Peer/cgal/box_intersection_d/" + size_label(n)).c_str(),
                                 [n](benchmark::State& s) { bm_cgal(s, n); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  for (const std::string& scene : exact_scene_names()) {
    benchmark::RegisterBenchmark(("Exact/" + scene + "/cgal").c_str(),
                                 [scene](benchmark::State& s) { bm_cgal_exact(s, scene); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
