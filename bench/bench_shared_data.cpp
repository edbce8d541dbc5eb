// Optional: clashes between real scanned meshes from the shared test data (INTERFERE_BENCH_DATA,
// default <source>/../shared/data/mesh). Registered only when the files are there; skipped silently
// otherwise.
//   Data/<case>/threads:<t>  both default trees + default clash (exact, regions, curves), meshes in
//   memory
// Cases: the armadillo pushed half into the high-resolution bunny, and that bunny against itself
// turned 5 degrees about its vertical axis (intersection curves all over the surface).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "common.h"
#include "interfere/mesh/io.h"
#include "interfere/query/clash.h"

namespace interfere::bench {
namespace {

namespace fs = std::filesystem;

struct DataCase {
  std::string name;
  TriMesh a, b;
};

std::optional<TriMesh> load(const fs::path& p) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return std::nullopt;
  Expected<TriMesh> m = read_mesh(p);
  if (!m) return std::nullopt;
  return std::move(m.value());
}

Transform rotation_z(double degrees, const Vec3& about) {
  const double a = degrees * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  Transform t;
  t.r = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  // p' = R (p - about) + about
  t.t = about - Vec3{c * about.x - s * about.y, s * about.x + c * about.y, about.z};
  return t;
}

void bm_data(benchmark::State& state, std::shared_ptr<const DataCase> dc, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::optional<Model> ma, mb;
  ClashResult r;
  for (auto _ : state) {
    state.PauseTiming();
    ma.reset(), mb.reset(), r = ClashResult{};
    TriMesh a = dc->a, b = dc->b;
    state.ResumeTiming();
    ma.emplace(make_model(std::move(a), BvhBuildOptions{}, false));
    mb.emplace(make_model(std::move(b), BvhBuildOptions{}, false));
    r = clash(*ma, *mb, ClashRequest{});
    benchmark::DoNotOptimize(r.pairs.data());
  }
  const std::size_t na = dc->a.num_triangles(), nb = dc->b.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (na + nb)));
  state.counters["tris_a"] = static_cast<double>(na);
  state.counters["tris_b"] = static_cast<double>(nb);
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
  state.counters["cross"] = static_cast<double>(r.cross_pairs);
  state.counters["touch"] = static_cast<double>(r.touch_pairs);
  state.counters["regions"] = static_cast<double>(r.regions.size());
  state.counters["threads"] = static_cast<double>(threads);
}

[[maybe_unused]] const bool registered = [] {
  const fs::path dir = env_string("INTERFERE_BENCH_DATA",
                                  std::string(INTERFERE_SOURCE_DIR) + "/../shared/data/mesh");
  std::vector<std::shared_ptr<const DataCase>> cases;
  const auto bunny = load(dir / "bunny_closed_hr_odedstein.obj");
  const auto armadillo = load(dir / "armadillo_closed_odedstein.obj");
  if (bunny && armadillo) {
    auto dc = std::make_shared<DataCase>();
    dc->name = "armadillo_into_bunny_hr";
    dc->a = *bunny;
    Transform shift;
    shift.t = Vec3{0.6, 0.0, 0.0};
    dc->b = transformed(*armadillo, shift);
    cases.push_back(dc);
  }
  if (bunny) {
    auto dc = std::make_shared<DataCase>();
    dc->name = "bunny_hr_vs_rotated_5deg";
    dc->a = *bunny;
    dc->b = transformed(*bunny, rotation_z(5.0, bunny->bounds().center()));
    cases.push_back(dc);
  }
  std::size_t max_threads = 1;
  for (std::size_t t : thread_counts()) max_threads = std::max(max_threads, t);
  for (const auto& dc : cases) {
    benchmark::RegisterBenchmark(
        ("Data/" + dc->name + "/threads:" + std::to_string(max_threads)).c_str(),
        [dc, max_threads](benchmark::State& s) { bm_data(s, dc, max_threads); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
