// `interfere-mpi clash --distribute frames` (issue #31, item 3; docs/mpi.md, "Time series"): a
// scene's motion frames or FE load steps split across ranks in contiguous blocks, each rank running
// the whole scene's check (scene::clash_scene, the engine call of `interfere clash --scene`) on its
// block with the trees refitted from frame to frame inside it; rank 0 merges the per-frame tables
// in order and writes the same report as one process.
#pragma once
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "args.h"
#include "comm.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/io.h"
#include "interfere/scene/load.h"
#include "interfere/scene/scene.h"

namespace interfere::mpi {

/// What run() has checked on every rank before the work (the checksum agreed): the parsed scene
/// file, the tests, the loader's options, the motion file (or empty), the baseline's text.
struct SeriesInputs {
  const scene::SceneSpec& spec;
  const std::vector<scene::ClashTest>& tests;
  const scene::LoadOptions& load;
  const std::string& motion;
  const std::string& baseline_text;
  std::chrono::steady_clock::time_point start;
};

/// Runs the frames-distributed check; the exit status (every rank the same), or nothing when the
/// scene has no frames (the job then goes by body pairs; every rank alike). Input errors every
/// rank finds alike are thrown as UsageError.
std::optional<int> run_frames(const World& w, const Options& o, const SeriesInputs& in);

}  // namespace interfere::mpi
