// What interfere-mpi's time-series subcommands (`bearing`, `cell`, `sweep`; docs/mpi.md "Time
// series") share around their work: the input error every rank finds alike, the atomic output
// write and the common error handling of a subcommand's entry point (issue #31).
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

#include "args.h"
#include "comm.h"

namespace interfere::mpi {

/// An input error every rank finds the same way (options, the input files): rank 0 says it, exit 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writes text to path through a temporary file renamed over it (nothing half-written is left);
/// "-" is stdout, an empty path writes nothing. Throws std::runtime_error naming the path.
void write_file(const std::string& path, const std::string& text);

/// Runs a subcommand's body (parsing included) with the drivers' conventions: --help/--version on
/// rank 0's stdout, exit 0; usage and input errors printed once by rank 0, exit status 2 on every
/// rank (each rank finds them alike, so no MPI_Abort is needed); anything else propagates to main.
template <class Body>
int run_guarded(const World& w, Body&& body) {
  try {
    return body();
  } catch (const InfoRequest& info) {
    if (w.rank == 0) std::fputs(info.text.c_str(), stdout);
    return 0;
  } catch (const UsageError& e) {
    if (w.rank == 0) std::fprintf(stderr, "interfere: error: %s\n", e.what());
    return 2;
  } catch (const InputError& e) {
    if (w.rank == 0) std::fprintf(stderr, "interfere: error: %s\n", e.what());
    return 2;
  }
}

}  // namespace interfere::mpi
