// QEM edge collapse after Garland & Heckbert, "Surface Simplification Using Quadric Error Metrics"
// (SIGGRAPH 1997): §4 (area-weighted plane quadrics, optimal placement by solving the 3x3 system,
// fallback to the endpoints and the midpoint), §6.1 (penalty planes through constrained edges), a
// min-heap of candidate collapses invalidated lazily by per-vertex stamps; the link condition
// (Dey et al. 1999) keeps the mesh manifold; moved triangles must not flip. Assembly features as in
// He & Xu (SJTU 2023, §3.3): edges touching feature faces get the maximum unmodified cost added.
#include "interfere/simplify/qem.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <cmath>
#include <limits>
#include <memory>
#include <queue>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "interfere/np/tri_tri.h"

#include "interfere/simplify/hausdorff.h"

namespace interfere {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

struct Quadric {
  // Symmetric 4x4 (a b c d)^T (a b c d): xx xy xz xw yy yz yw zz zw ww.
  double q[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  void add_plane(const Vec3& n, double d, double w) {
    q[0] += w * n.x * n.x, q[1] += w * n.x * n.y, q[2] += w * n.x * n.z, q[3] += w * n.x * d;
    q[4] += w * n.y * n.y, q[5] += w * n.y * n.z, q[6] += w * n.y * d;
    q[7] += w * n.z * n.z, q[8] += w * n.z * d, q[9] += w * d * d;
  }
  Quadric& operator+=(const Quadric& o) {
    for (int i = 0; i < 10; ++i) q[i] += o.q[i];
    return *this;
  }
  double eval(const Vec3& p) const {
    const double x = p.x, y = p.y, z = p.z;
    const double e = q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y +
                     2 * q[5] * y * z + 2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
    return e > 0 ? e : 0;
  }
  /// Minimiser of eval: solves A p = -b by the cofactor inverse; false when A is near singular
  /// (relative determinant test), then the caller falls back to endpoints/midpoint.
  bool optimum(Vec3& p) const {
    const double a = q[0], b = q[1], c = q[2], d = q[4], e = q[5], f = q[7];
    const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
    const double det = a * c00 + b * c01 + c * c02;
    const double scale = std::max({std::abs(a), std::abs(d), std::abs(f)});
    if (!(std::abs(det) > 1e-10 * scale * scale * scale) || scale == 0) return false;
    const double c11 = a * f - c * c, c12 = b * c - a * e, c22 = a * d - b * b;
    const double inv = 1.0 / det;
    const double rx = -q[3], ry = -q[6], rz = -q[8];
    p = {(c00 * rx + c01 * ry + c02 * rz) * inv, (c01 * rx + c11 * ry + c12 * rz) * inv,
         (c02 * rx + c12 * ry + c22 * rz) * inv};
    return is_finite(p);
  }
};

enum VertexClass : std::uint8_t { kInterior = 0, kSeam = 1, kCorner = 2 };

struct Candidate {
  double cost;
  Vec3 p;
  std::uint32_t keep, remove;
  std::uint32_t stamp_keep, stamp_remove;
  bool last_tier = false;  ///< FeatureMode::last: ordered after every non-feature candidate
  bool operator>(const Candidate& o) const {
    if (cost != o.cost) return cost > o.cost;
    if (keep != o.keep) return keep > o.keep;
    return remove > o.remove;
  }
};

// Heap entry: 16 bytes (the heap's cache misses dominate large runs). Placement is recomputed when
// an entry is popped; the 16-bit stamps invalidate entries whose end vertices changed since.
struct HeapEntry {
  float cost;
  std::uint32_t keep, remove;
  std::uint16_t stamp_keep, stamp_remove;
  bool before(const HeapEntry& o) const {
    if (cost != o.cost) return cost < o.cost;
    if (keep != o.keep) return keep < o.keep;
    return remove < o.remove;
  }
};
static_assert(sizeof(HeapEntry) == 16);

HeapEntry entry_of(const Candidate& c) {
  // Costs are >= 0 (eval clamps); +0.0f so that -0.0 cannot appear; the bits of a non-negative float
  // order like its value and leave the top bit free: set, it puts the entry in the last tier.
  HeapEntry e{static_cast<float>(c.cost) + 0.0f, c.keep, c.remove, static_cast<std::uint16_t>(c.stamp_keep),
              static_cast<std::uint16_t>(c.stamp_remove)};
  if (c.last_tier) {
    std::uint32_t k;
    std::memcpy(&k, &e.cost, 4);
    k |= 0x80000000u;
    std::memcpy(&e.cost, &k, 4);
  }
  return e;
}

/// Radix heap (Ahuja, Mehlhorn, Orlin & Tarjan 1990) on the bits of the non-negative float cost,
/// which order like the floats: pushes are O(1) appends, a pop redistributes one bucket
/// sequentially, so the lazy queue's millions of entries are touched in cache-friendly sweeps.
/// Keys must not decrease below the last popped key: a cheaper candidate created by a collapse is
/// clamped to it, i.e. it is taken next (the order is otherwise the exact cost order; equal keys
/// come out last-in first-out, deterministically).
class RadixHeap {
 public:
  bool empty() const { return size_ == 0; }
  void push(HeapEntry e) {
    std::uint32_t k = key(e);
    if (k < last_) k = last_;
    std::memcpy(&e.cost, &k, 4);
    buckets_[bucket(k)].push_back(e);
    ++size_;
  }
  HeapEntry pop() {
    if (buckets_[0].empty()) {
      std::size_t i = 1;
      while (buckets_[i].empty()) ++i;
      std::uint32_t m = std::numeric_limits<std::uint32_t>::max();
      for (const HeapEntry& e : buckets_[i]) m = std::min(m, key(e));
      last_ = m;
      std::vector<HeapEntry> moving;
      moving.swap(buckets_[i]);
      for (const HeapEntry& e : moving) buckets_[bucket(key(e))].push_back(e);
      moving.clear();
      moving.swap(buckets_[i]);  // keep the capacity
    }
    const HeapEntry e = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return e;
  }
  void assign(const std::vector<HeapEntry>& all) {
    for (const HeapEntry& e : all) push(e);
  }

 private:
  static std::uint32_t key(const HeapEntry& e) {
    std::uint32_t k;
    std::memcpy(&k, &e.cost, 4);
    return k;
  }
  std::size_t bucket(std::uint32_t k) const { return k == last_ ? 0 : 32 - std::countl_zero(k ^ last_); }
  std::vector<HeapEntry> buckets_[33];
  std::uint32_t last_ = 0;
  std::size_t size_ = 0;
};

constexpr std::uint32_t kBlock = 4096;  ///< vertices per parallel block (fixed: deterministic output)

std::size_t num_blocks(std::size_t n) { return (n + kBlock - 1) / kBlock; }

/// f(first, last, block) over fixed vertex blocks, in parallel.
template <class F>
void for_vertex_blocks(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_blocks(n)), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b)
      f(static_cast<std::uint32_t>(b * kBlock), static_cast<std::uint32_t>(std::min(n, (b + 1) * kBlock)), b);
  });
}

class Simplifier {
 public:
  Simplifier(TriMesh mesh, std::vector<std::uint32_t> face, std::vector<std::uint8_t> feature_tri,
             const SimplifyOptions& o)
      : pos_(std::move(mesh.positions)),
        tris_(std::move(mesh.triangles)),
        face_(std::move(face)),
        feature_tri_(std::move(feature_tri)),
        o_(o) {}

  void run(std::size_t target, SimplifyResult& r);
  std::vector<Vec3> pos_;
  std::vector<Tri> tris_;
  std::vector<std::uint32_t> face_;
  std::vector<std::uint8_t> feature_tri_;
  std::vector<std::uint8_t> dead_;

 private:
  void build_fans();
  void set_fan(std::uint32_t v, const std::vector<std::uint32_t>& tris);
  bool seam_edge(std::uint32_t a, std::uint32_t b, int* shared) const;
  /// Calls f(w) once for every neighbour w > v of v on its live triangles (each undirected edge is
  /// visited from its smaller end only); `seen` is per-thread scratch of size nv.
  template <class F>
  void for_each_upper_neighbour(std::uint32_t v, std::vector<std::uint32_t>& seen, F&& f) const {
    for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
      const std::uint32_t t = refs_[fan_start_[v] + i];
      if (dead_[t]) continue;
      for (std::uint32_t w : tris_[t]) {
        if (w <= v || seen[w] == v) continue;
        seen[w] = v;
        f(w);
      }
    }
  }
  bool evaluate(std::uint32_t a, std::uint32_t b, Candidate& out);
  bool evaluate(std::uint32_t a, std::uint32_t b, bool seam, Candidate& out);
  bool direction(std::uint32_t keep, std::uint32_t remove, bool seam, Candidate& out);
  bool link_ok(std::uint32_t a, std::uint32_t b, int shared);
  bool flip_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p) const;
  bool intersection_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p);
  void grid_insert(std::uint32_t t);
  void rebuild_grid(std::size_t live);
  template <class F>
  void grid_cells(const Aabb& box, F&& f);
  void push_edges_of(std::uint32_t v);
  void collapse(std::uint32_t a, std::uint32_t b, const Vec3& p, std::size_t& live);
  void compact_fans();
  void batched_passes(std::vector<HeapEntry>& list, std::size_t handoff, std::size_t& live, SimplifyResult& r);
  bool movable(std::uint32_t v) const { return cls_[v] == kInterior && !locked_[v]; }

  const SimplifyOptions& o_;
  std::vector<std::uint32_t> fan_start_, fan_count_;
  std::vector<std::uint32_t> refs_;
  std::vector<Quadric> quad_;
  std::vector<std::uint8_t> cls_, locked_, touches_feature_, vdead_;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::uint32_t> mark_a_, mark_b_, slot_;
  struct Neighbour {
    std::uint32_t w, count, face;
    bool differ;
  };
  std::vector<Neighbour> nbr_;
  std::uint32_t mark_id_ = 0;
  double feature_offset_ = 0;
  RadixHeap heap_;
  std::vector<std::uint32_t> scratch_;
  std::size_t rejected_link_ = 0, rejected_flip_ = 0, rejected_intersection_ = 0;
  // Self-intersection guard: a uniform hash grid of triangle boxes (entries may be stale: every
  // candidate is re-checked against the current mesh).
  bool guard_ = false;
  double cell_ = 1;
  Vec3 origin_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;
  std::vector<std::uint32_t> tri_mark_;
  std::uint32_t tri_mark_id_ = 0;
  double surface_area_ = 0;
  std::size_t grid_live_ = 0;  ///< live triangles when the grid was last built
};

// Cells about twice the current mean triangle size; rebuilt whenever the live count halves, so a
// cell holds a few triangles throughout and stale entries are dropped.
void Simplifier::rebuild_grid(std::size_t live) {
  Aabb all;
  for (std::size_t v = 0; v < pos_.size(); ++v)
    if (!vdead_[v] && fan_count_[v] > 0) all.expand(pos_[v]);
  const double diag = norm(all.extent());
  cell_ = std::max(2.0 * std::sqrt(surface_area_ / double(std::max<std::size_t>(live, 1))), 1e-9 * diag);
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
  origin_ = all.lo;
  grid_.clear();
  grid_.reserve(live / 2 + 16);
  for (std::uint32_t t = 0; t < tris_.size(); ++t)
    if (!dead_[t]) grid_insert(t);
  grid_live_ = live;
}

template <class F>
void Simplifier::grid_cells(const Aabb& box, F&& f) {
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

void Simplifier::grid_insert(std::uint32_t t) {
  Aabb b;
  for (std::uint32_t v : tris_[t]) b.expand(pos_[v]);
  grid_cells(b, [&](std::uint64_t key) { grid_[key].push_back(t); });
}

// The triangles a collapse creates or moves must not meet any other triangle of the mesh except
// through shared vertices (exact test: np/tri_tri.h).
bool Simplifier::intersection_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p) {
  ++tri_mark_id_;
  for (int side = 0; side < 2; ++side) {
    const std::uint32_t v = side == 0 ? remove : keep;
    const std::uint32_t other = side == 0 ? keep : remove;
    if (side == 1 && p == pos_[keep]) break;
    for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
      const std::uint32_t t = refs_[fan_start_[v] + i];
      if (dead_[t]) continue;
      Tri tr = tris_[t];
      if (tr[0] == other || tr[1] == other || tr[2] == other) continue;
      std::array<Vec3, 3> c;
      Aabb box;
      for (int k = 0; k < 3; ++k) {
        if (tr[k] == v) tr[k] = keep;
        c[k] = tr[k] == keep ? p : pos_[tr[k]];
        box.expand(c[k]);
      }
      bool ok = true;
      grid_cells(box, [&](std::uint64_t key) {
        if (!ok) return;
        auto it = grid_.find(key);
        if (it == grid_.end()) return;
        for (std::uint32_t s : it->second) {
          if (dead_[s] || tri_mark_[s] == tri_mark_id_) continue;
          tri_mark_[s] = tri_mark_id_;
          const Tri& q = tris_[s];
          bool share = false;
          for (std::uint32_t w : q) share = share || w == keep || w == remove || w == tr[0] || w == tr[1] || w == tr[2];
          if (share) continue;
          Aabb qb;
          for (std::uint32_t w : q) qb.expand(pos_[w]);
          if (!qb.overlaps(box)) continue;
          if (tri_tri_exact_intersects(c, {pos_[q[0]], pos_[q[1]], pos_[q[2]]})) {
            ok = false;
            return;
          }
        }
      });
      if (!ok) return false;
      // Candidates of one moved triangle were marked: the next moved triangle re-examines them.
      ++tri_mark_id_;
    }
  }
  return true;
}


void Simplifier::build_fans() {
  const std::size_t nv = pos_.size();
  fan_start_.assign(nv + 1, 0);
  fan_count_.assign(nv, 0);
  for (const Tri& t : tris_)
    for (std::uint32_t v : t) ++fan_count_[v];
  for (std::size_t v = 0; v < nv; ++v) fan_start_[v + 1] = fan_start_[v] + fan_count_[v];
  refs_.assign(fan_start_[nv], 0);
  std::vector<std::uint32_t> fill(fan_start_.begin(), fan_start_.end() - 1);
  for (std::uint32_t t = 0; t < tris_.size(); ++t)
    for (std::uint32_t v : tris_[t]) refs_[fill[v]++] = t;
  fan_start_.pop_back();
}

void Simplifier::set_fan(std::uint32_t v, const std::vector<std::uint32_t>& tris) {
  if (tris.size() <= fan_count_[v]) {  // shrinking: reuse the slot
    std::copy(tris.begin(), tris.end(), refs_.begin() + fan_start_[v]);
  } else {
    fan_start_[v] = static_cast<std::uint32_t>(refs_.size());
    refs_.insert(refs_.end(), tris.begin(), tris.end());
  }
  fan_count_[v] = static_cast<std::uint32_t>(tris.size());
}

// Constrained (seam) edge: not exactly two live triangles, or two with different face ids.
bool Simplifier::seam_edge(std::uint32_t a, std::uint32_t b, int* shared) const {
  int n = 0;
  std::uint32_t f0 = kNone;
  bool differ = false;
  for (std::uint32_t i = 0; i < fan_count_[a]; ++i) {
    const std::uint32_t t = refs_[fan_start_[a] + i];
    if (dead_[t]) continue;
    const Tri& tr = tris_[t];
    if (tr[0] != b && tr[1] != b && tr[2] != b) continue;
    ++n;
    if (f0 == kNone) f0 = face_[t];
    else if (face_[t] != f0) differ = true;
  }
  if (shared) *shared = n;
  return n != 2 || differ;
}

bool Simplifier::direction(std::uint32_t keep, std::uint32_t remove, bool seam, Candidate& out) {
  if (locked_[remove] || cls_[remove] == kCorner) return false;
  if (cls_[remove] == kSeam && (!seam || cls_[keep] == kInterior)) return false;
  Quadric q = quad_[keep];
  q += quad_[remove];
  Vec3 p = pos_[keep];
  if (movable(keep) && movable(remove)) {
    // Optimal placement, else the best of the endpoints and the midpoint.
    if (!q.optimum(p)) {
      const Vec3 mid = (pos_[keep] + pos_[remove]) * 0.5;
      const Vec3 cand[3] = {pos_[keep], pos_[remove], mid};
      double best = std::numeric_limits<double>::infinity();
      for (const Vec3& c : cand) {
        const double e = q.eval(c);
        if (e < best) best = e, p = c;
      }
    }
  }
  out.cost = q.eval(p);
  out.p = p;
  out.keep = keep, out.remove = remove;
  out.stamp_keep = stamp_[keep], out.stamp_remove = stamp_[remove];
  if (touches_feature_[keep] || touches_feature_[remove]) {
    out.cost += feature_offset_;
    out.last_tier = o_.feature_mode == FeatureMode::last;
  }
  return true;
}

bool Simplifier::evaluate(std::uint32_t a, std::uint32_t b, Candidate& out) {
  return evaluate(a, b, seam_edge(a, b, nullptr), out);
}

bool Simplifier::evaluate(std::uint32_t a, std::uint32_t b, bool seam, Candidate& out) {
  Candidate c1, c2;
  const bool ok1 = direction(a, b, seam, c1);
  // Both movable: one symmetric placement, no second direction needed.
  const bool ok2 = !(ok1 && movable(a) && movable(b)) && direction(b, a, seam, c2);
  if (!ok1 && !ok2) return false;
  out = (ok1 && (!ok2 || c1.cost <= c2.cost)) ? c1 : c2;
  return true;
}

// One sweep over v's fan gathers every neighbour w with the number of live triangles on (v, w) and
// whether their face ids differ (the seam test of seam_edge for all edges at once), in order of
// first appearance.
void Simplifier::push_edges_of(std::uint32_t v) {
  ++mark_id_;
  nbr_.clear();
  for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
    const std::uint32_t t = refs_[fan_start_[v] + i];
    if (dead_[t]) continue;
    const std::uint32_t f = face_[t];
    for (std::uint32_t w : tris_[t]) {
      if (w == v) continue;
      if (mark_a_[w] != mark_id_) {
        mark_a_[w] = mark_id_;
        slot_[w] = static_cast<std::uint32_t>(nbr_.size());
        nbr_.push_back({w, 1, f, false});
      } else {
        Neighbour& n = nbr_[slot_[w]];
        ++n.count;
        n.differ = n.differ || n.face != f;
      }
    }
  }
  // The neighbours' quadrics and positions are scattered (cost order is spatially random): fetch
  // them all before the evaluations so that the cache misses overlap.
  for (const Neighbour& n : nbr_) {
    __builtin_prefetch(&quad_[n.w]);
    __builtin_prefetch(reinterpret_cast<const char*>(&quad_[n.w]) + 64);
    __builtin_prefetch(&pos_[n.w]);
    __builtin_prefetch(&stamp_[n.w]);
  }
  for (const Neighbour& n : nbr_) {
    Candidate c;
    if (evaluate(v, n.w, n.count != 2 || n.differ, c)) heap_.push(entry_of(c));
  }
}

// Link condition: the common neighbours of a and b are exactly the apexes of the triangles on ab.
bool Simplifier::link_ok(std::uint32_t a, std::uint32_t b, int shared) {
  ++mark_id_;
  const std::uint32_t id = mark_id_;
  for (std::uint32_t i = 0; i < fan_count_[a]; ++i) {
    const std::uint32_t t = refs_[fan_start_[a] + i];
    if (dead_[t]) continue;
    for (std::uint32_t w : tris_[t]) mark_a_[w] = id;
  }
  int common = 0;
  for (std::uint32_t i = 0; i < fan_count_[b]; ++i) {
    const std::uint32_t t = refs_[fan_start_[b] + i];
    if (dead_[t]) continue;
    for (std::uint32_t w : tris_[t]) {
      if (w == a || w == b || mark_b_[w] == id) continue;
      mark_b_[w] = id;
      if (mark_a_[w] == id) ++common;
    }
  }
  return common == shared;
}

bool normal_ok(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& pa, const Vec3& pb,
               const Vec3& pc, double min_cos) {
  const Vec3 n0 = cross(b - a, c - a);
  const Vec3 n1 = cross(pb - pa, pc - pa);
  const double l0 = squared_norm(n0), l1 = squared_norm(n1);
  if (!(l1 > 0)) return false;
  if (!(l0 > 0)) return true;  // a degenerate triangle becoming non-degenerate is no flip
  const double d = dot(n0, n1);
  if (d <= 0) return false;
  return d * d >= min_cos * min_cos * l0 * l1 || min_cos <= 0;
}

// Every live triangle moved by the collapse (those of `remove` that do not contain `keep`, and, if
// `keep` moves, those of `keep` that do not contain `remove`) keeps its orientation.
bool Simplifier::flip_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p) const {
  const double mc = o_.min_normal_cos;
  for (int side = 0; side < 2; ++side) {
    const std::uint32_t v = side == 0 ? remove : keep;
    const std::uint32_t other = side == 0 ? keep : remove;
    if (side == 1 && p == pos_[keep]) break;
    for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
      const std::uint32_t t = refs_[fan_start_[v] + i];
      if (dead_[t]) continue;
      const Tri& tr = tris_[t];
      if (tr[0] == other || tr[1] == other || tr[2] == other) continue;
      Vec3 q[3];
      for (int k = 0; k < 3; ++k) q[k] = tr[k] == v ? p : pos_[tr[k]];
      if (!normal_ok(pos_[tr[0]], pos_[tr[1]], pos_[tr[2]], q[0], q[1], q[2], mc)) return false;
    }
  }
  return true;
}

// Collapses b into a at p: triangles on ab die, b's others take a, a's fan becomes the union
// (its triangles in scratch_ afterwards).
void Simplifier::collapse(std::uint32_t a, std::uint32_t b, const Vec3& p, std::size_t& live) {
  std::vector<std::uint32_t>& merged = scratch_;
  merged.clear();
  for (std::uint32_t i = 0; i < fan_count_[b]; ++i) {
    const std::uint32_t t = refs_[fan_start_[b] + i];
    if (dead_[t]) continue;
    Tri& tr = tris_[t];
    if (tr[0] == a || tr[1] == a || tr[2] == a) {
      dead_[t] = 1;
      --live;
      continue;
    }
    for (std::uint32_t& w : tr)
      if (w == b) w = a;
    merged.push_back(t);
  }
  bool feat = false;
  for (std::uint32_t i = 0; i < fan_count_[a]; ++i) {
    const std::uint32_t t = refs_[fan_start_[a] + i];
    if (!dead_[t]) merged.push_back(t);
  }
  for (std::uint32_t t : merged) feat = feat || feature_tri_[t];
  set_fan(a, merged);
  fan_count_[b] = 0;
  vdead_[b] = 1;
  pos_[a] = p;
  quad_[a] += quad_[b];
  touches_feature_[a] = feat;
  ++stamp_[a];
}

void Simplifier::compact_fans() {
  if (refs_.size() <= 8 * tris_.size() + 1024) return;
  std::vector<std::uint32_t> pool;
  pool.reserve(tris_.size() * 3);
  for (std::uint32_t v = 0; v < pos_.size(); ++v) {
    const std::uint32_t s = static_cast<std::uint32_t>(pool.size());
    for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
      const std::uint32_t t = refs_[fan_start_[v] + i];
      if (!dead_[t]) pool.push_back(t);
    }
    fan_start_[v] = s;
    fan_count_[v] = static_cast<std::uint32_t>(pool.size() - s);
  }
  refs_.swap(pool);
}

std::uint32_t key_bits(const HeapEntry& e) {
  std::uint32_t k;
  std::memcpy(&k, &e.cost, 4);
  return k;
}

/// Total order of the pass lists: the radix heap's key (cost bits, last tier on top), then the ends
/// and stamps, so sorting gives one result for any thread count. A functor, so sorts inline it.
struct KeyBefore {
  bool operator()(const HeapEntry& x, const HeapEntry& y) const {
    const std::uint64_t a = (std::uint64_t{key_bits(x)} << 32) | x.keep;
    const std::uint64_t b = (std::uint64_t{key_bits(y)} << 32) | y.keep;
    if (a != b) return a < b;
    const std::uint64_t c = (std::uint64_t{x.remove} << 32) | (std::uint32_t{x.stamp_keep} << 16) | x.stamp_remove;
    const std::uint64_t d = (std::uint64_t{y.remove} << 32) | (std::uint32_t{y.stamp_keep} << 16) | y.stamp_remove;
    return c < d;
  }
};
constexpr KeyBefore key_before{};

// Batched passes (the scheme of meshoptimizer's simplifier, Kapoulkine 2017-2023, and of the
// independent-set parallel decimation of Franc & Skala 2001 / Papageorgiou & Platis 2015): the
// candidate list, sorted by cost, is walked from the cheapest; a candidate is selected when none of
// the triangles around its two ends was taken by an earlier selection of the pass (so the selected
// collapses touch disjoint triangle sets and are independent: the checks of one see none of the
// others' changes), up to 1.5x the cost at the pass's half goal (meshoptimizer's error limit) and
// at most `live - handoff` triangles. The selected collapses are then checked (link, flips) and
// applied in vertex order (memory locality instead of the heap's random cost order); the edges of
// the changed vertices are evaluated again, sorted and merged into the list. Below `handoff`
// triangles the heap takes over for the exact budget. Everything is a fixed function of the list
// order: results do not depend on timing or thread count.
void Simplifier::batched_passes(std::vector<HeapEntry>& list, std::size_t handoff, std::size_t& live,
                                SimplifyResult& r) {
  tbb::parallel_sort(list.begin(), list.end(), key_before);
  std::vector<std::uint32_t> taken(pos_.size(), 0);  // pass that used the vertex as an end
  struct Scratch {
    std::vector<std::uint32_t> mark, slot;
    std::vector<Neighbour> nbr;
    std::uint32_t id = 0;
  };
  const std::size_t nv = pos_.size();
  tbb::enumerable_thread_specific<Scratch> scratch_tls([nv] {
    Scratch sc;
    sc.mark.assign(nv, 0), sc.slot.assign(nv, 0);
    return sc;
  });
  std::uint32_t pass = 0;
  std::vector<HeapEntry> kept, fresh, merged_list;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> selected;  // (keep, remove)
  while (live > handoff && !list.empty()) {
    ++pass;
    const std::size_t goal = live - handoff;
    const HeapEntry& at = list[std::min(list.size() - 1, goal / 2)];
    std::uint32_t limit = std::numeric_limits<std::uint32_t>::max();
    if (!(key_bits(at) & 0x80000000u)) {
      const float lim = at.cost * 1.5f;
      std::memcpy(&limit, &lim, 4);
      if (!std::isfinite(lim)) limit = 0x7fffffffu;
    }
    kept.clear();
    kept.reserve(list.size());
    selected.clear();
    std::size_t planned = 0;
    std::size_t i = 0;
    for (; i < list.size(); ++i) {
      const HeapEntry& e = list[i];
      if (planned >= goal || key_bits(e) > limit) break;
      const std::uint32_t a = e.keep, b = e.remove;
      if (vdead_[a] || vdead_[b] || static_cast<std::uint16_t>(stamp_[a]) != e.stamp_keep ||
          static_cast<std::uint16_t>(stamp_[b]) != e.stamp_remove)
        continue;  // stale: dropped
      if (taken[a] == pass || taken[b] == pass) {
        kept.push_back(e);
        continue;
      }
      taken[a] = taken[b] = pass;
      selected.push_back({a, b});
      planned += 2;
    }
    // The rest is kept without its stale entries (ends removed or changed since evaluation).
    for (; i < list.size(); ++i) {
      const HeapEntry& e = list[i];
      if (!vdead_[e.keep] && !vdead_[e.remove] && static_cast<std::uint16_t>(stamp_[e.keep]) == e.stamp_keep &&
          static_cast<std::uint16_t>(stamp_[e.remove]) == e.stamp_remove)
        kept.push_back(e);
    }
    if (selected.empty()) break;
    // Independent collapses: checked and applied in vertex order.
    std::sort(selected.begin(), selected.end());
    std::vector<std::uint32_t> changed;
    for (const auto& [a, b] : selected) {
      int shared = 0;
      const bool seam = seam_edge(a, b, &shared);
      if (shared == 0) continue;
      Candidate c;
      if (!direction(a, b, seam, c)) continue;
      if (!link_ok(a, b, shared)) {
        ++rejected_link_;
        continue;
      }
      if (!flip_ok(a, b, c.p)) {
        ++rejected_flip_;
        continue;
      }
      collapse(a, b, c.p, live);
      ++r.collapses;
      changed.push_back(a);
    }
    if (changed.empty()) {
      list.swap(kept);
      break;
    }
    compact_fans();
    // New candidates of the changed vertices (in vertex order), sorted and merged into the list.
    // Evaluation only reads the mesh: in parallel over fixed chunks of `changed`, concatenated in
    // order (the list is sorted afterwards anyway; the chunks keep it independent of threads).
    constexpr std::size_t kChunk = 1024;
    std::vector<std::vector<HeapEntry>> chunks((changed.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size()), [&](const tbb::blocked_range<std::size_t>& rg) {
      Scratch& sc = scratch_tls.local();
      for (std::size_t ci = rg.begin(); ci < rg.end(); ++ci) {
        std::vector<HeapEntry>& out = chunks[ci];
        for (std::size_t k0 = ci * kChunk; k0 < std::min(changed.size(), (ci + 1) * kChunk); ++k0) {
          const std::uint32_t v = changed[k0];
          ++sc.id;
          sc.nbr.clear();
          for (std::uint32_t k = 0; k < fan_count_[v]; ++k) {
            const std::uint32_t t = refs_[fan_start_[v] + k];
            if (dead_[t]) continue;
            const std::uint32_t f = face_[t];
            for (std::uint32_t w : tris_[t]) {
              if (w == v) continue;
              if (sc.mark[w] != sc.id) {
                sc.mark[w] = sc.id;
                sc.slot[w] = static_cast<std::uint32_t>(sc.nbr.size());
                sc.nbr.push_back({w, 1, f, false});
              } else {
                Neighbour& n = sc.nbr[sc.slot[w]];
                ++n.count;
                n.differ = n.differ || n.face != f;
              }
            }
          }
          for (const Neighbour& n : sc.nbr) {
            Candidate c;
            if (evaluate(v, n.w, n.count != 2 || n.differ, c)) out.push_back(entry_of(c));
          }
        }
      }
    });
    fresh.clear();
    for (const auto& ch : chunks) fresh.insert(fresh.end(), ch.begin(), ch.end());
    tbb::parallel_sort(fresh.begin(), fresh.end(), key_before);
    merged_list.resize(kept.size() + fresh.size());
    std::merge(kept.begin(), kept.end(), fresh.begin(), fresh.end(), merged_list.begin(), key_before);
    list.swap(merged_list);
  }
}

void Simplifier::run(std::size_t target, SimplifyResult& r) {
  const std::size_t nv = pos_.size(), nt = tris_.size();
  dead_.assign(nt, 0);
  vdead_.assign(nv, 0);
  build_fans();
  // Degenerate input triangles (repeated index) are dropped first.
  std::size_t live = nt;
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& tr = tris_[t];
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) dead_[t] = 1, --live;
  }
  // Per-vertex quadrics in parallel: each vertex sums the planes of its fan in triangle order, the
  // same order (and bits) as a serial sweep over the triangles, for any thread count.
  quad_.assign(nv, Quadric{});
  for_vertex_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t) {
    for (std::uint32_t v = v0; v < v1; ++v)
      for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
        const std::uint32_t t = refs_[fan_start_[v] + i];
        if (dead_[t]) continue;
        const auto& tr = tris_[t];
        const Vec3 n2 = cross(pos_[tr[1]] - pos_[tr[0]], pos_[tr[2]] - pos_[tr[0]]);
        const double len = norm(n2);
        if (!(len > 0)) continue;
        const Vec3 n = n2 / len;
        const double area = 0.5 * len;
        const double d = -dot(n, pos_[tr[0]]);
        quad_[v].add_plane(n, d, area);
      }
  });
  if (o_.prevent_self_intersections) {
    guard_ = true;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tr = tris_[t];
      surface_area_ += 0.5 * norm(cross(pos_[tr[1]] - pos_[tr[0]], pos_[tr[2]] - pos_[tr[0]]));
    }
    tri_mark_.assign(nt, 0);
    rebuild_grid(live);
  }
  mark_a_.assign(nv, 0), mark_b_.assign(nv, 0), slot_.assign(nv, 0);
  stamp_.assign(nv, 0);
  cls_.assign(nv, kInterior);
  locked_.assign(nv, 0);
  touches_feature_.assign(nv, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    if (dead_[t] || !feature_tri_[t]) continue;
    for (std::uint32_t v : tris_[t]) touches_feature_[v] = 1;
  }
  if (o_.feature_mode == FeatureMode::lock) locked_ = touches_feature_;
  // Constrained edges: found in parallel (per vertex v, its edges to w > v in fan order), then
  // counted and given their penalty planes serially in that order (deterministic sums).
  struct SeamEdge {
    std::uint32_t v, w;
    int shared;
  };
  std::vector<std::vector<SeamEdge>> seam_blocks(num_blocks(nv));
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> seen_tls(
      [&] { return std::vector<std::uint32_t>(nv, kNone); });
  for_vertex_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t block) {
    std::vector<std::uint32_t>& seen = seen_tls.local();
    for (std::uint32_t v = v0; v < v1; ++v)
      for_each_upper_neighbour(v, seen, [&](std::uint32_t w) {
        int shared = 0;
        if (seam_edge(v, w, &shared)) seam_blocks[block].push_back({v, w, shared});
      });
  });
  std::vector<std::uint8_t> seam_count(nv, 0);
  for (const auto& block : seam_blocks)
    for (const SeamEdge& se : block) {
      const std::uint32_t v = se.v, w = se.w;
      seam_count[v] = static_cast<std::uint8_t>(std::min(255, seam_count[v] + 1));
      seam_count[w] = static_cast<std::uint8_t>(std::min(255, seam_count[w] + 1));
      if (se.shared > 2) seam_count[v] = seam_count[w] = 255;  // non-manifold edge: corners
      // Penalty planes through the edge, perpendicular to each triangle on it.
      const Vec3 e = pos_[w] - pos_[v];
      for (std::uint32_t j = 0; j < fan_count_[v]; ++j) {
        const std::uint32_t u = refs_[fan_start_[v] + j];
        if (dead_[u]) continue;
        const Tri& tr = tris_[u];
        if (tr[0] != w && tr[1] != w && tr[2] != w) continue;
        const Vec3 fn = cross(pos_[tr[1]] - pos_[tr[0]], pos_[tr[2]] - pos_[tr[0]]);
        Vec3 n = cross(e, fn);
        const double l = norm(n);
        if (!(l > 0)) continue;
        n = n / l;
        const double d = -dot(n, pos_[v]);
        const double w8 = o_.seam_weight * squared_norm(e);
        quad_[v].add_plane(n, d, w8);
        quad_[w].add_plane(n, d, w8);
      }
    }
  std::vector<std::vector<SeamEdge>>().swap(seam_blocks);
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (fan_count_[v] == 0) continue;
    if (seam_count[v] == 2) cls_[v] = kSeam, ++r.seam_vertices;
    else if (seam_count[v] != 0) cls_[v] = kCorner, ++r.corner_vertices;
    if (locked_[v]) ++r.locked_vertices;
  }
  // Initial candidates in parallel (evaluate only reads the mesh), concatenated in vertex order so
  // the heap sees the same sequence for any thread count; the maximum unmodified cost is the
  // feature offset (weight mode).
  struct Initial {  // 24 bytes: the placement is recomputed when the entry is popped
    double cost;
    std::uint32_t keep, remove;
    bool last_tier;
  };
  std::vector<std::vector<Initial>> blocks(num_blocks(nv));
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> cand_seen_tls(
      [&] { return std::vector<std::uint32_t>(nv, kNone); });
  for_vertex_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t block) {
    std::vector<std::uint32_t>& seen = cand_seen_tls.local();
    std::vector<Initial>& out = blocks[block];
    out.reserve(3 * (v1 - v0));
    for (std::uint32_t v = v0; v < v1; ++v) {
      for_each_upper_neighbour(v, seen, [&](std::uint32_t w) {
        Candidate c;
        if (evaluate(v, w, c)) out.push_back({c.cost, c.keep, c.remove, c.last_tier});
      });
    }
  });
  double max_cost = 0;
  for (const auto& bl : blocks)
    for (const Initial& c : bl) max_cost = std::max(max_cost, c.cost);
  r.max_unmodified_cost = max_cost;
  const bool weight = o_.feature_mode == FeatureMode::weight;
  // Strictly above every unmodified cost even when that maximum is 0 (a flat mesh).
  if (weight) feature_offset_ = max_cost > 0 ? max_cost : std::numeric_limits<double>::min();
  const std::size_t handoff = target + std::max<std::size_t>(target, 1024);
  const bool batched =
      !guard_ && o_.batched_passes && live >= o_.batched_min_triangles && live > handoff + handoff / 2;
  std::vector<HeapEntry> list;
  for (auto& bl : blocks) {
    for (const Initial& i : bl) {
      Candidate c;
      c.cost = i.cost;
      if (weight && (touches_feature_[i.keep] || touches_feature_[i.remove])) c.cost += feature_offset_;
      c.keep = i.keep, c.remove = i.remove;
      c.stamp_keep = c.stamp_remove = 0;  // no vertex changed yet
      c.last_tier = i.last_tier;
      if (batched) list.push_back(entry_of(c));
      else heap_.push(entry_of(c));
    }
    std::vector<Initial>().swap(bl);
  }
  if (batched) {
    batched_passes(list, handoff, live, r);
    for (const HeapEntry& e : list) heap_.push(e);
    std::vector<HeapEntry>().swap(list);
  }

  // Collapses that would overshoot the budget are kept aside; if the budget cannot be met exactly
  // (only 2-triangle collapses left at budget + 1) they are retried to end at budget - 1.
  std::vector<HeapEntry> deferred;
  std::size_t floor = target;
  for (;;) {
    if (live <= target) break;
    if (heap_.empty()) {
      if (floor == target && target > 1 && live == target + 1 && !deferred.empty()) {
        floor = target - 1;
        for (const HeapEntry& d : deferred) heap_.push(d);
        deferred.clear();
        continue;
      }
      break;
    }
    const HeapEntry e = heap_.pop();
    const std::uint32_t a = e.keep, b = e.remove;
    if (vdead_[a] || vdead_[b] || static_cast<std::uint16_t>(stamp_[a]) != e.stamp_keep ||
        static_cast<std::uint16_t>(stamp_[b]) != e.stamp_remove)
      continue;
    int shared = 0;
    const bool seam = seam_edge(a, b, &shared);
    if (shared == 0) continue;  // no longer an edge
    Candidate c;
    if (!direction(a, b, seam, c)) continue;  // placement recomputed (same quadrics: same result)
    if (live - static_cast<std::size_t>(shared) < floor) {  // would overshoot the budget
      deferred.push_back(e);
      continue;
    }
    if (!link_ok(a, b, shared)) {
      ++rejected_link_;
      continue;
    }
    if (!flip_ok(a, b, c.p)) {
      ++rejected_flip_;
      continue;
    }
    if (guard_ && !intersection_ok(a, b, c.p)) {
      ++rejected_intersection_;
      continue;
    }
    // Collapse b into a at c.p.
    collapse(a, b, c.p, live);
    ++r.collapses;
    if (guard_) {
      if (live * 2 < grid_live_) rebuild_grid(live);
      else
        for (std::uint32_t t : scratch_) grid_insert(t);
    }
    push_edges_of(a);
    compact_fans();
  }
  r.rejected_link = rejected_link_, r.rejected_flip = rejected_flip_;
  r.rejected_intersection = rejected_intersection_;
}

std::size_t budget_of(const TriMesh& mesh, const SimplifyOptions& o, Error& err) {
  const std::size_t n = mesh.num_triangles();
  if (o.target_triangles > 0) {
    if (o.target_triangles > n) {
      err.reason = "triangle budget " + std::to_string(o.target_triangles) + " is larger than the mesh (" +
                   std::to_string(n) + " triangles)";
      return 0;
    }
    return o.target_triangles;
  }
  if (!(o.ratio > 0 && o.ratio <= 1)) {
    err.reason = o.ratio == 0 ? "no triangle budget: give target_triangles > 0 or a ratio in (0, 1]"
                              : "ratio must lie in (0, 1], got " + std::to_string(o.ratio);
    return 0;
  }
  const auto t = static_cast<std::size_t>(std::llround(o.ratio * static_cast<double>(n)));
  if (t == 0) {
    err.reason = "ratio " + std::to_string(o.ratio) + " leaves no triangle of " + std::to_string(n);
    return 0;
  }
  return t;
}

}  // namespace

Expected<SimplifyResult> simplify(const TriMesh& mesh, const SimplifyOptions& options) {
  const std::size_t nt = mesh.num_triangles();
  if (nt == 0) return Error{.reason = "the mesh has no triangles"};
  for (const Vec3& p : mesh.positions)
    if (!is_finite(p)) return Error{.reason = "the mesh has a non-finite vertex position"};
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t v : mesh.triangles[t])
      if (v >= mesh.num_vertices())
        return Error{.reason = "triangle " + std::to_string(t) + " has a vertex index out of range"};
  if (!options.face_ids.empty() && options.face_ids.size() != nt)
    return Error{.reason = "face_ids has " + std::to_string(options.face_ids.size()) + " entries for " +
                           std::to_string(nt) + " triangles"};
  Error err;
  const std::size_t target = budget_of(mesh, options, err);
  if (target == 0) return err;

  SimplifyResult r;
  r.input_triangles = nt;
  r.target_triangles = target;
  const Aabb box = mesh.bounds();
  r.bbox_diagonal = norm(box.extent());

  std::vector<std::uint32_t> face = options.face_ids;
  const bool have_faces = !face.empty();
  if (!have_faces) {
    face = options.sharp_angle_deg > 0 ? sharp_edge_regions(mesh, options.sharp_angle_deg)
                                       : std::vector<std::uint32_t>(nt, 0);
  }
  std::vector<std::uint32_t> features = options.feature_faces;
  std::sort(features.begin(), features.end());
  std::vector<std::uint8_t> feature_tri(nt, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    feature_tri[t] = std::binary_search(features.begin(), features.end(), face[t]) ? 1 : 0;
    r.feature_triangles_in += feature_tri[t];
  }
  if (!features.empty() && r.feature_triangles_in == 0)
    r.warnings.push_back("no triangle carries one of the feature face ids");

  TriMesh welded = weld_positions(mesh);
  r.input_vertices_welded = welded.num_vertices();
  // No self-intersections: plain QEM first, its result checked with the engine's exact self-clash;
  // only when it created an intersection is the run repeated with the per-collapse guard (which
  // costs about 10x). Either way the result has no self-intersection the input did not have.
  SimplifyOptions plain = options;
  plain.prevent_self_intersections = options.prevent_self_intersections && options.guard_every_collapse;
  const SimplifyResult before = r;
  // The welded input is not copied for a possible rerun (rare): it is welded again then.
  auto sp = std::make_unique<Simplifier>(std::move(welded), face, feature_tri, plain);
  sp->run(target, r);
  // Surviving triangles in input order, unused vertices dropped (new ids in order of first use).
  auto compact = [&](const Simplifier& s, std::vector<std::uint32_t>* out_face) {
    TriMesh m;
    std::vector<std::uint32_t> used(s.pos_.size(), kNone);
    for (std::size_t t = 0; t < nt; ++t) {
      if (s.dead_[t]) continue;
      Tri tr = s.tris_[t];
      for (std::uint32_t& v : tr) {
        if (used[v] == kNone) {
          used[v] = static_cast<std::uint32_t>(m.positions.size());
          m.positions.push_back(s.pos_[v]);
        }
        v = used[v];
      }
      m.triangles.push_back(tr);
      if (out_face) out_face->push_back(face[t]);
    }
    return m;
  };
  std::vector<std::uint32_t> out_face;
  TriMesh out = compact(*sp, &out_face);
  if (options.prevent_self_intersections && !options.guard_every_collapse) {
    // The input's own intersections (touching parts of an assembly, say) cannot be removed: rerun
    // only when the plain result has more than the input.
    const std::size_t out_x = count_self_intersections(out);
    if (out_x > 0) {
      TriMesh input = weld_positions(mesh);
      if (out_x > count_self_intersections(input)) {
        r = before;
        r.guard_rerun = true;
        sp = std::make_unique<Simplifier>(std::move(input), face, feature_tri, options);
        sp->run(target, r);
        out_face.clear();
        out = compact(*sp, &out_face);
      }
    }
  }
  Simplifier& s = *sp;
  for (std::size_t t = 0; t < nt; ++t)
    if (!s.dead_[t]) r.feature_triangles_out += feature_tri[t];
  // Split along faces when face ids were given or regions were made.
  if (have_faces || options.sharp_angle_deg > 0) {
    r.mesh = split_by_face(out, out_face);
  } else {
    r.mesh = std::move(out);
  }
  if (have_faces) r.face_ids = std::move(out_face);
  r.reached = r.mesh.num_triangles() == target;
  if (!r.reached)
    r.warnings.push_back("budget " + std::to_string(target) + " not reached: " +
                         std::to_string(r.mesh.num_triangles()) +
                         " triangles remain (constrained seams/corners, locks, parity of a closed mesh, or "
                         "rejected collapses)");
  if (options.measure_error) {
    r.hausdorff = hausdorff(mesh, r.mesh).symmetric();
    r.error_bound = r.hausdorff;
    if (r.feature_triangles_in > 0) {
      std::vector<std::uint32_t> fin, fout;
      for (std::uint32_t t = 0; t < nt; ++t)
        if (feature_tri[t]) fin.push_back(t);
      const std::vector<std::uint32_t>& of = have_faces ? r.face_ids : std::vector<std::uint32_t>{};
      for (std::uint32_t t = 0; t < r.mesh.num_triangles(); ++t)
        if (!of.empty() && std::binary_search(features.begin(), features.end(), of[t])) fout.push_back(t);
      if (!have_faces) {  // regions from sharp edges: recompute the output's region of each triangle
        std::uint32_t i = 0;
        for (std::uint32_t t = 0; t < nt; ++t) {
          if (s.dead_[t]) continue;
          if (feature_tri[t]) fout.push_back(i);
          ++i;
        }
      }
      if (fout.empty()) {
        r.hausdorff_features = std::numeric_limits<double>::infinity();
      } else {
        r.hausdorff_features = hausdorff(submesh(mesh, fin), submesh(r.mesh, fout)).symmetric();
      }
    }
  }
  return r;
}

}  // namespace interfere
