// FEM reader throughput (issue #3, item 1): a generated 10^6-tet box (55^3 cubes, 6 tets each,
// 998,250 tets, 175,616 nodes) written once by our writers as MSH 4.1 binary, VTU appended and
// Nastran free field, then read back; the gmsh SDK reading the same MSH is the peer
// (peer_gmsh.cpp, when libgmsh is found). Items/s = elements per second.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include "fem_io_bench.h"
#include "interfere/fem/io.h"

namespace interfere::bench_fem {

FemMesh tet_box(int n) {
  FemMesh m;
  const int p = n + 1;
  m.nodes.reserve(static_cast<std::size_t>(p) * p * p);
  for (int k = 0; k < p; ++k) {
    for (int j = 0; j < p; ++j) {
      for (int i = 0; i < p; ++i) {
        m.nodes.push_back(Vec3{i / static_cast<double>(n), j / static_cast<double>(n), k / static_cast<double>(n)});
        m.node_ids.push_back(static_cast<std::int64_t>(m.nodes.size()));
      }
    }
  }
  auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>((k * p + j) * p + i); };
  // Kuhn subdivision of each cube into 6 positively oriented tets along the main diagonal.
  static const int kPaths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  m.groups.push_back(FemGroup{.name = "box", .id = 1});
  std::int64_t eid = 0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        for (const auto& path : kPaths) {
          int c[3] = {i, j, k};
          std::uint32_t v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[path[s]];
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          // Orientation alternates with the parity of the permutation.
          const int inversions = (path[0] > path[1]) + (path[0] > path[2]) + (path[1] > path[2]);
          if (inversions % 2 == 1) std::swap(v[1], v[2]);
          m.add_element(ElemType::tet4, ++eid, 0, v, 4);
        }
      }
    }
  }
  return m;
}

namespace {
char g_dir[4096];  // the temporary directory, removed at exit (plain buffer: outlives every static)
void remove_dir() {
  std::error_code ec;
  if (g_dir[0]) std::filesystem::remove_all(g_dir, ec);
}
}  // namespace

const std::filesystem::path& bench_file(const std::string& ext) {
  static std::filesystem::path dir = [] {
    std::string t = (std::filesystem::temp_directory_path() / "interfere_bench_fem_XXXXXX").string();
    if (!::mkdtemp(t.data()) || t.size() >= sizeof g_dir) std::abort();
    std::memcpy(g_dir, t.c_str(), t.size() + 1);
    std::atexit(remove_dir);
    const FemMesh m = tet_box(55);
    write_fem(m, std::filesystem::path(t) / "box.msh", {.binary = true});
    write_fem(m, std::filesystem::path(t) / "box.vtu", {.vtu_encoding = VtuEncoding::appended});
    write_fem(m, std::filesystem::path(t) / "box.bdf");
    return std::filesystem::path(t);
  }();
  static std::map<std::string, std::filesystem::path> files;
  auto it = files.find(ext);
  if (it == files.end()) it = files.emplace(ext, dir / ("box" + ext)).first;
  return it->second;
}

namespace {

void read_bench(benchmark::State& state, const std::string& ext) {
  const std::filesystem::path& p = bench_file(ext);
  std::size_t elements = 0;
  for (auto _ : state) {
    Expected<FemMesh> m = read_fem(p);
    if (!m) {
      state.SkipWithError(m.error().message().c_str());
      return;
    }
    elements = m->num_elements();
    benchmark::DoNotOptimize(m->elem_nodes.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * elements));
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(p)) / 1e6;
}

void BM_FemRead_Msh41Binary(benchmark::State& s) { read_bench(s, ".msh"); }
void BM_FemRead_VtuAppended(benchmark::State& s) { read_bench(s, ".vtu"); }
void BM_FemRead_NastranFree(benchmark::State& s) { read_bench(s, ".bdf"); }
BENCHMARK(BM_FemRead_Msh41Binary)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FemRead_VtuAppended)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FemRead_NastranFree)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace interfere::bench_fem
