// The few MPI collectives interfere-mpi uses, on byte strings (issue #31).
#pragma once
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

namespace interfere::mpi {

struct World {
  int rank = 0, size = 1;
};

/// Every rank's bytes, on every rank, in rank order.
std::vector<std::string> allgather(const std::string& mine);
/// Every rank's bytes on rank 0 (empty elsewhere).
std::vector<std::string> gather(const std::string& mine);
/// Rank 0's value on every rank.
int broadcast(int value);

/// Prints "interfere: error: rank R: MESSAGE" on stderr and ends the whole job with exit
/// status 2 (MPI_Abort): a failure only this rank sees (a body it cannot read, memory).
[[noreturn]] void abort_job(const World& w, const std::string& message);

}  // namespace interfere::mpi
