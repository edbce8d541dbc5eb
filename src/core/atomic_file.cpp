#include "interfere/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <unistd.h>

namespace interfere {

std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path p = target;
  p += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  return p;
}

Status write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path tmp = temporary_sibling(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return Error{.file = path.string(), .reason = std::string("cannot create: ") + std::strerror(errno)};
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    return Error{.file = path.string(), .reason = "write failed (disk full?)"};
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return Error{.file = path.string(), .reason = "cannot rename temporary file into place: " + ec.message()};
  }
  return {};
}

StagedFiles::~StagedFiles() {
  for (const auto& [tmp, target] : staged_) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  }
}

std::filesystem::path StagedFiles::stage(const std::filesystem::path& target) {
  staged_.emplace_back(temporary_sibling(target), target);
  return staged_.back().first;
}

Status StagedFiles::commit() {
  for (const auto& [tmp, target] : staged_) {
    std::error_code ec;
    std::filesystem::rename(tmp, target, ec);
    if (ec) return Error{.file = target.string(), .reason = "cannot rename temporary file into place: " + ec.message()};
  }
  staged_.clear();
  return {};
}

}  // namespace interfere
