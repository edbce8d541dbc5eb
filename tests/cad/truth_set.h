// What the truth-set tests share (tests/cad/test_hole_truth.cpp, test_floor_truth.cpp; issue #29,
// item 2): the labels' files, the STEP files they label (../shared/data/step, absent in a clone)
// and the precision / recall counts.
#pragma once
#include <algorithm>
#include <cstddef>
#include <filesystem>
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

}  // namespace interfere::cad::testing
