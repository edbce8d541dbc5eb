// The input's own contact zone: see contact_zone.h.
#include "contact_zone.h"

#include <algorithm>
#include <cmath>

#include "interfere/np/tri_tri.h"
#include "interfere/simplify/hausdorff.h"

namespace interfere::qem {
namespace {

Aabb box_of(const std::array<Vec3, 3>& t) {
  Aabb b;
  for (const Vec3& p : t) b.expand(p);
  return b;
}

double max_abs(const Aabb& b) {
  return std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x), std::abs(b.hi.y),
                   std::abs(b.hi.z)});
}

constexpr double kMaxCells = 64;

}  // namespace

BoxGrid::BoxGrid(std::vector<Aabb> boxes) : boxes_(std::move(boxes)) {
  if (boxes_.empty()) return;
  std::vector<double> sizes;
  sizes.reserve(boxes_.size());
  Aabb all;
  for (const Aabb& b : boxes_) {
    const Vec3 e = b.extent();
    sizes.push_back(std::max({e.x, e.y, e.z}));
    all.expand(b);
  }
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
  cell_ = sizes[sizes.size() / 2];
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = std::max(norm(all.extent()), 1.0);
  if (!std::isfinite(cell_)) cell_ = 1;
  origin_ = all.lo;
  for (std::uint32_t i = 0; i < boxes_.size(); ++i) {
    const Aabb& b = boxes_[i];
    if (!(cells(b) <= kMaxCells)) {
      big_.push_back(i);
      continue;
    }
    const Cell c0 = cell_of(b.lo), c1 = cell_of(b.hi);
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z) grid_[key({x, y, z})].push_back(i);
  }
}

// Rounding is monotonic: a box holding p spans p's cell.
BoxGrid::Cell BoxGrid::cell_of(const Vec3& p) const {
  const auto c = [&](double v, double o) { return static_cast<std::int64_t>(std::floor((v - o) / cell_)); };
  return {c(p.x, origin_.x), c(p.y, origin_.y), c(p.z, origin_.z)};
}

std::uint64_t BoxGrid::key(const Cell& c) {
  const auto k = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1fffff; };
  return (k(c[0]) << 42) | (k(c[1]) << 21) | k(c[2]);
}

double BoxGrid::cells(const Aabb& b) const {
  const auto span = [&](double lo, double hi, double o) {
    return std::floor((hi - o) / cell_) - std::floor((lo - o) / cell_) + 1;
  };
  return span(b.lo.x, b.hi.x, origin_.x) * span(b.lo.y, b.hi.y, origin_.y) * span(b.lo.z, b.hi.z, origin_.z);
}

bool BoxGrid::contains(const Aabb& b) const {
  const auto in = [&](std::uint32_t i) { return boxes_[i].contains(b.lo) && boxes_[i].contains(b.hi); };
  for (std::uint32_t i : big_)
    if (in(i)) return true;
  if (const auto it = grid_.find(key(cell_of(b.lo))); it != grid_.end())
    for (std::uint32_t i : it->second)
      if (in(i)) return true;
  return false;
}

bool BoxGrid::overlaps(const Aabb& b) const {
  const auto meets = [&](std::uint32_t i) { return boxes_[i].overlaps(b); };
  for (std::uint32_t i : big_)
    if (meets(i)) return true;
  if (!(cells(b) <= kMaxCells)) {  // a box over many cells: every box
    for (std::uint32_t i = 0; i < boxes_.size(); ++i)
      if (meets(i)) return true;
    return false;
  }
  const Cell c0 = cell_of(b.lo), c1 = cell_of(b.hi);
  for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
    for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
      for (std::int64_t z = c0[2]; z <= c1[2]; ++z)
        if (const auto it = grid_.find(key({x, y, z})); it != grid_.end())
          for (std::uint32_t i : it->second)
            if (meets(i)) return true;
  return false;
}

std::vector<Aabb> pair_neighbourhoods(const TriMesh& m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                                      double grow) {
  std::vector<Aabb> out;
  out.reserve(pairs.size());
  for (const auto& [x, y] : pairs) {
    Aabb b = box_of(m.corners(x));
    b.expand(box_of(m.corners(y)));
    const double g = grow * norm(b.extent());
    out.push_back({b.lo - Vec3{g, g, g}, b.hi + Vec3{g, g, g}});
  }
  return out;
}

ContactZone::ContactZone(const TriMesh& input, const std::vector<Aabb>* near) {
  TriMesh part;
  const TriMesh* m = &input;
  if (near) {  // the triangles meeting the boxes, their vertices renumbered in order of use
    const BoxGrid region(*near);
    Aabb all;
    for (const Aabb& b : *near) all.expand(b);
    std::unordered_map<std::uint32_t, std::uint32_t> id;
    for (std::size_t t = 0; t < input.num_triangles(); ++t) {
      const Aabb b = input.triangle_box(t);
      if (!b.overlaps(all) || !region.overlaps(b)) continue;
      Tri tr = input.triangles[t];
      for (std::uint32_t& v : tr) {
        const auto [it, fresh] = id.try_emplace(v, static_cast<std::uint32_t>(part.positions.size()));
        if (fresh) part.positions.push_back(input.positions[v]);
        v = it->second;
      }
      part.triangles.push_back(tr);
    }
    m = &part;
  }
  zone_ = BoxGrid(pair_neighbourhoods(*m, self_intersecting_pairs(*m), 1));
}

Aabb ContactZone::meet(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  const Aabb ba = box_of(a), bb = box_of(b);
  Aabb meet{max(ba.lo, bb.lo), min(ba.hi, bb.hi)};  // holds every common point
  const TriTriResult r = tri_tri_exact(a, b);
  if (r.kind == ContactKind::none) return Aabb{};
  if (r.kind == ContactKind::cross) {
    // The segment, about 1e-15 relative to the edges (tri_tri.h): grown by far more than that.
    Aabb s;
    s.expand(r.segment[0]);
    s.expand(r.segment[1]);
    const double pad = 1e-12 * (norm(ba.extent()) + norm(bb.extent())) + 1e-15 * std::max(max_abs(ba), max_abs(bb));
    s = {s.lo - Vec3{pad, pad, pad}, s.hi + Vec3{pad, pad, pad}};
    meet = {max(meet.lo, s.lo), min(meet.hi, s.hi)};
    if (meet.empty()) meet = {max(ba.lo, bb.lo), min(ba.hi, bb.hi)};  // (rounding: the boxes' overlap)
  }
  return meet;
}

std::vector<Aabb> ContactZone::reach(const TriMesh& m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  std::vector<Aabb> out;
  out.reserve(pairs.size());
  for (const auto& [x, y] : pairs) {
    const Aabb b = meet(m.corners(x), m.corners(y));
    if (b.empty()) continue;
    const double g = norm(b.extent());
    out.push_back({b.lo - Vec3{g, g, g}, b.hi + Vec3{g, g, g}});
  }
  return out;
}

bool ContactZone::holds(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) const {
  if (zone_.empty()) return false;
  const Aabb m = meet(a, b);
  return m.empty() || zone_.contains(m);  // (empty: not a contact at all)
}

}  // namespace interfere::qem
