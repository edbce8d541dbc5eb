// interfere-mpi's command line (issue #31; docs/mpi.md, "Run" and "Options"), read with CLI11 as
// the CLI's: the options of `mpirun -n K interfere-mpi clash --scene FILE ...`, their meaning that
// of `interfere clash --scene` (apps/cli/cmd_clash_scene.cpp) plus interfere-mpi's own
// (--distribute, --cost-model, --memory-limit); and those of `interfere-mpi bearing`, as
// `interfere bearing --assembly`.
#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "plan.h"

namespace interfere::mpi {

/// An error every rank finds the same way (usage, the scene file): rank 0 prints it, all exit 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// --help and --version: printed on stdout by rank 0, exit status 0 (the CLI's conventions, issue #30 item 5).
struct InfoRequest {
  std::string text;
};

/// How a time series (motion frames, FE load steps) is split across ranks (docs/mpi.md, "Time
/// series"): by body pair (every frame of a pair on one rank; the default) or by frames (each rank
/// a contiguous block of frames for the whole scene; series.h).
enum class Distribute { pairs, frames };

struct Options {
  std::string scene, json, csv, frames_csv, frame_pairs_csv, baseline, motion, units, group_by = "pair";
  double group_distance = 0;
  int threads = 0;
  double memory_limit_mb = 0;  ///< --memory-limit MB: address space a rank may add after its start (0: none)
  bool quiet = false;
  // As `interfere clash --scene` (apps/cli/cmd_clash_scene.cpp): clash tests, the default test's
  // clearance and tolerance, the exit status policy, the FE inputs' options.
  std::vector<std::string> test_texts;
  std::string tests_file, fail_on;
  double clearance = 0, tolerance = 0;
  bool clearance_given = false, tolerance_given = false;
  std::string fem_field, fem_disp, fem_split = "auto";
  double fem_scale = 1;
  bool fem_linear_faces = false, reference = true;
  CostModel cost;  ///< --cost-model PAIR_S,PAIR_TRI_S,BODY_TRI_S,READ_TRI_S[,MERGE_PAIR_S] (default: plan.h, fitted in docs/scaling.md)
  Distribute distribute = Distribute::pairs;  ///< --distribute pairs|frames
};

/// The synopsis and exit statuses (--help).
extern const char* const kUsage;

/// argv[1] is "clash" (or --help / --version: InfoRequest). Throws UsageError naming the flag.
Options parse_clash(int argc, char** argv);

/// `interfere-mpi bearing` (bearing.h): as `interfere bearing --assembly`.
struct BearingOptions {
  std::string assembly, motion, out, json, fail_on;
  std::optional<int> frames;
  std::optional<std::uint64_t> seed;
  std::optional<double> clearance;
  int threads = 0;
  bool quiet = false;
};

extern const char* const kBearingUsage;

/// argv[0] is "bearing". Throws UsageError naming the flag, InfoRequest for --help / --version.
BearingOptions parse_bearing(int argc, char** argv);

}  // namespace interfere::mpi
