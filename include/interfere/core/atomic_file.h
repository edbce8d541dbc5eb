// Atomic file output: content goes to a temporary file beside the target and is renamed over it only
// when complete, so a failed run never leaves a half-written or clobbered file behind.
#pragma once
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string_view>

#include "interfere/core/error.h"

namespace interfere {

/// Writes `content` to `path` atomically.
Status write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Atomic write with a caller-supplied body: `body(file)` writes everything and returns 0 or an
/// errno value. The data is flushed and fsync'ed before the rename; a replaced file keeps its
/// permissions; on any failure (or exception) the temporary file is removed and `path` is untouched.
Status write_file_atomic(const std::filesystem::path& path, const std::function<int(std::FILE*)>& body);

/// A unique temporary path in the directory of `target` (not created).
std::filesystem::path temporary_sibling(const std::filesystem::path& target);

}  // namespace interfere
