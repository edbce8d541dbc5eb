#include "interfere/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace interfere {

std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path p = target;
  p += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  return p;
}

Expected<std::filesystem::path> resolve_output_path(const std::filesystem::path& path) {
  // Follow the chain of links by hand (readlink), not canonical(): a dangling link is written
  // through too (its target is created, as a shell's redirection does).
  std::filesystem::path p = path;
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    const auto st = std::filesystem::symlink_status(p, ec);
    if (ec || !std::filesystem::is_symlink(st)) return p;
    if (hops == 40) return Error{.file = path.string(), .reason = "too many levels of symbolic links"};
    const std::filesystem::path target = std::filesystem::read_symlink(p, ec);
    if (ec) return Error{.file = path.string(), .reason = "cannot read symbolic link '" + p.string() + "': " + ec.message()};
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
}

namespace {

// An existing file that is neither regular nor a directory nor a link (a FIFO, a character or
// block device, a socket): written in place, it cannot be replaced.
bool is_special_file(const std::filesystem::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return false;
  return !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

Status write_special(const std::filesystem::path& path, const std::string& name,
                     const std::function<int(std::FILE*)>& body) {
  // O_WRONLY without O_TRUNC/O_CREAT: the file exists and is not replaced (a FIFO waits for its
  // reader). Opened before the body runs; a body that fails writes nothing (write_to_descriptor).
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return Error{.file = name, .reason = std::string("cannot open for writing: ") + std::strerror(errno)};
  Status s = write_to_descriptor(fd, name, body);
  if (::close(fd) != 0 && s && errno != EINTR)
    return Error{.file = name, .reason = std::string("write failed: ") + std::strerror(errno)};
  return s;
}

}  // namespace

Status write_to_descriptor(int fd, const std::string& name, const std::function<int(std::FILE*)>& body) {
  char* data = nullptr;
  std::size_t size = 0;
  std::FILE* mem = ::open_memstream(&data, &size);
  if (!mem) return Error{.file = name, .reason = std::string("cannot buffer the output: ") + std::strerror(errno)};
  struct Free {
    std::FILE*& mem;
    char*& data;
    ~Free() {
      if (mem) std::fclose(mem);
      std::free(data);
    }
  } release{mem, data};
  int err = body(mem);
  if (std::fclose(mem) != 0 && err == 0) err = errno;
  mem = nullptr;
  if (err != 0) return Error{.file = name, .reason = std::string("write failed: ") + std::strerror(err)};
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Error{.file = name, .reason = std::string("write failed: ") + std::strerror(n < 0 ? errno : EIO)};
    done += static_cast<std::size_t>(n);
  }
  return {};
}

Status write_file_atomic(const std::filesystem::path& path, const std::function<int(std::FILE*)>& body) {
  const std::string name = path.string();
  // Through symbolic links: the link stays, its final target is replaced (issue #23, item 11).
  const Expected<std::filesystem::path> resolved = resolve_output_path(path);
  if (!resolved) return resolved.error();
  const std::filesystem::path& target = *resolved;
  if (is_special_file(target)) return write_special(target, name, body);
  const std::filesystem::path tmp = temporary_sibling(target);
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
  if (const auto st = std::filesystem::status(target, ec); !ec && std::filesystem::is_regular_file(st)) {
    std::filesystem::permissions(tmp, st.permissions(), ec);  // keep the permissions of a replaced file
  }
  std::filesystem::rename(tmp, target, ec);
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
