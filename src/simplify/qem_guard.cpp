// Self-intersection guard of the QEM simplifier (issue #6, item 6: simplification introduces no
// self-intersections): a uniform hash grid of the live triangles' boxes, and the exact test
// (np/tri_tri.h, Shewchuk-style filtered predicates) of every triangle a collapse creates or moves
// against the non-adjacent triangles near it; a pair inside the input's own contact zone
// (contact_zone.h) is allowed.
#include <array>
#include <cmath>
#include <limits>

#include "interfere/np/tri_tri.h"
#include "contact_zone.h"
#include "qem_internal.h"

namespace interfere::qem {

// Cells about twice the current mean triangle size; rebuilt whenever the live count halves or the
// entries added since the last build (moved triangles, re-inserted) outnumber twice the entries it
// was built with and a quarter of the live triangles (a build scans them all): so a cell holds a
// few triangles throughout and stale entries do not pile up where the collapses concentrate.
bool Simplifier::grid_stale(std::size_t live) const {
  return live * 2 < grid_live_ || (grid_inserted_ > 2 * grid_size_ && grid_inserted_ > live / 4);
}

void Simplifier::rebuild_grid(std::size_t live) {
  Aabb all;
  for (std::size_t v = 0; v < pos_.size(); ++v)
    if (!vdead_[v] && fan_count_[v] > 0) all.expand(pos_[v]);
  const double diag = norm(all.extent());
  cell_ = std::max(2.0 * std::sqrt(surface_area_ / double(std::max<std::size_t>(live, 1))), 1e-9 * diag);
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
  origin_ = all.lo;
  grid_.clear();
  grid_big_.clear();
  grid_inserted_ = 0;
  grid_.reserve(live / 2 + 16);
  for (std::uint32_t t = 0; t < tris_.size(); ++t)
    if (!dead_[t]) grid_insert(t);
  grid_live_ = live;
  grid_size_ = grid_inserted_;
  grid_inserted_ = 0;
}

// Cells of a box: their number (in double: a sliver across the part next to tiny triangles spans
// more cells than an int64 counts) and, when not too many, each key.
double Simplifier::grid_cell_count(const Aabb& box) const {
  auto span = [&](double lo, double hi) { return std::floor(hi / cell_) - std::floor(lo / cell_) + 1; };
  const double n = span(box.lo.x - origin_.x, box.hi.x - origin_.x) * span(box.lo.y - origin_.y, box.hi.y - origin_.y) *
                   span(box.lo.z - origin_.z, box.hi.z - origin_.z);
  return std::isfinite(n) ? n : std::numeric_limits<double>::infinity();
}

template <class F>
void Simplifier::grid_cells(const Aabb& box, F&& f) const {
  auto cell = [&](double v, double o) { return static_cast<std::int64_t>(std::floor((v - o) / cell_)); };
  const std::int64_t x0 = cell(box.lo.x, origin_.x), x1 = cell(box.hi.x, origin_.x);
  const std::int64_t y0 = cell(box.lo.y, origin_.y), y1 = cell(box.hi.y, origin_.y);
  const std::int64_t z0 = cell(box.lo.z, origin_.z), z1 = cell(box.hi.z, origin_.z);
  for (std::int64_t x = x0; x <= x1; ++x)
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t z = z0; z <= z1; ++z)
        f((static_cast<std::uint64_t>(x & 0x1fffff) << 42) | (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
          static_cast<std::uint64_t>(z & 0x1fffff));
}

// A triangle whose box spans more than kMaxCells cells (a sliver across the part beside tiny
// triangles: a mutated STL with one vertex at 1e28 spanned ~1e40 and never finished inserting)
// goes to one list scanned by every check instead.
void Simplifier::grid_insert(std::uint32_t t) {
  Aabb b;
  for (std::uint32_t v : tris_[t]) b.expand(pos_[v]);
  if (!near_region(b)) return;
  if (grid_cell_count(b) > kMaxCells) {
    grid_big_.push_back(t);
    ++grid_inserted_;
    return;
  }
  grid_cells(b, [&](std::uint64_t key) {
    grid_[key].push_back(t);
    ++grid_inserted_;
  });
}

// The triangles a collapse creates or moves must not meet any other triangle of the mesh except
// through shared vertices (exact test: np/tri_tri.h). The grid is scanned once per collapse, over
// the cells of the box of all the moved triangles (they surround one vertex and share their cells:
// scanning per moved triangle read the same entries about ten times, which dominated guarded runs
// next to finely tessellated kept features); each candidate is then tested against each moved
// triangle whose box it overlaps.
bool Simplifier::intersection_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc,
                                 const Aabb& all) {
  // With a guard region the grid holds only the triangles near it: a collapse reaching beyond that
  // neighbourhood cannot be checked and is refused.
  if (!guard_boxes_.empty() && !within_region(all)) return false;
  guard_moved_.clear();
  for (int side = 0; side < 2; ++side) {
    const std::uint32_t v = side == 0 ? remove : keep;
    const std::uint32_t other = side == 0 ? keep : remove;
    if (side == 1 && p == pos_[keep]) break;
    for (const Scratch::FanTri& f : side == 0 ? sc.fan_b : sc.fan_a) {
      Tri tr = f.tr;
      if (tr[0] == other || tr[1] == other || tr[2] == other) continue;
      GuardMoved m;
      for (int k = 0; k < 3; ++k) {
        if (tr[k] == v) tr[k] = keep;
        m.c[k] = tr[k] == keep ? p : pos_[tr[k]];
        m.box.expand(m.c[k]);
      }
      m.tr = tr;
      guard_moved_.push_back(m);
    }
  }
  if (guard_moved_.empty()) return true;
  ++tri_mark_id_;
  bool ok = true;
  // The cell sheds its entries of dead triangles and its repeated entries while it is scanned
  // (a moved triangle is inserted again, its old entries stay): they were half of the entries.
  const auto scan = [&](std::vector<std::uint32_t>& cell) {
    if (!ok) return;
    const std::uint32_t cell_id = ++cell_mark_id_;
    std::size_t kept = 0, i = 0;
    for (; i < cell.size() && ok; ++i) {
      const std::uint32_t s = cell[i];
      if (dead_[s]) continue;
      GuardMark& mark = guard_mark_[s];
      if (mark.cell == cell_id) continue;
      mark.cell = cell_id;
      cell[kept++] = s;
      if (mark.tri == tri_mark_id_) continue;
      mark.tri = tri_mark_id_;
      const Tri& q = tris_[s];
      if (q[0] == keep || q[1] == keep || q[2] == keep || q[0] == remove || q[1] == remove || q[2] == remove) continue;
      Aabb qb;
      for (std::uint32_t w : q) qb.expand(pos_[w]);
      if (!qb.overlaps(all)) continue;
      for (const GuardMoved& m : guard_moved_) {
        if (!qb.overlaps(m.box)) continue;  // the cheaper test first: most fail it
        bool share = false;
        for (std::uint32_t w : q) share = share || w == m.tr[0] || w == m.tr[1] || w == m.tr[2];
        if (share) continue;
        const std::array<Vec3, 3> qc{pos_[q[0]], pos_[q[1]], pos_[q[2]]};
        if (tri_tri_exact_intersects(m.c, qc) && !(zone_ && zone_->holds(m.c, qc))) {
          ok = false;
          break;
        }
      }
    }
    cell.erase(cell.begin() + static_cast<std::ptrdiff_t>(kept), cell.begin() + static_cast<std::ptrdiff_t>(i));
  };
  scan(grid_big_);
  if (grid_cell_count(all) > std::max<double>(kMaxCells, double(grid_.size()))) {
    for (auto& [key, cell] : grid_) scan(cell);  // a box larger than the occupied cells: all of them
  } else {
    grid_cells(all, [&](std::uint64_t key) {
      if (auto it = grid_.find(key); it != grid_.end()) scan(it->second);
    });
  }
  return ok;
}

// The box of the triangles the collapse moves, at their new place.
Aabb Simplifier::moved_box(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc) const {
  Aabb moved;
  for (const auto* fan : {&sc.fan_b, &sc.fan_a})
    for (const Scratch::FanTri& f : *fan)
      for (std::uint32_t w : f.tr) moved.expand(w == remove || w == keep ? p : pos_[w]);
  return moved;
}

bool Simplifier::near_region(const Aabb& b) const {
  if (guard_boxes_.empty()) return true;
  if (!b.overlaps(guard_outer_all_)) return false;
  for (const Aabb& o : guard_outer_)
    if (b.overlaps(o)) return true;
  return false;
}

bool Simplifier::within_region(const Aabb& b) const {
  if (guard_boxes_.empty()) return true;
  for (const Aabb& o : guard_outer_)
    if (o.contains(b.lo) && o.contains(b.hi)) return true;
  return false;
}

// The moved triangles (their box `moved`) reach a guard box.
bool Simplifier::guarded(const Aabb& moved) const {
  if (guard_boxes_.empty()) return true;
  if (!moved.overlaps(guard_all_)) return false;
  for (const Aabb& b : guard_boxes_)
    if (moved.overlaps(b)) return true;
  return false;
}

bool Simplifier::guard_refuses(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc) {
  const Aabb moved = moved_box(keep, remove, p, sc);
  return guarded(moved) && !intersection_ok(keep, remove, p, sc, moved);
}

void Simplifier::grid_insert_fan(std::uint32_t v) {
  for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
    const std::uint32_t t = refs_[fan_start_[v] + i];
    if (!dead_[t]) grid_insert(t);
  }
}

}  // namespace interfere::qem
