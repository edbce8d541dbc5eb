// Atomic file output: content goes to a temporary file beside the target and is renamed over it only
// when complete, so a failed run never leaves a half-written or clobbered file behind.
// Through the file system as it is (issue #23, item 11): a symbolic link is written through (the
// link stays, its final target is replaced atomically: the temporary file is made in the target's
// directory); an existing special file (FIFO, character device such as /dev/stdout or /dev/null,
// socket) cannot be replaced and is written directly, the whole output buffered in memory first so
// that a failing body writes nothing. Standard output as "-" is a CLI convention, not handled here.
#pragma once
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "interfere/core/error.h"

namespace interfere {

/// The file a write to `path` lands in: `path` with its symbolic links followed (relative link
/// targets resolved against the link's directory; a dangling link gives its missing target); an
/// error after 40 links (a loop).
Expected<std::filesystem::path> resolve_output_path(const std::filesystem::path& path);

/// Writes `content` to `path` atomically.
Status write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Atomic write with a caller-supplied body: `body(file)` writes everything and returns 0 or an
/// errno value. The data is flushed and fsync'ed before the rename; a replaced file keeps its
/// permissions; on any failure (or exception) the temporary file is removed and `path` is untouched.
/// `body` writes a stream (fwrite/fprintf): it may not seek, nor use the file descriptor.
Status write_file_atomic(const std::filesystem::path& path, const std::function<int(std::FILE*)>& body);

/// Writes what `body` writes to the open descriptor `fd` (a pipe, a terminal, a FIFO: anything
/// that cannot be replaced), buffered in memory first so that a failing body writes nothing; `name`
/// names the destination in errors. The descriptor stays open.
Status write_to_descriptor(int fd, const std::string& name, const std::function<int(std::FILE*)>& body);

/// A unique temporary path in the directory of `target` (not created).
std::filesystem::path temporary_sibling(const std::filesystem::path& target);

}  // namespace interfere
