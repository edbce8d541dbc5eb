// Peer for bench_fem_io.cpp: the gmsh SDK (libgmsh 4.8) reading the same MSH 4.1 binary file:
// gmsh::open + gmsh::model::mesh::getNodes + getElements (what a caller needs to build a mesh).
#include <benchmark/benchmark.h>
#include <gmsh.h>

#include "fem_io_bench.h"

namespace interfere::bench_fem {
namespace {

void BM_FemRead_GmshSdkMsh41Binary(benchmark::State& state) {
  const std::filesystem::path& p = bench_file(".msh");
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  std::size_t elements = 0;
  for (auto _ : state) {
    gmsh::clear();
    gmsh::open(p.string());
    std::vector<std::size_t> tags;
    std::vector<double> coords, param;
    gmsh::model::mesh::getNodes(tags, coords, param, -1, -1, false, false);
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    gmsh::model::mesh::getElements(types, etags, enodes, 3, -1);
    elements = 0;
    for (const auto& t : etags) elements += t.size();
    benchmark::DoNotOptimize(coords.data());
  }
  gmsh::finalize();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * elements));
  state.counters["elements"] = static_cast<double>(elements);
}
BENCHMARK(BM_FemRead_GmshSdkMsh41Binary)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace interfere::bench_fem
