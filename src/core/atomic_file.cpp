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

Status write_file_atomic(const std::filesystem::path& path, const std::function<int(std::FILE*)>& body) {
  const std::string name = path.string();
  const std::filesystem::path tmp = temporary_sibling(path);
  std::FILE* file = std::fopen(tmp.c_str(), "wbx");
  if (!file) {
    return Error{.file = name, .reason = "cannot create temporary file '" + tmp.string() + "': " + std::strerror(errno)};
  }
  // Whatever happens from here (including an exception), the temporary file does not outlive us.
  struct Cleanup {
    std::FILE* file;
    const std::filesystem::path& tmp;
    bool armed = true;
    ~Cleanup() {
      if (file) std::fclose(file);
      std::error_code ec;
      if (armed) std::filesystem::remove(tmp, ec);
    }
  } cleanup{file, tmp};
  int err = body(file);
  if (err == 0 && std::fflush(file) != 0) err = errno;
  // Data on disk before the rename publishes it (otherwise a crash can leave an empty target).
  if (err == 0 && ::fsync(::fileno(file)) != 0 && errno != EINVAL && errno != EROFS) err = errno;
  cleanup.file = nullptr;
  if (std::fclose(file) != 0 && err == 0) err = errno;
  if (err != 0) return Error{.file = name, .reason = std::string("write failed: ") + std::strerror(err)};
  std::error_code ec;
  if (const auto st = std::filesystem::status(path, ec); !ec && std::filesystem::is_regular_file(st)) {
    std::filesystem::permissions(tmp, st.permissions(), ec);  // keep the permissions of a replaced file
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) return Error{.file = name, .reason = "cannot replace the target with the written temporary file: " + ec.message()};
  cleanup.armed = false;
  return {};
}

Status write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  return write_file_atomic(path, [content](std::FILE* f) {
    return std::fwrite(content.data(), 1, content.size(), f) == content.size() ? 0 : (errno ? errno : EIO);
  });
}

}  // namespace interfere
