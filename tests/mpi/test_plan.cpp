// The distribution plan of interfere-mpi (apps/mpi/plan.h; issue #31, item 2), without MPI:
// - the plan's broad phase finds the scene engine's candidates: its candidate and suppressed
//   counts equal scene::clash_scene's, and every clash the engine reports is of one of its pairs
//   (random scenes of rotated, scaled and overlapping boxes; hard, clearance with an override,
//   A-vs-B selections, a suppression rule; static and with frames);
// - the partition gives every pair to exactly one block, and every engine call of every rank
//   holds, among its bodies, exactly its own pairs (brute force over all pairs of the call's
//   bodies against the pair list), for 1..7 ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>

#include "plan.h"
#include "interfere/scene/engine.h"

namespace interfere::mpi {
namespace {

std::shared_ptr<const TriMesh> box_mesh(double sx, double sy, double sz) {
  auto m = std::make_shared<TriMesh>();
  for (int c = 0; c < 8; ++c) m->positions.push_back({c & 1 ? sx : 0.0, c & 2 ? sy : 0.0, c & 4 ? sz : 0.0});
  m->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                  {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

Transform rotation(double ax, double ay, double az, double angle, Vec3 t) {
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n, ay /= n, az /= n;
  const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
  Transform r;
  r.r = {{{c + ax * ax * k, ax * ay * k - az * s, ax * az * k + ay * s},
          {ay * ax * k + az * s, c + ay * ay * k, ay * az * k - ax * s},
          {az * ax * k - ay * s, az * ay * k + ax * s, c + az * az * k}}};
  r.t = t;
  return r;
}

scene::Scene random_scene(std::uint64_t seed, std::size_t n, std::size_t frames) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  scene::Scene s;
  std::vector<std::shared_ptr<const TriMesh>> meshes;
  for (int k = 0; k < 4; ++k) meshes.push_back(box_mesh(0.5 + u(rng), 0.5 + u(rng), 0.5 + u(rng)));
  const double side = std::cbrt(static_cast<double>(n)) * 1.6;
  for (std::size_t i = 0; i < n; ++i) {
    scene::Body b;
    b.id = "b" + std::to_string(1000 + (i * 7919) % 1000);  // (ids not in body order)
    b.name = b.id;
    b.tags = {i % 3 ? "part" : "bolt"};
    b.mesh = meshes[i % meshes.size()];
    b.pose = rotation(u(rng) - 0.5, u(rng) - 0.5, u(rng) + 0.1, 3 * u(rng), {side * u(rng), side * u(rng), side * u(rng)});
    s.bodies.push_back(std::move(b));
  }
  for (std::size_t f = 0; f < frames; ++f) {
    scene::Frame fr;
    fr.label = "frame " + std::to_string(f);
    for (std::uint32_t i = 0; i < n; i += 3)
      fr.poses.push_back({i, rotation(u(rng), u(rng), 1, u(rng), {side * u(rng), side * u(rng), side * u(rng)})});
    s.frames.push_back(std::move(fr));
  }
  return s;
}

std::vector<scene::ClashTest> tests() {
  std::vector<scene::ClashTest> t(3);
  t[0].name = "hard";
  t[1].name = "gap", t[1].mode = scene::ClashMode::clearance, t[1].clearance = 0.3;
  t[1].a = {{scene::Selector::Kind::tag, "bolt"}}, t[1].b = {{scene::Selector::Kind::tag, "part"}};
  t[1].clearance_overrides.push_back({{{scene::Selector::Kind::id, "b1*"}}, {{scene::Selector::Kind::all, ""}}, 0.6});
  t[2].name = "sup";
  t[2].suppressions.push_back({{{scene::Selector::Kind::id, "b10*"}}, {{scene::Selector::Kind::all, ""}}, "designed"});
  return t;
}

std::vector<std::vector<AabbF>> plan_boxes(const scene::Scene& s) {
  const std::size_t n = s.bodies.size();
  std::vector<std::vector<AabbF>> boxes(s.frames.empty() ? 1 : s.frames.size(), std::vector<AabbF>(n));
  std::vector<Transform> pose(n);
  for (std::size_t i = 0; i < n; ++i) pose[i] = s.bodies[i].pose;
  for (std::size_t f = 0; f < boxes.size(); ++f) {
    if (!s.frames.empty())
      for (const scene::Frame::Pose& p : s.frames[f].poses) pose[p.body] = p.pose;
    for (std::size_t i = 0; i < n; ++i) {
      Aabb local;
      for (const Vec3& p : s.bodies[i].mesh->positions) local.expand(p);
      boxes[f][i] = broad_box(local, pose[i]);
    }
  }
  return boxes;
}

TEST(MpiPlan, BroadPhaseFindsTheEngineCandidates) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    for (const std::size_t frames : {std::size_t{0}, std::size_t{3}}) {
      const scene::Scene s = random_scene(seed, 60 + 20 * seed, frames);
      const BroadResult b = broad_phase(s.bodies, tests(), plan_boxes(s));
      scene::SceneClashOptions o;
      o.depth = false, o.curves = false;
      const scene::SceneClashResult r = scene::clash_scene(s, tests(), o);
      EXPECT_EQ(b.candidate_pairs, r.candidate_pairs) << "seed " << seed << ", frames " << frames;
      EXPECT_EQ(b.suppressed, r.suppressed) << "seed " << seed;
      EXPECT_GT(r.clashes.size(), 0u);
      std::set<std::pair<std::uint32_t, std::uint32_t>> units;
      for (const Unit& u : b.units) units.emplace(u.a, u.b);
      for (const scene::SceneClash& c : r.clashes) EXPECT_TRUE(units.count({c.a, c.b})) << c.id;
    }
  }
}

TEST(MpiPlan, EveryCallHoldsExactlyItsOwnPairs) {
  const scene::Scene s = random_scene(7, 300, 0);  // (dense enough for one large component)
  const std::vector<std::vector<AabbF>> boxes = plan_boxes(s);
  BroadResult b = broad_phase(s.bodies, tests(), boxes);
  ASSERT_GT(b.units.size(), 100u);
  for (Unit& u : b.units) u.cost = pair_cost(12, 12) * (1 + (u.a * 31 + u.b) % 5);
  std::set<std::pair<std::uint32_t, std::uint32_t>> all;
  for (const Unit& u : b.units) all.emplace(u.a, u.b);
  const std::size_t components = partition(b, boxes[0], 1).blocks.size();
  std::size_t most_blocks = 0;
  for (std::size_t ranks = 1; ranks <= 7; ++ranks) {
    const Partition p = partition(b, boxes[0], ranks);
    most_blocks = std::max(most_blocks, p.blocks.size());
    std::vector<int> seen(b.units.size(), 0);
    for (const Block& blk : p.blocks)
      for (const std::uint32_t k : blk.units) ++seen[k];
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "unit " << k << ", " << ranks << " ranks";
    std::vector<int> called(b.units.size(), 0);
    for (std::size_t r = 0; r < ranks; ++r) {
      for (const Block& call : p.calls[r]) {
        std::set<std::pair<std::uint32_t, std::uint32_t>> own;
        for (const std::uint32_t k : call.units) own.emplace(b.units[k].a, b.units[k].b), ++called[k];
        std::size_t induced = 0;
        for (const std::uint32_t x : call.bodies)
          for (const std::uint32_t y : call.bodies)
            if (all.count({x, y})) {
              ++induced;
              EXPECT_TRUE(own.count({x, y})) << "a pair of another call among a call's bodies, " << ranks << " ranks";
            }
        EXPECT_EQ(induced, own.size());
      }
    }
    for (std::size_t k = 0; k < called.size(); ++k) EXPECT_EQ(called[k], 1) << "unit " << k << ", " << ranks << " ranks";
  }
  EXPECT_GT(most_blocks, components);  // (some component was cut: groups and pairs between them)
}

}  // namespace
}  // namespace interfere::mpi
