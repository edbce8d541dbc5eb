// Peer: FCL 0.7 (Pan, Chitta, Manocha, ICRA 2012) on the same sphere pairs. Its own translation
// unit so that FCL/Eigen headers stay local.
//   Peer/fcl/build/<n>    both BVHModel<OBBRSS> trees (beginModel/addSubModel/endModel); the
//   conversion
//                         of our positions to Eigen vectors is not timed (like our untimed mesh
//                         copy)
//   Peer/fcl/collide/<n>  collide() asking for every contact (num_max_contacts large, no contact
//                         points); counters compare FCL's pair list with the engine's exact one
//   Exact/<scene>/fcl     the exactness scenes of common.h: both trees built + collide(), timed
//                         together; counters as for collide plus fcl_collides
//                         (CollisionResult::isCollision(), 0/1)
// FCL decides triangle pairs with its double-precision triangle test, so `missing`/`extra` count
// the pairs where it disagrees with the exact result (touching pairs are where double tests usually
// differ). The meshes are handed over in world coordinates with identity transforms, exactly the
// coordinates the engine and CGAL see.
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
#include "interfere/np/tri_tri.h"

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

const fcl::CollisionRequestd& all_contacts_request() {
  static const fcl::CollisionRequestd request(/*num_max_contacts=*/std::size_t{1} << 40,
                                              /*enable_contact=*/false);
  return request;
}

/// FCL's (triangle of A, triangle of B) pairs of one collide() result, sorted and unique.
PairList fcl_pairs(fcl::CollisionResultd& result) {  // getContacts() is not const
  std::vector<fcl::Contactd> contacts;
  result.getContacts(contacts);
  PairList pairs;
  pairs.reserve(contacts.size());
  for (const fcl::Contactd& c : contacts) {
    pairs.emplace_back(static_cast<std::uint32_t>(c.b1), static_cast<std::uint32_t>(c.b2));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}


void bm_fcl_collide(benchmark::State& state, std::size_t n) {
  const SpherePair& p = sphere_pair(n);
  const fcl::CollisionObjectd oa(build_fcl(to_fcl(p.a)), fcl::Transform3d::Identity());
  const fcl::CollisionObjectd ob(build_fcl(to_fcl(p.b)), fcl::Transform3d::Identity());
  PairList pairs;
  for (auto _ : state) {
    fcl::CollisionResultd result;
    fcl::collide(&oa, &ob, all_contacts_request(), result);
    state.PauseTiming();
    pairs = fcl_pairs(result);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(
      static_cast<std::int64_t>(state.iterations() * (p.a.num_triangles() + p.b.num_triangles())));
  set_diff_counters(state, pairs, reference_pairs(n), p.a, p.b);
}

/// An exactness scene: both trees + collide(), timed together (the conversion to Eigen is not).
void bm_fcl_exact(benchmark::State& state, const std::string& scene) {
  const ExactScene& sc = exact_scene(scene);
  const FclInput a = to_fcl(sc.a), b = to_fcl(sc.b);
  PairList pairs;
  bool collides = false;
  for (auto _ : state) {
    const fcl::CollisionObjectd oa(build_fcl(a), fcl::Transform3d::Identity());
    const fcl::CollisionObjectd ob(build_fcl(b), fcl::Transform3d::Identity());
    fcl::CollisionResultd result;
    fcl::collide(&oa, &ob, all_contacts_request(), result);
    state.PauseTiming();
    collides = result.isCollision();
    pairs = fcl_pairs(result);
    state.ResumeTiming();
  }
  const std::size_t na = sc.a.num_triangles(), nb = sc.b.num_triangles();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (na + nb)));
  set_diff_counters(state, pairs, exact_scene_reference(scene), sc.a, sc.b);
  state.counters["fcl_collides"] = collides ? 1 : 0;
  state.counters["tris_a"] = static_cast<double>(na);
  state.counters["tris_b"] = static_cast<double>(nb);
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
  for (const std::string& scene : exact_scene_names()) {
    benchmark::RegisterBenchmark(("Exact/" + scene + "/fcl").c_str(),
                                 [scene](benchmark::State& s) { bm_fcl_exact(s, scene); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace interfere::bench
