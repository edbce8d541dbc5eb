// The 1e7 x 1e7 run (issue #2: peak memory <= 6 GB), too heavy for Google Benchmark's repetitions:
//   interfere_big_run [N=1e7 triangles per part] [threads=all]
// generates the overlapping sphere pair, builds both default trees (BvhBuildOptions{}), runs the
// default clash (exact test, regions and curves) and prints one JSON object with the phase times
// and the peak resident set (getrusage ru_maxrss; includes the generated meshes, which a reader
// would hold as well). Also prints the builder used.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace {

double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux: kilobytes
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace interfere;
  std::size_t n = 10000000;
  std::size_t threads = static_cast<std::size_t>(tbb::info::default_concurrency());
  if (argc > 1) {
    const double v = std::strtod(argv[1], nullptr);
    if (!(v >= 1) || !std::isfinite(v)) {
      std::fprintf(stderr, "usage: %s [triangles_per_part=1e7] [threads]\n", argv[0]);
      return 2;
    }
    n = static_cast<std::size_t>(std::llround(v));
  }
  if (argc > 2) threads = static_cast<std::size_t>(std::max(1L, std::strtol(argv[2], nullptr, 10)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

  auto t0 = std::chrono::steady_clock::now();
  std::optional<SpherePair> pair(make_overlapping_spheres(n));
  const double generate_s = seconds_since(t0);
  const double rss_generated = peak_rss_bytes();
  const std::size_t na = pair->a.num_triangles(), nb = pair->b.num_triangles();

  t0 = std::chrono::steady_clock::now();
  // The meshes move into the models (no copy), as a caller that reads files and builds would do.
  const auto [a, b] = make_models(std::move(pair->a), std::move(pair->b), BvhBuildOptions{}, false);
  const double build_s = seconds_since(t0);
  pair.reset();

  t0 = std::chrono::steady_clock::now();
  const ClashResult r = clash(a, b, ClashRequest{});
  const double query_s = seconds_since(t0);

  std::size_t curves = 0;
  double curve_length = 0;
  for (const ClashRegion& g : r.regions) curves += g.curves.size(), curve_length += g.curve_length;
  std::printf(
      "{\"triangles_per_part\": %zu, \"tris_a\": %zu, \"tris_b\": %zu, \"threads\": %zu,\n"
      " \"generate_s\": %.6f, \"build_s\": %.6f, \"query_s\": %.6f, \"build_and_query_s\": %.6f,\n"
      " \"pairs\": %zu, \"cross\": %zu, \"touch\": %zu, \"candidates\": %zu, \"regions\": %zu,\n"
      " \"curves\": %zu, \"curve_length\": %.9g, \"nodes_a\": %zu, \"nodes_b\": %zu,\n"
      " \"builder\": \"%s\", \"peak_rss_after_generate_bytes\": %.0f, \"peak_rss_bytes\": %.0f}\n",
      n, na, nb, threads, generate_s, build_s, query_s, build_s + query_s, r.pairs.size(),
      r.cross_pairs, r.touch_pairs, r.candidate_pairs, r.regions.size(), curves, curve_length,
      a.bvh.nodes.size(), b.bvh.nodes.size(), bvh_builder_name(BvhBuildOptions{}.builder),
      rss_generated, peak_rss_bytes());
  return 0;
}
