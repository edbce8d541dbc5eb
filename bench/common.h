// Shared fixtures of the benchmark suite: cached sphere pairs and models (built once per process,
// never inside a timed region), the engine's exact pair list as the reference that peers are
// compared to, and the environment knobs that bench/run_benchmarks.py uses to size a run.
//
// Environment (all optional):
//   INTERFERE_BENCH_SIZES        triangles per part for the strategy table, default "1e4,1e5,1e6"
//   INTERFERE_BENCH_BRUTE_MAX    largest size for the O(n^2) brute-force strategies, default 1e4
//   INTERFERE_BENCH_PRETEST_MAX  largest size for the O(n^2) box pre-test strategy, default 1e5
//   INTERFERE_BENCH_PEER_MAX     largest size for the FCL/CGAL peers, default 1e6
//   INTERFERE_BENCH_THREADS      thread counts for the parallel rows, default "1,2"
//   INTERFERE_BENCH_STL_TRIANGLES  triangles of the generated binary STL, default 2e6 (~100 MB)
//   INTERFERE_BENCH_DATA         folder with shared meshes (default <source>/../shared/data/mesh)
//   INTERFERE_BENCH_REPETITIONS  repetitions of the rows that targets are judged on (median),
//   default 3
//   INTERFERE_BENCH_EXACT_BOX_N   subdivisions per box edge of the coplanar exactness scenes,
//   default "50,100,200" (12·n² triangles per box)
//   INTERFERE_BENCH_EXACT_SPHERE  triangles per sphere of the containment and rotated-copy scenes,
//   default 1e5
#pragma once
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "interfere/bvh/bvh.h"
#include "interfere/mesh/generate.h"
#include "interfere/query/model.h"

namespace interfere::bench {

/// Integer from the environment ("1e6", "100000"), or `fallback`.
std::size_t env_size(const char* name, std::size_t fallback);
/// Comma-separated list of integers from the environment, or `fallback`.
std::vector<std::size_t> env_sizes(const char* name, std::vector<std::size_t> fallback);
/// String from the environment, or `fallback`.
std::string env_string(const char* name, const std::string& fallback);

/// Repetitions for the rows that targets are judged on (the report takes their median).
int target_repetitions();

/// The strategy-table sizes (triangles per part).
std::vector<std::size_t> table_sizes();
/// Thread counts for the parallel rows.
std::vector<std::size_t> thread_counts();

/// "1e4" for 10000, "1e6" for 1000000, otherwise the decimal number.
std::string size_label(std::size_t n);

/// make_overlapping_spheres(n), generated once per process.
const SpherePair& sphere_pair(std::size_t n);

/// Models of the pair built with `builder` (no statistics), built once per process.
struct ModelPair {
  Model a, b;
};
const ModelPair& model_pair(std::size_t n, BvhBuilder builder);

/// The engine's exact pair list (a, b) for the sphere pair (SAH trees, exact test), cached.
const std::vector<std::pair<std::uint32_t, std::uint32_t>>& reference_pairs(std::size_t n);

/// |found \ reference| and |reference \ found| for two sorted, duplicate-free pair lists.
struct PairDiff {
  std::size_t extra = 0, missing = 0;
  std::pair<std::uint32_t, std::uint32_t> first_extra{},
      first_missing{};  ///< valid when the count > 0
};
PairDiff diff_pairs(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& found,
                    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& reference);

/// Sorted, duplicate-free (triangle of A, triangle of B) pairs.
using PairList = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// Counters pairs / reference_pairs / extra / missing of a peer's pair list against the exact
/// reference, plus one example of each disagreement (first_extra_a/b/distance,
/// first_missing_a/b/kind) for the report.
void set_diff_counters(benchmark::State& state, const PairList& pairs, const PairList& reference,
                       const TriMesh& a, const TriMesh& b);

/// The engine's exact pair list for any two meshes (binned-SAH trees, exact test), sorted.
PairList exact_pairs(const TriMesh& a, const TriMesh& b);

// ---- "Exactness beside the peers": small fixed scenes on which double-precision tests go wrong.
// Every scene is run by the engine (bench_exactness.cpp) and by each peer (peer_fcl.cpp,
// peer_cgal.cpp) as Exact/<scene>/<method>; the peers' pair lists are compared with the engine's.
//   coplanar_face/n:<n>   make_box([0,1]³, n) and the same box translated by exactly its width
//                         along x: the two x = 1 faces coincide (identical grids), every pair
//                         touches
//   resting_box/n:<n>     A = make_box([-0.5,0.5]² × [0,1], n) shifted by 0.6/n in x and y, resting
//                         on B = make_box([-1,1]² × [-1,0], n): coplanar contact at z = 0 with
//                         grids that never line up (spacing 1/n on A, 2/n on B)
//   contained_sphere      a closed sphere (radius 0.5, off-centre) wholly inside a closed sphere of
//                         radius 1: no surface pair, the answer is containment (A inside B)
//   rotated_sphere/0.001rad, rotated_sphere/quarter_turn
//                         make_sphere against a copy of itself turned about z by 1e-3 rad, and by
//                         exactly a quarter turn (matrix entries 0, ±1: (x, y) -> (-y, x) exactly)
std::vector<std::string> exact_scene_names();  ///< cheap: no geometry is generated

struct ExactScene {
  TriMesh a, b;
};
/// The scene's meshes, generated once per process.
const ExactScene& exact_scene(const std::string& name);
/// exact_pairs() of the scene, cached.
const PairList& exact_scene_reference(const std::string& name);

}  // namespace interfere::bench
