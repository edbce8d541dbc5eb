// Static clash query (issue #2, item 5): every intersecting triangle pair, clash regions with their
// intersection curves, containment of closed parts, and clearance pairs.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/mesh/polyline.h"
#include "interfere/np/tri_tri.h"
#include "interfere/query/model.h"
#include "interfere/query/verdict.h"

namespace interfere {

enum class TriTest {
  exact,             ///< default: exact decision + cross/touch classification + segment
  moller,            ///< Möller 1997 in double (not robust; every hit reported as `cross`)
  guigue_devillers,  ///< Guigue–Devillers 2003 in double (not robust; every hit reported as `cross`)
};

enum class Broadphase {
  bvh,           ///< tree vs tree (default), parallel when threads > 1
  brute_force,   ///< all |A|·|B| pairs (strategy 1/2 of the paper's table)
  box_pretest,   ///< all pairs, triangle boxes compared first (strategy 3)
};

struct ClashRequest {
  TriTest test = TriTest::exact;
  Broadphase broadphase = Broadphase::bvh;
  bool parallel = true;         ///< use oneTBB (thread count from the caller's tbb::global_control)
  double clearance = 0.0;       ///< > 0: also report non-intersecting pairs closer than this
  bool regions = true;          ///< group pairs into regions with curves
  bool containment = true;      ///< test whether a closed part lies wholly inside the other (and touching_overlap)
  /// Where the parts' statistics (closedness) come from: unset, the models' own (Model::stats);
  /// set, called with 0 (A) or 1 (B) only when containment or touching overlap needs them (the
  /// scene engine computes statistics lazily: most body pairs never need them).
  std::function<const MeshStats&(int side)> stats;
};

struct TrianglePair {
  std::uint32_t a = 0, b = 0;  ///< triangle indices in A and B (input order)
  ContactKind kind = ContactKind::none;
  friend bool operator==(const TrianglePair&, const TrianglePair&) = default;
};

struct ClearancePair {
  std::uint32_t a = 0, b = 0;
  double distance = 0;  ///< > 0 and < clearance
  Vec3 point_a, point_b;
};

struct ClashRegion {
  std::vector<std::uint32_t> triangles_a;  ///< sorted
  std::vector<std::uint32_t> triangles_b;  ///< sorted
  std::size_t cross_pairs = 0, touch_pairs = 0;
  Aabb box;                                ///< of the region's triangles on both parts
  std::vector<Polyline> curves;            ///< intersection curves (crossing pairs' segments chained)
  double curve_length = 0;
};

enum class Containment {
  none,            ///< neither closed part lies inside the other (or surfaces intersect)
  a_inside_b,      ///< A, or one of A's connected components, lies inside the closed B
  b_inside_a,      ///< B, or one of B's connected components, lies inside the closed A
  not_checked,     ///< a part is open (see warnings) or the check was disabled
};
const char* containment_name(Containment c);

struct ClashResult {
  std::vector<TrianglePair> pairs;        ///< sorted by (a, b)
  std::vector<ClashRegion> regions;       ///< sorted by smallest triangle of A, then of B
  std::vector<ClearancePair> clearance;   ///< sorted by (a, b); disjoint from `pairs`
  Containment containment = Containment::not_checked;
  std::size_t cross_pairs = 0, touch_pairs = 0;
  /// The surfaces only touch (touch pairs, no crossing pair) and both parts are closed, yet their
  /// interiors overlap: faces coincide while the solids interpenetrate (two blocks shifted along a
  /// face, a part seated inside another on a common face). Decided exactly (common faces by their
  /// outward sides, a point of one surface off the other's and inside it by ray parity); checked
  /// with `containment`. Cost: about 0.7x the clash itself where fine meshes share large faces
  /// (two 270k-triangle boxes stacked: 95 vs 55 ms on 2 cores), nothing when surfaces cross.
  bool touching_overlap = false;
  std::size_t candidate_pairs = 0;        ///< box-overlapping pairs handed to the triangle test
  std::vector<std::string> warnings;
  /// The verdict model (query/verdict.h): `clash` (crossing pairs, containment, touching_overlap),
  /// `contact` (touch pairs only, the solids' interiors disjoint), `clearance` (clearance pairs
  /// only), `clear`, or `undecided` when inside/outside mattered and could not be decided (an open
  /// part with containment requested, every ray direction degenerate): never clear then.
  /// `verdict_reasons` says why for undecided. Without `containment` in the request, touching
  /// parts are a contact and apart parts clear (the caller chose not to check solids).
  Verdict verdict = Verdict::clear;
  std::vector<std::string> verdict_reasons;
  /// The surfaces meet (any pair, touch included) or one part lies inside the other; see `verdict`
  /// for clash versus contact.
  bool interference() const {
    return !pairs.empty() || containment == Containment::a_inside_b ||
           containment == Containment::b_inside_a;
  }
};

ClashResult clash(const Model& a, const Model& b, const ClashRequest& request = {});

/// Whether p lies inside the closed part `solid` (exact ray parity, as the containment test): 1
/// inside, 0 outside, -1 undecided (every ray direction tried was degenerate). p must not lie on
/// the surface (a point there may be classified either way).
int point_in_solid(const Model& solid, const Vec3& p);

}  // namespace interfere
