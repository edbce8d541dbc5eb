// Atomic file output: content goes to a temporary file beside the target and is renamed over it only
// when complete, so a failed run never leaves a half-written or clobbered file behind.
#pragma once
#include <filesystem>
#include <string_view>
#include <utility>
#include <vector>

#include "interfere/core/error.h"

namespace interfere {

/// Writes `content` to `path` atomically.
Status write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Two-phase variant for several outputs that must appear together: stage() writes temporaries,
/// commit() renames them all, and the destructor removes whatever was not committed.
class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles();
  /// Returns the temporary path to write for `target` (created next to it).
  std::filesystem::path stage(const std::filesystem::path& target);
  Status commit();

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // (temp, target)
};

/// A unique temporary path in the directory of `target` (not created).
std::filesystem::path temporary_sibling(const std::filesystem::path& target);

}  // namespace interfere
