// `interfere-mpi simulate` (issue #31, item 6; docs/scaling.md): the partitioner (plan.h) run on a
// synthetic product of N bodies and T triangles (no geometry, no MPI traffic), and the cost model
// applied to its blocks: per number of ranks, the load imbalance, bodies and triangles each rank
// reads, bytes exchanged, memory per rank and the predicted time.
#pragma once

namespace interfere::mpi {

/// argv after "simulate"; prints one JSON object on stdout; returns the exit status.
int simulate(int argc, char** argv);

}  // namespace interfere::mpi
