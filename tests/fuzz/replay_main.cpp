// interfere_fuzz_replay: runs a fuzz target's entry point over corpus files without libFuzzer, so
// that the committed seed corpus (tests/fuzz/corpus/<target>/) is a regression test with any
// compiler (ctest fuzz_replay_<target>).
//
//   interfere_fuzz_replay TARGET PATH...   PATH: a file, or a directory (its regular files, sorted)
//   interfere_fuzz_replay --list
//
// Invariant violations are collected (every failing file is listed) and make the exit status 1;
// a crash in the library ends the run at once (the last "running" line names the input when
// INTERFERE_FUZZ_VERBOSE is set).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_common.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  auto& targets = interfere::fuzz::registry();
  if (argc == 2 && std::string(argv[1]) == "--list") {
    for (const auto& [name, entry] : targets) std::printf("%s\n", name.c_str());
    return 0;
  }
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s TARGET PATH... | --list\n", argv[0]);
    return 2;
  }
  const auto it = targets.find(argv[1]);
  if (it == targets.end()) {
    std::fprintf(stderr, "unknown fuzz target '%s' (--list shows them)\n", argv[1]);
    return 2;
  }
  std::vector<fs::path> files;
  for (int i = 2; i < argc; ++i) {
    const fs::path p = argv[i];
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> in_dir;
      for (const auto& e : fs::directory_iterator(p))
        if (e.is_regular_file()) in_dir.push_back(e.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else if (fs::is_regular_file(p, ec)) {
      files.push_back(p);
    } else {
      std::fprintf(stderr, "%s: no such file or directory\n", p.c_str());
      return 2;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "no corpus files given\n");
    return 2;
  }

  interfere::fuzz::replay_mode() = true;
  const bool verbose = std::getenv("INTERFERE_FUZZ_VERBOSE") != nullptr;
  std::size_t failures = 0;
  double slowest = 0;
  fs::path slowest_file;
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (verbose) std::fprintf(stderr, "running %s (%zu bytes)\n", f.c_str(), bytes.size());
    const auto start = std::chrono::steady_clock::now();
    try {
      it->second(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const interfere::fuzz::Failure& e) {
      ++failures;
      std::fprintf(stderr, "FAIL %s\n  %s\n", f.c_str(), e.what());
    } catch (const std::exception& e) {
      ++failures;
      std::fprintf(stderr, "FAIL %s\n  exception escaped the library: %s\n", f.c_str(), e.what());
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (s > slowest) slowest = s, slowest_file = f;
  }
  std::printf("%s: %zu inputs, %zu failing; slowest %.3f s (%s)\n", argv[1], files.size(), failures,
              slowest, slowest_file.filename().c_str());
  return failures == 0 ? 0 : 1;
}
