// The generated assembly (scene/generate.h): every part mesh closed, consistently oriented and
// outward, its volume (divergence theorem) equal to the volume of the polygonal solid computed here
// from the dimensions (so within the tessellation's error of the smooth part); the layout's counts,
// ids and ground truth; the moving scene's frames.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "interfere/mesh/validate.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/generate.h"

namespace interfere::scene {
namespace {

double signed_volume(const TriMesh& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    v += dot(c[0], cross(c[1], c[2]));
  }
  return v / 6;
}

// Area of the regular n-gon inscribed in a circle of radius r, and the smooth circle's excess.
double polygon_area(double r, int n) {
  return 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n);
}
double deficit(double r, int n) {
  return std::numbers::pi * r * r - polygon_area(r, n);
}

TEST(SceneGenerate, PartsAreClosedOutwardAndHaveTheirVolume) {
  const JointDims d;
  for (int n : {24, 48, 96}) {
    const std::vector<AssemblyPart> parts = assembly_parts(d, n);
    ASSERT_EQ(parts.size(), 5u);
    const double shaft =
        d.shaft_protrusion + d.nut_thickness + 2 * d.washer_thickness + 2 * d.plate_thickness;
    // The polygonal solids, and the bound on their difference from the smooth parts.
    const std::map<std::string, std::pair<double, double>> expected = {
        {"plate",
         {(d.plate_width * d.plate_width - polygon_area(d.hole_radius, n)) * d.plate_thickness,
          deficit(d.hole_radius, n) * d.plate_thickness}},
        {"bolt",
         {polygon_area(d.shaft_radius, n) * shaft + polygon_area(d.head_radius, n) * d.head_height,
          deficit(d.shaft_radius, n) * shaft + deficit(d.head_radius, n) * d.head_height}},
        {"washer",
         {(polygon_area(d.washer_outer, n) - polygon_area(d.washer_inner, n)) * d.washer_thickness,
          (deficit(d.washer_outer, n) + deficit(d.washer_inner, n)) * d.washer_thickness}},
        {"nut",
         {(2 * std::sqrt(3.0) * d.nut_apothem * d.nut_apothem - polygon_area(d.nut_inner, n)) *
              d.nut_thickness,
          deficit(d.nut_inner, n) * d.nut_thickness}},
        {"bracket",
         {(d.bracket_width * d.bracket_thickness +
           d.bracket_thickness * (d.bracket_height - d.bracket_thickness)) *
              d.bracket_length,
          0.0}},
    };
    for (const AssemblyPart& p : parts) {
      SCOPED_TRACE(p.type + " at " + std::to_string(n) + " segments");
      const MeshStats s = mesh_stats(*p.mesh);
      EXPECT_TRUE(s.closed());
      EXPECT_EQ(s.open_edges, 0u);
      EXPECT_EQ(s.nonmanifold_edges, 0u);
      EXPECT_EQ(s.inconsistent_edges, 0u);
      EXPECT_EQ(s.degenerate_triangles, 0u);
      EXPECT_EQ(s.duplicate_triangles, 0u);
      EXPECT_EQ(s.components, 1u);
      const double v = signed_volume(*p.mesh);
      EXPECT_GT(v, 0) << "inward";
      const auto [poly, bound] = expected.at(p.type);
      EXPECT_NEAR(v, poly, 1e-9 * poly);
      EXPECT_LE(std::fabs(v - p.analytic_volume), bound * (1 + 1e-9) + 1e-9 * poly);
    }
  }
  EXPECT_THROW(assembly_parts(d, 40), std::invalid_argument);
}

TEST(SceneGenerate, AssemblyLayoutIdsAndGroundTruth) {
  AssemblyGenOptions o;
  o.bodies = 68;  // 9 full joints and one cut short
  o.clashes = 3;  // one of each kind
  o.gaps = 2;
  AssemblyInfo info;
  const Scene s = generate_assembly(o, &info);
  ASSERT_EQ(s.bodies.size(), 68u);
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(info.joints, 10u);
  std::map<std::string, int> per_tag;
  std::size_t triangles = 0;
  for (const Body& b : s.bodies) {
    ASSERT_EQ(b.tags.size(), 1u);
    ++per_tag[b.tags[0]];
    EXPECT_EQ(b.id.rfind(b.tags[0] + "-", 0), 0u) << b.id;
    EXPECT_EQ(b.id.size(), b.tags[0].size() + 7);
    EXPECT_TRUE(b.pose.is_rigid());
    triangles += b.mesh->num_triangles();
  }
  EXPECT_EQ(info.triangles, triangles);
  EXPECT_EQ(per_tag["plate"], 20);
  EXPECT_EQ(per_tag["bolt"], 10);
  EXPECT_EQ(per_tag["washer"], 20);
  EXPECT_EQ(per_tag["nut"], 9);
  EXPECT_EQ(per_tag["bracket"], 9);
  EXPECT_GE(s.find("bolt-000009"), 0);
  EXPECT_LT(s.find("bracket-000009"), 0);
  // One shifted bolt (5 pairs, unless it is the cut joint's), one sunk bracket, one bracket in a
  // washer.
  EXPECT_GE(info.clash_pairs.size(), 5u);
  EXPECT_LE(info.clash_pairs.size(), 7u);
  EXPECT_LE(info.gap_pairs.size(), 2u);
  // Ground truth pairs are distinct and name existing bodies.
  std::set<std::pair<std::string, std::string>> all;
  for (const auto* v : {&info.clash_pairs, &info.contact_pairs, &info.gap_pairs})
    for (const auto& p : *v) {
      EXPECT_LT(p.first, p.second);
      EXPECT_GE(s.find(p.first), 0);
      EXPECT_GE(s.find(p.second), 0);
      EXPECT_TRUE(all.insert(p).second) << p.first << " " << p.second;
    }
  // Deterministic.
  AssemblyInfo again;
  const Scene t = generate_assembly(o, &again);
  ASSERT_EQ(t.bodies.size(), s.bodies.size());
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    EXPECT_EQ(t.bodies[i].id, s.bodies[i].id);
    EXPECT_EQ(t.bodies[i].pose, s.bodies[i].pose);
  }
  EXPECT_EQ(again.clash_pairs, info.clash_pairs);
}

TEST(SceneGenerate, DefaultAssemblyHasAboutTenMillionTriangles) {
  AssemblyInfo info;
  const Scene s = generate_assembly({}, &info);
  EXPECT_EQ(s.bodies.size(), 10000u);
  EXPECT_GT(info.triangles, 8'000'000u);
  EXPECT_LT(info.triangles, 13'000'000u);
  // Every joint is special at most once: clashes (a third shifted bolts with 5 pairs each) and
  // gaps.
  EXPECT_EQ(info.clash_pairs.size(), 100u * 5 + 200u);
  EXPECT_EQ(info.gap_pairs.size(), 100u);
}

// Every pose of every frame rigid and small: every corner of the local box moves by at most the
// translation (per axis) plus the rotation about the part's centre (angle x the box's diagonal).
void expect_small_rigid_motions(const Scene& s, const MovingSceneGenOptions& o) {
  EXPECT_NO_THROW(s.validate());
  ASSERT_EQ(s.frames.size(), o.frames);
  for (const Frame& f : s.frames) {
    ASSERT_EQ(f.poses.size(), s.bodies.size());
    for (const Frame::Pose& p : f.poses) {
      EXPECT_TRUE(p.pose.is_rigid());
      const Body& b = s.bodies[p.body];
      const Aabb box = b.mesh->bounds();
      for (int c = 0; c < 8; ++c) {
        const Vec3 q{c & 1 ? box.lo.x : box.hi.x, c & 2 ? box.lo.y : box.hi.y, c & 4 ? box.lo.z : box.hi.z};
        EXPECT_LE(distance(p.pose.apply(q), b.pose.apply(q)),
                  o.max_translation * std::sqrt(3.0) + o.max_rotation_deg * std::numbers::pi / 180 * norm(box.extent()));
      }
    }
  }
}

// The world box of a body in a frame, from its local box's corners.
Aabb world_box(const Body& b, const Transform& pose) {
  const Aabb box = b.mesh->bounds();
  Aabb w;
  for (int c = 0; c < 8; ++c)
    w.expand(pose.apply(Vec3{c & 1 ? box.lo.x : box.hi.x, c & 2 ? box.lo.y : box.hi.y, c & 4 ? box.lo.z : box.hi.z}));
  return w;
}

TEST(SceneGenerate, MovingAssemblyMovesEveryBodyRigidlyEveryFrame) {
  MovingSceneGenOptions o;
  o.layout = MovingLayout::assembly, o.bodies = 140, o.frames = 5, o.seed = 7;
  const Scene s = generate_moving_scene(o);
  ASSERT_EQ(s.bodies.size(), 140u);
  expect_small_rigid_motions(s, o);
  const Scene t = generate_moving_scene(o);
  EXPECT_EQ(t.frames[4].poses[77].pose, s.frames[4].poses[77].pose);
  o.seed = 8;
  const Scene u = generate_moving_scene(o);
  EXPECT_NE(u.frames[4].poses[77].pose, s.frames[4].poses[77].pose);
}

// The moving scene of the benchmark (MovingLayout::cell): bodies apart by their cells' clearance
// in every frame, except the near pairs, checked on the world boxes of the poses (independent of
// any clash query); deterministic per seed.
TEST(SceneGenerate, MovingCellsKeepBodiesApartExceptNearPairs) {
  MovingSceneGenOptions o;
  o.bodies = 250, o.frames = 6, o.seed = 3;
  std::vector<std::pair<std::string, std::string>> near;
  const Scene s = generate_moving_scene(o, &near);
  ASSERT_EQ(s.bodies.size(), 250u);
  ASSERT_EQ(near.size(), 5u);  // 4 % of 250 bodies in pairs
  expect_small_rigid_motions(s, o);
  const std::set<std::pair<std::string, std::string>> near_set(near.begin(), near.end());
  std::size_t near_boxes_meet = 0;
  for (const Frame& f : s.frames) {
    std::vector<Aabb> w;
    for (const Frame::Pose& p : f.poses) w.push_back(world_box(s.bodies[p.body], p.pose));
    for (std::size_t i = 0; i < w.size(); ++i)
      for (std::size_t j = i + 1; j < w.size(); ++j) {
        double gap = 0;  // the largest separation of the boxes along an axis
        for (int k = 0; k < 3; ++k) gap = std::max({gap, w[j].lo[k] - w[i].hi[k], w[i].lo[k] - w[j].hi[k]});
        if (near_set.contains(std::minmax(s.bodies[i].id, s.bodies[j].id))) {
          near_boxes_meet += gap <= 0;
        } else {
          ASSERT_GT(gap, 1.5) << s.bodies[i].id << " " << s.bodies[j].id;  // clearance 2 less the motions
        }
      }
  }
  EXPECT_GT(near_boxes_meet, 0u);
  std::vector<std::pair<std::string, std::string>> again;
  const Scene t = generate_moving_scene(o, &again);
  EXPECT_EQ(again, near);
  EXPECT_EQ(t.frames[5].poses[100].pose, s.frames[5].poses[100].pose);
}

// The engine on the moving cells: only near pairs are ever reported, the fits (bolt in a plate's
// hole, 0.5 mm radial clearance) never, and the stacks clash in some frames and not in others.
TEST(SceneGenerate, MovingCellsClashOnlyInNearPairsInSomeFrames) {
  MovingSceneGenOptions o;
  o.bodies = 500, o.frames = 12, o.seed = 1, o.segments = 24;
  std::vector<std::pair<std::string, std::string>> near;
  const Scene s = generate_moving_scene(o, &near);
  ASSERT_EQ(near.size(), 10u);
  ClashTest hard;
  hard.name = "hard";
  SceneClashOptions opt;
  opt.curves = false;
  const SceneClashResult r = clash_scene(s, {hard}, opt);
  const std::set<std::pair<std::string, std::string>> near_set(near.begin(), near.end());
  for (const PairSummary& p : r.pairs) {
    const auto ids = std::minmax(s.bodies[p.a].id, s.bodies[p.b].id);
    EXPECT_TRUE(near_set.contains(ids)) << ids.first << " " << ids.second;
    EXPECT_FALSE(ids.first.starts_with("bolt") || ids.second.starts_with("bolt")) << ids.first << " " << ids.second;
    EXPECT_NE(p.verdict, Verdict::undecided);
  }
  ASSERT_EQ(r.frames.size(), 12u);
  std::size_t with = 0;
  for (const FrameRow& f : r.frames) with += f.clashes > 0;
  EXPECT_GT(with, 0u);
  EXPECT_LT(with, 12u);
}

// The engine against the generator's construction: the clashing body pairs of a small assembly
// are exactly the designed clashes, and every designed contact is a contact, every gap a clearance.
TEST(SceneGenerate, EngineFindsTheDesignedClashesContactsAndGaps) {
  AssemblyGenOptions o;
  o.bodies = 140;
  o.segments = 24;
  o.clashes = 6;
  o.gaps = 3;
  AssemblyInfo info;
  const Scene s = generate_assembly(o, &info);
  ClashTest hard;
  hard.name = "hard";
  ClashTest clear;
  clear.name = "clearance";
  clear.mode = ClashMode::clearance;
  clear.clearance = 0.1;
  SceneClashOptions opt;
  opt.curves = false;
  const SceneClashResult r = clash_scene(s, {hard, clear}, opt);
  std::map<std::string, std::set<std::pair<std::string, std::string>>> by_verdict[2];
  for (const PairSummary& p : r.pairs) {
    const int test = p.test == "hard" ? 0 : 1;
    by_verdict[test][verdict_name(p.verdict)].insert(
        std::minmax(s.bodies[p.a].id, s.bodies[p.b].id));
  }
  using Set = std::set<std::pair<std::string, std::string>>;
  const Set clashes(info.clash_pairs.begin(), info.clash_pairs.end());
  const Set contacts(info.contact_pairs.begin(), info.contact_pairs.end());
  const Set gaps(info.gap_pairs.begin(), info.gap_pairs.end());
  for (int test : {0, 1}) {
    SCOPED_TRACE(test == 0 ? "hard" : "clearance 0.1");
    EXPECT_EQ(by_verdict[test]["clash"], clashes);
    EXPECT_EQ(by_verdict[test]["contact"], contacts);
    EXPECT_EQ(by_verdict[test]["undecided"], Set{});
  }
  EXPECT_EQ(by_verdict[0]["clearance"], Set{});
  EXPECT_EQ(by_verdict[1]["clearance"], gaps);
}

}  // namespace
}  // namespace interfere::scene
