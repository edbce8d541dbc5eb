// Binary STL read throughput (target >= 1 GB/s): a generated sphere of ~2e6 triangles (~100 MB) is
// written once to a fresh temporary folder, removed at exit. The file is read from the page cache
// (just written), so this measures parsing + welding, not the disk.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>

#include "common.h"
#include "interfere/mesh/io.h"

namespace interfere::bench {
namespace {

namespace fs = std::filesystem;

/// Owns the temporary folder; the static instance's destructor removes it at normal exit.
class TempStl {
 public:
  TempStl() {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("interfere_bench_" + std::to_string(rd()));
    fs::create_directories(dir_);
    path_ = dir_ / "sphere.stl";
    const std::size_t tris = env_size("INTERFERE_BENCH_STL_TRIANGLES", 2000000);
    const TriMesh mesh =
        make_sphere(SphereOptions{.target_triangles = tris, .bump_amplitude = 0.02});
    triangles_ = mesh.num_triangles();
    const Status s = write_mesh(path_, mesh, WriteOptions{.format = MeshFormat::stl_binary});
    if (!s) error_ = s.error().reason;  // .message() trips GCC 12 -Wrestrict (PR 105651)
    std::error_code ec;
    bytes_ = fs::file_size(path_, ec);
  }
  ~TempStl() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  TempStl(const TempStl&) = delete;
  TempStl& operator=(const TempStl&) = delete;

  const fs::path& path() const { return path_; }
  std::size_t bytes() const { return bytes_; }
  std::size_t triangles() const { return triangles_; }
  const std::string& error() const { return error_; }

 private:
  fs::path dir_, path_;
  std::size_t bytes_ = 0, triangles_ = 0;
  std::string error_;
};

const TempStl& temp_stl() {
  static TempStl t;
  return t;
}

void read_stl(benchmark::State& state, bool weld) {
  const TempStl& f = temp_stl();
  if (!f.error().empty()) {
    state.SkipWithError(("write_mesh failed: " + f.error()).c_str());
    return;
  }
  std::size_t vertices = 0, triangles = 0;
  for (auto _ : state) {
    Expected<TriMesh> m =
        read_mesh(f.path(), ReadOptions{.format = MeshFormat::automatic, .weld = weld});
    if (!m) {
      state.SkipWithError(("read_mesh failed: " + m.error().reason).c_str());
      return;
    }
    vertices = m->num_vertices(), triangles = m->num_triangles();
    benchmark::DoNotOptimize(m->positions.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * f.bytes()));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * triangles));
  state.counters["file_bytes"] = static_cast<double>(f.bytes());
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["triangles"] = static_cast<double>(triangles);
}

void BM_ReadStlBinary_weld(benchmark::State& state) {
  read_stl(state, true);
}
void BM_ReadStlBinary_noweld(benchmark::State& state) {
  read_stl(state, false);
}

[[maybe_unused]] const bool registered = [] {
  for (auto [name, fn] : {std::pair{"BM_ReadStlBinary_weld", &BM_ReadStlBinary_weld},
                          std::pair{"BM_ReadStlBinary_noweld", &BM_ReadStlBinary_noweld}}) {
    benchmark::RegisterBenchmark(name, fn)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(target_repetitions());
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
