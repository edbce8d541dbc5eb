// `mpirun -n K interfere-mpi bearing --assembly FILE ...` (issue #31, item 3; docs/mpi.md, "Time
// series"): the frames of a bearing assembly split across ranks in blocks, the rows gathered to
// rank 0, which writes the same CSV and JSON as `interfere bearing --assembly` (plus "mpi").
#pragma once
#include "comm.h"

namespace interfere::mpi {

/// argv[0] is "bearing". Returns the exit status (every rank the same). An input error every rank
/// finds alike (options, the assembly or motion file): rank 0 prints it, status 2; a failure only
/// one rank meets is thrown (main ends the job with MPI_Abort, status 2).
int run_bearing(const World& w, int argc, char** argv);

}  // namespace interfere::mpi
