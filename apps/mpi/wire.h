// What the ranks of `interfere-mpi` send each other (issue #31): body metadata after the first
// read, and each rank's findings after its engine call, as flat binary records (exact doubles,
// infinities included; little-endian host order: the ranks of one job run one binary). A body's
// record leaves out what every rank knows already (its scene-file entry: every rank parsed the
// scene file) or what is the usual value (the identity pose, no tags, a name equal to the id, ...)
// behind a flag: 10^5 bodies are ~8 MB to receive and decode on every rank, not ~27 MB (issue #31:
// fresh memory costs ~6 ms a MB in page faults on the VMs measured).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/io.h"

namespace interfere::mpi {

/// One body as the plan and the report need it: metadata, triangle count, local box, and which
/// scene-file entry it comes from (its index there and its position among that entry's bodies).
struct BodyInfo {
  scene::Body meta;  ///< without geometry (mesh null)
  std::uint64_t triangles = 0;
  Aabb local_box;
  std::uint32_t spec = 0, ordinal = 0;
  /// Which mesh it has, as the scene loader shares meshes (scene/load.h: bodies of one mesh file
  /// and unit share it across entries; a STEP or glTF entry's instances share their part's): equal
  /// keys, one mesh. FNV-1a of "F" + the file's canonical path + unit, or "E" + entry + the
  /// ordinal of the entry's first body with that mesh.
  std::uint64_t mesh_key = 0;
  /// How far its broad box grows to find its zero-clearance fits (scene::SceneClashOptions::
  /// zero_clearance_fits, from a STEP assembly's B-Rep: LoadedScene::zero_clearance_fits); 0: none.
  double fit_reach = 0;
};

/// The steps of a rank, timed (RankResult::phases; the report's mpi.per_rank[].phases).
inline constexpr std::size_t kPhaseCount = 6;
inline constexpr const char* kPhases[kPhaseCount] = {"inputs", "read", "exchange", "plan", "read_pairs", "engine"};

/// A rank's findings: the clashes of its pairs (global body indices), its frame rows (counts of
/// its pairs per frame), frames x pairs rows, reference verdicts, the engine's warnings about its
/// bodies, its core runs and timings.
struct RankResult {
  std::vector<scene::SceneClash> clashes;
  std::vector<scene::FrameRow> frames;
  std::vector<scene::FramePairRow> frame_pairs;
  std::vector<scene::ReferencePair> reference_pairs;
  std::vector<std::string> warnings;
  std::size_t core_runs = 0, calls = 0, pairs = 0, bodies_loaded = 0;
  std::uint64_t pair_triangles = 0;     ///< sum over its pairs of both bodies' triangles
  std::uint64_t triangles_loaded = 0;   ///< of the bodies it read
  std::size_t bodies_used = 0;          ///< bodies in its engine call (those its pairs need)
  std::uint64_t body_triangles = 0;     ///< their triangles
  bool reference_checked = false;
  double load_seconds = 0, engine_seconds = 0, prepare_seconds = 0, broad_seconds = 0, narrow_seconds = 0;
  double peak_rss_mb = 0;
  double cpu_seconds = 0;  ///< the rank's user + system CPU time (getrusage) at the end of its work
  double load_cpu_seconds = 0, engine_cpu_seconds = 0;  ///< of its reads, of its engine call
  /// Wall and CPU seconds of each step of the rank (kPhases: where the time of a job goes).
  std::vector<std::array<double, 2>> phases = std::vector<std::array<double, 2>>(kPhaseCount, {0.0, 0.0});
};

/// Body records (`entries`: the scene file's entries, BodyInfo::spec indexes them on every rank).
std::string encode(const std::vector<BodyInfo>& bodies, const std::vector<scene::BodySpec>& entries);
/// Appends the bodies of `bytes` (one rank's encode) to `out`.
void decode_bodies(std::string_view bytes, const std::vector<scene::BodySpec>& entries, std::vector<BodyInfo>& out);
/// How many bodies `bytes` holds (to reserve before decode_bodies).
std::size_t count_bodies(std::string_view bytes);
std::string encode(const RankResult& r);
RankResult decode_result(std::string_view bytes);

}  // namespace interfere::mpi
