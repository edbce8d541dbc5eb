// Shared plumbing of the fuzz targets (tests/fuzz/): a registry of entry points, so that one replay
// driver (replay_main.cpp, built with any compiler) can run every target over its committed
// corpus, and the invariant check that aborts under libFuzzer but, in the replay driver, throws so
// that every failing corpus file is listed before the test fails.
//
// A target file defines `int entry(const std::uint8_t*, std::size_t)` and registers it with
// INTERFERE_FUZZ_TARGET(name, entry). Built as a libFuzzer binary (INTERFERE_LIBFUZZER defined),
// the same macro also defines LLVMFuzzerTestOneInput.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>

namespace interfere::fuzz {

using Entry = int (*)(const std::uint8_t* data, std::size_t size);

inline std::map<std::string, Entry>& registry() {
  static std::map<std::string, Entry> targets;
  return targets;
}

inline bool register_target(const char* name, Entry entry) {
  registry()[name] = entry;
  return true;
}

/// An invariant violation found while replaying (the replay driver catches it and goes on).
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Set by the replay driver: violations throw Failure instead of aborting.
inline bool& replay_mode() {
  static bool on = false;
  return on;
}

/// True when $INTERFERE_FUZZ_IGNORE (a comma-separated list) names `tag`: lets a fuzzing run go on
/// past a known, reported library bug (the corpus replay never sets it).
inline bool ignored(const char* tag) {
  const char* env = std::getenv("INTERFERE_FUZZ_IGNORE");
  if (!env) return false;
  const std::string list = std::string(",") + env + ",";
  return list.find(std::string(",") + tag + ",") != std::string::npos;
}

[[noreturn]] inline void fail(const char* file, int line, const std::string& what) {
  const std::string msg =
      std::string(file) + ":" + std::to_string(line) + ": invariant violated: " + what;
  if (replay_mode()) throw Failure(msg);
  std::fprintf(stderr, "%s\n", msg.c_str());
  std::fflush(stderr);
  std::abort();
}

/// A private directory for a target's input files: $INTERFERE_FUZZ_TMPDIR, else /dev/shm (the
/// writers fsync; tmpfs keeps that cheap), else the system temp directory. One per tag, removed at
/// exit.
inline const std::filesystem::path& work_dir(const std::string& tag) {
  namespace fs = std::filesystem;
  struct Dir {
    fs::path path;
    ~Dir() {
      std::error_code ec;
      if (!path.empty()) fs::remove_all(path, ec);
    }
  };
  static std::map<std::string, Dir> dirs;
  Dir& d = dirs[tag];
  if (!d.path.empty()) return d.path;
  std::error_code ec;
  fs::path base;
  if (const char* env = std::getenv("INTERFERE_FUZZ_TMPDIR"); env && *env) {
    base = env;
  } else if (fs::is_directory("/dev/shm", ec) && ::access("/dev/shm", W_OK) == 0) {
    base = "/dev/shm";
  } else {
    base = fs::temp_directory_path();
  }
  std::string templ = (base / ("interfere_fuzz_" + tag + "_XXXXXX")).string();
  if (!::mkdtemp(templ.data())) {
    std::fprintf(stderr, "fuzz: cannot create a directory under %s\n", base.c_str());
    std::abort();
  }
  d.path = templ;
  return d.path;
}

/// Writes the fuzz input to `p` (aborts if it cannot: the harness itself is broken then).
inline void put_file(const std::filesystem::path& p, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(p.c_str(), "wb");
  const bool ok = f && (size == 0 || std::fwrite(data, 1, size, f) == size);
  if (f) std::fclose(f);
  if (!ok) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", p.c_str());
    std::abort();
  }
}

}  // namespace interfere::fuzz

/// Aborts (libFuzzer) or throws (replay) with `what` (a std::string expression, evaluated only on
/// failure) when `cond` is false.
#define FUZZ_CHECK(cond, what)                                        \
  do {                                                                \
    if (!(cond)) ::interfere::fuzz::fail(__FILE__, __LINE__, (what)); \
  } while (0)

#ifdef INTERFERE_LIBFUZZER
#define INTERFERE_FUZZ_TARGET(name, entry)                                            \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    return entry(data, size);                                                         \
  }                                                                                   \
  static const bool interfere_fuzz_registered_##entry =                               \
      ::interfere::fuzz::register_target(name, entry)
#else
#define INTERFERE_FUZZ_TARGET(name, entry)              \
  static const bool interfere_fuzz_registered_##entry = \
      ::interfere::fuzz::register_target(name, entry)
#endif
