// Internal types shared by the clash query's stages (narrow phase -> regions/curves).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/query/clash.h"

namespace interfere::detail {

/// One intersecting triangle pair with the exact topology of its intersection segment.
struct Hit {
  std::uint32_t a = 0, b = 0;
  ContactKind kind = ContactKind::none;
  bool has_segment = false;  ///< exact test and kind == cross
  std::array<Vec3, 2> segment{};
  std::array<Feature, 2> feature_a{}, feature_b{};
};

/// Groups hits (sorted by (a, b)) into regions and chains crossing segments into curves.
std::vector<ClashRegion> build_regions(const TriMesh& a, const TriMesh& b, const std::vector<Hit>& hits);

/// Exact point-in-closed-mesh by ray parity; p must not lie on the mesh surface.
/// Returns +1 inside, 0 outside, -1 undecided (every ray direction tried was degenerate).
int point_in_closed_mesh(const Model& model, const Vec3& p);

}  // namespace interfere::detail
