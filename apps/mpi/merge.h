// Rank 0's merge of the ranks' findings into one scene clash result (issue #31, item 2): the same
// result, and so the same report, as scene::clash_scene on the whole scene on one process.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "plan.h"
#include "wire.h"
#include "interfere/scene/engine.h"

namespace interfere::mpi {

/// Adds a block's frame row (counts of its pairs) to the rank's row of that frame.
void add_row(scene::FrameRow& into, const scene::FrameRow& from);

/// The whole scene's result from the ranks' findings: clashes in the engine's order (test, body
/// ids, clash id), counts, pair summaries, the frames table (the ranks' rows added), the frames x
/// pairs table and first frames (engine_frames.cpp), groups (engine_groups.cpp), the broad phase's
/// candidate and suppressed counts and selection warnings, then the engine's open-body warnings
/// in body order. core_runs: the ranks' sum (one process's: a class of pairs the engine decides
/// once is kept on one rank, plan.h join_classes). `reference_checked`: the scene deforms (the engine's reference pass ran).
/// The ranks' clashes, frames x pairs rows and reference verdicts are moved out of `ranks` (the
/// rest of each RankResult stays for report_with_mpi).
scene::SceneClashResult merge(const scene::Scene& skeleton, const std::vector<scene::ClashTest>& tests,
                              const scene::SceneClashOptions& options, const BroadResult& broad,
                              const std::vector<std::uint64_t>& triangles, std::vector<RankResult>& ranks,
                              bool reference_checked);

/// The report of scene::report_json (written from a scene of metadata, meshes not sent to rank 0)
/// with every body's triangle count and an "mpi" section: ranks, per rank its pairs, engine
/// calls, bodies read, estimated cost, load and engine seconds and peak memory; and the envelope
/// of every report (options, result, seconds: `seconds` the job's wall time on rank 0, through the
/// merge); mpi.merge: rank 0's wall and CPU seconds of the gather and merge (`merge_s`).
std::string report_with_mpi(const std::string& report, const std::vector<std::uint64_t>& triangles,
                            const std::vector<RankResult>& ranks, const Partition& part, double seconds,
                            const std::array<double, 2>& merge_s);

}  // namespace interfere::mpi
