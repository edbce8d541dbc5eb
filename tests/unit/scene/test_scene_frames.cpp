// The table frames x body pairs and the reference configuration (issue #26, items 2 and 4): a
// block B bonded to A (sharing A's top face), a block C that a deformation moves toward A's side
// by 0.25 per frame from a gap of 0.5 — clear at frames 0 and 1, touching at frame 2, sunk 0.25 at
// frame 3. Expectations from that geometry alone: which pairs have rows in which frames, each
// row's verdict, C's first (clashing) frame, B's contacts designed (touching before any load),
// C's contact new, C's clash a new penetration; and a clash that existed before the load is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>

#include "interfere/mesh/generate.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/report.h"
#include "interfere/view/scene_document.h"

namespace interfere::scene {
namespace {

Body block(const std::string& id, const Vec3& lo, const Vec3& hi) {
  Body b;
  b.id = b.name = id;
  b.path = "/" + id;
  b.mesh = std::make_shared<const TriMesh>(make_box(lo, hi, 2));
  return b;
}

// Frames moving body `i` by (dx, 0, 0) * k at frame k (a deformation: new local positions).
void add_frames(Scene& s, std::uint32_t i, double dx, int count) {
  for (int k = 0; k < count; ++k) {
    Frame f;
    f.label = "step " + std::to_string(k);
    f.time = k;
    auto p = std::make_shared<std::vector<Vec3>>(s.bodies[i].mesh->positions);
    for (Vec3& v : *p) v.x += dx * k;
    f.shapes.push_back({i, std::move(p)});
    s.frames.push_back(std::move(f));
  }
}

Scene bonded_and_approaching() {
  Scene s;
  s.bodies.push_back(block("A", {0, 0, 0}, {1, 1, 1}));
  s.bodies.push_back(block("B", {0, 0, 1}, {1, 1, 2}));         // bonded on A's top face
  s.bodies.push_back(block("C", {-1.5, 0.25, 0.25}, {-0.5, 0.75, 0.75}));  // 0.5 left of A, clear of B
  add_frames(s, 2, 0.25, 4);
  return s;
}

ClashTest hard() {
  ClashTest t;
  t.name = "hard";
  return t;
}

const FramePairRow* row(const SceneClashResult& r, std::uint32_t frame, const std::string& a, const std::string& b,
                        const Scene& s) {
  for (const FramePairRow& x : r.frame_pairs)
    if (x.frame == frame && s.bodies[x.a].id == a && s.bodies[x.b].id == b) return &x;
  return nullptr;
}

TEST(SceneFrames, TableOfFramesAndPairsFollowsTheGeometry) {
  const Scene s = bonded_and_approaching();
  const SceneClashResult r = clash_scene(s, {hard()});
  ASSERT_EQ(r.frames.size(), 4u);
  for (std::uint32_t f = 0; f < 4; ++f) {
    const FramePairRow* ab = row(r, f, "A", "B", s);
    ASSERT_NE(ab, nullptr) << f;
    EXPECT_EQ(ab->verdict, Verdict::contact) << f;
    EXPECT_EQ(ab->min_distance, 0.0);
    const FramePairRow* ac = row(r, f, "A", "C", s);
    if (f < 2) {
      EXPECT_EQ(ac, nullptr) << f;  // gap 0.5, 0.25: no finding in a hard test
    } else {
      ASSERT_NE(ac, nullptr) << f;
      EXPECT_EQ(ac->verdict, f == 2 ? Verdict::contact : Verdict::clash) << f;
      if (f == 3) {
        EXPECT_GT(ac->max_depth, 0.0);
        EXPECT_LE(ac->max_depth, 0.25 + 1e-12);       // sampled: at most the true depth 0.25
        EXPECT_GE(ac->max_depth_bound, 0.25 - 1e-12);  // bound: at least it
      }
    }
    EXPECT_EQ(row(r, f, "B", "C", s), nullptr) << f;  // C stays below z = 0.75
  }
  // Rows sorted by frame, then body ids.
  for (std::size_t i = 1; i < r.frame_pairs.size(); ++i)
    EXPECT_LE(r.frame_pairs[i - 1].frame, r.frame_pairs[i].frame);
  // Pairs: first frames.
  bool seen_ac = false;
  for (const PairSummary& p : r.pairs) {
    const std::string a = s.bodies[p.a].id, b = s.bodies[p.b].id;
    if (a == "A" && b == "B") {
      EXPECT_EQ(p.first_frame, 0);
      EXPECT_EQ(p.first_clash_frame, -1);
      EXPECT_EQ(p.reference_verdict, Verdict::contact);
    }
    if (a == "A" && b == "C") {
      seen_ac = true;
      EXPECT_EQ(p.first_frame, 2);
      EXPECT_EQ(p.first_clash_frame, 3);
      EXPECT_EQ(p.reference_verdict, Verdict::clear);
    }
  }
  EXPECT_TRUE(seen_ac);
}

TEST(SceneFrames, DesignedContactsAreToldFromNewContactsAndPenetrations) {
  const Scene s = bonded_and_approaching();
  const SceneClashResult r = clash_scene(s, {hard()});
  ASSERT_TRUE(r.reference_checked);
  std::size_t designed = 0, fresh = 0, penetrations = 0;
  for (const SceneClash& c : r.clashes) {
    const std::string a = s.bodies[c.a].id, b = s.bodies[c.b].id;
    if (c.verdict == Verdict::contact) {
      EXPECT_EQ(c.designed, a == "A" && b == "B") << a << "-" << b;
      ++(c.designed ? designed : fresh);
    }
    if (c.verdict == Verdict::clash) {
      EXPECT_EQ(a + b, "AC");
      ++penetrations;
    }
  }
  EXPECT_GE(designed, 1u);
  EXPECT_GE(fresh, 1u);
  EXPECT_EQ(penetrations, 1u);
  EXPECT_EQ(r.designed_contact_count, designed);
  EXPECT_EQ(r.new_contact_count, fresh);
  EXPECT_EQ(r.new_penetration_count, penetrations);
  // The reference pass does not count as a frame, nor its candidates.
  const SceneClashResult without = clash_scene(s, {hard()}, {.reference = false});
  EXPECT_FALSE(without.reference_checked);
  EXPECT_EQ(without.candidate_pairs, r.candidate_pairs);
  EXPECT_EQ(without.frames.size(), r.frames.size());
  EXPECT_EQ(without.designed_contact_count + without.new_contact_count, 0u);
  for (const SceneClash& c : without.clashes) EXPECT_FALSE(c.designed);
}

TEST(SceneFrames, AClashBeforeTheLoadIsNotANewPenetration) {
  Scene s;
  s.bodies.push_back(block("A", {0, 0, 0}, {1, 1, 1}));
  s.bodies.push_back(block("B", {0.5, 0.25, 0.25}, {1.5, 0.75, 0.75}));  // sunk 0.5 into A before any load
  add_frames(s, 1, 0.125, 2);                                            // still sunk 0.375 at frame 1
  const SceneClashResult r = clash_scene(s, {hard()});
  EXPECT_EQ(r.verdict, Verdict::clash);
  EXPECT_EQ(r.new_penetration_count, 0u);
  ASSERT_EQ(r.reference_pairs.size(), 1u);
  EXPECT_EQ(r.reference_pairs[0].verdict, Verdict::clash);
}

TEST(SceneFrames, ReportAndCsvCarryTheTable) {
  const Scene s = bonded_and_approaching();
  const std::vector<ClashTest> tests{hard()};
  const SceneClashResult r = clash_scene(s, tests);
  const auto j = nlohmann::json::parse(report_json(s, tests, r, {}));
  ASSERT_EQ(j["frame_pairs"].size(), r.frame_pairs.size());
  EXPECT_EQ(j["summary"]["new_penetrations"], 1);
  EXPECT_TRUE(j["summary"]["reference_checked"].get<bool>());
  for (const auto& p : j["pairs"])
    if (p["body_b"]["id"] == "C") EXPECT_EQ(p["first_clash_frame"], 3);
  const std::string csv = frame_pairs_table_csv(s, tests, r);
  std::size_t lines = 0;
  for (char ch : csv) lines += ch == '\n';
  EXPECT_EQ(lines, r.frame_pairs.size() + 1);
  EXPECT_NE(csv.find("3,step 3,3,hard,A,C,clash,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("0,step 0,0,hard,A,B,contact,0,1,0,0,0,0,0,contact\n"), std::string::npos) << csv;
}

// Depth of point p inside the box [lo, hi] (distance to its surface), or -1 when p is not strictly
// inside: the analytic oracle of the depth maps below.
double box_depth(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  if (!(p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y && p.z > lo.z && p.z < hi.z)) return -1;
  return std::min({p.x - lo.x, hi.x - p.x, p.y - lo.y, hi.y - p.y, p.z - lo.z, hi.z - p.z});
}

TEST(SceneFrames, DepthMapsMatchTheBoxesAnalyticDepths) {
  const Scene s = bonded_and_approaching();
  SceneClashOptions o;
  o.depth_maps = true;
  const SceneClashResult r = clash_scene(s, {hard()}, o);
  ASSERT_EQ(r.depth_maps.size(), 1u);  // A-C at frame 3 only (A-B touch: no vertex inside)
  const PairDepthMap& m = r.depth_maps[0];
  EXPECT_EQ(m.frame, 3u);
  EXPECT_EQ(s.bodies[m.a].id + s.bodies[m.b].id, "AC");
  // Frame 3: C is [-0.75, 0.25] x [0.25, 0.75]^2.
  const Vec3 a_lo{0, 0, 0}, a_hi{1, 1, 1}, c_lo{-0.75, 0.25, 0.25}, c_hi{0.25, 0.75, 0.75};
  const auto check = [&](std::uint32_t body, const VertexDepths& vd, const std::vector<Vec3>& pos, const Vec3& lo,
                         const Vec3& hi) {
    EXPECT_EQ(vd.undecided, 0u);
    std::size_t listed = 0;
    for (std::uint32_t v = 0; v < pos.size(); ++v) {
      const double expect = box_depth(pos[v], lo, hi);
      const auto it = std::find(vd.vertices.begin(), vd.vertices.end(), v);
      if (expect < 0) {
        EXPECT_EQ(it, vd.vertices.end()) << s.bodies[body].id << " vertex " << v;
        continue;
      }
      ASSERT_NE(it, vd.vertices.end()) << s.bodies[body].id << " vertex " << v;
      EXPECT_NEAR(vd.depths[it - vd.vertices.begin()], expect, 1e-12);
      ++listed;
    }
    EXPECT_EQ(listed, vd.vertices.size());
    EXPECT_GT(listed, 0u);
  };
  std::vector<Vec3> c_pos = s.bodies[2].mesh->positions;
  for (Vec3& p : c_pos) p.x += 0.75;
  check(m.a, m.a_in_b, s.bodies[0].mesh->positions, c_lo, c_hi);
  check(m.b, m.b_in_a, c_pos, a_lo, a_hi);
  ASSERT_TRUE(m.has_deepest);
  EXPECT_NEAR(m.deepest.depth, 0.25, 1e-12);
  const Vec3 p = m.deepest.point;
  EXPECT_NEAR(m.deepest.body == 0 ? box_depth(p, c_lo, c_hi) : box_depth(p, a_lo, a_hi), 0.25, 1e-12);
  EXPECT_EQ(m.deepest.node, m.deepest.vertex);  // (no vertex ids: the index)
  // The clash and the frame's pair row carry it.
  bool carried = false;
  for (const SceneClash& c : r.clashes)
    if (c.verdict == Verdict::clash) carried = c.has_deepest && c.deepest.depth == m.deepest.depth && c.deepest.frame == 3;
  EXPECT_TRUE(carried);
  EXPECT_TRUE(row(r, 3, "A", "C", s)->has_deepest);
  // Drawn: the frame-3 meshes of A and C carry the depths, other frames none or zeros.
  const view::Document doc = view::scene_document(s, {hard()}, r, {});
  for (std::uint32_t body : {0u, 2u}) {
    const view::ViewBody& vb = doc.bodies[body];
    ASSERT_EQ(vb.frame_meshes.size(), 4u);
    const view::ViewMesh& vm = doc.meshes[vb.frame_meshes[3]];
    ASSERT_EQ(vm.point_depth.size(), vm.mesh.num_vertices());
    const VertexDepths& vd = body == 0 ? m.a_in_b : m.b_in_a;
    for (std::size_t i = 0; i < vd.vertices.size(); ++i) EXPECT_EQ(vm.point_depth[vd.vertices[i]], vd.depths[i]);
    for (std::uint32_t f = 0; f < 3; ++f) {
      const view::ViewMesh& other = doc.meshes[vb.frame_meshes[f]];
      for (double d : other.point_depth) EXPECT_EQ(d, 0.0);
    }
  }
  // clash_region: on C's frame-3 mesh (C deforms: a mesh per frame) exactly the clash's triangles
  // carry its index (scene::SceneClash order = the document's clashes), the others -1. (A does
  // not deform: its one mesh carries the regions of every frame, the first clash listing each.)
  std::size_t clashes = 0;
  for (std::size_t i = 0; i < r.clashes.size(); ++i) {
    const SceneClash& c = r.clashes[i];
    if (c.verdict != Verdict::clash) continue;
    ++clashes;
    ASSERT_EQ(s.bodies[c.b].id, "C");
    const view::ViewMesh& vm = doc.meshes[doc.bodies[c.b].frame_meshes[3]];
    ASSERT_EQ(vm.clash_region.size(), vm.mesh.num_triangles());
    for (std::uint32_t t : c.triangles_b) EXPECT_EQ(vm.clash_region[t], static_cast<std::int32_t>(i)) << t;
    std::size_t marked = 0, other = 0;
    for (std::int32_t g : vm.clash_region) marked += g == static_cast<std::int32_t>(i), other += g >= 0 && g != static_cast<std::int32_t>(i);
    EXPECT_EQ(marked, c.triangles_b.size());
    EXPECT_EQ(other, 0u);
  }
  EXPECT_EQ(clashes, 1u);
}

}  // namespace
}  // namespace interfere::scene
