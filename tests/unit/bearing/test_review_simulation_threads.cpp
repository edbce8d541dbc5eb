// Review of 18a8222 and 9590eae (issue #27, Table 3): the frame loop's passes now run over blocked
// ranges with an affinity partitioner, the partners' cylinders are computed once, and the broad phase
// runs as a task beside the row pass (box_overlap and the cross pairs filled in after both). Attacked
// where the claims are weakest: a packed grid (pitch below R + r + R + r, so that every roller reaches
// into its neighbours' partners and the cross-pair pass is busy every frame), raised scars (grown
// boxes), a clearance band, odd pair counts that do not fill the 16-pair blocks, and each broad-phase
// kind. Oracles: the brute-force broad phase (all box pairs, no state) for box_overlap and the cross
// pairs; 1, 2, 3 and 5 threads for the rows (everything bit for bit); and an independent monotonicity
// fact: a row or cross pair within the clearance must have been reported by the broad phase.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "interfere/bearing/simulation.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

SceneParams packed_scene(BroadPhaseKind kind, int pairs) {
  SceneParams p;
  p.pairs = pairs;
  p.frames = 7;
  p.roller = {.radius = 10, .height = 40, .radial_segments = 24, .height_segments = 23};
  p.partner_radius = 30;
  p.gap = -0.05;
  p.max_tilt_deg = 1.0;
  p.spin_deg_per_frame = 11.0;
  p.scar = {.angle_center_deg = 0, .angle_width_deg = 300, .z_min = 0, .z_max = 40, .depth = 0.15, .seed = 9, .raised = true};
  p.scar_fraction = 0.5;
  p.seed = 1234;
  p.broad_phase = kind;
  p.spacing = 79.7;  // the roller of pair k (x + 39.95 +- 10) reaches the partner of pair k + 1 (x + 79.7 - 30)
  p.clearance = 0.3;
  return p;
}

bool same_row(const PairFrame& a, const PairFrame& b) {
  return a.frame == b.frame && a.pair == b.pair && a.distance == b.distance && a.point_a == b.point_a &&
         a.point_b == b.point_b && a.tilt_deg == b.tilt_deg && a.azimuth_deg == b.azimuth_deg &&
         a.spin_deg == b.spin_deg && a.scarred_roller == b.scarred_roller && a.scar_in_range == b.scar_in_range &&
         a.box_overlap == b.box_overlap && a.solver == b.solver && a.path == b.path && a.evaluated == b.evaluated &&
         a.verdict == b.verdict;
}

bool same_cross(const CrossPair& a, const CrossPair& b) {
  return a.frame == b.frame && a.part_a == b.part_a && a.part_b == b.part_b && a.distance == b.distance &&
         a.point_a == b.point_a && a.point_b == b.point_b && a.solver == b.solver && a.verdict == b.verdict;
}

SimulationResult run(const SceneParams& p, int threads) {
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
  auto r = simulate(p);
  EXPECT_TRUE(r.has_value()) << r.error().message();
  return r ? std::move(*r) : SimulationResult{};
}

void expect_same(const SimulationResult& a, const SimulationResult& b, const std::string& what, bool counts_too) {
  ASSERT_EQ(a.rows.size(), b.rows.size()) << what;
  for (std::size_t k = 0; k < a.rows.size(); ++k) ASSERT_TRUE(same_row(a.rows[k], b.rows[k])) << what << " row " << k;
  ASSERT_EQ(a.cross_results.size(), b.cross_results.size()) << what;
  for (std::size_t k = 0; k < a.cross_results.size(); ++k)
    ASSERT_TRUE(same_cross(a.cross_results[k], b.cross_results[k])) << what << " cross " << k;
  EXPECT_EQ(a.row_verdicts, b.row_verdicts) << what;
  EXPECT_EQ(a.cross_verdicts, b.cross_verdicts) << what;
  EXPECT_EQ(a.verdict, b.verdict) << what;
  EXPECT_EQ(a.min_distance, b.min_distance) << what;
  EXPECT_EQ(a.cross_pairs, b.cross_pairs) << what;
  if (counts_too) EXPECT_EQ(a.broad_pairs_total, b.broad_pairs_total) << what;
  EXPECT_EQ(a.scarred_solves, b.scarred_solves) << what;
  EXPECT_EQ(a.interfering_rows, b.interfering_rows) << what;
}

}  // namespace

TEST(ReviewSimulationThreads, PackedGridSameForAnyThreadCountAndBroadPhase) {
  for (const int pairs : {1, 17, 37}) {
    const SimulationResult ref = run(packed_scene(BroadPhaseKind::brute_force, pairs), 1);
    ASSERT_EQ(ref.rows.size(), static_cast<std::size_t>(pairs) * 7);
    if (pairs > 1) {
      EXPECT_GT(ref.cross_pairs, 0u) << "the packed grid must give cross pairs";
      EXPECT_GT(ref.cross_results.size(), 0u) << "cross pairs within the clearance";
    }
    // every row within the clearance (or clashing) was reported by the broad phase
    for (const PairFrame& row : ref.rows)
      if (row.distance <= 0.3) EXPECT_TRUE(row.box_overlap) << "pairs " << pairs << " frame " << row.frame << " pair " << row.pair;
    for (const BroadPhaseKind kind : {BroadPhaseKind::brute_force, BroadPhaseKind::sweep_and_prune,
                                      BroadPhaseKind::loose_octree, BroadPhaseKind::bvh}) {
      for (const int threads : {1, 2, 3, 5}) {
        const SimulationResult r = run(packed_scene(kind, pairs), threads);
        expect_same(ref, r,
                    std::string(broad_phase_name(kind)) + " pairs " + std::to_string(pairs) + " threads " +
                        std::to_string(threads),
                    true);
      }
    }
  }
}
