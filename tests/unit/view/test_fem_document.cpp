// Two deforming parts over load steps as a viewer document (issue #25, include/interfere/view/
// fem_document.h). Two boxes, B moving toward A by 0.125 per step: the steps' clash results come from
// the clash query itself, and the document is checked against the analytic motion (positions, the
// onset steps, the intersection curve's length, where the regions lie), not against its own code.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "interfere/mesh/generate.h"
#include "interfere/query/model.h"
#include "interfere/view/fem_document.h"
#include "interfere/view/json.h"

namespace interfere::view {
namespace {

// A = [0,1]^3; B = [1.5,2.3] x [0.2,0.8]^2 at step 0 (2 x 2 x 2 cells each; none of B's node planes
// reaches A's face x = 1 in the steps used), moving by -0.125 in x per step: the gap 0.5 closes at
// step 4 (faces touch: a contact), B crosses A's face x = 1 from step 5 (a clash).
constexpr double kV = 0.125;
const Vec3 kBLo{1.5, 0.2, 0.2}, kBHi{2.3, 0.8, 0.8};

struct Series {
  TriMesh a = make_box({0, 0, 0}, {1, 1, 1}, 2);
  TriMesh b = make_box(kBLo, kBHi, 2);
  FemSeriesInput input;
};

std::vector<Vec3> shifted(const TriMesh& m, double dx) {
  std::vector<Vec3> p = m.positions;
  for (Vec3& v : p) v.x += dx;
  return p;
}

// (Fills `s` in place: the bodies point at its meshes.)
void make_series(Series& s, std::size_t steps) {
  s.input.bodies[0] = {.id = "A", .name = "left", .path = "model.msh/left", .surface = &s.a};
  s.input.bodies[1] = {.id = "B", .name = "right", .path = "model.msh/right", .surface = &s.b};
  for (std::size_t t = 0; t < s.b.num_triangles(); ++t) s.input.bodies[1].source_ids.push_back(9001 + static_cast<std::int64_t>(t));
  s.input.num_steps = steps;
  for (std::size_t k = 0; k < steps; ++k) {
    const std::vector<Vec3> pb = shifted(s.b, -kV * static_cast<double>(k));
    TriMesh moved = s.b;
    moved.positions = pb;
    const ClashResult r = clash(make_model(s.a), make_model(moved), {.containment = true});
    FemSeriesStep step = fem_series_step(k, 0.5 * static_cast<double>(k), r);
    step.positions = {s.a.positions, pb};
    s.input.verdict = std::max(s.input.verdict, r.verdict);
    s.input.steps.push_back(std::move(step));
  }
}

const ViewMesh& drawn(const Document& doc, std::size_t body, std::size_t frame) {
  const ViewBody& b = doc.bodies[body];
  return doc.meshes[b.frame_meshes.empty() ? b.mesh : b.frame_meshes[frame]];
}

double polyline_length(const std::vector<Vec3>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += distance(p[i], p[i - 1]);
  return l;
}

bool box_touches(const Vec3& lo, const Vec3& hi, const std::array<Vec3, 3>& tri, double eps) {
  for (std::size_t k = 0; k < 3; ++k) {
    const double mn = std::min({tri[0][k], tri[1][k], tri[2][k]}), mx = std::max({tri[0][k], tri[1][k], tri[2][k]});
    if (mx < lo[k] - eps || mn > hi[k] + eps) return false;
  }
  return true;
}

TEST(FemSeriesDocument, FramesBodiesAndRowsFollowTheMotion) {
  constexpr std::size_t kSteps = 10;
  Series s;
  make_series(s, kSteps);
  const Document doc = fem_series_document(std::move(s.input));
  EXPECT_EQ(doc.verdict, "clash");
  // Frames: one per step, labelled with step and time, verdicts from the analytic onsets.
  ASSERT_EQ(doc.frames.labels.size(), kSteps);
  ASSERT_EQ(doc.frames.times.size(), kSteps);
  ASSERT_EQ(doc.frames.verdicts.size(), kSteps);
  EXPECT_EQ(doc.frames.labels[3], "step 3 (time 1.5)");
  for (std::size_t k = 0; k < kSteps; ++k) {
    EXPECT_EQ(doc.frames.times[k], 0.5 * static_cast<double>(k));
    EXPECT_EQ(doc.frames.verdicts[k], k < 4 ? "clear" : k == 4 ? "contact" : "clash") << k;
  }
  // Bodies: A at rest, B shifted by -0.125 k at frame k; the surfaces' triangles every frame.
  ASSERT_EQ(doc.bodies.size(), 2u);
  EXPECT_EQ(doc.bodies[0].name, "left");
  EXPECT_EQ(doc.bodies[1].path, "model.msh/right");
  ASSERT_EQ(doc.bodies[1].frame_meshes.size(), kSteps);
  std::set<std::uint32_t> b_meshes(doc.bodies[1].frame_meshes.begin(), doc.bodies[1].frame_meshes.end());
  EXPECT_EQ(b_meshes.size(), kSteps);  // a new shape every step
  for (std::size_t k = 0; k < kSteps; ++k) {
    const ViewMesh& ma = drawn(doc, 0, k);
    const ViewMesh& mb = drawn(doc, 1, k);
    EXPECT_EQ(ma.mesh.positions, s.a.positions) << k;
    EXPECT_EQ(ma.mesh.triangles, s.a.triangles) << k;
    EXPECT_EQ(mb.mesh.positions, shifted(s.b, -kV * static_cast<double>(k))) << k;
    EXPECT_EQ(mb.mesh.triangles, s.b.triangles) << k;
    EXPECT_TRUE(ma.source_ids.empty());
    ASSERT_EQ(mb.source_ids.size(), s.b.num_triangles());
    EXPECT_EQ(mb.source_ids[5], 9006);
    // Clash flags: none before the contact; after it, only on triangles that reach the other box.
    for (std::size_t side = 0; side < 2; ++side) {
      const ViewMesh& m = side == 0 ? ma : mb;
      if (k < 4) {
        EXPECT_TRUE(m.clash_flags.empty()) << k;
        continue;
      }
      ASSERT_EQ(m.clash_flags.size(), m.mesh.num_triangles()) << k;
      const double dx = -kV * static_cast<double>(k);
      const Vec3 lo = side == 0 ? Vec3{kBLo.x + dx, kBLo.y, kBLo.z} : Vec3{0, 0, 0};
      const Vec3 hi = side == 0 ? Vec3{kBHi.x + dx, kBHi.y, kBHi.z} : Vec3{1, 1, 1};
      std::size_t flagged = 0;
      for (std::size_t t = 0; t < m.mesh.num_triangles(); ++t) {
        if (!m.clash_flags[t]) continue;
        ++flagged;
        const Tri& tri = m.mesh.triangles[t];
        EXPECT_TRUE(box_touches(lo, hi, {m.mesh.positions[tri[0]], m.mesh.positions[tri[1]], m.mesh.positions[tri[2]]}, 1e-12))
            << "step " << k << " side " << side << " triangle " << t;
      }
      EXPECT_GT(flagged, 0u) << k;
    }
  }
  // A draws one mesh while its flags are unchanged: the clear steps 0-3 share one.
  ASSERT_EQ(doc.bodies[0].frame_meshes.size(), kSteps);
  EXPECT_EQ(doc.bodies[0].frame_meshes[0], doc.bodies[0].frame_meshes[3]);
  EXPECT_NE(doc.bodies[0].frame_meshes[3], doc.bodies[0].frame_meshes[4]);

  // Rows: steps 4 (contact) to 9 (clash), each in its own frame.
  ASSERT_EQ(doc.clashes.size(), 6u);
  for (std::size_t i = 0; i < doc.clashes.size(); ++i) {
    const ViewClash& c = doc.clashes[i];
    const std::size_t k = 4 + i;
    EXPECT_EQ(c.id, "step " + std::to_string(k));
    EXPECT_EQ(c.frames, std::vector<std::uint32_t>{static_cast<std::uint32_t>(k)});
    EXPECT_EQ(c.verdict, k == 4 ? "contact" : "clash");
    EXPECT_EQ(c.status, k <= 5 ? "new" : "active") << k;
    EXPECT_EQ(c.kind, k == 4 ? "touch" : "crossing");
    EXPECT_EQ(c.body_a, 0u);
    EXPECT_EQ(c.body_b, 1u);
    // The overlap of the two boxes at step k: x in [1.5 - 0.125 k, 1] (a face at k = 4), y, z in [0.2, 0.8].
    const Vec3 lo{kBLo.x - kV * static_cast<double>(k), 0.2, 0.2}, hi{1, 0.8, 0.8};
    // Where the surfaces meet: the square x = 1, y, z in [0.2, 0.8] (touching, then crossing).
    const Vec3 meet_lo{1, 0.2, 0.2}, meet_hi{1, 0.8, 0.8};
    // The intersection curve (clash steps): B's 0.6 x 0.6 section through A's face x = 1.
    if (k >= 5) {
      double total = 0;
      for (const auto& curve : c.curves) {
        total += polyline_length(curve);
        for (const Vec3& p : curve) {
          EXPECT_NEAR(p.x, 1.0, 1e-12);
          EXPECT_TRUE(p.y >= 0.2 - 1e-12 && p.y <= 0.8 + 1e-12 && p.z >= 0.2 - 1e-12 && p.z <= 0.8 + 1e-12);
        }
      }
      EXPECT_NEAR(total, 2.4, 1e-9) << k;
    }
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_GE(c.point[a], c.box_min[a]);
      EXPECT_LE(c.point[a], c.box_max[a]);
      EXPECT_LE(c.box_min[a], meet_lo[a] + 1e-12);  // the region box holds where the surfaces meet
      EXPECT_GE(c.box_max[a], meet_hi[a] - 1e-12);
    }
    // The region mesh: world triangles, each reaching the overlap box.
    ASSERT_GE(c.region_mesh, 0);
    const ViewMesh& region = doc.meshes[static_cast<std::size_t>(c.region_mesh)];
    ASSERT_GT(region.mesh.num_triangles(), 0u);
    for (const Tri& t : region.mesh.triangles)
      EXPECT_TRUE(box_touches(lo, hi, {region.mesh.positions[t[0]], region.mesh.positions[t[1]], region.mesh.positions[t[2]]}, 1e-12));
    // As many triangles as the two bodies flag in that frame.
    std::size_t flagged = 0;
    for (std::size_t side = 0; side < 2; ++side)
      for (const std::uint8_t f : drawn(doc, side, k).clash_flags) flagged += f;
    EXPECT_EQ(region.mesh.num_triangles(), flagged) << k;
  }
  // The document is a valid viewer document (the JSON writer checks every index and length).
  const auto json = document_json(doc);
  EXPECT_TRUE(json) << json.error().message();
}

TEST(FemSeriesDocument, ABodyThatNeverChangesDrawsOneMesh) {
  Series s;
  make_series(s, 4);  // clear steps only
  const Document doc = fem_series_document(std::move(s.input), {.title = "gap closing"});
  EXPECT_EQ(doc.title, "gap closing");
  EXPECT_EQ(doc.verdict, "clear");
  EXPECT_TRUE(doc.clashes.empty());
  EXPECT_TRUE(doc.bodies[0].frame_meshes.empty());
  EXPECT_EQ(doc.meshes[doc.bodies[0].mesh].mesh.positions, s.a.positions);
  EXPECT_EQ(doc.bodies[1].frame_meshes.size(), 4u);
  EXPECT_EQ(doc.meshes.size(), 5u);  // A once, B per step
}

TEST(FemSeriesDocument, CheckedStepsOfALongerSeriesAndBadPositions) {
  Series s;
  make_series(s, 6);
  s.input.num_steps = 20;
  s.input.steps[2].positions[1].pop_back();  // a wrong length: not drawn, said
  const Document doc = fem_series_document(std::move(s.input));
  EXPECT_EQ(doc.title, "interfere clash: FE series, 20 steps");
  ASSERT_EQ(doc.notes.size(), 2u);
  EXPECT_NE(doc.notes[0].find("6 of the series' 20 steps checked"), std::string::npos) << doc.notes[0];
  EXPECT_NE(doc.notes[1].find("step 2 (time 1)"), std::string::npos) << doc.notes[1];
  EXPECT_EQ(drawn(doc, 1, 2).mesh.num_triangles(), 0u);
  EXPECT_EQ(drawn(doc, 1, 3).mesh.num_triangles(), s.b.num_triangles());
}

}  // namespace
}  // namespace interfere::view
