// Shared helpers of the CAD tests (tests/cad/): a per-process scratch directory, generated test
// parts read back through STEP.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "interfere/cad/model.h"

namespace interfere::cad::testing {

/// temp/<prefix>_<pid>, created.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const auto d = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

/// The one part of TestPart p written to STEP and imported (once per process; a failure is a test
/// failure and gives an empty part list, so `.at(0)` throws).
inline const Part& generated_part(TestPart p) {
  static std::map<TestPart, CadModel> cache;
  if (auto it = cache.find(p); it == cache.end()) {
    const auto file = scratch_dir("interfere_test_parts") / (std::string(test_part_name(p)) + ".step");
    const Status s = write_test_part(p, file);
    EXPECT_TRUE(s.ok()) << s.error().message();
    auto m = import_step(file);
    EXPECT_TRUE(m.has_value() && m->parts.size() == 1);
    cache[p] = m.has_value() ? std::move(*m) : CadModel{};
  }
  return cache[p].parts.at(0);
}

}  // namespace interfere::cad::testing
