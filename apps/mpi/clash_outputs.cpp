// Rank 0's CSV tables and summary line parts of `interfere-mpi clash` (clash_outputs.h).
#include "clash_outputs.h"

#include <cctype>

#include "driver.h"
#include "interfere/scene/report.h"

namespace interfere::mpi {

void write_clash_tables(const Options& o, const scene::Scene& s, const std::vector<scene::ClashTest>& tests,
                        const scene::SceneClashResult& result) {
  if (!o.csv.empty()) write_file(o.csv, scene::clash_table_csv(s, result));
  if (!o.frames_csv.empty()) write_file(o.frames_csv, scene::frames_table_csv(result));
  if (!o.frame_pairs_csv.empty()) write_file(o.frame_pairs_csv, scene::frame_pairs_table_csv(s, tests, result));
}

std::FILE* summary_stream(const Options& o) {
  return o.json == "-" || o.csv == "-" || o.frames_csv == "-" || o.frame_pairs_csv == "-" ? stderr : stdout;
}

std::string summary_verdict(Verdict v) {
  std::string verdict = verdict_name(v);
  if (v == Verdict::clash || v == Verdict::undecided)
    for (char& ch : verdict) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return verdict;
}

}  // namespace interfere::mpi
