// Whole-process peer (issue #24, item 8): FCL 0.7 on two binary STL files, as a program built on
// FCL runs: read (peer_stl.h), build both BVHModel<OBBRSS> trees, collide() asking for every
// contact (num_max_contacts unlimited, no contact points), print one JSON object with the phase
// times and the number of distinct triangle pairs. Single-threaded (FCL is).
//   interfere_peer_process_fcl A.stl B.stl
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "peer_stl.h"

using namespace interfere::bench;
using Clock = std::chrono::steady_clock;
static double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

static std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> build(const std::vector<Facet>& soup) {
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> tris;
  points.reserve(3 * soup.size());
  tris.reserve(soup.size());
  for (const Facet& f : soup) {
    const auto base = points.size();
    for (const Corner& c : f) points.emplace_back(c[0], c[1], c[2]);
    tris.emplace_back(base, base + 1, base + 2);
  }
  auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  m->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size()));
  m->addSubModel(points, tris);
  m->endModel();
  return m;
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
  const fcl::CollisionObjectd oa(build(a), fcl::Transform3d::Identity());
  const fcl::CollisionObjectd ob(build(b), fcl::Transform3d::Identity());
  const double build_s = since(t);
  t = Clock::now();
  const fcl::CollisionRequestd request(std::size_t{1} << 40, false);
  fcl::CollisionResultd result;
  fcl::collide(&oa, &ob, request, result);
  std::vector<fcl::Contactd> contacts;
  result.getContacts(contacts);
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(contacts.size());
  for (const fcl::Contactd& c : contacts) pairs.emplace_back(c.b1, c.b2);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const double query_s = since(t);
  std::printf(
      "{\"peer\": \"fcl\", \"tris_a\": %zu, \"tris_b\": %zu, \"read_s\": %.6f, \"build_s\": %.6f, "
      "\"query_s\": %.6f, \"total_s\": %.6f, \"pairs\": %zu}\n",
      a.size(), b.size(), read_s, build_s, query_s, since(t0), pairs.size());
  return 0;
}
