// Triangle–triangle intersection tests (issue #2, item 4).
//  - tri_tri_exact: the engine's default. Exact decision and classification through the filtered
//    predicates of core/predicates.h (Guigue & Devillers 2003 decision structure; degenerate
//    triangles handled as segments/points). Never uses an epsilon.
//  - tri_tri_moller: Möller, "A Fast Triangle-Triangle Intersection Test", JGT 2(2), 1997 (double,
//    not robust; kept for the paper's strategy table).
//  - tri_tri_guigue_devillers: Guigue & Devillers, "Fast and Robust Triangle-Triangle Overlap Test
//    Using Orientation Predicates", JGT 8(1), 2003, with plain double determinants (not robust).
#pragma once
#include <array>
#include <cstdint>

#include "interfere/core/vec.h"

namespace interfere {

enum class ContactKind : std::uint8_t {
  none = 0,
  touch = 1,  ///< they meet only on a boundary (edge/vertex) or in a coplanar overlap
  cross = 2,  ///< the relative interiors penetrate (non-coplanar, segment of positive length)
};

/// Where an intersection-segment endpoint lies on one triangle: a corner, an edge (corner i to
/// corner (i+1)%3), or the interior. Decided exactly, so that neighbouring pairs describe a shared
/// endpoint identically (used to chain segments into curves without any tolerance).
struct Feature {
  enum Type : std::uint8_t { vertex = 0, edge = 1, face = 2 } type = face;
  std::uint8_t index =
      0;  ///< corner index for vertex, first corner for edge (edge i = (i, (i+1)%3))
  friend bool operator==(const Feature&, const Feature&) = default;
};

struct TriTriResult {
  ContactKind kind = ContactKind::none;
  /// For kind == cross: the intersection segment (computed in double from exact topology), ordered
  /// along nA x nB (nX = (x1-x0)x(x2-x0)). A vertex-feature end is that corner exactly; an end
  /// where an edge crosses the other triangle's plane, or two edges cross, is computed from
  /// canonically ordered input, so pairs that share the edge (and pass the other triangle with the
  /// same corner order) get bit-identical points; accuracy about 1e-15 relative to the edge, also
  /// when nearly coplanar.
  std::array<Vec3, 2> segment{};
  /// For kind == cross: the feature of triangle A and of triangle B that each endpoint lies on.
  /// Every end lies on the boundary of A or of B (or both); the other one is then `face`.
  std::array<Feature, 2> feature_a{};
  std::array<Feature, 2> feature_b{};
};

/// Exact test with classification. Accepts degenerate triangles (kind is then none or touch).
TriTriResult tri_tri_exact(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

/// Exact yes/no only (cheaper: no classification or segment).
bool tri_tri_exact_intersects(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

/// Exact kind only (none/touch/cross, identical to tri_tri_exact(a, b).kind): skips the segment and
/// features, i.e. two orient3d and the endpoint constructions per crossing pair.
ContactKind tri_tri_exact_kind(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

/// Non-robust reference tests (double arithmetic, as published). True = intersecting.
bool tri_tri_moller(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);
bool tri_tri_guigue_devillers(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

}  // namespace interfere
