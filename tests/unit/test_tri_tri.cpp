// np/tri_tri.h: hand-built configurations with exact expected classification and endpoint features,
// invariance under swapping the triangles, cyclic corner permutations and orientation reversal,
// and random comparisons of the double tests (Möller, Guigue–Devillers) and the exact test against
// a brute-force oracle (every edge of each triangle against the other triangle).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "interfere/core/predicates.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"

namespace interfere {
namespace {

using Tri = std::array<Vec3, 3>;
using EndFeatures = std::pair<Feature, Feature>;  // (on A, on B) for one segment endpoint

const Feature kFace{Feature::face, 0};
Feature vtx(int i) {
  return {Feature::vertex, static_cast<std::uint8_t>(i)};
}
Feature edg(int i) {
  return {Feature::edge, static_cast<std::uint8_t>(i)};
}

std::string str(const Feature& f) {
  const char* n[] = {"v", "e", "f"};
  return std::string(n[f.type]) + (f.type == Feature::face ? "" : std::to_string(f.index));
}

std::string str(const Tri& a, const Tri& b) {
  std::string s;
  char buf[96];
  for (const Tri* t : {&a, &b}) {
    s += t == &a ? "A:" : " B:";
    for (const Vec3& v : *t) {
      std::snprintf(buf, sizeof buf, " (%.17g %.17g %.17g)", v.x, v.y, v.z);
      s += buf;
    }
  }
  return s;
}

/// Corner permutations: new corner i is old corner perm[i] (3 rotations x 2 orientations).
constexpr int kPerms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

Tri permute(const Tri& t, const int* perm) {
  return {t[perm[0]], t[perm[1]], t[perm[2]]};
}

/// A feature in the permuted triangle, expressed with the original corner indices.
Feature unpermute(const Feature& f, const int* perm) {
  if (f.type == Feature::vertex) return vtx(perm[f.index]);
  if (f.type == Feature::edge) {
    const int p = perm[f.index], q = perm[(f.index + 1) % 3];
    return edg((p + 1) % 3 == q ? p : q);
  }
  return f;
}

bool same_ends(std::vector<EndFeatures> x, std::vector<EndFeatures> y) {
  auto key = [](const EndFeatures& e) {
    return std::make_pair(e.first.type * 3 + e.first.index, e.second.type * 3 + e.second.index);
  };
  auto less = [&](const EndFeatures& l, const EndFeatures& r) { return key(l) < key(r); };
  std::sort(x.begin(), x.end(), less);
  std::sort(y.begin(), y.end(), less);
  return x == y;
}

std::vector<EndFeatures> ends_of(const TriTriResult& r) {
  return {{r.feature_a[0], r.feature_b[0]}, {r.feature_a[1], r.feature_b[1]}};
}

/// Checks kind (and, for cross, the endpoint features as a set) of (a, b) under all corner
/// permutations of both triangles and under swapping them.
void check_all_variants(const Tri& a, const Tri& b, ContactKind kind,
                        const std::vector<EndFeatures>& ends = {}) {
  for (const auto& pa : kPerms)
    for (const auto& pb : kPerms) {
      const Tri ta = permute(a, pa), tb = permute(b, pb);
      const TriTriResult r = tri_tri_exact(ta, tb);
      const TriTriResult s = tri_tri_exact(tb, ta);
      ASSERT_EQ(static_cast<int>(r.kind), static_cast<int>(kind)) << str(ta, tb);
      ASSERT_EQ(static_cast<int>(s.kind), static_cast<int>(kind)) << str(tb, ta);
      ASSERT_EQ(tri_tri_exact_intersects(ta, tb), kind != ContactKind::none) << str(ta, tb);
      ASSERT_EQ(tri_tri_exact_intersects(tb, ta), kind != ContactKind::none) << str(tb, ta);
      ASSERT_EQ(static_cast<int>(tri_tri_exact_kind(ta, tb)), static_cast<int>(kind))
          << str(ta, tb);
      if (kind != ContactKind::cross) continue;
      // Endpoints: bit-identical when only the roles are swapped (constructions are canonical),
      // and equal up to rounding under corner permutations.
      if (&pa == &kPerms[0] && &pb == &kPerms[0]) {
        const bool same = (r.segment[0] == s.segment[0] && r.segment[1] == s.segment[1]) ||
                          (r.segment[0] == s.segment[1] && r.segment[1] == s.segment[0]);
        ASSERT_TRUE(same) << str(ta, tb);
      }
      const TriTriResult ref = tri_tri_exact(a, b);
      for (const Vec3& p : r.segment) {
        const double d = std::min(distance(p, ref.segment[0]), distance(p, ref.segment[1]));
        ASSERT_LT(d, 1e-12 * (1 + norm(p))) << str(ta, tb);
      }
      if (ends.empty()) continue;
      std::vector<EndFeatures> got_r, got_s;
      for (int k = 0; k < 2; ++k) {
        got_r.emplace_back(unpermute(r.feature_a[k], pa), unpermute(r.feature_b[k], pb));
        got_s.emplace_back(unpermute(s.feature_b[k], pa), unpermute(s.feature_a[k], pb));
      }
      ASSERT_TRUE(same_ends(got_r, ends))
          << str(ta, tb) << "\ngot " << str(got_r[0].first) << "/" << str(got_r[0].second) << ", "
          << str(got_r[1].first) << "/" << str(got_r[1].second);
      ASSERT_TRUE(same_ends(got_s, ends)) << str(tb, ta);
    }
}

void expect_segment(const TriTriResult& r, const Vec3& p, const Vec3& q) {
  const bool straight = r.segment[0] == p && r.segment[1] == q;
  const bool swapped = r.segment[0] == q && r.segment[1] == p;
  EXPECT_TRUE(straight || swapped)
      << r.segment[0].x << " " << r.segment[0].y << " " << r.segment[0].z << " / " << r.segment[1].x
      << " " << r.segment[1].y << " " << r.segment[1].z;
}

// A lies in z = 0: edge 0 on y = 0, edge 1 on x + y = 4, edge 2 on x = 0.
const Tri kA{Vec3{0, 0, 0}, Vec3{4, 0, 0}, Vec3{0, 4, 0}};

TEST(TriTriExact, CrossingLikeChainLinks) {
  // B in the plane y = 1 enters A through A's edge 2 and leaves B through B's edge 1.
  const Tri b{Vec3{-2, 1, -1}, Vec3{2, 1, -1}, Vec3{2, 1, 2}};
  check_all_variants(kA, b, ContactKind::cross, {{edg(2), kFace}, {kFace, edg(1)}});
  expect_segment(tri_tri_exact(kA, b), Vec3{0, 1, 0}, Vec3{2, 1, 0});
}

TEST(TriTriExact, BPiercesAWithTwoEdges) {
  const Tri b{Vec3{0, 1, -1}, Vec3{2, 1, -1}, Vec3{1, 1, 1}};
  check_all_variants(kA, b, ContactKind::cross, {{kFace, edg(2)}, {kFace, edg(1)}});
  expect_segment(tri_tri_exact(kA, b), Vec3{0.5, 1, 0}, Vec3{1.5, 1, 0});
}

TEST(TriTriExact, EdgeThroughInteriorAndCornerInPlane) {
  // B's edge 0 pierces A's interior at (1,1,0); B's corner 2 lies in A's plane outside A, so the
  // segment ends on A's edge 1 in B's interior.
  const Tri b{Vec3{1, 1, -1}, Vec3{1, 1, 1}, Vec3{5, 1, 0}};
  check_all_variants(kA, b, ContactKind::cross, {{kFace, edg(0)}, {edg(1), kFace}});
  expect_segment(tri_tri_exact(kA, b), Vec3{1, 1, 0}, Vec3{3, 1, 0});
}

TEST(TriTriExact, SegmentEndingOnBothEdgesAndOnACorner) {
  // One end where A's edge 1 meets B's edge 0 (both boundaries), the other at B's corner 2 inside
  // A.
  const Tri b{Vec3{3, 1, -1}, Vec3{3, 1, 1}, Vec3{1, 1, 0}};
  check_all_variants(kA, b, ContactKind::cross, {{edg(1), edg(0)}, {kFace, vtx(2)}});
  expect_segment(tri_tri_exact(kA, b), Vec3{3, 1, 0}, Vec3{1, 1, 0});
}

TEST(TriTriExact, SegmentStartingAtACornerOfA) {
  // B in the plane x = y passes through A's corner 0; A's corner 0 lies in B's interior.
  const Tri b{Vec3{-1, -1, -1}, Vec3{3, 3, -1}, Vec3{1, 1, 2}};
  check_all_variants(kA, b, ContactKind::cross, {{vtx(0), kFace}, {edg(1), kFace}});
  expect_segment(tri_tri_exact(kA, b), Vec3{0, 0, 0}, Vec3{2, 2, 0});
}

TEST(TriTriExact, TinyPenetrationIsCrossTinyGapIsNone) {
  const double e = 0x1p-60;
  check_all_variants(kA, Tri{Vec3{1, 1, -e}, Vec3{2, 1, 3}, Vec3{1, 2, 3}}, ContactKind::cross,
                     {{kFace, edg(0)}, {kFace, edg(2)}});
  check_all_variants(kA, Tri{Vec3{1, 1, e}, Vec3{2, 1, 3}, Vec3{1, 2, 3}}, ContactKind::none);
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{2, 1, 3}, Vec3{1, 2, 3}}, ContactKind::touch);
}

TEST(TriTriExact, Disjoint) {
  check_all_variants(kA, Tri{Vec3{8, 1, -1}, Vec3{12, 1, -1}, Vec3{12, 1, 2}}, ContactKind::none);
  // A's plane cuts B and B's plane cuts A, but the intervals on the common line are disjoint.
  check_all_variants(kA, Tri{Vec3{3, 3, -1}, Vec3{3, 3, 1}, Vec3{5, 5, 0}}, ContactKind::none);
  // Parallel planes.
  check_all_variants(kA, Tri{Vec3{0, 0, 1}, Vec3{4, 0, 1}, Vec3{0, 4, 1}}, ContactKind::none);
}

TEST(TriTriExact, Coplanar) {
  // Separated, with overlapping boxes.
  check_all_variants(kA, Tri{Vec3{2.5, 2.5, 0}, Vec3{4, 4, 0}, Vec3{1.5, 4, 0}}, ContactKind::none);
  // Overlap, containment, identical.
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{5, 1, 0}, Vec3{1, 5, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{2, 1, 0}, Vec3{1, 2, 0}}, ContactKind::touch);
  check_all_variants(kA, kA, ContactKind::touch);
  // Sharing an edge (the mesh neighbour across edge 1), a partial edge, or a corner only.
  check_all_variants(kA, Tri{Vec3{4, 0, 0}, Vec3{4, 4, 0}, Vec3{0, 4, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{2, 0, 0}, Vec3{6, 0, 0}, Vec3{3, -2, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{4, 0, 0}, Vec3{6, 0, 0}, Vec3{5, 1, 0}}, ContactKind::touch);
  // Star of David: no corner inside the other, edges cross.
  check_all_variants(Tri{Vec3{0, 0, 0}, Vec3{6, 0, 0}, Vec3{3, 6, 0}},
                     Tri{Vec3{0, 4, 0}, Vec3{3, -2, 0}, Vec3{6, 4, 0}}, ContactKind::touch);
  // Tilted plane, so that no projection is trivial.
  auto lift = [](double x, double y) { return Vec3{x, y, 2 * x - 3 * y + 1}; };
  check_all_variants(Tri{lift(0, 0), lift(4, 0), lift(0, 4)},
                     Tri{lift(2, 2), lift(3, 3), lift(2, 5)}, ContactKind::touch);
  check_all_variants(Tri{lift(0, 0), lift(4, 0), lift(0, 4)},
                     Tri{lift(2.5, 2), lift(3, 3), lift(2, 5)}, ContactKind::none);
}

TEST(TriTriExact, BoundaryContactsAreTouch) {
  // Edge on edge (skew edges crossing at (2,0,0)); both planes are cut, the intervals meet in a
  // point.
  check_all_variants(kA, Tri{Vec3{2, -1, 1}, Vec3{2, 1, -1}, Vec3{2, -3, 1}}, ContactKind::touch);
  // Corner on face, corner on corner, corner on edge.
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{2, 1, 3}, Vec3{1, 2, 3}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{0, 0, 0}, Vec3{-1, 0, 2}, Vec3{0, -1, 2}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{2, 0, 0}, Vec3{2, -1, 2}, Vec3{3, -1, 2}}, ContactKind::touch);
  // Edge lying in the other's interior; edge lying across the other's boundary.
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{2, 1, 0}, Vec3{1.5, 1, 3}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{-1, 1, 0}, Vec3{2, 1, 0}, Vec3{1.5, 1, -3}}, ContactKind::touch);
  // Mesh neighbours sharing edge 0, folded up or down; sharing a corner only.
  check_all_variants(kA, Tri{Vec3{4, 0, 0}, Vec3{0, 0, 0}, Vec3{2, -2, 1}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{0, 0, 0}, Vec3{4, 0, 0}, Vec3{2, 2, -3}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{0, 4, 0}, Vec3{-2, 5, 1}, Vec3{-1, 6, -2}}, ContactKind::touch);
}

TEST(TriTriExact, DegenerateTriangles) {
  // Segments (collinear corners, or a repeated corner) and points against A.
  check_all_variants(kA, Tri{Vec3{1, 1, -1}, Vec3{1, 1, 1}, Vec3{1, 1, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{1, 1, -1}, Vec3{1, 1, 1}, Vec3{1, 1, 1}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{1, 1, 1}, Vec3{1, 1, 2}, Vec3{1, 1, 3}}, ContactKind::none);
  check_all_variants(kA, Tri{Vec3{3, 3, -1}, Vec3{3, 3, 1}, Vec3{3, 3, 0}}, ContactKind::none);
  check_all_variants(kA, Tri{Vec3{-1, 1, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{-3, 1, 0}, Vec3{-1, 1, 0}, Vec3{-2, 1, 0}}, ContactKind::none);
  check_all_variants(kA, Tri{Vec3{1, 1, 0}, Vec3{1, 1, 0}, Vec3{1, 1, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{2, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 0, 0}}, ContactKind::touch);
  check_all_variants(kA, Tri{Vec3{1, 1, 1}, Vec3{1, 1, 1}, Vec3{1, 1, 1}}, ContactKind::none);
  check_all_variants(kA, Tri{Vec3{3, 3, 0}, Vec3{3, 3, 0}, Vec3{3, 3, 0}}, ContactKind::none);
  // Degenerate against degenerate.
  const Tri s{Vec3{0, 0, 0}, Vec3{2, 2, 0}, Vec3{1, 1, 0}};
  check_all_variants(s, Tri{Vec3{0, 2, 0}, Vec3{2, 0, 0}, Vec3{2, 0, 0}}, ContactKind::touch);
  check_all_variants(s, Tri{Vec3{0, 2, 1}, Vec3{2, 0, 1}, Vec3{1, 1, 1}}, ContactKind::none);
  check_all_variants(s, Tri{Vec3{1, 1, 0}, Vec3{3, 3, 0}, Vec3{3, 3, 0}}, ContactKind::touch);
  check_all_variants(s, Tri{Vec3{3, 3, 0}, Vec3{4, 4, 0}, Vec3{5, 5, 0}}, ContactKind::none);
  check_all_variants(s, Tri{Vec3{2, 2, 0}, Vec3{2, 2, 0}, Vec3{2, 2, 0}}, ContactKind::touch);
  check_all_variants(s, Tri{Vec3{2, 2, 1e-300}, Vec3{2, 2, 1e-300}, Vec3{2, 2, 1e-300}},
                     ContactKind::none);
  // Parallel, coplanar, not collinear.
  check_all_variants(s, Tri{Vec3{0, 1, 0}, Vec3{2, 3, 0}, Vec3{1, 2, 0}}, ContactKind::none);
}

// ---- random comparisons ----

/// Closed segment vs closed non-coplanar triangle, exact (independent of tri_tri code paths).
bool segment_hits_triangle(const Vec3& p, const Vec3& q, const Tri& t) {
  const int sp = orient3d(t[0], t[1], t[2], p), sq = orient3d(t[0], t[1], t[2], q);
  if (sp == sq) return false;  // same side, or both in the plane (excluded by the callers)
  const int e0 = orient3d(p, q, t[0], t[1]), e1 = orient3d(p, q, t[1], t[2]),
            e2 = orient3d(p, q, t[2], t[0]);
  return !((e0 > 0 || e1 > 0 || e2 > 0) && (e0 < 0 || e1 < 0 || e2 < 0));
}

/// Brute force for non-coplanar, non-degenerate pairs: they meet iff an edge of one meets the
/// other.
bool brute_force_intersects(const Tri& a, const Tri& b) {
  for (int i = 0; i < 3; ++i) {
    if (segment_hits_triangle(a[i], a[(i + 1) % 3], b)) return true;
    if (segment_hits_triangle(b[i], b[(i + 1) % 3], a)) return true;
  }
  return false;
}

Tri random_tri(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 c = Vec3{0.3, -0.2, 0.7} + Vec3{u(rng), u(rng), u(rng)} * (0.5 * spread);
  Tri t;
  for (Vec3& v : t) v = c + Vec3{u(rng), u(rng), u(rng)} * spread;
  return t;
}

TEST(TriTriDouble, MollerAndGuigueDevillersAgreeWithBruteForceOnGenericInput) {
  std::mt19937_64 rng(21);
  int hits = 0, misses = 0;
  for (int i = 0; i < 30000; ++i) {
    const Tri a = random_tri(rng, 0.6), b = random_tri(rng, 0.6);
    const bool expected = brute_force_intersects(a, b);
    ASSERT_EQ(tri_tri_moller(a, b), expected) << str(a, b);
    ASSERT_EQ(tri_tri_guigue_devillers(a, b), expected) << str(a, b);
    ASSERT_EQ(tri_tri_exact_intersects(a, b), expected) << str(a, b);
    ASSERT_EQ(tri_tri_exact(a, b).kind != ContactKind::none, expected) << str(a, b);
    hits += expected;
    misses += !expected;
  }
  EXPECT_GT(hits, 3000);
  EXPECT_GT(misses, 3000);
}

TEST(TriTriDouble, CoplanarGenericInput) {
  // Coplanar in exact arithmetic (z = 0): the double tests' coplanar branches.
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    Tri a, b;
    for (Vec3& v : a) v = {u(rng), u(rng), 0.0};
    for (Vec3& v : b) v = {u(rng) + 0.8, u(rng), 0.0};
    const bool expected = tri_tri_exact_intersects(a, b);
    ASSERT_EQ(tri_tri_moller(a, b), expected) << str(a, b);
    ASSERT_EQ(tri_tri_guigue_devillers(a, b), expected) << str(a, b);
    hits += expected;
  }
  EXPECT_GT(hits, 500);
  EXPECT_LT(hits, 4500);
}

TEST(TriTriExact, CrossSegmentsLieOnBothTriangles) {
  std::mt19937_64 rng(23);
  int crosses = 0;
  for (int i = 0; i < 20000; ++i) {
    const double spread = i % 2 ? 0.6 : 1e-3;
    const Tri a = random_tri(rng, spread), b = random_tri(rng, spread);
    const TriTriResult r = tri_tri_exact(a, b);
    if (r.kind != ContactKind::cross) continue;
    ++crosses;
    const double size = spread;
    for (const Vec3& p : r.segment) {
      ASSERT_LT(distance(p, closest_point_on_triangle(p, a)), 1e-12 * size) << str(a, b);
      ASSERT_LT(distance(p, closest_point_on_triangle(p, b)), 1e-12 * size) << str(a, b);
    }
    // Ordered along nA x nB.
    const Vec3 dir = cross(cross(a[1] - a[0], a[2] - a[0]), cross(b[1] - b[0], b[2] - b[0]));
    ASSERT_GE(dot(r.segment[1] - r.segment[0], dir), 0) << str(a, b);
    // Features: a vertex end is that corner, an edge end lies on that edge's line, exactly up to
    // rounding of the construction.
    for (int k = 0; k < 2; ++k) {
      for (const auto& [f, t] : {std::pair{r.feature_a[k], &a}, std::pair{r.feature_b[k], &b}}) {
        if (f.type == Feature::vertex) {
          ASSERT_EQ(r.segment[k], (*t)[f.index]);
        } else if (f.type == Feature::edge) {
          const ClosestPoints c = segment_segment_closest(r.segment[k], r.segment[k], (*t)[f.index],
                                                          (*t)[(f.index + 1) % 3]);
          ASSERT_LT(c.distance, 1e-12 * size) << str(a, b);
        }
      }
    }
  }
  EXPECT_GT(crosses, 2000);
}

TEST(TriTriExact, SharedFeaturesGiveIdenticalPoints) {
  // Two triangles of A sharing an edge, crossed by B: both pairs report the point where the curve
  // crosses the shared edge with the edge feature and bit-identical coordinates.
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)}, q{u(rng), u(rng), u(rng)};
    const Tri a1{p, q, Vec3{u(rng), u(rng), u(rng)}};
    const Tri a2{q, p, Vec3{u(rng), u(rng), u(rng)}};  // edge 0 of both is {p, q}
    const Tri b = random_tri(rng, 1.0);
    const TriTriResult r1 = tri_tri_exact(a1, b), r2 = tri_tri_exact(a2, b);
    if (r1.kind != ContactKind::cross || r2.kind != ContactKind::cross) continue;
    for (int k1 = 0; k1 < 2; ++k1) {
      if (r1.feature_a[k1] != edg(0)) continue;
      bool found = false;
      for (int k2 = 0; k2 < 2; ++k2)
        if (r2.feature_a[k2] == edg(0) && r2.feature_b[k2] == r1.feature_b[k1]) {
          EXPECT_EQ(r1.segment[k1], r2.segment[k2]) << str(a1, b);
          found = true;
        }
      EXPECT_TRUE(found) << str(a1, b);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(TriTriExact, GridPairsAreInvariantUnderPermutationAndSwap) {
  std::mt19937_64 rng(25);
  std::uniform_int_distribution<int> d(0, 2);
  auto p = [&]() { return Vec3{double(d(rng)), double(d(rng)), double(d(rng))}; };
  int kinds[3] = {0, 0, 0};
  for (int i = 0; i < 1500; ++i) {
    const Tri a{p(), p(), p()}, b{p(), p(), p()};
    const TriTriResult r = tri_tri_exact(a, b);
    ++kinds[static_cast<int>(r.kind)];
    check_all_variants(a, b, r.kind,
                       r.kind == ContactKind::cross ? ends_of(r) : std::vector<EndFeatures>{});
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(kinds[0], 100);
  EXPECT_GT(kinds[1], 100);
  EXPECT_GT(kinds[2], 100);
}

}  // namespace
}  // namespace interfere
