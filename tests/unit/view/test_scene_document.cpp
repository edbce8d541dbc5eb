// A scene clash run as a viewer document (issue #25, include/interfere/view/scene_document.h): a
// generated assembly with real clashes through the scene engine, checked against the scene and the
// engine's result (not against the document code's own arithmetic).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <map>
#include <set>

#include "interfere/scene/generate.h"
#include "interfere/scene/report.h"
#include "interfere/view/json.h"
#include "interfere/view/scene_document.h"

namespace interfere::view {
namespace {

using namespace interfere::scene;

struct ClashRun {
  Scene scene;
  std::vector<ClashTest> tests;
  SceneClashResult result;
};

ClashRun assembly_run() {
  AssemblyGenOptions o;
  o.bodies = 21;  // three joints
  o.segments = 24;
  o.clashes = 1;
  o.gaps = 1;
  ClashRun r;
  r.scene = generate_assembly(o);
  ClashTest hard;
  hard.name = "hard";
  ClashTest clear;
  clear.name = "clearance";
  clear.mode = ClashMode::clearance;
  clear.clearance = 0.1;
  r.tests = {hard, clear};
  r.result = clash_scene(r.scene, r.tests);
  return r;
}

const ClashRun& shared_run() {
  static const ClashRun r = assembly_run();
  return r;
}

TEST(SceneDocument, BodiesAndSharedMeshes) {
  const ClashRun& r = shared_run();
  const Document d = scene_document(r.scene, r.tests, r.result);
  ASSERT_EQ(d.bodies.size(), r.scene.bodies.size());
  std::map<const TriMesh*, std::uint32_t> seen;
  for (std::size_t i = 0; i < d.bodies.size(); ++i) {
    const Body& b = r.scene.bodies[i];
    const ViewBody& v = d.bodies[i];
    EXPECT_EQ(v.id, b.id);
    EXPECT_EQ(v.name, b.name);
    EXPECT_EQ(v.path, b.path);
    EXPECT_EQ(v.tags, b.tags);
    EXPECT_EQ(v.pose, b.pose);
    EXPECT_EQ(v.color, body_color(i));
    EXPECT_TRUE(v.frame_poses.empty());
    // Instances share one ViewMesh, and it is the body's geometry.
    const auto [it, fresh] = seen.emplace(b.mesh.get(), v.mesh);
    EXPECT_EQ(it->second, v.mesh) << b.id;
    if (fresh) {
      EXPECT_EQ(d.meshes[v.mesh].mesh.positions, b.mesh->positions);
      EXPECT_EQ(d.meshes[v.mesh].mesh.triangles, b.mesh->triangles);
      EXPECT_TRUE(d.meshes[v.mesh].clash_flags.empty());  // shared: no flags without flag_instances
    }
  }
  EXPECT_EQ(seen.size(), 5u);  // plate, bolt, washer, nut, bracket
  EXPECT_EQ(d.units, "mm");
  EXPECT_EQ(d.verdict, "clash");
  EXPECT_TRUE(d.frames.labels.empty());
}

TEST(SceneDocument, OneRowPerClashWithItsRegionAtFullResolution) {
  const ClashRun& r = shared_run();
  ASSERT_FALSE(r.result.clashes.empty());
  const Document d = scene_document(r.scene, r.tests, r.result);
  ASSERT_EQ(d.clashes.size(), r.result.clashes.size());
  std::size_t regions = 0, clashes = 0, clearances = 0;
  for (std::size_t i = 0; i < d.clashes.size(); ++i) {
    const SceneClash& c = r.result.clashes[i];
    const ViewClash& v = d.clashes[i];
    SCOPED_TRACE(c.id);
    EXPECT_EQ(v.id, c.id);
    EXPECT_EQ(v.verdict, verdict_name(c.verdict));
    EXPECT_EQ(v.status, "new");
    EXPECT_EQ(v.kind, c.kind);
    EXPECT_EQ(v.body_a, c.a);
    EXPECT_EQ(v.body_b, c.b);
    EXPECT_EQ(v.point, c.point);
    EXPECT_EQ(v.curves.size(), c.curves.size());
    clashes += c.verdict == Verdict::clash;
    if (c.verdict == Verdict::clearance) {
      ++clearances;
      EXPECT_TRUE(v.has_witness);
      EXPECT_EQ(v.witness_a, c.witness_a);
      EXPECT_EQ(v.distance, c.distance);
      EXPECT_LT(v.depth, 0);
    }
    if (c.verdict == Verdict::clash && c.kind == "crossing") {
      EXPECT_EQ(v.depth, c.depth);
      EXPECT_EQ(v.depth_bound, c.depth_bound);
      EXPECT_GT(v.depth_bound, 0);
    }
    if (c.triangles_a.empty() && c.triangles_b.empty()) {
      EXPECT_EQ(v.region_mesh, -1);
      continue;
    }
    ASSERT_GE(v.region_mesh, 0);
    ++regions;
    const ViewMesh& region = d.meshes[static_cast<std::size_t>(v.region_mesh)];
    ASSERT_EQ(region.mesh.num_triangles(), c.triangles_a.size() + c.triangles_b.size());
    // Triangle by triangle: a's in triangles_a order, then b's, each the body's triangle in the world.
    std::size_t k = 0;
    for (const auto& [body, tris] : {std::pair{c.a, &c.triangles_a}, std::pair{c.b, &c.triangles_b}}) {
      const Body& b = r.scene.bodies[body];
      for (const std::uint32_t t : *tris) {
        const auto local = b.mesh->corners(t);
        const auto world = region.mesh.corners(k++);
        for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(world[j], b.pose.apply(local[j]));
      }
    }
    EXPECT_EQ(region.decimation_error, 0.0);
  }
  EXPECT_GT(clashes, 0u);
  EXPECT_GT(regions, 0u);
  EXPECT_GT(clearances, 0u);
  // The whole document is valid JSON of the contract.
  const Expected<std::string> text = document_json(d);
  ASSERT_TRUE(text) << text.error().message();
  const nlohmann::json j = nlohmann::json::parse(*text);
  EXPECT_EQ(j["clashes"].size(), r.result.clashes.size());
  EXPECT_EQ(j["bodies"].size(), r.scene.bodies.size());
}

TEST(SceneDocument, FlagInstancesGivesClashingBodiesTheirOwnFlaggedMesh) {
  const ClashRun& r = shared_run();
  SceneDocumentOptions o;
  o.flag_instances = true;
  const Document d = scene_document(r.scene, r.tests, r.result, o);
  // The clashes' triangles per body, from the engine's result.
  std::map<std::uint32_t, std::set<std::uint32_t>> expected;
  for (const SceneClash& c : r.result.clashes) {
    expected[c.a].insert(c.triangles_a.begin(), c.triangles_a.end());
    expected[c.b].insert(c.triangles_b.begin(), c.triangles_b.end());
  }
  std::size_t checked = 0;
  for (const auto& [body, tris] : expected) {
    if (tris.empty()) continue;
    const ViewMesh& m = d.meshes[d.bodies[body].mesh];
    ASSERT_EQ(m.clash_flags.size(), m.mesh.num_triangles()) << r.scene.bodies[body].id;
    std::set<std::uint32_t> flagged;
    for (std::uint32_t t = 0; t < m.clash_flags.size(); ++t)
      if (m.clash_flags[t]) flagged.insert(t);
    EXPECT_EQ(flagged, tris) << r.scene.bodies[body].id;
    ++checked;
  }
  EXPECT_GT(checked, 0u);
  // Each drawn mesh with flags is drawn by one body only.
  std::map<std::uint32_t, int> users;
  for (const ViewBody& b : d.bodies) ++users[b.mesh];
  for (const auto& [m, n] : users)
    if (!d.meshes[m].clash_flags.empty()) EXPECT_EQ(n, 1) << m;
  EXPECT_TRUE(document_json(d));
}

TEST(SceneDocument, ResolvedBaselineClashIsARow) {
  const ClashRun& r = shared_run();
  ASSERT_GE(r.result.clashes.size(), 2u);
  const std::string baseline = report_json(r.scene, r.tests, r.result, ReportContext{});
  SceneClashResult now = r.result;
  const SceneClash gone = now.clashes.front();
  now.clashes.erase(now.clashes.begin());
  ASSERT_TRUE(apply_baseline(now, baseline, "baseline.json"));
  ASSERT_EQ(now.resolved.size(), 1u);
  const Document d = scene_document(r.scene, r.tests, now);
  ASSERT_EQ(d.clashes.size(), now.clashes.size() + 1);
  for (std::size_t i = 0; i + 1 < d.clashes.size(); ++i) EXPECT_EQ(d.clashes[i].status, "active");
  const ViewClash& v = d.clashes.back();
  EXPECT_EQ(v.id, gone.id);
  EXPECT_EQ(v.status, "resolved");
  EXPECT_EQ(v.verdict, verdict_name(gone.verdict));
  EXPECT_EQ(v.body_a, gone.a);
  EXPECT_EQ(v.body_b, gone.b);
  EXPECT_EQ(v.region_mesh, -1);
  EXPECT_NEAR(v.point.x, gone.point.x, 1e-9);
  EXPECT_TRUE(document_json(d));
  SceneDocumentOptions o;
  o.resolved = false;
  EXPECT_EQ(scene_document(r.scene, r.tests, now, o).clashes.size(), now.clashes.size());
}

TEST(SceneDocument, MotionFramesAndPoses) {
  MovingSceneGenOptions o;
  o.bodies = 60, o.frames = 6, o.segments = 24, o.near_fraction = 0.2;
  const Scene s = generate_moving_scene(o);
  ClashTest hard;
  hard.name = "hard";
  const SceneClashResult result = clash_scene(s, {hard});
  const Document d = scene_document(s, {hard}, result);
  ASSERT_EQ(d.frames.labels.size(), 6u);
  ASSERT_EQ(d.frames.verdicts.size(), 6u);
  ASSERT_EQ(result.frames.size(), 6u);
  for (const FrameRow& row : result.frames) {
    EXPECT_EQ(d.frames.labels[row.frame], s.frames[row.frame].label.empty() ? "frame " + std::to_string(row.frame)
                                                                            : s.frames[row.frame].label);
    EXPECT_EQ(d.frames.verdicts[row.frame], verdict_name(row.verdict));
  }
  // Every body moves in every frame of this scene: its pose per frame is the frame's.
  for (std::size_t f = 0; f < s.frames.size(); ++f)
    for (const Frame::Pose& p : s.frames[f].poses) {
      ASSERT_EQ(d.bodies[p.body].frame_poses.size(), 6u);
      EXPECT_EQ(d.bodies[p.body].frame_poses[f], p.pose);
    }
  // A clash's region is drawn where the bodies are in its first frame.
  for (std::size_t i = 0; i < result.clashes.size(); ++i) {
    const SceneClash& c = result.clashes[i];
    if (d.clashes[i].region_mesh < 0 || c.triangles_a.empty()) continue;
    ASSERT_FALSE(c.frames.empty());
    const Transform& pose = d.bodies[c.a].frame_poses[c.frames.front()];
    const TriMesh& region = d.meshes[static_cast<std::size_t>(d.clashes[i].region_mesh)].mesh;
    EXPECT_EQ(region.corners(0)[0], pose.apply(s.bodies[c.a].mesh->corners(c.triangles_a.front())[0]));
  }
  const Expected<std::string> text = document_json(d);
  ASSERT_TRUE(text) << text.error().message();
}

TEST(SceneDocument, BodyWithoutGeometryIsNamedInANote) {
  Scene s;
  Body b;
  b.id = "empty-part";
  s.bodies.push_back(b);
  const Document d = scene_document(s, {}, SceneClashResult{});
  ASSERT_EQ(d.bodies.size(), 1u);
  EXPECT_EQ(d.meshes[d.bodies[0].mesh].mesh.num_triangles(), 0u);
  ASSERT_FALSE(d.notes.empty());
  EXPECT_NE(d.notes[0].find("empty-part"), std::string::npos);
  EXPECT_TRUE(document_json(d));
}

}  // namespace
}  // namespace interfere::view
