// The few MPI collectives interfere-mpi uses, on byte strings (issue #31).
#pragma once
#include <mpi.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace interfere::mpi {

struct World {
  int rank = 0, size = 1;
};

/// Every rank's bytes, on every rank, in rank order.
std::vector<std::string> allgather(const std::string& mine);

/// Every rank's bytes received into one buffer (no copy per rank: the body records of a 10^5-body
/// product are megabytes on every rank); part(r) is rank r's.
struct Gathered {
  std::string all;
  std::vector<std::size_t> offset;  ///< ranks + 1 offsets into `all`
  std::size_t size() const { return offset.empty() ? 0 : offset.size() - 1; }
  std::string_view part(std::size_t r) const { return std::string_view(all).substr(offset[r], offset[r + 1] - offset[r]); }
};
Gathered allgather_buffer(const std::string& mine);
/// As gather, into one buffer on rank 0 (empty elsewhere).
Gathered gather_buffer(const std::string& mine);
/// Every rank's bytes on rank 0 (empty elsewhere).
std::vector<std::string> gather(const std::string& mine);
/// Rank 0's value on every rank.
int broadcast(int value);

/// Prints "interfere: error: rank R: MESSAGE" on stderr and ends the whole job with exit
/// status 2 (MPI_Abort): a failure only this rank sees (a body it cannot read, memory).
[[noreturn]] void abort_job(const World& w, const std::string& message);

}  // namespace interfere::mpi
