// The simplifier's local frame (src/simplify/local_frame.h; issue #6, item 5 and "never a silently
// wrong answer"): meshes far from the origin or of extreme size are simplified as well as the same
// mesh at the origin and of unit size — before the frame, scales beyond 1e10 or below 1e-10 made
// every float cost inf or 0 (15x the error) and an offset of 1e8 sizes left garbage.
#include <gtest/gtest.h>

#include <cmath>

#include "interfere/mesh/generate.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace interfere {
namespace {

TriMesh mapped(const TriMesh& m, double scale_exp, Vec3 offset) {
  TriMesh out = m;
  for (Vec3& p : out.positions)
    p = {std::ldexp(p.x, int(scale_exp)) + offset.x, std::ldexp(p.y, int(scale_exp)) + offset.y,
         std::ldexp(p.z, int(scale_exp)) + offset.z};
  return out;
}

bool uses_frame(const SimplifyResult& r) { return !r.phases.empty() && r.phases.front().first == "local frame"; }

// Power-of-two scales are exact both ways: the result is the unit-size result, scaled, bit for bit.
TEST(LocalFrame, ExtremeScalesGiveTheUnitScaleResultScaled) {
  const TriMesh s = make_sphere({.target_triangles = 6000, .bump_amplitude = 0.04});
  const SimplifyOptions o{.ratio = 0.1};
  const auto ref = simplify(s, o);
  ASSERT_TRUE(ref.has_value());
  EXPECT_FALSE(uses_frame(*ref));  // an ordinary mesh is simplified as it is
  for (int e : {-900, -600, -70, 70, 600, 900}) {
    SCOPED_TRACE(e);
    const auto r = simplify(mapped(s, e, {}), o);
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(uses_frame(*r));
    EXPECT_EQ(r->mesh.triangles, ref->mesh.triangles);
    EXPECT_EQ(mapped(ref->mesh, e, {}).positions, r->mesh.positions);
    EXPECT_EQ(r->hausdorff, std::ldexp(ref->hausdorff, e));
    EXPECT_EQ(r->error_bound, std::ldexp(ref->error_bound, e));
    EXPECT_EQ(r->bbox_diagonal, std::ldexp(ref->bbox_diagonal, e));
    EXPECT_TRUE(std::isfinite(r->error_bound));
    EXPECT_EQ(count_self_intersections(mapped(r->mesh, -e, {})), 0u);
  }
}

// A part 2^30 sizes from the origin: simplified like the same part at the origin, then moved.
TEST(LocalFrame, FarFromTheOriginGivesTheResultAtTheOriginMoved) {
  const double c = std::ldexp(1.0, 30);
  // Positions on the grid of the far part (p + c - c is exact), so both inputs are the same shape.
  TriMesh s = make_sphere({.target_triangles = 6000, .bump_amplitude = 0.04});
  for (Vec3& p : s.positions) p = {(p.x + c) - c, (p.y - c) + c, p.z};
  const SimplifyOptions o{.ratio = 0.1};
  const auto ref = simplify(s, o);
  const TriMesh far = mapped(s, 0, {c, -c, 0});
  const auto r = simplify(far, o);
  ASSERT_TRUE(ref.has_value() && r.has_value());
  EXPECT_TRUE(uses_frame(*r));
  EXPECT_EQ(r->mesh.triangles, ref->mesh.triangles);
  EXPECT_EQ(mapped(ref->mesh, 0, {c, -c, 0}).positions, r->mesh.positions);
  EXPECT_GE(r->error_bound, ref->error_bound);  // plus the rounding of the moved vertices
  EXPECT_LE(r->error_bound, ref->error_bound + 1e-6);
  EXPECT_EQ(count_self_intersections(r->mesh), 0u);
  // The error is measured against the far input itself and stays that of the part at the origin.
  const double h = hausdorff(far, r->mesh, false).symmetric();
  EXPECT_NEAR(h, ref->hausdorff, 1e-6);
}

// Kept vertices map back exactly: locked feature faces stay bit-identical far away and tiny.
TEST(LocalFrame, LockedFeaturesStayBitIdenticalInTheFrame) {
  const TriMesh base = make_sphere({.target_triangles = 6000, .bump_amplitude = 0.04});
  for (const TriMesh& s : {mapped(base, 0, {3e7, 1e-3, -7e6}), mapped(base, -800, {})}) {
    std::vector<std::uint32_t> faces(s.num_triangles());
    std::vector<std::array<Vec3, 3>> kept;
    const double top = s.bounds().hi.z, bottom = s.bounds().lo.z;
    for (std::size_t t = 0; t < s.num_triangles(); ++t) {
      const auto k = s.corners(t);
      faces[t] = (k[0].z + k[1].z + k[2].z) / 3 > bottom + 0.9 * (top - bottom) ? 1 : 0;
      if (faces[t]) kept.push_back(k);
    }
    const auto r = simplify(s, {.ratio = 0.2, .face_ids = faces, .feature_faces = {1},
                                .feature_mode = FeatureMode::lock});
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(uses_frame(*r));
    std::vector<std::array<Vec3, 3>> out;
    for (std::size_t t = 0; t < r->mesh.num_triangles(); ++t)
      if (r->face_ids[t] == 1) out.push_back(r->mesh.corners(t));
    EXPECT_EQ(out, kept);  // same triangles, same corners, same order
    EXPECT_LE(r->hausdorff_features, 1e-12 * r->bbox_diagonal);  // closest-point rounding only
  }
}

}  // namespace
}  // namespace interfere
