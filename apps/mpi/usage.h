// This process's resource use (getrusage), for the ranks' timings in interfere-mpi's reports (issue #31).
#pragma once

namespace interfere::mpi {

/// User + system CPU seconds this process has used so far.
double cpu_seconds();
/// This process's peak resident set (MB).
double peak_rss_mb();

}  // namespace interfere::mpi
