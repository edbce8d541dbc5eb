// What `interfere-mpi cell` and `interfere-mpi sweep` (issue #31, item 3; docs/mpi.md) share around
// their blocks of path points: each rank's block sent to rank 0 behind a fixed header, and rank 0's
// outputs (the CLI's JSON report plus "mpi", its CSV, its summary plus "(K ranks)").
#pragma once
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "comm.h"
#include "driver.h"
#include "report_envelope.h"

namespace interfere::mpi {

/// Every rank's header (plain bytes: every rank runs one binary) then its rows, on rank 0 in rank
/// order (empty elsewhere).
template <class Header>
std::vector<std::string> gather_blocks(const Header& head, const std::string& rows) {
  static_assert(std::is_trivially_copyable_v<Header>);
  std::string bytes(sizeof head, '\0');
  std::memcpy(bytes.data(), &head, sizeof head);
  bytes += rows;
  return gather(bytes);
}

/// One gathered block: its header into `head`, its rows returned.
template <class Header>
std::string_view block_rows(const std::string& block, Header& head) {
  std::memcpy(&head, block.data(), sizeof head);
  return std::string_view(block).substr(sizeof head);
}

/// Where rank 0 writes and whether it talks.
struct BlockOutputs {
  const std::string& json;
  const std::string& csv;
  bool quiet = false;
  std::chrono::steady_clock::time_point start;  ///< the run's start (the report's mpi.seconds)
};

/// Rank 0's files: report() (the CLI's JSON without the envelope) with "mpi": {ranks, seconds,
/// per_rank} to --json, then csv() to --csv.
template <class Report, class Csv>
void write_block_reports(const World& w, const BlockOutputs& out, nlohmann::json per_rank, Report&& report, Csv&& csv) {
  if (!out.json.empty()) {
    nlohmann::json j = report();
    j["mpi"] = {{"ranks", w.size},
                {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - out.start).count()},
                {"per_rank", std::move(per_rank)}};
    write_file(out.json, cli::report_text(std::move(j), 1));
  }
  if (!out.csv.empty()) write_file(out.csv, csv());
}

/// Rank 0's summary(), then "(K ranks)": unless quiet or an output is stdout.
template <class Summary>
void print_block_summary(const World& w, const BlockOutputs& out, Summary&& summary) {
  if (out.quiet || out.json == "-" || out.csv == "-") return;
  summary();
  std::printf("(%d ranks)\n", w.size);
}

}  // namespace interfere::mpi
