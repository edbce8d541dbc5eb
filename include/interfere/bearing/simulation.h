// Dynamic simulation of N bearing pairs (Jia & Zheng 2019, §4): each pair is a roller A (radius r,
// length h_b, pivoting about its bottom end centre) next to a partner cylinder B (radius R) whose
// axis is parallel to A's nominal axis at distance R + r + gap. Every frame A spins about its axis
// and its tilt (angle <= max_tilt, any azimuth) performs a seeded random walk; a quarter (by
// default) of the rollers carry a scar (generated, inward or raised, or imported: issue #27). Per
// frame: a broad phase over all 2N parts, then every
// pair's maximum interference distance and point pair, by the standard solver (analytic.h) when no
// scar is in the window of Eq. (1), else by the scarred solver (scarred.h). Every other pair of
// parts whose boxes the broad phase reports overlapping (parts of different pairs) is decided too
// (part_pair.h). Every row and cross pair carries a verdict (query/verdict.h; part_pair.h).
//
// Deterministic: the random walk of pair k at frame f depends only on (seed, k, f); pairs are
// solved in parallel into their own slots; results are identical for any thread count.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "interfere/bearing/broad_phase.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/roller.h"
#include "interfere/bearing/scar.h"
#include "interfere/bearing/scar_import.h"
#include "interfere/core/error.h"

namespace interfere::bearing {

struct SceneParams {
  int pairs = 16;                    ///< N >= 1
  int frames = 10;                   ///< F >= 1
  RollerParams roller;               ///< the roller A
  double partner_radius = 30.0;      ///< R > 0
  double partner_height = 60.0;      ///< > 0; B is centred on A's mid height
  double gap = 0.0;                  ///< nominal surface gap (may be < 0: preload), > -(r + R)
  double max_tilt_deg = 1.0;         ///< alpha; Eq. (1) must hold
  double tilt_step = 0.25;           ///< random-walk step as a fraction of alpha, in [0, 1]
  double spin_deg_per_frame = 3.0;   ///< roller spin per frame (any finite value)
  double scar_fraction = 0.25;       ///< fraction of scarred rollers, in [0, 1]
  ScarParams scar;                   ///< scar window; each scarred roller gets seed scar.seed + k
  /// Non-empty (scar_import.h, issue #27): every scarred roller carries this imported scar (on the
  /// roller's grid, applied as measured: no border filter) instead of a generated one; the range
  /// test of Eq. (1) then uses its covered_window().
  VertexHeights imported_scar;
  std::uint64_t seed = 1;
  BroadPhaseKind broad_phase = BroadPhaseKind::sweep_and_prune;
  double spacing = 0.0;              ///< grid pitch between pairs; 0 = automatic (no cross contacts)
  double clearance = 0.0;            ///< >= 0: apart but closer than this is the verdict `clearance`
};

Status validate(const SceneParams& p);

struct PairFrame {
  std::int32_t frame = 0, pair = 0;
  double distance = 0;     ///< > 0 clearance, < 0 interference (maximum interference distance)
  Vec3 point_a, point_b;   ///< world frame
  double tilt_deg = 0, azimuth_deg = 0, spin_deg = 0;
  bool scarred_roller = false;
  bool scar_in_range = false;
  bool box_overlap = false;  ///< the broad phase reported this pair
  std::uint8_t solver = 0;   ///< 0 standard (analytic), 1 scarred (mesh)
  std::uint8_t path = 0;     ///< AnalyticPath of the standard solver
  std::uint32_t evaluated = 0;  ///< triangles evaluated exactly by the scarred solver
  Verdict verdict = Verdict::clear;  ///< of distance (part_pair.h), or clash by containment
};

/// A pair of parts of different bearing pairs that the broad phase reported, decided
/// (part_pair.h). Part index 2k is the roller of pair k, 2k + 1 its partner.
struct CrossPair {
  std::int32_t frame = 0;
  std::uint32_t part_a = 0, part_b = 0;  ///< A and B of s(A, B) (A: the roller when there is one)
  double distance = 0;                   ///< s(A, B) (solver `bound`: a lower bound)
  Vec3 point_a, point_b;                 ///< world frame
  PartPairSolver solver = PartPairSolver::standard;
  Verdict verdict = Verdict::clear;
};

struct SimulationResult {
  std::vector<PairFrame> rows;          ///< frame-major, then pair
  std::uint64_t broad_pairs_total = 0;  ///< box-overlap pairs over all frames
  std::uint64_t cross_pairs = 0;        ///< box overlaps between parts of different pairs, all decided
  std::vector<CrossPair> cross_results; ///< the cross pairs whose verdict is not clear (frame, pair order)
  std::array<std::uint64_t, 5> row_verdicts{};    ///< rows per Verdict (indexed by its value)
  std::array<std::uint64_t, 5> cross_verdicts{};  ///< cross pairs per Verdict
  Verdict verdict = Verdict::clear;     ///< the worst verdict of every row and cross pair
  std::vector<std::string> undecided_reasons;  ///< distinct reasons of undecided verdicts
  std::uint64_t scarred_solves = 0, general_solves = 0;
  std::int32_t scarred_rollers = 0;
  double theta = 0;                     ///< Eq. (1): the full range angle MCN, radians (window.h)
  double min_distance = 0;              ///< over all rows
  PairFrame worst;                      ///< the row with min_distance (first in frame, pair order)
  std::uint64_t interfering_rows = 0;
  double setup_seconds = 0, broad_seconds = 0, narrow_seconds = 0, total_seconds = 0;
  double frames_per_second = 0;         ///< frames / (broad + narrow seconds)
  double cpu_seconds = 0;               ///< process CPU time (all threads) of the frame loop
  int threads = 1;                      ///< worker threads available (oneTBB arena)
  double spacing = 0;
  // With keep_rows (for viewers, view/bearing_document.h): the roller poses (body frame -> world,
  // frame-major then pair, as rows), the scarred roller meshes (body frame) and, per pair, the index
  // of its scarred mesh (-1: an unscarred roller). The partner of pair k is the cylinder of radius
  // partner_radius on the grid point of pair k (bearing_partner_pose).
  std::vector<Transform> roller_poses;
  std::vector<TriMesh> scar_meshes;
  std::vector<std::int32_t> pair_variant;
};

/// Where the partner (the cylinder B) of pair k stands: body frame (axis +z from its base) -> world,
/// for the grid pitch `spacing` (SimulationResult::spacing).
Transform partner_pose(const SceneParams& p, double spacing, int k);

/// Runs the simulation. `keep_rows` false keeps only the summary (benchmarks). Errors: validate().
/// `progress`, when set, is called after each frame with (frames done, frame count), on the
/// calling thread (the CLI's progress bar).
Expected<SimulationResult> simulate(const SceneParams& p, bool keep_rows = true,
                                    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace interfere::bearing
