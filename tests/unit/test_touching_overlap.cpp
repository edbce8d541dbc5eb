// ClashResult::touching_overlap (query/touching_overlap.cpp): closed parts whose surfaces only touch
// are told apart exactly into face contacts and overlapping solids, on configurations whose answer
// is known by construction.
#include <gtest/gtest.h>

#include <cmath>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"

namespace interfere {
namespace {

ClashResult touch_only(const TriMesh& a, const TriMesh& b) {
  const ClashResult r = clash(make_model(a), make_model(b));
  EXPECT_EQ(r.cross_pairs, 0u);
  EXPECT_GT(r.touch_pairs, 0u);
  return r;
}

TriMesh reversed(TriMesh m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

TriMesh joined(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const auto base = static_cast<std::uint32_t>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (const Tri& t : b.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return m;
}

TEST(TouchingOverlap, FaceContactsAreNotOverlaps) {
  const TriMesh a = make_box({0, 0, 0}, {1, 1, 1}, 3);
  EXPECT_FALSE(touch_only(a, make_box({1, 0, 0}, {2, 1, 1}, 2)).touching_overlap);        // side by side
  EXPECT_FALSE(touch_only(a, make_box({0.2, 0.3, 1}, {0.7, 0.6, 1.5}, 2)).touching_overlap);  // resting on top
  EXPECT_FALSE(touch_only(a, make_box({1, 1, 0}, {2, 2, 1}, 2)).touching_overlap);        // along an edge
  // A part filling a cavity of the other exactly: the common faces have opposite outward sides.
  const TriMesh hollow = joined(make_box({-1, -1, -1}, {2, 2, 2}, 2), reversed(make_box({0, 0, 0}, {1, 1, 1}, 3)));
  EXPECT_FALSE(touch_only(a, hollow).touching_overlap);
}

TEST(TouchingOverlap, TiltedFaceContactsAreNotOverlaps) {
  // Stacked boxes turned by the same rotation (0.7 rad about (1, 2, 3)): the common face's
  // triangles are the same doubles, but their rounded centroids fall off it by an ulp, and on the
  // wrong side for some: they must not pass for points inside the other box.
  const Vec3 k = Vec3{1, 2, 3} / std::sqrt(14.0);
  const double c = std::cos(0.7), s = std::sin(0.7);
  Transform r;
  const double K[3][3] = {{0, -k.z, k.y}, {k.z, 0, -k.x}, {-k.y, k.x, 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double kk = 0;
      for (int l = 0; l < 3; ++l) kk += K[i][l] * K[l][j];
      r.r[i][j] = (i == j ? 1.0 : 0.0) + s * K[i][j] + (1 - c) * kk;
    }
  r.t = {0.3, -0.2, 0.1};
  for (int n : {1, 3}) {
    const TriMesh a = transformed(make_box({0, 0, 0}, {1, 1, 1}, n), r);
    const TriMesh b = transformed(make_box({0, 0, 1}, {1, 1, 2}, n), r);
    const ClashResult contact = clash(make_model(a), make_model(b));
    EXPECT_FALSE(contact.touching_overlap) << n;
    EXPECT_EQ(contact.cross_pairs, 0u) << n;
    EXPECT_TRUE(clash(make_model(a), make_model(a)).touching_overlap) << n;  // the same box twice
  }
}

TEST(TouchingOverlap, CoincidentFacesOfOverlappingSolidsAreOverlaps) {
  const TriMesh a = make_box({0, 0, 0}, {1, 1, 1}, 3);
  // Shifted along a face: half of each inside the other, every intersection on common faces.
  const ClashResult shifted = touch_only(a, make_box({0.5, 0, 0}, {1.5, 1, 1}, 3));
  EXPECT_TRUE(shifted.touching_overlap);
  EXPECT_TRUE(shifted.interference());
  // Seated inside on the bottom face, and in a corner (three common faces).
  EXPECT_TRUE(touch_only(a, make_box({0.2, 0.2, 0}, {0.6, 0.6, 0.5}, 2)).touching_overlap);
  EXPECT_TRUE(touch_only(make_box({0, 0, 0}, {0.4, 0.4, 0.4}, 1), a).touching_overlap);
  // The same part twice (an instance placed twice), with the same or another tessellation.
  EXPECT_TRUE(touch_only(a, a).touching_overlap);
  EXPECT_TRUE(touch_only(a, make_box({0, 0, 0}, {1, 1, 1}, 5)).touching_overlap);
  const TriMesh s = make_sphere({.target_triangles = 800});
  EXPECT_TRUE(touch_only(s, s).touching_overlap);
  // Crossing surfaces are not "touching": the flag stays off (the crossing pairs say it).
  const ClashResult crossing = clash(make_model(a), make_model(make_box({0.5, 0.5, 0.5}, {2, 2, 2}, 2)));
  EXPECT_GT(crossing.cross_pairs, 0u);
  EXPECT_FALSE(crossing.touching_overlap);
  // Disabled with the containment test.
  EXPECT_FALSE(clash(make_model(a), make_model(a), {.containment = false}).touching_overlap);
}

}  // namespace
}  // namespace interfere
