// Whole-process peer (issue #24, item 8): CGAL on two binary STL files, the textbook exact
// pipeline: read (peer_stl.h), one box per triangle, the two-set box_intersection_d sweep
// (Zomorodian & Edelsbrunner 2000), CGAL::do_intersect with
// Exact_predicates_inexact_constructions_kernel on each box pair; prints one JSON object with the
// phase times and the number of intersecting triangle pairs. Single-threaded (CGAL's sweep is).
//   interfere_peer_process_cgal A.stl B.stl
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "peer_stl.h"

using namespace interfere::bench;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
using Clock = std::chrono::steady_clock;
static double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

static std::vector<Box> boxes(const std::vector<Facet>& soup) {
  std::vector<Box> out;
  out.reserve(soup.size());
  for (std::size_t t = 0; t < soup.size(); ++t) {
    const Facet& f = soup[t];
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min({f[0][k], f[1][k], f[2][k]});
      hi[k] = std::max({f[0][k], f[1][k], f[2][k]});
    }
    out.emplace_back(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]),
                     static_cast<std::uint32_t>(t));
  }
  return out;
}

static K::Triangle_3 triangle(const Facet& f) {
  return {K::Point_3(f[0][0], f[0][1], f[0][2]), K::Point_3(f[1][0], f[1][1], f[1][2]),
          K::Point_3(f[2][0], f[2][1], f[2][2])};
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s A.stl B.stl\n", argv[0]);
    return 2;
  }
  const auto t0 = Clock::now();
  auto t = Clock::now();
  const std::vector<Facet> a = read_binary_stl(argv[1]), b = read_binary_stl(argv[2]);
  const double read_s = since(t);
  t = Clock::now();
  std::vector<Box> ba = boxes(a), bb = boxes(b);
  const double build_s = since(t);
  t = Clock::now();
  std::size_t candidates = 0, pairs = 0;
  CGAL::box_intersection_d(ba.begin(), ba.end(), bb.begin(), bb.end(),
                           [&](const Box& x, const Box& y) {
                             ++candidates;
                             if (CGAL::do_intersect(triangle(a[x.info()]), triangle(b[y.info()])))
                               ++pairs;
                           });
  const double query_s = since(t);
  std::printf(
      "{\"peer\": \"cgal\", \"tris_a\": %zu, \"tris_b\": %zu, \"read_s\": %.6f, \"build_s\": %.6f, "
      "\"query_s\": %.6f, \"total_s\": %.6f, \"candidates\": %zu, \"pairs\": %zu}\n",
      a.size(), b.size(), read_s, build_s, query_s, since(t0), candidates, pairs);
  return 0;
}
