// MPI collectives on byte strings (comm.h; issue #31).
#include "comm.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numeric>

namespace interfere::mpi {
namespace {

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> d(counts.size(), 0);
  for (std::size_t i = 1; i < counts.size(); ++i) d[i] = d[i - 1] + counts[i - 1];
  return d;
}

// Waits until every rank has arrived, sleeping (MPI_Ibarrier polled every 0.2 ms) instead of
// spinning in the collective as Open MPI does: a rank that finished its share early leaves its
// core to the ranks still working (2 ranks on 2 shared cores: a spinning rank slows the busy one).
void wait_for_all() {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  int done = 0;
  MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  while (!done) {
    const timespec pause{0, 200000};
    nanosleep(&pause, nullptr);
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

}  // namespace

Gathered allgather_buffer(const std::string& mine) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  wait_for_all();
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  const std::vector<int> displ = displacements(counts);
  Gathered out;
  out.all.resize(static_cast<std::size_t>(std::accumulate(counts.begin(), counts.end(), 0L)));
  MPI_Allgatherv(mine.data(), n, MPI_BYTE, out.all.data(), counts.data(), displ.data(), MPI_BYTE, MPI_COMM_WORLD);
  for (std::size_t r = 0; r < counts.size(); ++r) out.offset.push_back(static_cast<std::size_t>(displ[r]));
  out.offset.push_back(out.all.size());
  return out;
}

Gathered gather_buffer(const std::string& mine) {
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  wait_for_all();
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  const std::vector<int> displ = displacements(counts);
  Gathered out;
  if (rank == 0) out.all.resize(static_cast<std::size_t>(std::accumulate(counts.begin(), counts.end(), 0L)));
  MPI_Gatherv(mine.data(), n, MPI_BYTE, out.all.data(), counts.data(), displ.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
  if (rank == 0) {
    for (std::size_t r = 0; r < counts.size(); ++r) out.offset.push_back(static_cast<std::size_t>(displ[r]));
    out.offset.push_back(out.all.size());
  }
  return out;
}

namespace {
std::vector<std::string> split(const Gathered& g) {
  std::vector<std::string> out;
  for (std::size_t r = 0; r < g.size(); ++r) out.emplace_back(g.part(r));
  return out;
}
}  // namespace

std::vector<std::string> allgather(const std::string& mine) { return split(allgather_buffer(mine)); }

std::vector<std::string> gather(const std::string& mine) { return split(gather_buffer(mine)); }

int broadcast(int value) {
  wait_for_all();  // (the other ranks wait for rank 0's merge without spinning)
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

void abort_job(const World& w, const std::string& message) {
  std::fprintf(stderr, "interfere: error: rank %d: %s\n", w.rank, message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 2);
  std::exit(2);
}

}  // namespace interfere::mpi
