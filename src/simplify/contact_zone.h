// The input's own contact zone (issue #6, item 6: "simplification introduces no
// self-intersections"). Where the input already has intersecting or touching triangle pairs
// (penetrating or touching bodies such as the Newell teapot's spout in its body, CAD exports with
// cracks and T-junctions), no collapse near them can keep the pairs' triangles unchanged, so a
// guard that refuses every new intersecting pair stalls there or moves the collapses elsewhere.
// The zone is the union of the input pairs' boxes, each grown by its diagonal; a pair of result
// triangles whose intersection (its segment, from the exact test; the boxes' overlap for a touch)
// lies inside one zone box is inherited: the input's contact, moved by the simplification. Every
// other intersecting pair is new, and refused as before.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::qem {

/// Boxes in a uniform grid (cells of their median size; a box over more than 64 cells is kept
/// aside and tested by every query).
class BoxGrid {
 public:
  BoxGrid() = default;
  explicit BoxGrid(std::vector<Aabb> boxes);
  bool empty() const { return boxes_.empty(); }
  std::size_t size() const { return boxes_.size(); }
  /// Whether one box holds all of b.
  bool contains(const Aabb& b) const;
  /// Whether some box meets b.
  bool overlaps(const Aabb& b) const;

 private:
  using Cell = std::array<std::int64_t, 3>;
  Cell cell_of(const Vec3& p) const;
  static std::uint64_t key(const Cell& c);
  double cells(const Aabb& b) const;
  std::vector<Aabb> boxes_;
  double cell_ = 1;
  Vec3 origin_{};
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;
  std::vector<std::uint32_t> big_;
};

/// The box of each pair of triangles of m (both triangles), grown on every side by `grow` times
/// its diagonal: the neighbourhood of intersecting pairs (contact zone, guard region).
std::vector<Aabb> pair_neighbourhoods(const TriMesh& m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                                      double grow);

class ContactZone {
 public:
  ContactZone() = default;
  /// The zone of `input`'s own intersecting pairs (the engine's exact self-clash of the input).
  /// With `near`: of the pairs among the input triangles meeting those boxes only (a zone where it
  /// is needed, without a self-clash of a large input); elsewhere the zone is empty.
  explicit ContactZone(const TriMesh& input, const std::vector<Aabb>* near = nullptr);
  bool empty() const { return zone_.empty(); }
  /// The input's intersecting or touching pairs the zone was made from.
  std::size_t input_pairs() const { return zone_.size(); }
  /// A box holding every common point of triangles a and b: the segment of the exact test (padded
  /// by far more than its rounding) within the two boxes' overlap, or that overlap for a touch;
  /// empty when they do not meet.
  static Aabb meet(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);
  /// Where a zone is needed for these intersecting pairs of m: the box where each meets, grown by
  /// its diagonal (an input pair whose grown box holds that meet has a triangle there unless the
  /// pair is larger than the meet; a pair missed is only refused: conservative).
  static std::vector<Aabb> reach(const TriMesh& m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs);
  /// Whether triangles a and b, which intersect, meet only inside one zone box (conservative:
  /// false when unsure).
  bool holds(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) const;

 private:
  BoxGrid zone_;
};

}  // namespace interfere::qem
