// Shared helpers of the CAD tests (tests/cad/): a per-process scratch directory.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>

namespace interfere::cad::testing {

/// temp/<prefix>_<pid>, created.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const auto d = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace interfere::cad::testing
