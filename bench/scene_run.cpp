// Separate-process runs of the scene benchmarks (issue #24, items 8 and 9), for
// bench/scene_tables.py:
//   interfere_scene_run assembly [bodies=10000] [segments=48] [threads=all]
//   [depth_bound_splits=engine default]
//       generates the assembly (scene/generate.h), runs clash_scene once with the benchmark's tests
//       (all pairs hard + all pairs clearance 0.1 mm) and prints one JSON object: phase times,
//       counts, and the peak resident set (VmHWM of /proc/self/status; getrusage as a fallback) of
//       this process, which holds nothing else: the issue's "peak memory of the 10^7-triangle
//       scene".
//   interfere_scene_run spheres DIR [triangles=1e6]
//       writes DIR/sphere_a.stl and DIR/sphere_b.stl (binary STL): make_overlapping_spheres, two
//       bumpy spheres overlapping about 1 % of their triangles, for the whole-process runs.
//   interfere_scene_run scene-file DIR [bodies=10000] [segments=48]
//       writes the generated assembly as users would give it: its five part meshes as binary STL
//       (DIR/<type>.stl) and DIR/scene.json listing every body (file, id, path, tags, transform)
//       with the benchmark's two tests, and prints the construction's pair counts (clashing,
//       contact, gap) for the caller to check `interfere clash --scene DIR/scene.json` against.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"

#include <map>
#include <nlohmann/json.hpp>

namespace {

double peak_rss_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) * 1024.0;  // kB
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::size_t number(const char* s) {
  return static_cast<std::size_t>(std::llround(std::strtod(s, nullptr)));
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s assembly [bodies=10000] [segments=48] [threads] [depth_bound_splits]\n   "
               "    %s spheres DIR [triangles=1e6]\n       %s scene-file DIR [bodies=10000] [segments=48]\n",
               argv0, argv0, argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace interfere;
  if (argc < 2) return usage(argv[0]);
  const std::string mode = argv[1];
  if (mode == "spheres") {
    if (argc < 3) return usage(argv[0]);
    const std::filesystem::path dir = argv[2];
    const std::size_t n = argc > 3 ? number(argv[3]) : 1000000;
    const SpherePair p = make_overlapping_spheres(n);
    std::filesystem::create_directories(dir);
    for (const auto& [name, mesh] :
         {std::pair{"sphere_a.stl", &p.a}, std::pair{"sphere_b.stl", &p.b}}) {
      if (const Status s = write_mesh(dir / name, *mesh); !s) {
        std::fprintf(stderr, "%s\n", s.error().message().c_str());
        return 1;
      }
    }
    std::printf("{\"a\": \"%s\", \"b\": \"%s\", \"tris_a\": %zu, \"tris_b\": %zu}\n",
                (dir / "sphere_a.stl").c_str(), (dir / "sphere_b.stl").c_str(), p.a.num_triangles(),
                p.b.num_triangles());
    return 0;
  }
  if (mode == "scene-file") {
    if (argc < 3) return usage(argv[0]);
    const std::filesystem::path dir = argv[2];
    scene::AssemblyGenOptions o;
    if (argc > 3) o.bodies = number(argv[3]);
    if (argc > 4) o.segments = static_cast<int>(number(argv[4]));
    scene::AssemblyInfo info;
    const scene::Scene s = scene::generate_assembly(o, &info);
    std::filesystem::create_directories(dir);
    std::map<const TriMesh*, std::string> files;
    nlohmann::json bodies = nlohmann::json::array();
    for (const scene::Body& b : s.bodies) {
      const std::string type = b.tags.empty() ? "part" : b.tags.front();
      auto [it, added] = files.emplace(b.mesh.get(), type + ".stl");
      if (added)
        if (const Status st = write_mesh(dir / it->second, *b.mesh); !st) {
          std::fprintf(stderr, "%s\n", st.error().message().c_str());
          return 1;
        }
      const auto m = b.pose.to_row_major();
      bodies.push_back({{"file", it->second}, {"id", b.id}, {"path", b.path}, {"tags", b.tags},
                        {"transform", std::vector<double>(m.begin(), m.end())}});
    }
    const nlohmann::json doc{{"units", "mm"},
                             {"bodies", bodies},
                             {"tests", {{{"name", "hard"}, {"a", "*"}, {"mode", "hard"}},
                                        {{"name", "clearance"}, {"a", "*"}, {"mode", "clearance"}, {"clearance", 0.1}}}}};
    std::ofstream(dir / "scene.json") << doc.dump(1) << "\n";
    std::printf("{\"scene\": \"%s\", \"bodies\": %zu, \"triangles\": %zu, \"clash_pairs\": %zu, "
                "\"contact_pairs\": %zu, \"gap_pairs\": %zu}\n",
                (dir / "scene.json").c_str(), s.bodies.size(), info.triangles, info.clash_pairs.size(),
                info.contact_pairs.size(), info.gap_pairs.size());
    return 0;
  }
  if (mode != "assembly") return usage(argv[0]);
  scene::AssemblyGenOptions o;
  if (argc > 2) o.bodies = number(argv[2]);
  if (argc > 3) o.segments = static_cast<int>(number(argv[3]));
  std::size_t threads = static_cast<std::size_t>(tbb::info::default_concurrency());
  if (argc > 4) threads = std::max<std::size_t>(1, number(argv[4]));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  scene::SceneClashOptions options;
  if (argc > 5) options.depth_bound_splits = number(argv[5]);

  auto t0 = std::chrono::steady_clock::now();
  scene::AssemblyInfo info;
  const scene::Scene s = scene::generate_assembly(o, &info);
  const double generate_s = since(t0);
  const double rss_generated = peak_rss_bytes();
  scene::ClashTest hard;
  hard.name = "hard";
  scene::ClashTest clear;
  clear.name = "clearance";
  clear.mode = scene::ClashMode::clearance;
  clear.clearance = 0.1;
  t0 = std::chrono::steady_clock::now();
  const scene::SceneClashResult r = scene::clash_scene(s, {hard, clear}, options);
  const double clash_s = since(t0);
  std::printf(
      "{\"bodies\": %zu, \"triangles\": %zu, \"segments\": %d, \"threads\": %zu, "
      "\"depth_bound_splits\": %zu,\n"
      " \"generate_s\": %.6f,"
      " \"clash_s\": %.6f, \"prepare_s\": %.6f, \"broad_s\": %.6f, \"narrow_s\": %.6f,\n"
      " \"candidate_pairs\": %zu, \"clashes\": %zu, \"contacts\": %zu, \"clearances\": %zu, "
      "\"undecided\": %zu,\n"
      " \"peak_rss_after_generate_bytes\": %.0f, \"peak_rss_bytes\": %.0f}\n",
      s.bodies.size(), info.triangles, o.segments, threads, options.depth_bound_splits, generate_s,
      clash_s, r.prepare_seconds, r.broad_seconds, r.narrow_seconds, r.candidate_pairs,
      r.clash_count, r.contact_count, r.clearance_count, r.undecided_count, rss_generated,
      peak_rss_bytes());
  return 0;
}
