// Shared fixtures of the scene benchmarks (issue #24, item 9; bench/bench_scene.cpp and its FCL
// peer bench/peer_fcl_scene.cpp, executable interfere_bench_scene): the generated 10,000-body
// assembly, its clash tests, and the exact result the peer is compared with. Generated once per
// process, never inside a timed region.
//
// Environment (all optional):
//   INTERFERE_BENCH_SCENE_BODIES     bodies of the assembly, default 10000
//   INTERFERE_BENCH_SCENE_SEGMENTS   segments around every circle, default 48 (~1,000 triangles a
//   body) INTERFERE_BENCH_SCENE_CLEARANCE  clearance of the clearance test (mm, 1e-3 units),
//   default 100 (0.1 mm) INTERFERE_BENCH_SCENE_THREADS    thread counts of the interfere rows,
//   default "2" INTERFERE_BENCH_MOVING_BODIES    bodies of the moving scene, default 1000
//   INTERFERE_BENCH_MOVING_FRAMES    frames of the moving scene, default 3
#pragma once
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"

namespace interfere::bench {

struct AssemblyFixture {
  scene::AssemblyGenOptions options;
  scene::Scene scene;
  scene::AssemblyInfo info;  ///< ground truth by construction
};
const AssemblyFixture& assembly_fixture();

/// "hard" (all pairs), and with `with_clearance` also "clearance" (all pairs, the clearance knob).
std::vector<scene::ClashTest> assembly_tests(bool with_clearance);

using BodyPairs =
    std::set<std::pair<std::uint32_t, std::uint32_t>>;  ///< body indices, first < second

/// The exact result of the hard test (clash_scene, once per process): body pairs whose verdict is
/// clash, and those whose verdict is contact.
struct ExactPairs {
  BodyPairs clash, contact, undecided;
};
const ExactPairs& exact_assembly_pairs();

}  // namespace interfere::bench
