// Hand-over of CAD runs from `interfere` to `interfere-cad` (cad_exec.h).
#include "cad_exec.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common.h"

namespace interfere::cli {
namespace {
char** g_argv = nullptr;
}

void remember_arguments(char** argv) { g_argv = argv; }

void require_cad_for_step_files(const std::vector<std::string>& files) {
  for (const std::string& f : files)
    if (is_step_file(f)) require_cad("STEP input " + f);
}

void use_installed_data_dir() {
#if defined(INTERFERE_CAD_DATA_FROM_LIBEXEC)  // (share/interfere relative to libexec/interfere)
  namespace fs = std::filesystem;
  if (std::getenv("INTERFERE_DATA_DIR")) return;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return;
  const fs::path data = (self.parent_path() / INTERFERE_CAD_DATA_FROM_LIBEXEC).lexically_normal();
  if (fs::is_regular_file(data / "features" / "library.json", ec)) ::setenv("INTERFERE_DATA_DIR", data.c_str(), 0);
#endif
}

#if defined(INTERFERE_HAS_CAD)
void require_cad(const std::string&) {}
#elif defined(INTERFERE_CAD_EXECUTABLE)
// glibc malloc settings for the CAD process (issue #29: the casing's whole command), read by glibc
// at its start, so given here, in the environment of the exec; a GLIBC_TUNABLES the user set is
// left as it is. BRepMesh, the importer and the simplifier allocate and free many arrays of up to
// a few MB: by default each one above the dynamic mmap threshold is a fresh mmap whose every 4 KiB
// page faults in (about 2 us a page on this project's VMs), and freed memory at the heap's top is
// handed back and faulted in again. With these the arrays come from the heap (mmap threshold
// 32 MiB), which grows 64 MiB at a time (top pad) and is not trimmed (trim threshold 1 GiB: the
// process is short-lived), in transparent huge pages where the kernel allows
// them for madvised memory (hugetlb=1: malloc madvises its heaps). The casing P1/P2: 13,300 ->
// 1,900 minor page faults, CPU time 0.90 -> 0.71 s, peak resident set 63 -> 73 MB (docs/simplify.md,
// "Whole command on the casing", fourth round).
static void use_cad_malloc_settings() {
  if (std::getenv("GLIBC_TUNABLES")) return;
  ::setenv("GLIBC_TUNABLES",
           "glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=67108864:"
           "glibc.malloc.trim_threshold=1073741824",
           0);
}

// INTERFERE_CAD_EXECUTABLE: its file name; INTERFERE_CAD_LIBEXEC: the installed libexec folder
// relative to the installed bin folder (apps/cli/CMakeLists.txt).
void require_cad(const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw InputError(what + " needs " INTERFERE_CAD_EXECUTABLE ", which is found beside this executable: /proc/self/exe: " + ec.message());
  const fs::path dir = self.parent_path();
  // The build tree has it beside `interfere`, the installed tree in libexec.
  const fs::path candidates[] = {dir / INTERFERE_CAD_EXECUTABLE, (dir / INTERFERE_CAD_LIBEXEC / INTERFERE_CAD_EXECUTABLE).lexically_normal()};
  std::string tried;
  for (const fs::path& p : candidates) {
    tried += (tried.empty() ? "" : ", ") + p.string();
    if (::access(p.c_str(), X_OK) != 0) continue;
    std::fflush(nullptr);
    use_cad_malloc_settings();
    ::execv(p.c_str(), g_argv);
    throw InputError(what + " needs " + p.string() + ", which does not run: " + std::strerror(errno));
  }
  throw InputError(what + " needs the CAD executable " INTERFERE_CAD_EXECUTABLE " (interfere built with OpenCASCADE), "
                   "which is missing: not found at " + tried);
}
#else
void require_cad(const std::string& what) {
  throw InputError(what + " needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
}
#endif

}  // namespace interfere::cli
