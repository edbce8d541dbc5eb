// The 10^7-tet FEM run (issue #3: read, extracted and clashed within 8 GB), too heavy for Google
// Benchmark's repetitions:
//   interfere_fem_big_run [elements=1e7] [threads=all] [dir=/tmp]
// generates a tet4 box of about `elements` tets and writes it as binary MSH 4.1 in a child process
// (so that the peak resident set below is that of the read, not of the generator), then times
// read_fem, extract_surface, and the clash (with a tree build) of its surface against a tet4 ball of
// 10^6 tets overlapping one corner. Prints one JSON object with the phase times and the peak
// resident set (getrusage ru_maxrss) after each phase. The MSH file is removed at the end.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "interfere/fem/generate.h"
#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace {

double peak_rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0 / 1e9;  // Linux: kilobytes
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace interfere;
  double elements = 1e7;
  int threads = tbb::info::default_concurrency();
  std::filesystem::path dir = std::filesystem::temp_directory_path();
  if (argc > 1) elements = std::strtod(argv[1], nullptr);
  if (argc > 2) threads = std::max(1, std::atoi(argv[2]));
  if (argc > 3) dir = argv[3];
  if (!(elements >= 6)) {
    std::fprintf(stderr, "usage: %s [elements=1e7] [threads] [dir]\n", argv[0]);
    return 2;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const std::filesystem::path file = dir / ("interfere_fem_big_" + std::to_string(::getpid()) + ".msh");
  const int n = static_cast<int>(std::lround(std::cbrt(elements / 6)));

  auto t0 = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child < 0) {
    std::perror("fork");
    return 1;
  }
  if (child == 0) {
    GeneratedFem g = make_fem_box({.type = ElemType::tet4, .nx = n, .ny = n, .nz = n});
    const double generate_s = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    FemWriteOptions wo;
    wo.binary = true;
    const Status st = write_fem(g.mesh, file, wo);
    if (!st) {
      std::fprintf(stderr, "write: %s\n", st.error().message().c_str());
      std::_Exit(1);
    }
    std::fprintf(stderr, "generated %zu tets in %.2f s, written in %.2f s (%.0f MB; generator peak RSS %.3f GB)\n",
                 g.mesh.num_elements(), generate_s, seconds_since(t0),
                 static_cast<double>(std::filesystem::file_size(file)) / 1e6, peak_rss_gb());
    std::_Exit(0);
  }
  int wstatus = 0;
  ::waitpid(child, &wstatus, 0);
  if (!WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) return 1;
  const double rss_before = peak_rss_gb();

  t0 = std::chrono::steady_clock::now();
  auto mesh = read_fem(file);
  const double read_s = seconds_since(t0);
  std::filesystem::remove(file);
  if (!mesh) {
    std::fprintf(stderr, "read: %s\n", mesh.error().message().c_str());
    return 1;
  }
  const double rss_read = peak_rss_gb();

  t0 = std::chrono::steady_clock::now();
  auto surface = extract_surface(*mesh);
  const double extract_s = seconds_since(t0);
  const double rss_extract = peak_rss_gb();
  const std::size_t num_elements = mesh->num_elements();

  // Part B: a 10^6-tet ball of radius 0.3 centred on the box's corner (1,1,1).
  const int nb = static_cast<int>(std::lround(std::cbrt(1e6 / 6)));
  FemMesh ball = make_fem_sphere({.type = ElemType::tet4, .nx = nb, .ny = nb, .nz = nb}, 0.3, {1, 1, 1}).mesh;
  auto surface_b = extract_surface(ball);
  t0 = std::chrono::steady_clock::now();
  auto models = make_models(surface->parts[0].mesh, surface_b->parts[0].mesh);
  const double build_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const ClashResult r = clash(models.first, models.second);
  const double clash_s = seconds_since(t0);
  const double rss_end = peak_rss_gb();

  std::printf(
      "{\"elements\": %zu, \"threads\": %d, \"surface_triangles\": %zu, \"ball_triangles\": %zu,\n"
      " \"read_s\": %.3f, \"extract_s\": %.3f, \"extract_elements_per_s\": %.4g, \"build_s\": %.3f, \"clash_s\": %.3f,\n"
      " \"pairs\": %zu, \"regions\": %zu,\n"
      " \"peak_rss_gb\": {\"before_read\": %.3f, \"after_read\": %.3f, \"after_extract\": %.3f, "
      "\"end\": %.3f}}\n",
      num_elements, threads, surface->parts[0].mesh.num_triangles(), surface_b->parts[0].mesh.num_triangles(),
      read_s, extract_s, static_cast<double>(num_elements) / extract_s, build_s, clash_s, r.pairs.size(),
      r.regions.size(), rss_before, rss_read, rss_extract, rss_end);
  return 0;
}
