// What the truth-set tests share (tests/cad/test_hole_truth.cpp, test_floor_truth.cpp; issue #29,
// item 2): the labels' files, the STEP files they label (../shared/data/step, absent in a clone)
// the one-to-one matching of recognised features to the labels, and the precision / recall counts and
// their table.
#pragma once
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace interfere::cad::testing {

/// ../shared/data/step beside the repository (skip when it is not a directory).
inline std::filesystem::path shared_step_dir() {
  return std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step";
}

/// tests/data/<set>/*.json, sorted by name.
inline std::vector<std::filesystem::path> truth_files(const std::string& set) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(INTERFERE_SOURCE_DIR) / "tests" /
                                                           "data" / set))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Matched counts: precision = found / reported, recall = found / truth (1 when nothing to count);
/// "typed" when the type matches too.
struct Score {
  std::size_t truth = 0, reported = 0, found = 0, typed = 0;
  double precision() const { return reported ? double(found) / double(reported) : 1.0; }
  double recall() const { return truth ? double(found) / double(truth) : 1.0; }
  double typed_precision() const { return reported ? double(typed) / double(reported) : 1.0; }
  double typed_recall() const { return truth ? double(typed) / double(truth) : 1.0; }
};

/// One part's one-to-one matching, typed matches first (pass 0 pairs a label with a recognised
/// feature of its type only, pass 1 with any left): label i and feature j pair when matches(truth[i],
/// found[j]); both have a `type`.
struct Matching {
  Score score;
  std::vector<char> truth_used, found_used, truth_typed;
};
template <class T, class F, class Matches>
Matching match_one_to_one(const std::vector<T>& truth, const std::vector<F>& found, Matches&& matches) {
  Matching m;
  m.score.truth = truth.size(), m.score.reported = found.size();
  m.truth_used.assign(truth.size(), 0), m.found_used.assign(found.size(), 0), m.truth_typed.assign(truth.size(), 0);
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < truth.size(); ++i)
      for (std::size_t j = 0; j < found.size() && !m.truth_used[i]; ++j) {
        if (m.found_used[j] || (pass == 0 && found[j].type != truth[i].type) || !matches(truth[i], found[j])) continue;
        m.truth_used[i] = m.found_used[j] = 1;
        ++m.score.found;
        if (found[j].type == truth[i].type) ++m.score.typed, m.truth_typed[i] = 1;
      }
  return m;
}

/// Adds a part's matching to the counts per type (recall over the labels of the type, precision over
/// the recognised features of the type) and to the total.
template <class T, class F>
void add_part(const Matching& m, const std::vector<T>& truth, const std::vector<F>& found,
              std::map<std::string, Score>& by_type, Score& total) {
  for (std::size_t i = 0; i < truth.size(); ++i) {
    Score& b = by_type[truth[i].type];
    ++b.truth, b.found += m.truth_used[i], b.typed += m.truth_typed[i];
  }
  for (std::size_t j = 0; j < found.size(); ++j) ++by_type[found[j].type].reported;
  total.truth += m.score.truth, total.reported += m.score.reported, total.found += m.score.found,
      total.typed += m.score.typed;
}

/// A part's table row, and its line on stdout (the file name `width` wide).
inline nlohmann::json part_row(const std::string& file, const Score& s, int width) {
  std::printf("%-*s truth %3zu reported %3zu  P %.3f R %.3f  typed P %.3f R %.3f\n", width, file.c_str(), s.truth,
              s.reported, s.precision(), s.recall(), s.typed_precision(), s.typed_recall());
  return {{"file", file}, {"truth", s.truth}, {"reported", s.reported}, {"found", s.found}, {"typed", s.typed},
          {"precision", s.precision()}, {"recall", s.recall()}, {"typed_precision", s.typed_precision()},
          {"typed_recall", s.typed_recall()}};
}

/// The counts per type (a line each on stdout, the type `width` wide), then the TOTAL line.
inline nlohmann::json type_rows(const std::map<std::string, Score>& by_type, const Score& total, int width) {
  nlohmann::json types = nlohmann::json::object();
  for (const auto& [type, b] : by_type) {
    types[type] = {{"truth", b.truth}, {"reported", b.reported}, {"typed_found", b.typed}, {"found", b.found}};
    std::printf("  %-*s truth %3zu found %3zu typed %3zu reported %3zu\n", width, type.c_str(), b.truth, b.found,
                b.typed, b.reported);
  }
  std::printf("TOTAL truth %zu reported %zu P %.3f R %.3f typed P %.3f R %.3f\n", total.truth, total.reported,
              total.precision(), total.recall(), total.typed_precision(), total.typed_recall());
  return types;
}

/// The table (parts, types, total) to the file the environment variable `env` names, if it is set
/// (tools/hole_truth/pr_table.py, tools/floor_truth/pr_table.py put it in docs/simplify.md).
inline void write_pr_json(const char* env, const nlohmann::json& parts, const nlohmann::json& types, const Score& total) {
  const char* out = std::getenv(env);
  if (!out) return;
  std::ofstream o(out);
  o << nlohmann::json{{"parts", parts},
                      {"types", types},
                      {"total",
                       {{"truth", total.truth}, {"reported", total.reported}, {"found", total.found}, {"typed", total.typed}}}}
           .dump(1);
}

}  // namespace interfere::cad::testing
