// Penetration depth maps in the FE series document (issue #26, item 3; view/fem_document.h,
// FemSeriesStep::depth -> ViewMesh::point_depth, the .pvd's point array penetration_depth): the
// depths given for a step are the drawn mesh's at that step, every other step's mesh carries zeros,
// and meshes are not shared across steps whose depths differ.
#include <gtest/gtest.h>

#include <string>

#include "interfere/mesh/generate.h"
#include "interfere/view/fem_document.h"

namespace interfere::view {
namespace {

const ViewMesh& drawn(const Document& doc, std::size_t body, std::size_t frame) {
  const ViewBody& b = doc.bodies[body];
  return doc.meshes[b.frame_meshes.empty() ? b.mesh : b.frame_meshes[frame]];
}

struct Fixture {
  TriMesh a = make_box({0, 0, 0}, {1, 1, 1}, 1);
  TriMesh b = make_box({2, 0, 0}, {3, 1, 1}, 1);
  FemSeriesInput input;
  Fixture(std::size_t steps) {
    input.bodies[0] = {.id = "A", .surface = &a};
    input.bodies[1] = {.id = "B", .surface = &b};
    input.num_steps = steps;
    for (std::size_t k = 0; k < steps; ++k) {
      FemSeriesStep s{.step = k, .time = static_cast<double>(k)};
      s.positions = {a.positions, b.positions};  // nothing moves: only the depths tell steps apart
      input.steps.push_back(std::move(s));
    }
  }
};

std::vector<double> ramp(std::size_t n, double scale) {
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = scale * static_cast<double>(i % 3);
  return d;
}

TEST(FemSeriesDocumentDepth, StepDepthsAreTheDrawnMeshesPointDepth) {
  Fixture f(4);
  const std::vector<double> da = ramp(f.a.num_vertices(), 0.25), db = ramp(f.b.num_vertices(), 0.5);
  f.input.steps[2].depth = {da, db};
  const Document doc = fem_series_document(f.input);
  ASSERT_EQ(doc.bodies.size(), 2u);
  for (std::size_t body = 0; body < 2; ++body) {
    const std::size_t nv = (body == 0 ? f.a : f.b).num_vertices();
    const std::vector<double> zeros(nv, 0.0);
    for (std::size_t k = 0; k < 4; ++k) {
      const ViewMesh& m = drawn(doc, body, k);
      EXPECT_EQ(m.point_depth, k == 2 ? (body == 0 ? da : db) : zeros) << body << " " << k;
    }
    // Steps 0 and 1 share a mesh; step 2 has its own; step 3 (zeros again) does not reuse step 2's.
    const ViewBody& vb = doc.bodies[body];
    ASSERT_EQ(vb.frame_meshes.size(), 4u);
    EXPECT_EQ(vb.frame_meshes[0], vb.frame_meshes[1]);
    EXPECT_NE(vb.frame_meshes[1], vb.frame_meshes[2]);
    EXPECT_NE(vb.frame_meshes[2], vb.frame_meshes[3]);
  }
}

TEST(FemSeriesDocumentDepth, NoDepthsNoArrayAndWrongLengthsAreNoted) {
  Fixture none(2);
  const Document plain = fem_series_document(none.input);
  for (std::size_t body = 0; body < 2; ++body)
    for (std::size_t k = 0; k < 2; ++k) EXPECT_TRUE(drawn(plain, body, k).point_depth.empty());

  Fixture bad(2);
  bad.input.steps[0].depth = {ramp(bad.a.num_vertices(), 1.0), std::vector<double>(3, 1.0)};
  const Document doc = fem_series_document(bad.input);
  EXPECT_EQ(drawn(doc, 0, 0).point_depth, ramp(bad.a.num_vertices(), 1.0));
  EXPECT_TRUE(drawn(doc, 1, 0).point_depth.empty());  // not drawn (NaN in the .pvd), not zeros
  EXPECT_EQ(drawn(doc, 1, 1).point_depth, std::vector<double>(bad.b.num_vertices(), 0.0));
  bool noted = false;
  for (const std::string& n : doc.notes) noted = noted || n.find("3 depths for") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace interfere::view
