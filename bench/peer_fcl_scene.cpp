// Peer of the scene benchmarks (issue #24, item 9): FCL 0.7 (Pan, Chitta, Manocha, ICRA 2012) on
// the generated assembly of bench_scene.cpp, as a clash tool built on FCL (IfcClash) runs it:
//   Scene/assembly/fcl/collide_all
//       one BVHModel<OBBRSS> per part type (the bodies share them, as they share our meshes), one
//       CollisionObject per body with its pose, a DynamicAABBTreeCollisionManager over them
//       (registerObjects + setup), and manager->collide with a callback that runs fcl::collide on
//       each candidate pair asking for every contact (num_max_contacts unlimited, no contact
//       points). Timed: all of that, from the meshes in memory (the conversion to Eigen vectors
//       included). Single-threaded (FCL is).
// Counters: fcl_candidates (pairs the manager hands to the callback), fcl_pairs (pairs collide()
// says collide), fcl_triangle_pairs, and against the exact result of the hard test
// (exact_assembly_pairs: verdict clash): false_pairs (FCL pairs that are not clashes), of which
// false_contact (exactly touching only) and false_clear, and missed_pairs (clashes FCL does not
// report).
#include <benchmark/benchmark.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <map>
#include <memory>
#include <vector>

#include "scene_bench.h"

namespace interfere::bench {
namespace {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<FclModel> build_model(const TriMesh& m) {
  std::vector<fcl::Vector3d> points;
  points.reserve(m.num_vertices());
  for (const Vec3& p : m.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<fcl::Triangle> tris;
  tris.reserve(m.num_triangles());
  for (const Tri& t : m.triangles) tris.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<FclModel>();
  model->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size()));
  model->addSubModel(points, tris);
  model->endModel();
  return model;
}

fcl::Transform3d to_fcl(const Transform& t) {
  fcl::Transform3d x = fcl::Transform3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      x.linear()(i, j) = t.r[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  x.translation() = fcl::Vector3d(t.t.x, t.t.y, t.t.z);
  return x;
}

struct CallbackData {
  fcl::CollisionRequestd request{/*num_max_contacts=*/std::size_t{1} << 40,
                                 /*enable_contact=*/false};
  BodyPairs pairs;
  std::size_t candidates = 0, triangle_pairs = 0;
};

std::uint32_t body_of(const fcl::CollisionObjectd* o) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o->getUserData()));
}

bool on_candidate(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* p) {
  auto* d = static_cast<CallbackData*>(p);
  ++d->candidates;
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, d->request, result);
  if (result.isCollision()) {
    const std::uint32_t a = body_of(o1), b = body_of(o2);
    d->pairs.insert(a < b ? std::pair{a, b} : std::pair{b, a});
    d->triangle_pairs += result.numContacts();
  }
  return false;  // never stop: every pair
}

void bm_fcl_assembly(benchmark::State& state) {
  const AssemblyFixture& fx = assembly_fixture();
  CallbackData data;
  for (auto _ : state) {
    data = CallbackData{};
    std::map<const TriMesh*, std::shared_ptr<FclModel>> models;
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
    objects.reserve(fx.scene.bodies.size());
    std::vector<fcl::CollisionObjectd*> raw;
    raw.reserve(fx.scene.bodies.size());
    for (std::size_t i = 0; i < fx.scene.bodies.size(); ++i) {
      const scene::Body& b = fx.scene.bodies[i];
      auto& model = models[b.mesh.get()];
      if (!model) model = build_model(*b.mesh);
      objects.push_back(std::make_unique<fcl::CollisionObjectd>(model, to_fcl(b.pose)));
      objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
      raw.push_back(objects.back().get());
    }
    fcl::DynamicAABBTreeCollisionManagerd manager;
    manager.registerObjects(raw);
    manager.setup();
    manager.collide(&data, on_candidate);
    benchmark::DoNotOptimize(data.pairs.size());
    state.PauseTiming();
    objects.clear();  // freed outside the timing, as our result is
    state.ResumeTiming();
  }
  const ExactPairs& exact = exact_assembly_pairs();
  std::size_t false_contact = 0, false_clear = 0, missed = 0;
  for (const auto& p : data.pairs)
    if (!exact.clash.contains(p)) ++(exact.contact.contains(p) ? false_contact : false_clear);
  for (const auto& p : exact.clash) missed += !data.pairs.contains(p);
  state.counters["bodies"] = static_cast<double>(fx.scene.bodies.size());
  state.counters["fcl_candidates"] = static_cast<double>(data.candidates);
  state.counters["fcl_pairs"] = static_cast<double>(data.pairs.size());
  state.counters["fcl_triangle_pairs"] = static_cast<double>(data.triangle_pairs);
  state.counters["exact_clash_pairs"] = static_cast<double>(exact.clash.size());
  state.counters["exact_contact_pairs"] = static_cast<double>(exact.contact.size());
  state.counters["false_pairs"] = static_cast<double>(false_contact + false_clear);
  state.counters["false_contact"] = static_cast<double>(false_contact);
  state.counters["false_clear"] = static_cast<double>(false_clear);
  state.counters["missed_pairs"] = static_cast<double>(missed);
  state.counters["threads"] = 1;
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * fx.scene.bodies.size()));
}

[[maybe_unused]] const bool registered = [] {
  benchmark::AddCustomContext("fcl_version", FCL_VERSION);
  benchmark::RegisterBenchmark("Scene/assembly/fcl/collide_all", bm_fcl_assembly)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  return true;
}();

}  // namespace
}  // namespace interfere::bench
