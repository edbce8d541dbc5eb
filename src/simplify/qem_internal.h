// Internals of the QEM simplifier (issue #6, item 5), shared by the qem_*.cpp files: the quadric of
// Garland & Heckbert (SIGGRAPH 1997, §4), the 16-byte candidate entries, the radix heap and the
// Simplifier state. Not installed.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <functional>
#include <memory>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "vertex_map.h"
#include "interfere/simplify/qem.h"

namespace interfere::qem {

class ContactZone;  // contact_zone.h

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Allocator whose default construction leaves trivial elements uninitialised: large arrays are
/// first touched by the parallel loop that fills them instead of a serial zeroing pass (on this
/// project's 2-core VMs a fresh page costs about 2 us to fault in).
template <class T>
struct NoInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = NoInitAllocator<U>;
  };
  NoInitAllocator() = default;
  template <class U>
  NoInitAllocator(const NoInitAllocator<U>&) noexcept {}
  template <class U, class... A>
  void construct(U* p, A&&... a) {
    if constexpr (sizeof...(A) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
  }
};

/// Trivial (no member initialiser: see NoInitAllocator); `Quadric{}` is the zero quadric.
struct Quadric {
  // Symmetric 4x4 (a b c d)^T (a b c d): xx xy xz xw yy yz yw zz zw ww.
  double q[10];
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
  /// Minimiser of eval (§4): solves A p = -b by the cofactor inverse; false when A is near singular
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

static_assert(std::is_trivially_default_constructible_v<Quadric>);

enum VertexClass : std::uint8_t { kInterior = 0, kSeam = 1, kCorner = 2 };

struct Candidate {
  double cost;
  Vec3 p;
  std::uint32_t keep, remove;
  std::uint32_t stamp_keep, stamp_remove;
  bool last_tier = false;  ///< FeatureMode::last: ordered after every non-feature candidate
};

// Candidate entry: 16 bytes (the queue's cache misses dominate large runs). The placement is
// recomputed when an entry is taken; the 16-bit stamps invalidate entries whose end vertices
// changed since. `cost` holds the key bits: a non-negative float, top bit set for the last tier.
struct HeapEntry {
  float cost;
  std::uint32_t keep, remove;
  std::uint16_t stamp_keep, stamp_remove;
};
static_assert(sizeof(HeapEntry) == 16);
/// Candidate lists of the batched passes (millions of entries: written in parallel, never zeroed).
using EntryList = std::vector<HeapEntry, NoInitAllocator<HeapEntry>>;

inline std::uint32_t key_bits(const HeapEntry& e) {
  std::uint32_t k;
  std::memcpy(&k, &e.cost, 4);
  return k;
}

inline HeapEntry entry_of(const Candidate& c) {
  // Costs are >= 0 (eval clamps); +0.0f so that -0.0 cannot appear; the bits of a non-negative float
  // order like its value and leave the top bit free: set, it puts the entry in the last tier.
  HeapEntry e{static_cast<float>(c.cost) + 0.0f, c.keep, c.remove, static_cast<std::uint16_t>(c.stamp_keep),
              static_cast<std::uint16_t>(c.stamp_remove)};
  if (c.last_tier) {
    const std::uint32_t k = key_bits(e) | 0x80000000u;
    std::memcpy(&e.cost, &k, 4);
  }
  return e;
}

/// Radix heap (Ahuja, Mehlhorn, Orlin & Tarjan 1990) on the key bits: pushes are O(1) appends, a
/// pop redistributes one bucket sequentially. A radix heap needs keys that do not decrease below the
/// last popped key; a cheaper candidate created by a collapse (or a deferred one pushed again) goes
/// to a small binary heap instead, emptied first: pops come in exact cost order (equal keys in a
/// fixed order: the result is deterministic). Such keys were once raised to the last popped key,
/// which gave them back last in, first out: the collapses kept aside at budget + 1 then came back
/// dearest first (fandisk to an odd budget: 35x the Hausdorff distance of the even one below).
/// Equal keys in the buckets come out first in, first out: on flat regions (every cost 0) last in,
/// first out took the edges a collapse had just re-evaluated first, so one vertex swallowed its
/// neighbours one after the other, its fan grew and most candidates were refused as flips (a flat
/// 80x80 grid to 5 %: 384,363 refused for 6,159 collapses, now 15; fandisk 42 -> 10 ms).
class RadixHeap {
 public:
  bool empty() const { return size_ == 0 && below_.empty(); }
  void push(HeapEntry e) {
    const std::uint32_t k = key_bits(e);
    if (k < last_) {
      below_.push_back(e);
      std::push_heap(below_.begin(), below_.end(), later);
      return;
    }
    buckets_[bucket(k)].push_back(e);
    ++size_;
  }
  HeapEntry pop() {
    if (!below_.empty()) {
      std::pop_heap(below_.begin(), below_.end(), later);
      const HeapEntry e = below_.back();
      below_.pop_back();
      return e;
    }
    if (head0_ == buckets_[0].size()) {
      buckets_[0].clear();
      head0_ = 0;
      std::size_t i = 1;
      while (buckets_[i].empty()) ++i;
      std::uint32_t m = std::numeric_limits<std::uint32_t>::max();
      for (const HeapEntry& e : buckets_[i]) m = std::min(m, key_bits(e));
      last_ = m;
      std::vector<HeapEntry> moving;
      moving.swap(buckets_[i]);
      for (const HeapEntry& e : moving) buckets_[bucket(key_bits(e))].push_back(e);
      moving.clear();
      moving.swap(buckets_[i]);  // keep the capacity
    }
    const HeapEntry e = buckets_[0][head0_++];
    --size_;
    return e;
  }

 private:
  static bool later(const HeapEntry& x, const HeapEntry& y) { return key_bits(x) > key_bits(y); }
  std::size_t bucket(std::uint32_t k) const { return k == last_ ? 0 : 32 - std::countl_zero(k ^ last_); }
  std::vector<HeapEntry> buckets_[33];
  std::vector<HeapEntry> below_;  ///< keys below last_ (binary min-heap)
  std::uint32_t last_ = 0;
  std::size_t size_ = 0;  ///< entries in the buckets
  std::size_t head0_ = 0;  ///< next entry of bucket 0 (first in, first out)
};

constexpr std::uint32_t kBlock = 1024;  ///< vertices per parallel block (results do not depend on it)

inline std::size_t num_blocks(std::size_t n) { return (n + kBlock - 1) / kBlock; }

/// f(first, last, block) over fixed blocks of [0, n), in parallel.
template <class F>
void for_blocks(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_blocks(n)), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b)
      f(static_cast<std::uint32_t>(b * kBlock), static_cast<std::uint32_t>(std::min(n, (b + 1) * kBlock)), b);
  });
}

/// Wall time of the phases of one run, appended to SimplifyResult::phases.
class PhaseClock {
 public:
  explicit PhaseClock(SimplifyResult& r) : r_(r) {}
  void restart() { last_ = std::chrono::steady_clock::now(); }
  void lap(const char* phase) {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    for (auto& [name, sec] : r_.phases)
      if (name == phase) {
        sec += s;
        return;
      }
    r_.phases.emplace_back(phase, s);
  }

 private:
  SimplifyResult& r_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// Per-thread scratch of the local operations: marks over the vertices (a fresh `id` per use
/// instead of clearing), or a small vertex map (vertex_map.h) where the marks, 12 bytes per vertex
/// and thread, would cost too much memory (see Simplifier::make_scratch); and the gathered
/// neighbours of a vertex.
struct Scratch {
  struct Neighbour {
    std::uint32_t w, count, face;
    bool differ;
  };
  /// A live triangle of a fan with its corners (snapshot of one collapse's two fans).
  struct FanTri {
    std::uint32_t t;
    Tri tr;
  };
  std::vector<std::uint32_t> mark_a, mark_b, slot;  ///< empty: the map instead
  std::uint32_t id = 0;
  VertexMap map;
  std::vector<Neighbour> nbr;
  std::vector<FanTri> fan_a, fan_b;  ///< live fans of the collapse's keep and remove ends
  int shared = 0;                    ///< live triangles on the collapsed edge
  bool seam = false;                 ///< the edge is constrained (see gather_neighbours)
  /// A seam collapse of a batched pass that removes a triangle of a face with fewer than
  /// kFragileFace triangles at the pass's start: left to the serial sweep (see face_ok).
  bool fragile = false;
  /// With marks over `marked` vertices (0: the map).
  explicit Scratch(std::size_t marked) {
    if (marked > 0) mark_a.assign(marked, 0), mark_b.assign(marked, 0), slot.assign(marked, 0);
  }
};

class Simplifier {
 public:
  Simplifier(TriMesh mesh, std::vector<std::uint32_t> face, std::vector<std::uint8_t> feature_tri,
             const SimplifyOptions& o)
      : pos_(std::move(mesh.positions)),
        tris_(std::move(mesh.triangles)),
        face_(std::move(face)),
        feature_tri_(std::move(feature_tri)),
        o_(o) {}

  Simplifier(const Simplifier&) = default;  ///< a copy (the handoff snapshot) has no scratch yet
  Simplifier& operator=(const Simplifier&) = delete;

  void run(std::size_t target, SimplifyResult& r);
  /// Large meshes: the run keeps a copy of its state where the batched passes hand over to the
  /// heap, so that a guarded rerun can start there instead of repeating the passes (resume).
  void keep_handoff() { keep_handoff_ = true; }
  /// The state kept at the handoff (null when none was kept: no batched passes, a small mesh).
  struct Handoff;
  std::shared_ptr<const Handoff> handoff() const { return handoff_; }
  /// A run from a kept handoff: the copy's heap phase, with the handoff check and guard of this
  /// Simplifier (set_guard_region, set_handoff_check); r's counters continue the copy's.
  static std::unique_ptr<Simplifier> resume(const Handoff& h, std::vector<Aabb> region, const ContactZone* zone,
                                            std::function<bool(const Simplifier&)> clean, std::size_t target,
                                            SimplifyResult& r);
  /// With prevent_self_intersections: only collapses whose moved triangles reach one of these boxes
  /// are checked by the guard (empty: every collapse).
  /// The grid then holds only the triangles near the region (each box grown by its diagonal), and
  /// a guarded collapse whose moved triangles leave that neighbourhood is refused (conservative).
  void set_guard_region(std::vector<Aabb> boxes) {
    guard_boxes_ = std::move(boxes);
    guard_all_ = guard_outer_all_ = Aabb{};
    guard_outer_.clear();
    for (const Aabb& b : guard_boxes_) {
      guard_all_.expand(b);
      const double g = norm(b.extent());
      guard_outer_.push_back({b.lo - Vec3{g, g, g}, b.hi + Vec3{g, g, g}});
      guard_outer_all_.expand(guard_outer_.back());
    }
  }
  /// The guard allows a new intersecting pair inside the input's contact zone (null: none).
  void set_contact_zone(const ContactZone* zone) { zone_ = zone; }
  /// Rerun that guards the heap phase only: the batched passes run as in the plain run (same
  /// options: the same collapses), then `clean()` judges the mesh at the handoff (see live_mesh);
  /// if it holds, every heap collapse is guarded, else the run stops there with handoff_failed().
  void set_handoff_check(std::function<bool()> clean) { handoff_check_ = std::move(clean); }
  bool handoff_failed() const { return handoff_failed_; }
  /// The live triangles as a mesh (unused vertices dropped) and each one's input triangle number.
  TriMesh live_mesh(std::vector<std::uint32_t>& origin) const;
  std::vector<Vec3> pos_;
  std::vector<Tri> tris_;
  std::vector<std::uint32_t> face_;
  std::vector<std::uint8_t> feature_tri_;
  std::vector<std::uint8_t> dead_;

 private:
  // Compaction (qem_compact.cpp): the live vertices and triangles renumbered densely in order (the
  // candidates' ends too; `sorted`, the length of the list's sorted prefix, follows);
  // uncompact_triangles restores the input's triangle numbering at the end.
  void compact_mesh(EntryList& list, std::size_t& sorted, std::size_t live);
  void uncompact_triangles(std::size_t input_triangles);
  std::vector<std::uint32_t> tri_origin_;  ///< input index of each triangle (empty: not compacted)
  // Setup (qem_run.cpp).
  void build_fans();
  void vertex_quadrics();
  void classify_vertices(SimplifyResult& r);
  /// One candidate per live edge (from its smaller end), in vertex order; in parallel.
  EntryList edge_candidates();
  void heap_loop(std::size_t target, std::size_t& live, SimplifyResult& r);
  /// From the handoff on: the handoff check (if any), the guard, the heap to the budget.
  void finish(EntryList& list, std::size_t live, std::size_t target, SimplifyResult& r, PhaseClock& clock);
  /// SimplifyOptions::progress: the fraction of the collapses from `progress_from_` live triangles
  /// to the target done, reported in steps of 2 %.
  void report_progress(std::size_t live) {
    if (!o_.progress || progress_from_ <= progress_target_) return;
    const double f = double(progress_from_ - std::min(live, progress_from_)) / double(progress_from_ - progress_target_);
    if (f - progress_last_ < 0.02 && f < 1) return;
    progress_last_ = f;
    o_.progress(std::min(1.0, f));
  }
  std::size_t progress_from_ = 0, progress_target_ = 0;
  double progress_last_ = -1;
  bool keep_handoff_ = false;
  std::shared_ptr<const Handoff> handoff_;
  std::size_t input_triangles_ = 0;
  // Local operations (qem_local.cpp); `sc` is the calling thread's scratch.
  void gather_neighbours(std::uint32_t v, Scratch& sc) const;
  template <class Index>
  void gather_with(std::uint32_t v, Scratch& sc, Index index) const;
  /// Candidates of every edge at v.
  void candidates_of(std::uint32_t v, Scratch& sc, std::vector<HeapEntry>& out) const;
  bool evaluate(std::uint32_t a, std::uint32_t b, bool seam, Candidate& out) const;
  bool direction(std::uint32_t keep, std::uint32_t remove, bool seam, Candidate& out) const;
  // One collapse (a keeps, b goes) works on one snapshot of both fans, taken by `snapshot`, which
  // also counts the triangles on ab (sc.shared) and tests the seam (sc.seam). With range != kNone
  // (batched passes) it returns false, taking nothing, when a triangle of either fan holds an end
  // of another range's selected collapse.
  bool snapshot(std::uint32_t a, std::uint32_t b, Scratch& sc, std::uint32_t range = kNone) const;
  bool link_ok(std::uint32_t a, std::uint32_t b, Scratch& sc) const;
  /// Every face losing triangles on ab keeps one (face_live_, exact: serial contexts only).
  bool face_ok(std::uint32_t a, const Scratch& sc) const;
  static constexpr std::int32_t kFragileFace = 32;
  /// Face ids dense (0..n-1, the same equalities) and their live triangles counted, when the mesh
  /// has two faces or more (run's setup).
  void count_faces();
  bool flip_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc) const;
  /// Collapses b into a at p: the triangles on ab die (counted in `died`), b's others take a; a's
  /// new fan (live triangles) is left in `merged` for the caller to store. The faces of the dead
  /// triangles lose them in face_live_, or, with `died_faces` (ranges of a batched pass, in
  /// parallel), are listed there for the caller to subtract.
  void collapse(std::uint32_t a, std::uint32_t b, const Vec3& p, const Scratch& sc,
                std::vector<std::uint32_t>& merged, std::size_t& died,
                std::vector<std::uint32_t>* died_faces = nullptr);
  void set_fan(std::uint32_t v, const std::vector<std::uint32_t>& tris);
  void reserve_fans(std::size_t extra);
  bool movable(std::uint32_t v) const { return cls_[v] == kInterior && !locked_[v]; }
  /// Evaluates the edges from v to the neighbours [first, last) into out (room for last - first
  /// entries), returns how many were written; with `mark`, only the neighbours w with
  /// mark[w] != pass or w > v (an edge between two marked vertices is evaluated from its smaller
  /// end).
  std::size_t evaluate_neighbours(std::uint32_t v, const Scratch::Neighbour* first, const Scratch::Neighbour* last,
                                  HeapEntry* out, const std::uint32_t* mark = nullptr, std::uint32_t pass = 0) const;
  /// The same for the gathered neighbours (see gather_neighbours), appended to out.
  template <class Vector>
  void evaluate_gathered(std::uint32_t v, const Scratch& sc, Vector& out, const std::uint32_t* mark = nullptr,
                         std::uint32_t pass = 0) const {
    const std::size_t n0 = out.size();
    out.resize(n0 + sc.nbr.size());
    out.resize(n0 + evaluate_neighbours(v, sc.nbr.data(), sc.nbr.data() + sc.nbr.size(), out.data() + n0, mark, pass));
  }
  // Batched passes (qem_passes.cpp).
  std::size_t apply_selected(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& selected,
                             std::size_t& live, std::vector<std::uint32_t>& changed);
  void batched_passes(EntryList& list, std::size_t handoff, std::size_t& live, SimplifyResult& r,
                      PhaseClock& clock);
  // Self-intersection guard (qem_guard.cpp).
  void start_guard(std::size_t live);
  std::function<bool()> handoff_check_;
  bool handoff_failed_ = false;
  /// The collapse of remove into keep at p (fans in sc) would make a moved triangle meet another:
  /// it reaches the guard region and fails the intersection test. Only with guard_.
  bool guard_refuses(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc);
  /// The moved triangles (box `moved`, see moved_box) meet no other triangle.
  bool intersection_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc, const Aabb& moved);
  /// The guard checks a collapse whose moved triangles have the box `moved` (it reaches the region).
  bool guarded(const Aabb& moved) const;
  /// Registers the live triangles of v's fan at their current positions.
  void grid_insert_fan(std::uint32_t v);
  void grid_insert(std::uint32_t t);
  void rebuild_grid(std::size_t live);
  template <class F>
  void grid_cells(const Aabb& box, F&& f) const;
  double grid_cell_count(const Aabb& box) const;
  static constexpr double kMaxCells = 512;  ///< a triangle spanning more goes to grid_big_

  const SimplifyOptions& o_;
  std::vector<std::uint32_t> fan_start_, fan_count_;
  /// Per vertex block: the neighbours w > v of its vertices in order (classify_vertices ->
  /// edge_candidates), upper_count_[v] of them for v.
  std::vector<std::vector<Scratch::Neighbour>> upper_;
  std::vector<std::uint32_t> upper_count_;
  using Refs = std::vector<std::uint32_t, NoInitAllocator<std::uint32_t>>;
  Refs refs_, refs_spare_;  ///< the fans' triangle lists (and the buffer reserve_fans packs into)
  std::vector<Quadric, NoInitAllocator<Quadric>> quad_;
  std::vector<std::uint8_t> cls_, locked_, touches_feature_, vdead_;
  std::vector<std::uint32_t> stamp_;
  /// Per-thread Scratch; a copy of the Simplifier starts without (see make_scratch).
  struct ScratchPool {
    std::unique_ptr<tbb::enumerable_thread_specific<Scratch>> p;
    ScratchPool() = default;
    ScratchPool(const ScratchPool&) {}
    tbb::enumerable_thread_specific<Scratch>* operator->() const { return p.get(); }
  };
  void make_scratch() {
    // Marks are the faster (apply 10 % faster than the map at 10^6 triangles, 25 % at 35,000);
    // they are used unless they would add more than about a tenth to the run's memory (some 400
    // bytes per vertex): up to 3 threads, or small meshes (up to 2^18 vertices: 3 MB a thread).
    const std::size_t nv = pos_.size();
    const bool marks = nv <= (std::size_t{1} << 18) || tbb::this_task_arena::max_concurrency() <= 3;
    const std::size_t marked = marks ? nv : 0;
    tls_.p = std::make_unique<tbb::enumerable_thread_specific<Scratch>>([marked] { return Scratch(marked); });
  }
  ScratchPool tls_;
  struct Owner {
    std::uint32_t pass = 0, range = 0;
  };
  std::vector<Owner> owner_;  ///< range of the selected collapse a vertex is an end of (batched passes)
  std::uint32_t owner_pass_ = 0;
  double feature_offset_ = 0;
  RadixHeap heap_;
  std::vector<std::uint32_t> merged_;
  std::size_t rejected_link_ = 0, rejected_flip_ = 0, rejected_intersection_ = 0, rejected_face_ = 0;
  /// Live triangles per (dense) face id, and their count when the current batched pass began;
  /// empty: one face (nothing to keep).
  std::vector<std::int32_t> face_live_, face_pass_;
  // Self-intersection guard: a uniform hash grid of triangle boxes (entries may be stale: every
  // candidate is re-checked against the current mesh).
  bool guard_ = false;
  const ContactZone* zone_ = nullptr;
  std::vector<Aabb> guard_boxes_;  ///< guard region (empty: everywhere)
  std::vector<Aabb> guard_outer_;  ///< its neighbourhood, where the grid is kept
  Aabb guard_all_, guard_outer_all_;
  bool near_region(const Aabb& b) const;    ///< overlaps the neighbourhood (always without a region)
  bool within_region(const Aabb& b) const;  ///< inside one neighbourhood box (always without a region)
  Aabb moved_box(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc) const;
  double cell_ = 1;
  Vec3 origin_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;
  std::vector<std::uint32_t> grid_big_;  ///< triangles spanning more than kMaxCells cells
  struct GuardMark {  ///< per triangle: last scan that examined it, last cell scan that kept it
    std::uint32_t tri = 0, cell = 0;
  };
  std::vector<GuardMark> guard_mark_;
  std::uint32_t tri_mark_id_ = 0, cell_mark_id_ = 0;
  struct GuardMoved {  ///< a triangle a guarded collapse moves, at its new place
    Tri tr;
    std::array<Vec3, 3> c;
    Aabb box;
  };
  std::vector<GuardMoved> guard_moved_;
  double surface_area_ = 0;
  std::size_t grid_live_ = 0;  ///< live triangles when the grid was last built
  std::size_t grid_size_ = 0, grid_inserted_ = 0;  ///< entries then, entries added since
  bool grid_stale(std::size_t live) const;        ///< time to rebuild the grid
};

/// The state of a run where the batched passes handed over to the heap (see keep_handoff).
struct Simplifier::Handoff {
  Simplifier state;
  EntryList list;
  std::size_t live = 0;
  SimplifyResult counters;  ///< r at the handoff (its phases are not used)
};

}  // namespace interfere::qem
