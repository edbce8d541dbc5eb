// interfere-mpi bearing (issue #31, item 3; docs/mpi.md, "Time series"). Bearing assembly frames are
// independent (assembly_run.cpp: each (frame, pair) is a pure function of that frame's poses), so
// rank k of K solves frames [k F / K, (k + 1) F / K) with bearing::run_assembly on that block of the
// motion (generated with the same seed on every rank, or read from the motion file by every rank),
// the rows (trivially copyable) are gathered to rank 0 in rank order, renumbered to global frames,
// summarised by bearing::summarize_assembly and written by the CLI's writer
// (apps/cli/bearing_assembly_report.h): the same CSV, and the same JSON apart from timing, threads,
// seconds and the added "mpi" section.
#include "bearing.h"

#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "args.h"
#include "driver.h"
#include "bearing_assembly_report.h"
#include "interfere/bearing/assembly.h"
#include "report_envelope.h"

namespace interfere::mpi {
namespace {

using namespace interfere::bearing;
using Clock = std::chrono::steady_clock;

std::string csv_text(const Assembly& as, const AssemblyResult& r) {
  char* buf = nullptr;
  std::size_t size = 0;
  std::FILE* f = open_memstream(&buf, &size);
  if (!f) throw std::runtime_error("cannot allocate the CSV text");
  const int bad = cli::write_assembly_csv(f, as, r);
  std::fclose(f);
  std::string text(buf, size);
  std::free(buf);
  if (bad) throw std::runtime_error("cannot format the CSV rows");
  return text;
}

int run_checked(const World& w, const BearingOptions& o) {
  const auto t_total = Clock::now();
  // The inputs: every rank reads them; the ranks agree on any error before the gather (a rank that
  // alone failed would leave the others waiting), rank 0 printing the first rank's message.
  std::optional<AssemblySpec> spec;
  std::optional<Assembly> as;
  AssemblyMotion motion;
  std::string error;
  try {
    Expected<AssemblySpec> read = read_assembly_file(o.assembly);
    if (!read) throw InputError(read.error().message());
    spec = std::move(*read);
    if (o.frames) spec->frames = *o.frames;
    if (o.seed) spec->seed = *o.seed;
    if (o.clearance) spec->clearance = *o.clearance;
    if (Status s = validate_assembly(*spec); !s) {
      Error e = s.error();
      if (e.file.empty()) e.file = o.assembly;
      throw InputError(e.message());
    }
    Expected<Assembly> built = build_assembly(*spec);
    if (!built) throw InputError(built.error().message());
    as = std::move(*built);
    if (!o.motion.empty()) {
      Expected<AssemblyMotion> m = read_assembly_motion(*as, o.motion);
      if (!m) throw InputError(m.error().message());
      motion = std::move(*m);
    } else {
      motion = generate_motion(*as, spec->frames, spec->seed);  // (frame f depends on (seed, f) only)
    }
    // Outputs: their folders must exist, and no output may be an input (checked by every rank
    // before any work, as `interfere bearing` checks them first; rank 0 writes them at the end).
    for (const auto& [flag, out] : {std::pair<const char*, const std::string*>{"--out", &o.out}, {"--json", &o.json}}) {
      if (out->empty() || *out == "-") continue;
      const std::filesystem::path path = std::filesystem::absolute(*out);
      if (!std::filesystem::is_directory(path.parent_path()))
        throw InputError(std::string(flag) + " " + *out + ": no folder " + path.parent_path().string());
      for (const std::string* input : {&o.assembly, &o.motion})
        if (!input->empty() && path == std::filesystem::absolute(*input))
          throw InputError(std::string(flag) + " " + *out + ": is an input file");
    }
    if (!o.out.empty() && o.out != "-" && !o.json.empty() && std::filesystem::absolute(o.out) == std::filesystem::absolute(o.json))
      throw InputError("--out and --json name the same file " + o.out);
  } catch (const InputError& e) {
    error = e.what();
  }
  for (const std::string& e : allgather(error))
    if (!e.empty()) throw InputError(e);
  const FailOn fail = o.fail_on.empty() ? FailOn{} : *parse_fail_on(o.fail_on);
  std::unique_ptr<tbb::global_control> threads;
  if (o.threads > 0) threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);

  // This rank's block of frames.
  const std::size_t nf = motion.poses.size(), k = static_cast<std::size_t>(w.size), r = static_cast<std::size_t>(w.rank);
  const std::size_t lo = r * nf / k, hi = (r + 1) * nf / k;
  if (w.rank == 0 && k > nf && !o.quiet)
    std::fprintf(stderr, "[interfere-mpi] warning: %d ranks for %zu frames: %zu ranks idle\n", w.size, nf, k - nf);
  AssemblyMotion block;
  block.source = motion.source;
  block.poses.assign(motion.poses.begin() + static_cast<std::ptrdiff_t>(lo), motion.poses.begin() + static_cast<std::ptrdiff_t>(hi));
  const auto t_run = Clock::now();
  AssemblyResult mine;
  if (!block.poses.empty()) mine = run_assembly(*as, block);
  const double run_seconds = std::chrono::duration<double>(Clock::now() - t_run).count();
  for (AssemblyRow& row : mine.rows) row.frame += static_cast<std::int32_t>(lo);

  // Rows as bytes (the same executable on every rank), then the rank's block and seconds.
  static_assert(std::is_trivially_copyable_v<AssemblyRow>);
  std::string bytes(sizeof(double), '\0');
  std::memcpy(bytes.data(), &run_seconds, sizeof(double));
  bytes.append(reinterpret_cast<const char*>(mine.rows.data()), mine.rows.size() * sizeof(AssemblyRow));
  const std::vector<std::string> all = gather(bytes);

  int status = 0;
  if (w.rank == 0) {
    AssemblyResult res;
    nlohmann::json ranks = nlohmann::json::array();
    for (std::size_t q = 0; q < all.size(); ++q) {
      double s = 0;
      std::memcpy(&s, all[q].data(), sizeof(double));
      const std::size_t n = (all[q].size() - sizeof(double)) / sizeof(AssemblyRow);
      const std::size_t at = res.rows.size();
      res.rows.resize(at + n);
      if (n) std::memcpy(static_cast<void*>(res.rows.data() + at), all[q].data() + sizeof(double), n * sizeof(AssemblyRow));
      ranks.push_back({{"rank", q}, {"frames", {q * nf / k, (q + 1) * nf / k}}, {"rows", n}, {"seconds", s}});
    }
    if (res.rows.size() != nf * as->pairs.size())
      throw std::logic_error("gathered " + std::to_string(res.rows.size()) + " rows, expected " + std::to_string(nf * as->pairs.size()));
    summarize_assembly(res, as->pairs.size());
    res.frames = static_cast<int>(nf);
    res.seconds = std::chrono::duration<double>(Clock::now() - t_total).count();
    status = verdict_exit_status(res.verdict, fail);
    const int nthreads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    if (!o.out.empty()) write_file(o.out, csv_text(*as, res));
    if (!o.json.empty()) {
      nlohmann::json j = cli::assembly_summary(*as, motion, res, spec->seed, status, nthreads);
      j["mpi"] = {{"ranks", w.size}, {"per_rank", std::move(ranks)}};
      write_file(o.json, cli::report_text(std::move(j)));
    }
    if (!o.quiet) {
      const AssemblyRow& wr = res.rows[res.worst];
      std::FILE* out = o.out == "-" || o.json == "-" ? stderr : stdout;
      std::fprintf(out, "%s: %zu bearings, %zu parts, %zu pairs x %d frames, %llu interfering pair-frames, worst %s %s-%s "
                   "distance %.17g (frame %d) (%d ranks)\n",
                   verdict_name(res.verdict), as->spec.bearings.size(), as->parts.size(), as->pairs.size(), res.frames,
                   static_cast<unsigned long long>(res.interfering_rows), assembly_pair_kind_name(as->pairs[wr.pair].kind),
                   as->parts[as->pairs[wr.pair].a].id.c_str(), as->parts[as->pairs[wr.pair].b].id.c_str(),
                   wr.result.distance, wr.frame, w.size);
    }
  }
  return broadcast(status);
}

}  // namespace

int run_bearing(const World& w, int argc, char** argv) {
  return run_guarded(w, [&] { return run_checked(w, parse_bearing(argc, argv)); });  // (args.h: CLI11)
}

}  // namespace interfere::mpi
