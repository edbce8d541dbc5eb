// Peer: FCL 0.7 (Pan, Chitta, Manocha, ICRA 2012) on the same sphere pairs. Its own translation
// unit so that FCL/Eigen headers stay local.
//   Peer/fcl/build/<n>    both BVHModel<OBBRSS> trees (beginModel/addSubModel/endModel); the
//   conversion
//                         of our positions to Eigen vectors is not timed (like our untimed mesh
//                         copy)
//   Peer/fcl/collide/<n>  collide() asking for every contact (num_max_contacts large, no contact
//                         points); counters compare FCL's pair list with the engine's exact one
// FCL decides triangle pairs with its double-precision triangle test, so `missing`/`extra` count
// the pairs where it disagrees with the exact result (touching pairs are where double tests usually
// differ).
#include <benchmark/benchmark.h>
#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "common.h"
#include "interfere/np/distance.h"

namespace interfere::bench {
namespace {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

struct FclInput {
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> triangles;
};

FclInput to_fcl(const TriMesh& m) {
  FclInput in;
  in.points.reserve(m.num_vertices());
  for (const Vec3& p : m.positions) in.points.emplace_back(p.x, p.y, p.z);
  in.triangles.reserve(m.num_triangles());
  for (const Tri& t : m.triangles) in.triangles.emplace_back(t[0], t[1], t[2]);
  return in;
}

std::shared_ptr<FclModel> build_fcl(const FclInput& in) {
  auto model = std::make_shared<FclModel>();
  model->beginModel(static_cast<int>(in.triangles.size()), static_cast<int>(in.points.size()));
  model->addSubModel(in.points, in.triangles);
  model->endModel();
  return model;
}

void bm_fcl_build(benchmark::State& state, std::size_t n) {
  const SpherePair& p = sphere_pair(n);
  const FclInput a = to_fcl(p.a), b = to_fcl(p.b);
  for (auto _ : state) {
    auto ma = build_fcl(a);
    auto mb = build_fcl(b);
    benchmark::DoNotOptimize(ma.get());
    benchmark::DoNotOptimize(mb.get());
    state.PauseTiming();
    ma.reset(), mb.reset();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(
      static_cast<std::int64_t>(state.iterations() * (p.a.num_triangles() + p.b.num_triangles())));
}

void bm_fcl_collide(benchmark::State& state, std::size_t n) {
  const SpherePair& p = sphere_pair(n);
  const fcl::CollisionObjectd oa(build_fcl(to_fcl(p.a)), fcl::Transform3d::Identity());
  const fcl::CollisionObjectd ob(build_fcl(to_fcl(p.b)), fcl::Transform3d::Identity());
  const fcl::CollisionRequestd request(/*num_max_contacts=*/std::size_t{1} << 40,
                                       /*enable_contact=*/false);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (auto _ : state) {
    fcl::CollisionResultd result;
    fcl::collide(&oa, &ob, request, result);
    state.PauseTiming();
    std::vector<fcl::Contactd> contacts;
    result.getContacts(contacts);
    pairs.clear();
    pairs.reserve(contacts.size());
    for (const fcl::Contactd& c : contacts) {
      pairs.emplace_back(static_cast<std::uint32_t>(c.b1), static_cast<std::uint32_t>(c.b2));
    }
    state.ResumeTiming();
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const PairDiff d = diff_pairs(pairs, reference_pairs(n));
  state.SetItemsProcessed(
      static_cast<std::int64_t>(state.iterations() * (p.a.num_triangles() + p.b.num_triangles())));
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["reference_pairs"] = static_cast<double>(reference_pairs(n).size());
  state.counters["extra"] = static_cast<double>(d.extra);
  state.counters["missing"] = static_cast<double>(d.missing);
  if (d.extra) {  // one example for the report: (triangle of A, triangle of B)
    state.counters["first_extra_a"] = d.first_extra.first;
    state.counters["first_extra_b"] = d.first_extra.second;
    state.counters["first_extra_distance"] =
        triangle_triangle_closest(p.a.corners(d.first_extra.first),
                                  p.b.corners(d.first_extra.second))
            .distance;
  }
  if (d.missing) {
    state.counters["first_missing_a"] = d.first_missing.first;
    state.counters["first_missing_b"] = d.first_missing.second;
  }
}

[[maybe_unused]] const bool registered = [] {
  benchmark::AddCustomContext("fcl_version", FCL_VERSION);
  const std::size_t peer_max = env_size("INTERFERE_BENCH_PEER_MAX", 1000000);
  for (std::size_t n : table_sizes()) {
    if (n > peer_max) continue;
    const std::string sn = size_label(n);
    benchmark::RegisterBenchmark(("Peer/fcl/build/" + sn).c_str(),
                                 [n](benchmark::State& s) { bm_fcl_build(s, n); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("Peer/fcl/collide/" + sn).c_str(),
                                 [n](benchmark::State& s) { bm_fcl_collide(s, n); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
