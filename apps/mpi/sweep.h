// `mpirun -n K interfere-mpi sweep ...` (issue #31, item 3; docs/mpi.md, "Sweep path points"): the
// inspection-probe path of `interfere sweep` split across ranks in contiguous blocks of path points,
// each rank running probe::sweep on its block, rank 0 merging the per-point and per-segment rows in
// order and writing the same JSON and CSV as `interfere sweep` (apps/cli/sweep_report.h) plus an
// "mpi" section.
#pragma once
#include "comm.h"

namespace interfere::mpi {

/// argv[0] is "sweep". Returns the exit status (every rank the same). An input error every rank
/// finds alike: rank 0 prints it, status 2.
int run_sweep(const World& w, int argc, char** argv);

}  // namespace interfere::mpi
