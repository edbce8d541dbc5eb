// Internal types shared by the clash query's stages (narrow phase -> regions/curves).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/query/clash.h"

namespace interfere::detail {

/// The intersection segment of a crossing pair (exact test) with the exact features its endpoints
/// lie on. Kept apart from the pair list so that touch-heavy scenes carry 12 bytes per pair.
struct Segment {
  std::uint32_t a = 0, b = 0;
  std::array<Vec3, 2> points{};
  std::array<Feature, 2> feature_a{}, feature_b{};
};

/// Groups pairs into regions and chains the segments into curves (both sorted by (a, b)).
std::vector<ClashRegion> build_regions(const TriMesh& a, const TriMesh& b, const std::vector<TrianglePair>& pairs,
                                       const std::vector<Segment>& segments);

/// Exact point-in-closed-mesh by ray parity; p must not lie on the mesh surface.
/// Returns +1 inside, 0 outside, -1 undecided (every ray direction tried was degenerate).
int point_in_closed_mesh(const Model& model, const Vec3& p);

/// Closed parts whose surfaces meet in touching pairs only (`pairs`: all of them): +1 when their
/// interiors overlap all the same, 0 when they do not, -1 undecided (a probe's rays were all
/// degenerate). touching_overlap.cpp.
int touching_overlap(const Model& a, const Model& b, const std::vector<TrianglePair>& pairs);

}  // namespace interfere::detail
