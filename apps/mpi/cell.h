// `mpirun -n K interfere-mpi cell CELL ...` (issue #31, item 3; docs/mpi.md, "Time series"): the
// inspection cell's joint path split across ranks in contiguous blocks of path points, each rank
// checking its block (robot::cell_scene, robot::check_cell_path: the engine call of `interfere
// cell`), rank 0 merging the per-frame rows in order and writing the same JSON and CSV as
// `interfere cell` (apps/cli/cell_report.h) plus an "mpi" section.
#pragma once
#include "comm.h"

namespace interfere::mpi {

/// argv[0] is "cell". Returns the exit status (every rank the same). An input error every rank
/// finds alike (options, the cell or path file): rank 0 prints it, status 2; a failure only one
/// rank meets is thrown (main ends the job with MPI_Abort, status 2).
int run_cell(const World& w, int argc, char** argv);

}  // namespace interfere::mpi
