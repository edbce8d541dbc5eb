// The distribution plan of interfere-mpi (apps/mpi/plan.h; issue #31, item 2), without MPI:
// - the plan's broad phase finds the scene engine's candidates: its candidate and suppressed
//   counts equal scene::clash_scene's, and every clash the engine reports is of one of its pairs
//   (random scenes of rotated, scaled and overlapping boxes; hard, clearance with an override,
//   A-vs-B selections, a suppression rule; static and with frames);
// - the partition gives every pair to exactly one rank, a class of pairs the engine decides once
//   to one rank, and each rank exactly the bodies its pairs need, for 1..7 ranks;
// - a skewed scene (one huge pair, 2,000 tiny bodies) is balanced within 10 % of the best possible;
// - repeated joints: the ranks' core runs add up to one process's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
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

std::vector<std::uint64_t> triangle_counts(const scene::Scene& s) {
  std::vector<std::uint64_t> t;
  for (const scene::Body& b : s.bodies) t.push_back(b.mesh->num_triangles());
  return t;
}

std::vector<std::uint64_t> mesh_keys(const scene::Scene& s) {
  std::vector<std::uint64_t> k;
  for (const scene::Body& b : s.bodies) k.push_back(reinterpret_cast<std::uintptr_t>(b.mesh.get()));
  return k;
}

std::vector<std::vector<Transform>> plan_poses(const scene::Scene& s) {
  std::vector<Transform> pose;
  for (const scene::Body& b : s.bodies) pose.push_back(b.pose);
  std::vector<std::vector<Transform>> out;
  if (s.frames.empty()) out.push_back(pose);
  for (const scene::Frame& f : s.frames) {
    for (const scene::Frame::Pose& p : f.poses) pose[p.body] = p.pose;
    out.push_back(pose);
  }
  return out;
}

// Every pair on exactly one rank, every item's pairs on one rank, and each rank holding exactly
// the bodies its pairs need (checked against the unit list, not the plan's own bookkeeping).
void expect_sound(const BroadResult& b, const Partition& p, std::size_t ranks) {
  ASSERT_EQ(p.rank_units.size(), ranks);
  std::vector<int> seen(b.units.size(), 0);
  std::map<std::uint32_t, std::set<std::size_t>> item_ranks;
  for (std::size_t r = 0; r < ranks; ++r) {
    std::set<std::uint32_t> need;
    for (const std::uint32_t k : p.rank_units[r]) {
      ++seen[k];
      need.insert(b.units[k].a), need.insert(b.units[k].b);
      item_ranks[b.units[k].item].insert(r);
    }
    EXPECT_EQ(std::vector<std::uint32_t>(need.begin(), need.end()), p.rank_bodies[r]) << "rank " << r << " of " << ranks;
  }
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "unit " << k << ", " << ranks << " ranks";
  for (const auto& [item, rs] : item_ranks) EXPECT_EQ(rs.size(), 1u) << "item " << item << " split, " << ranks << " ranks";
}

TEST(MpiPlan, EveryPairOnOneRankWithTheBodiesItNeeds) {
  const scene::Scene s = random_scene(7, 300, 0);  // (dense enough for one large component)
  const std::vector<std::vector<AabbF>> boxes = plan_boxes(s);
  BroadResult b = broad_phase(s.bodies, tests(), boxes);
  ASSERT_GT(b.units.size(), 100u);
  join_classes(b, mesh_keys(s), plan_poses(s));
  const CostModel model;
  for (Unit& u : b.units) u.cost = model.pair(12, 12) * (1 + (u.a * 31 + u.b) % 5);
  std::size_t most_pieces = 0;
  for (std::size_t ranks = 1; ranks <= 7; ++ranks) {
    const Partition p = partition(b, boxes[0], triangle_counts(s), model, ranks);
    most_pieces = std::max(most_pieces, p.pieces);
    expect_sound(b, p, ranks);
  }
  EXPECT_GT(most_pieces, partition(b, boxes[0], triangle_counts(s), model, 1).pieces);  // (a component was cut)
}

// Issue #31: a scene where one huge body pair dominates beside many tiny bodies. The plan's load
// imbalance (its busiest rank's estimated cost over the best any partition can do: the larger of
// the mean and the costliest single pair with its bodies) stays within 10 % for 2..8 ranks, and
// the tiny bodies are read about once (locality: a body's pairs on one rank).
TEST(MpiPlan, SkewedSceneIsBalanced) {
  const std::size_t tiny = 2000;
  std::vector<scene::Body> bodies(tiny + 2);
  std::vector<std::uint64_t> tris(tiny + 2, 12);
  std::vector<AabbF> boxes(tiny + 2);
  for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].id = "b" + std::to_string(100000 + i);
  tris[0] = tris[1] = 2000000;  // the huge pair
  boxes[0] = to_float_outward(Aabb{{-10, -10, -10}, {1, 10, 10}});
  boxes[1] = to_float_outward(Aabb{{-1, -10, -10}, {10, 10, 10}});
  const std::size_t side = 13;  // tiny boxes on a grid beside them, each touching its x and y neighbours
  for (std::size_t i = 0; i < tiny; ++i) {
    const double x = 20 + static_cast<double>(i % side), y = static_cast<double>((i / side) % side), z = 1.5 * static_cast<double>(i / side / side);
    boxes[i + 2] = to_float_outward(Aabb{{x, y, z}, {x + 1.0, y + 1.0, z + 0.5}});
  }
  BroadResult b = broad_phase(bodies, {scene::ClashTest{}}, {boxes});
  ASSERT_GT(b.units.size(), 2 * tiny);
  const CostModel model;
  for (Unit& u : b.units) u.cost = model.pair(tris[u.a], tris[u.b]);
  double total = 0, huge = model.body(tris[0]) + model.body(tris[1]);
  for (const Unit& u : b.units) {
    total += u.cost;
    if (u.a <= 1 && u.b <= 1) huge += u.cost;
  }
  for (const std::uint64_t t : tris) total += model.body(t);
  ASSERT_GT(huge, 0.3 * total);  // (it dominates)
  for (std::size_t ranks = 2; ranks <= 8; ++ranks) {
    const Partition p = partition(b, boxes, tris, model, ranks);
    expect_sound(b, p, ranks);
    // Independent of the plan's bookkeeping: each rank's pairs and bodies costed again.
    double most = 0;
    std::size_t reads = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      double c = 0;
      std::set<std::uint32_t> held;
      for (const std::uint32_t k : p.rank_units[r]) c += b.units[k].cost, held.insert(b.units[k].a), held.insert(b.units[k].b);
      for (const std::uint32_t i : held) c += model.body(tris[i]);
      most = std::max(most, c), reads += held.size();
    }
    const double best = std::max(total / static_cast<double>(ranks), huge);
    EXPECT_LE(most, 1.10 * best) << ranks << " ranks: busiest " << most << ", best possible " << best;
    EXPECT_LE(static_cast<double>(reads), 1.15 * static_cast<double>(bodies.size())) << ranks << " ranks";
  }
}

// A dense grid of bodies of log-normal sizes (each box overlapping ~19 neighbours, as the
// simulated product of docs/scaling.md): many ranks cut it into runs whose border bodies two ranks
// build. The busiest rank's true cost (its pairs and every body it holds, counted again here) is
// within 10 % of the mean of the ranks' true costs, for 2..64 ranks (the 10 % target of issue #31
// at 256 ranks is for the simulated 10^5-body product).
TEST(MpiPlan, GridRanksBalancedByTheirTrueCost) {
  const std::size_t side = 22, n = side * side * side;
  std::vector<scene::Body> bodies(n);
  std::vector<std::uint64_t> tris(n);
  std::vector<AabbF> boxes(n);
  std::uint64_t state = 31;
  const auto uniform = [&] {  // (splitmix64)
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL, z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    bodies[i].id = "g" + std::to_string(100000 + i);
    tris[i] = 12 + static_cast<std::uint64_t>(2000 * std::exp(2 * uniform() - 1) * uniform());
    const double x = static_cast<double>(i % side), y = static_cast<double>((i / side) % side), z = static_cast<double>(i / side / side);
    const double h = 0.45 + 0.15 * uniform();
    boxes[i] = to_float_outward(Aabb{{x - h, y - h, z - h}, {x + h, y + h, z + h}});
  }
  BroadResult b = broad_phase(bodies, {scene::ClashTest{}}, {boxes});
  const CostModel model;
  for (Unit& u : b.units) u.cost = model.pair(tris[u.a], tris[u.b]);
  for (const std::size_t ranks : {2, 3, 8, 16, 64}) {
    const Partition p = partition(b, boxes, tris, model, ranks);
    expect_sound(b, p, ranks);
    double most = 0, sum = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      double c = 0;
      std::set<std::uint32_t> held;
      for (const std::uint32_t k : p.rank_units[r]) c += b.units[k].cost, held.insert(b.units[k].a), held.insert(b.units[k].b);
      for (const std::uint32_t i : held) c += model.body(tris[i]);
      most = std::max(most, c), sum += c;
    }
    EXPECT_LE(most, 1.10 * sum / static_cast<double>(ranks)) << ranks << " ranks";
  }
}

// Pairs of the same two meshes in the same relative pose (a product's repeated joints) are one
// item, so one rank decides their class once: the ranks' engine runs (clash_scene with
// decide_pairs on the bodies each rank needs) add up to one process's core_runs and clashes.
TEST(MpiPlan, RepeatedJointsStayTogetherAndCoreRunsAddUp) {
  scene::Scene s;
  const auto plate = box_mesh(2, 2, 0.5), pin = box_mesh(0.4, 0.4, 2);
  for (int i = 0; i < 24; ++i) {
    scene::Body p, q;
    p.id = "plate" + std::to_string(100 + i), q.id = "pin" + std::to_string(100 + i);
    p.mesh = plate, q.mesh = pin;
    const double x = 4.0 * (i % 6), y = 4.0 * (i / 6);  // (binary-exact offsets: the relative poses are equal bit for bit)
    p.pose.t = {x, y, 0}, q.pose.t = {x + 0.75, y + 0.75, i % 2 ? -1.0 : -0.5};  // two relative poses
    s.bodies.push_back(p), s.bodies.push_back(q);
  }
  const std::vector<scene::ClashTest> t{scene::ClashTest{}};
  scene::SceneClashOptions o;
  o.curves = false;
  const scene::SceneClashResult whole = scene::clash_scene(s, t, o);
  ASSERT_EQ(whole.core_runs, 2u);
  ASSERT_EQ(whole.clash_count, 24u);
  const std::vector<std::vector<AabbF>> boxes = plan_boxes(s);
  BroadResult b = broad_phase(s.bodies, t, boxes);
  join_classes(b, mesh_keys(s), plan_poses(s));
  for (Unit& u : b.units) u.cost = pair_cost(12, 12);
  for (std::size_t ranks = 1; ranks <= 4; ++ranks) {
    const Partition p = partition(b, boxes[0], triangle_counts(s), CostModel{}, ranks);
    expect_sound(b, p, ranks);
    std::size_t runs = 0, clashes = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      if (p.rank_units[r].empty()) continue;
      scene::Scene sub;
      std::vector<std::uint32_t> local(s.bodies.size(), 0);
      for (const std::uint32_t i : p.rank_bodies[r]) local[i] = static_cast<std::uint32_t>(sub.bodies.size()), sub.bodies.push_back(s.bodies[i]);
      scene::SceneClashOptions ro = o;
      for (const std::uint32_t k : p.rank_units[r]) ro.decide_pairs.emplace_back(local[b.units[k].a], local[b.units[k].b]);
      const scene::SceneClashResult part = scene::clash_scene(sub, t, ro);
      runs += part.core_runs, clashes += part.clash_count;
    }
    EXPECT_EQ(runs, whole.core_runs) << ranks << " ranks";
    EXPECT_EQ(clashes, whole.clash_count) << ranks << " ranks";
  }
}

}  // namespace
}  // namespace interfere::mpi
