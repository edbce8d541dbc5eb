#include "common.h"

#include <benchmark/benchmark.h>
#include <tbb/version.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"
#include "interfere/query/clash.h"

namespace interfere::bench {
namespace {

std::size_t parse_size(const std::string& text, std::size_t fallback) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(v) || v < 0) return fallback;
  return static_cast<std::size_t>(std::llround(v));
}

std::mutex& cache_mutex() {
  static std::mutex m;
  return m;
}

[[maybe_unused]] const bool context_added = [] {
  benchmark::AddCustomContext("compiler", __VERSION__);
  benchmark::AddCustomContext("tbb_version", TBB_VERSION_STRING);
  benchmark::AddCustomContext("default_builder", bvh_builder_name(BvhBuildOptions{}.builder));
#ifdef NDEBUG
  benchmark::AddCustomContext("interfere_build", "release (NDEBUG)");
#else
  benchmark::AddCustomContext("interfere_build", "assertions on (not NDEBUG)");
#endif
  return true;
}();

}  // namespace

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? parse_size(v, fallback) : fallback;
}

std::vector<std::size_t> env_sizes(const char* name, std::vector<std::size_t> fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  std::vector<std::size_t> out;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::size_t n = parse_size(item, 0);
    if (n > 0) out.push_back(n);
  }
  return out.empty() ? fallback : out;
}

std::string env_string(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : fallback;
}

int target_repetitions() {
  return static_cast<int>(std::max<std::size_t>(1, env_size("INTERFERE_BENCH_REPETITIONS", 3)));
}

std::vector<std::size_t> table_sizes() {
  return env_sizes("INTERFERE_BENCH_SIZES", {10000, 100000, 1000000});
}

std::vector<std::size_t> thread_counts() {
  return env_sizes("INTERFERE_BENCH_THREADS", {1, 2});
}

std::string size_label(std::size_t n) {
  std::size_t p = 0, m = n;
  while (m >= 10 && m % 10 == 0) m /= 10, ++p;
  if (m == 1 && p > 0) return "1e" + std::to_string(p);
  return std::to_string(n);
}

const SpherePair& sphere_pair(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<SpherePair>> cache;
  std::lock_guard lock(cache_mutex());
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<SpherePair>(make_overlapping_spheres(n));
  return *slot;
}

const ModelPair& model_pair(std::size_t n, BvhBuilder builder) {
  static std::map<std::pair<std::size_t, int>, std::unique_ptr<ModelPair>> cache;
  const SpherePair& p = sphere_pair(n);
  std::lock_guard lock(cache_mutex());
  auto& slot = cache[{n, static_cast<int>(builder)}];
  if (!slot) {
    const BvhBuildOptions options{.builder = builder};
    slot = std::make_unique<ModelPair>(
        ModelPair{make_model(p.a, options, false), make_model(p.b, options, false)});
  }
  return *slot;
}

const std::vector<std::pair<std::uint32_t, std::uint32_t>>& reference_pairs(std::size_t n) {
  static std::map<std::size_t,
                  std::unique_ptr<std::vector<std::pair<std::uint32_t, std::uint32_t>>>>
      cache;
  const ModelPair& m = model_pair(n, BvhBuilder::binned_sah);
  std::lock_guard lock(cache_mutex());
  auto& slot = cache[n];
  if (!slot) {
    const ClashResult r = clash(m.a, m.b,
                                ClashRequest{.test = TriTest::exact,
                                             .broadphase = Broadphase::bvh,
                                             .parallel = true,
                                             .regions = false,
                                             .containment = false});
    slot = std::make_unique<std::vector<std::pair<std::uint32_t, std::uint32_t>>>();
    slot->reserve(r.pairs.size());
    for (const TrianglePair& tp : r.pairs) slot->emplace_back(tp.a, tp.b);
    std::sort(slot->begin(), slot->end());
  }
  return *slot;
}

PairList exact_pairs(const TriMesh& a, const TriMesh& b) {
  const BvhBuildOptions options{.builder = BvhBuilder::binned_sah};
  const Model ma = make_model(a, options, false), mb = make_model(b, options, false);
  const ClashResult r = clash(ma, mb,
                              ClashRequest{.test = TriTest::exact,
                                           .broadphase = Broadphase::bvh,
                                           .parallel = true,
                                           .regions = false,
                                           .containment = false});
  PairList out;
  out.reserve(r.pairs.size());
  for (const TrianglePair& tp : r.pairs) out.emplace_back(tp.a, tp.b);
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

std::vector<int> exact_box_subdivisions() {
  std::vector<int> out;
  for (std::size_t n : env_sizes("INTERFERE_BENCH_EXACT_BOX_N", {50, 100, 200})) {
    out.push_back(static_cast<int>(n));
  }
  return out;
}

std::size_t exact_sphere_triangles() {
  return env_size("INTERFERE_BENCH_EXACT_SPHERE", 100000);
}

Transform rotation_about_z(double c, double s) {
  Transform t;
  t.r = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  return t;
}

ExactScene generate_scene(const std::string& name) {
  ExactScene sc;
  int n = 0;
  if (std::sscanf(name.c_str(), "coplanar_face/n:%d", &n) == 1) {
    sc.a = make_box({0, 0, 0}, {1, 1, 1}, n);
    Transform shift;
    shift.t = Vec3{1, 0, 0};  // the box's width: A's x = 1 face and B's x = 0 + 1 face coincide
    sc.b = transformed(sc.a, shift);
  } else if (std::sscanf(name.c_str(), "resting_box/n:%d", &n) == 1) {
    // A's grid spacing is 1/n, B's 2/n, and A's lines sit 0.6/n off B's: for even n they never
    // coincide. Both contact faces lie exactly in z = 0.
    const double o = 0.6 / n;
    sc.a = make_box({-0.5 + o, -0.5 + o, 0}, {0.5 + o, 0.5 + o, 1}, n);
    sc.b = make_box({-1, -1, -1}, {1, 1, 0}, n);
  } else if (name == "contained_sphere") {
    const std::size_t t = exact_sphere_triangles();
    sc.a = make_sphere({.target_triangles = t,
                        .radius = 0.5,
                        .center = {0.1, 0.05, -0.02},
                        .bump_amplitude = 0.01,
                        .bump_frequency = 9});
    sc.b = make_sphere({.target_triangles = t,
                        .radius = 1.0,
                        .bump_amplitude = 0.01,
                        .bump_frequency = 11,
                        .twist = 0.123});
  } else if (name == "rotated_sphere/0.001rad") {
    sc.a = make_sphere({.target_triangles = exact_sphere_triangles()});
    sc.b = transformed(sc.a, rotation_about_z(std::cos(1e-3), std::sin(1e-3)));
  } else if (name == "rotated_sphere/quarter_turn") {
    sc.a = make_sphere({.target_triangles = exact_sphere_triangles()});
    sc.b = transformed(sc.a, rotation_about_z(0.0, 1.0));  // (x, y, z) -> (-y, x, z), exact
  } else {
    throw std::invalid_argument("unknown exactness scene " + name);
  }
  return sc;
}

}  // namespace

std::vector<std::string> exact_scene_names() {
  std::vector<std::string> names;
  const std::vector<int> ns = exact_box_subdivisions();
  for (int n : ns) names.push_back("coplanar_face/n:" + std::to_string(n));
  for (int n : ns) names.push_back("resting_box/n:" + std::to_string(n));
  names.push_back("contained_sphere");
  names.push_back("rotated_sphere/0.001rad");
  names.push_back("rotated_sphere/quarter_turn");
  return names;
}

const ExactScene& exact_scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<ExactScene>> cache;
  std::lock_guard lock(cache_mutex());
  auto& slot = cache[name];
  if (!slot) slot = std::make_unique<ExactScene>(generate_scene(name));
  return *slot;
}

const PairList& exact_scene_reference(const std::string& name) {
  static std::map<std::string, std::unique_ptr<PairList>> cache;
  const ExactScene& sc = exact_scene(name);
  {
    std::lock_guard lock(cache_mutex());
    if (const auto it = cache.find(name); it != cache.end()) return *it->second;
  }
  auto pairs = std::make_unique<PairList>(exact_pairs(sc.a, sc.b));
  std::lock_guard lock(cache_mutex());
  auto& slot = cache[name];
  if (!slot) slot = std::move(pairs);
  return *slot;
}

PairDiff diff_pairs(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& found,
                    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& reference) {
  PairDiff d;
  std::size_t i = 0, j = 0;
  while (i < found.size() || j < reference.size()) {
    if (j == reference.size() || (i < found.size() && found[i] < reference[j])) {
      if (d.extra++ == 0) d.first_extra = found[i];
      ++i;
    } else if (i == found.size() || reference[j] < found[i]) {
      if (d.missing++ == 0) d.first_missing = reference[j];
      ++j;
    } else {
      ++i, ++j;
    }
  }
  return d;
}

/// pairs / reference_pairs / extra / missing counters plus one example of each disagreement.
void set_diff_counters(benchmark::State& state, const PairList& pairs, const PairList& reference,
                       const TriMesh& a, const TriMesh& b) {
  const PairDiff d = diff_pairs(pairs, reference);
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["reference_pairs"] = static_cast<double>(reference.size());
  state.counters["extra"] = static_cast<double>(d.extra);
  state.counters["missing"] = static_cast<double>(d.missing);
  if (d.extra) {  // one example for the report: (triangle of A, triangle of B)
    state.counters["first_extra_a"] = d.first_extra.first;
    state.counters["first_extra_b"] = d.first_extra.second;
    state.counters["first_extra_distance"] =
        triangle_triangle_closest(a.corners(d.first_extra.first), b.corners(d.first_extra.second))
            .distance;
  }
  if (d.missing) {
    state.counters["first_missing_a"] = d.first_missing.first;
    state.counters["first_missing_b"] = d.first_missing.second;
    state.counters["first_missing_kind"] = static_cast<double>(static_cast<int>(
        tri_tri_exact(a.corners(d.first_missing.first), b.corners(d.first_missing.second)).kind));
  }
}

}  // namespace interfere::bench
