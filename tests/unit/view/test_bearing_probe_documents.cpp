// The bearing and probe viewer documents (issue #25): what they draw is checked against an
// independent method — the posed meshes through the mesh clash engine (bearing), the probe's
// cylinders recomputed from the path poses (probe) — not against the data they were built from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "interfere/bearing/simulation.h"
#include "interfere/probe/sweep.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"
#include "interfere/view/bearing_document.h"
#include "interfere/view/mesh_document.h"
#include "interfere/view/probe_document.h"
#include "interfere/mesh/generate.h"

namespace interfere::view {
namespace {

bearing::SceneParams bearing_scene(double gap) {
  bearing::SceneParams p;
  p.pairs = 4, p.frames = 6, p.gap = gap, p.scar_fraction = 0.5;
  p.roller.radial_segments = 32, p.roller.height_segments = 31;
  return p;
}

bool meshes_cross(const Document& doc, std::uint32_t a, std::uint32_t b, std::size_t frame) {
  const ViewBody& ba = doc.bodies[a];
  const ViewBody& bb = doc.bodies[b];
  const Transform pa = ba.frame_poses.empty() ? ba.pose : ba.frame_poses[frame];
  const Transform pb = bb.frame_poses.empty() ? bb.pose : bb.frame_poses[frame];
  const Model ma = make_model(transformed(doc.meshes[ba.mesh].mesh, pa));
  const Model mb = make_model(transformed(doc.meshes[bb.mesh].mesh, pb));
  const ClashResult r = clash(ma, mb);
  return r.verdict == Verdict::clash;
}

TEST(BearingDocument, PreloadedPairsClashAsMeshesInEveryFrameTheyAreListed) {
  const bearing::SceneParams p = bearing_scene(-0.5);
  auto r = bearing::simulate(p);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  auto doc = bearing_document(p, *r);
  ASSERT_TRUE(doc.has_value()) << doc.error().message();
  ASSERT_EQ(doc->bodies.size(), 8u);
  ASSERT_EQ(doc->frames.labels.size(), 6u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(doc->bodies[2 * k].frame_poses.size(), 6u);
  std::size_t listed = 0;
  for (const ViewClash& c : doc->clashes) {
    ASSERT_EQ(c.verdict, "clash");
    for (std::uint32_t f : c.frames) {
      EXPECT_TRUE(meshes_cross(*doc, c.body_a, c.body_b, f)) << c.id << " frame " << f;
      ++listed;
    }
  }
  EXPECT_EQ(listed, 4u * 6u);  // a preload of 0.5 presses every roller into its partner
}

TEST(BearingDocument, SeparatedPairsListNothingAndTheirMeshesDoNotCross) {
  const bearing::SceneParams p = bearing_scene(2.0);  // (a tilt of 1 degree moves the ends of a 40 mm roller by up to 0.7 mm)
  auto r = bearing::simulate(p);
  ASSERT_TRUE(r.has_value());
  auto doc = bearing_document(p, *r);
  ASSERT_TRUE(doc.has_value());
  EXPECT_TRUE(doc->clashes.empty());
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t f = 0; f < 6; ++f) EXPECT_FALSE(meshes_cross(*doc, 2 * k, 2 * k + 1, f));
  for (const std::string& v : doc->frames.verdicts) EXPECT_EQ(v, "clear");
}

TEST(BearingDocument, PartnerMeshLiesOnTheAnalyticCylinder) {
  const bearing::SceneParams p = bearing_scene(0);
  auto r = bearing::simulate(p);
  ASSERT_TRUE(r.has_value());
  auto doc = bearing_document(p, *r);
  ASSERT_TRUE(doc.has_value());
  for (std::size_t k = 0; k < 4; ++k) {
    const ViewBody& b = doc->bodies[2 * k + 1];
    // the partner's axis is vertical through its grid point (pairs on a square grid of pitch spacing)
    const double cx = static_cast<double>(k % 2) * r->spacing, cy = static_cast<double>(k / 2) * r->spacing;
    for (const Vec3& v : doc->meshes[b.mesh].mesh.positions) {
      const Vec3 w = b.pose.apply(v);
      const double radial = std::hypot(w.x - cx, w.y - cy);
      EXPECT_LE(radial, p.partner_radius + 1e-9);
      EXPECT_GE(w.z, 0.5 * p.roller.height - 0.5 * p.partner_height - 1e-9);
      EXPECT_LE(w.z, 0.5 * p.roller.height + 0.5 * p.partner_height + 1e-9);
    }
  }
}

TEST(BearingDocument, ResultWithoutRowsIsAnError) {
  const bearing::SceneParams p = bearing_scene(0);
  auto r = bearing::simulate(p, false);
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(bearing_document(p, *r).has_value());
}

TEST(ProbeDocument, ProbeFramesPlaceTheTipAndAxisOfEveryPose) {
  TriMesh plate = make_box({-50, -50, -10}, {50, 50, 0});
  probe::ProbeShape shape;
  shape.radius = 2, shape.length = 20;
  probe::ProbePath path;
  path.joint_space = false;
  for (int i = 0; i < 5; ++i) {
    // descending onto the plate: the last two poses go into it
    path.poses.push_back({.tip = {static_cast<double>(i) * 5, 0, 6 - 3.0 * i}, .axis = {0, 0, -1}, .ref = {1, 0, 0}});
    path.lines.push_back(i + 2);
  }
  const probe::Workpiece w = probe::prepare_workpiece(plate, shape);
  probe::SweepRequest req;
  req.probe = shape;
  const probe::SweepResult res = probe::sweep(w, path, nullptr, req);
  auto doc = probe_document(plate, shape, path, res);
  ASSERT_TRUE(doc.has_value()) << doc.error().message();
  ASSERT_EQ(doc->bodies.size(), 2u);
  const ViewBody& pb = doc->bodies[1];
  ASSERT_EQ(pb.frame_poses.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    const Vec3 tip = pb.frame_poses[i].apply({0, 0, 0});
    EXPECT_NEAR(norm(tip - path.poses[i].tip), 0, 1e-12);
    const Vec3 axis = pb.frame_poses[i].rotate({0, 0, 1});
    EXPECT_NEAR(norm(axis - path.poses[i].axis), 0, 1e-12);
    // every probe vertex within the probe's cylinder recomputed from the pose
    for (const Vec3& v : doc->meshes[pb.mesh].mesh.positions) {
      const Vec3 p = pb.frame_poses[i].apply(v) - path.poses[i].tip;
      const double along = -dot(p, path.poses[i].axis);
      EXPECT_GE(along, -1e-9);
      EXPECT_LE(along, shape.length + 1e-9);
      EXPECT_LE(norm(p + path.poses[i].axis * along), shape.radius + 1e-9);
    }
  }
  // tips at z = 6, 3, 0, -3, -6 with radius 2: points 2 (touching), 3 and 4 collide
  ASSERT_FALSE(doc->clashes.empty());
  std::vector<std::uint32_t> listed;
  for (const ViewClash& c : doc->clashes)
    if (c.verdict == "clash") listed.insert(listed.end(), c.frames.begin(), c.frames.end());
  for (std::size_t i = 0; i < 5; ++i) {
    const bool expect = path.poses[i].tip.z <= 0;
    EXPECT_EQ(std::count(listed.begin(), listed.end(), i) == 1, expect) << i;
    EXPECT_EQ(doc->frames.verdicts[i] == "clash", expect) << i;
  }
  for (const ViewClash& c : doc->clashes) {
    ASSERT_GE(c.region_mesh, 0);
    // the region's triangles are plate triangles touching the probe's end face: on the plate's top
    for (const Vec3& v : doc->meshes[static_cast<std::size_t>(c.region_mesh)].mesh.positions) EXPECT_LE(v.z, 0);
  }
}

TEST(MeshDocument, LabelsBecomeFaceColoursAndUnlabelledTrianglesTheLayerColour) {
  MeshLayer l;
  l.id = "p", l.name = "part";
  l.mesh = make_box({0, 0, 0}, {1, 1, 1});
  l.labels.assign(l.mesh.num_triangles(), kNoLabel);
  l.labels[0] = 1;
  const Document d = meshes_document("t", {l}, {{"hole", label_color(0)}, {"slot", label_color(1)}});
  ASSERT_EQ(d.meshes.size(), 1u);
  ASSERT_EQ(d.legend.size(), 3u);
  EXPECT_EQ(d.meshes[0].face_colors[0], 1u);
  EXPECT_EQ(d.meshes[0].face_colors[1], 2u);
  EXPECT_EQ(d.legend[2].color, l.color);
  EXPECT_NE(label_color(3), label_color(12));
}

}  // namespace
}  // namespace interfere::view
