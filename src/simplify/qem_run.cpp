// One simplification run (Garland & Heckbert, SIGGRAPH 1997): per-vertex area-weighted plane
// quadrics (§4), penalty planes through constrained edges (§6.1), vertex classes (interior, seam,
// corner), the initial candidates with the assembly-feature offset of He & Xu (SJTU 2023, §3.3),
// the batched passes for large meshes (qem_passes.cpp) and the min-heap loop to the exact budget.
// The setup is parallel over fixed vertex blocks; every sum is taken in a fixed order, so results
// are bit-identical for any thread count.
#include <numeric>

#include "qem_internal.h"
#include "radix_sort.h"

namespace interfere::qem {

// Per-vertex quadrics in parallel: each vertex sums the planes of its fan's triangles in fan order,
// the same order and bits as a serial sweep, for any thread count. Small meshes compute each
// triangle's plane once into an array; large ones compute it at each of its three corners (the same
// bits), since the array's fresh pages cost more than the arithmetic (10^6 triangles: 40 MB).
void Simplifier::vertex_quadrics() {
  struct Plane {
    Vec3 n;
    double d, w;  ///< w = area; 0: degenerate or dead (skipped)
  };
  const auto plane_of = [&](std::uint32_t t) {
    Plane p{{0, 0, 0}, 0, 0};
    if (dead_[t]) return p;
    const auto& tr = tris_[t];
    const Vec3 n2 = cross(pos_[tr[1]] - pos_[tr[0]], pos_[tr[2]] - pos_[tr[0]]);
    const double len = norm(n2);
    if (!(len > 0)) return p;
    const Vec3 n = n2 / len;
    return Plane{n, -dot(n, pos_[tr[0]]), 0.5 * len};
  };
  constexpr std::size_t kPlaneArrayMax = std::size_t{1} << 18;
  std::vector<Plane> plane(tris_.size() <= kPlaneArrayMax ? tris_.size() : 0);
  if (!plane.empty()) {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(plane.size()), 1 << 12),
                      [&](const tbb::blocked_range<std::uint32_t>& rg) {
                        for (std::uint32_t t = rg.begin(); t < rg.end(); ++t) plane[t] = plane_of(t);
                      });
  }
  quad_.resize(pos_.size());  // first touched in parallel below (no zeroing pass)
  for_blocks(pos_.size(), [&](std::uint32_t v0, std::uint32_t v1, std::size_t) {
    for (std::uint32_t v = v0; v < v1; ++v) {
      Quadric q{};
      for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
        const std::uint32_t t = refs_[fan_start_[v] + i];
        const Plane p = plane.empty() ? plane_of(t) : plane[t];
        if (p.w > 0) q.add_plane(p.n, p.d, p.w);
      }
      quad_[v] = q;
    }
  });
}

// Constrained edges: found in parallel (per vertex v, its edges to w > v in fan order), then
// counted and given their penalty planes serially in that order (deterministic sums). A vertex on
// two constrained edges is a seam vertex, on one or three and more (or on a non-manifold edge) a
// corner.
void Simplifier::classify_vertices(SimplifyResult& r) {
  const std::size_t nv = pos_.size();
  struct SeamEdge {
    std::uint32_t v, w;
    int shared;
  };
  std::vector<std::vector<SeamEdge>> seam_blocks(num_blocks(nv));
  // The same sweep keeps each vertex's larger neighbours for edge_candidates (no second gather).
  upper_.assign(num_blocks(nv), {});
  upper_count_.assign(nv, 0);
  for_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t block) {
    Scratch& sc = tls_->local();
    std::vector<Scratch::Neighbour>& upper = upper_[block];
    for (std::uint32_t v = v0; v < v1; ++v) {
      gather_neighbours(v, sc);
      for (const Scratch::Neighbour& n : sc.nbr) {
        if (n.w <= v) continue;
        upper.push_back(n);
        ++upper_count_[v];
        if (n.count != 2 || n.differ) seam_blocks[block].push_back({v, n.w, int(n.count)});
      }
    }
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
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (fan_count_[v] == 0) continue;
    if (seam_count[v] == 2) cls_[v] = kSeam, ++r.seam_vertices;
    else if (seam_count[v] != 0) cls_[v] = kCorner, ++r.corner_vertices;
    if (locked_[v]) ++r.locked_vertices;
  }
}

// One candidate per live edge, evaluated in parallel from the edge's smaller end (evaluation only
// reads the mesh; the neighbours are those kept by classify_vertices), written straight into the
// list at each vertex block's offset (its count of larger neighbours bounds its candidates); the
// gaps left by edges with no valid direction are closed up in order: the same sequence for any
// thread count.
EntryList Simplifier::edge_candidates() {
  const std::size_t nv = pos_.size(), nb = num_blocks(nv);
  std::vector<std::size_t> offset(nb + 1, 0), written(nb, 0);
  for (std::size_t b = 0; b < nb; ++b) offset[b + 1] = offset[b] + upper_[b].size();
  EntryList list(offset.back());
  for_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t block) {
    HeapEntry* out = list.data() + offset[block];
    std::size_t n = 0;
    const Scratch::Neighbour* upper = upper_[block].data();
    for (std::uint32_t v = v0; v < v1; ++v) {
      n += evaluate_neighbours(v, upper, upper + upper_count_[v], out + n);
      upper += upper_count_[v];
    }
    written[block] = n;
    std::vector<Scratch::Neighbour>().swap(upper_[block]);
  });
  std::vector<std::uint32_t>().swap(upper_count_);
  std::size_t k = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    if (k != offset[b]) std::copy_n(list.begin() + offset[b], written[b], list.begin() + k);  // k < offset[b]
    k += written[b];
  }
  list.resize(k);
  return list;
}

void Simplifier::run(std::size_t target, SimplifyResult& r) {
  PhaseClock clock(r);
  const std::size_t nv = pos_.size(), nt = tris_.size();
  input_triangles_ = nt;
  dead_.assign(nt, 0);
  vdead_.assign(nv, 0);
  make_scratch();
  build_fans();
  // Degenerate input triangles (repeated index) are dropped first.
  std::size_t live = nt;
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& tr = tris_[t];
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) dead_[t] = 1, --live;
  }
  r.degenerate_triangles = nt - live;
  count_faces();
  progress_from_ = live, progress_target_ = target;
  report_progress(live);
  vertex_quadrics();
  if (o_.prevent_self_intersections) start_guard(live);
  stamp_.assign(nv, 0);
  cls_.assign(nv, kInterior);
  locked_.assign(nv, 0);
  touches_feature_.assign(nv, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    if (dead_[t] || !feature_tri_[t]) continue;
    for (std::uint32_t v : tris_[t]) touches_feature_[v] = 1;
  }
  if (o_.feature_mode == FeatureMode::lock) locked_ = touches_feature_;
  clock.lap("setup");
  classify_vertices(r);
  clock.lap("seams");
  // The initial candidates without the feature offset give the maximum unmodified cost, the
  // offset (weight mode, He & Xu §3.3); then the feature edges get it.
  EntryList list = edge_candidates();
  std::uint32_t max_bits = 0;
  for (const HeapEntry& e : list) max_bits = std::max(max_bits, key_bits(e) & 0x7fffffffu);
  float max_cost;
  std::memcpy(&max_cost, &max_bits, 4);
  r.max_unmodified_cost = max_cost;
  if (o_.feature_mode == FeatureMode::weight) {
    // Strictly above every unmodified cost even when that maximum is 0 (a flat mesh).
    feature_offset_ = max_cost > 0 ? double(max_cost) : std::numeric_limits<double>::min();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, list.size(), 1 << 16), [&](const tbb::blocked_range<std::size_t>& rg) {
      for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
        HeapEntry& e = list[i];
        if (touches_feature_[e.keep] || touches_feature_[e.remove])
          e.cost = static_cast<float>(double(e.cost) + feature_offset_) + 0.0f;
      }
    });
  }
  clock.lap("initial candidates");
  // The heap takes over at 1.5x the budget (at least budget + 1024): the passes are cheaper per
  // collapse (casing 35,516 -> 5,200: about 2 ms less than handing over at 2x, same Hausdorff).
  const std::size_t handoff = target + std::max<std::size_t>(target / 2, 1024);
  // With a guard everywhere (every collapse checked serially) the heap alone is as fast.
  const bool batched = !(guard_ && guard_boxes_.empty()) && o_.batched_passes && live >= o_.batched_min_triangles &&
                       live > handoff + handoff / 2;
  if (batched) batched_passes(list, handoff, live, r, clock);
  // Large meshes keep their state here for a guarded rerun (10^6 -> 10 % of the bumpy sphere: the
  // copy costs about 10 ms, repeating the passes about 300).
  if (batched && keep_handoff_ && nt >= o_.compact_min_triangles) {
    handoff_ = std::make_shared<const Handoff>(Handoff{*this, list, live, r});
    clock.lap("handoff copy");
  }
  finish(list, live, target, r, clock);
}

void Simplifier::count_faces() {
  face_live_.clear();
  face_pass_.clear();
  const std::size_t nt = tris_.size();
  if (face_.size() != nt || nt == 0) return;
  std::uint32_t hi = *std::max_element(face_.begin(), face_.end());
  if (hi == 0) return;  // one face
  if (hi >= 2 * nt) {  // sparse ids (an `other` id near 2^32): renumbered, the same equalities
    std::vector<std::uint32_t> ids(face_);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (std::uint32_t& f : face_)
      f = static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), f) - ids.begin());
    hi = static_cast<std::uint32_t>(ids.size() - 1);
  }
  face_live_.assign(hi + std::size_t{1}, 0);
  for (std::size_t t = 0; t < nt; ++t) face_live_[face_[t]] += dead_[t] ? 0 : 1;
  if (std::count_if(face_live_.begin(), face_live_.end(), [](std::int32_t n) { return n > 0; }) < 2) face_live_.clear();
}

void Simplifier::finish(EntryList& list, std::size_t live, std::size_t target, SimplifyResult& r, PhaseClock& clock) {
  if (handoff_check_) {  // a rerun that guards the heap only (see set_handoff_check)
    if (!handoff_check_()) {
      handoff_failed_ = true;
      return;
    }
    start_guard(live);
    clock.lap("check");
  }
  for (const HeapEntry& e : list) heap_.push(e);
  EntryList().swap(list);
  heap_loop(target, live, r);
  uncompact_triangles(input_triangles_);
  clock.lap("heap");
  r.rejected_link = rejected_link_, r.rejected_flip = rejected_flip_;
  r.rejected_intersection = rejected_intersection_;
  r.rejected_face = rejected_face_;
}

std::unique_ptr<Simplifier> Simplifier::resume(const Handoff& h, std::vector<Aabb> region, const ContactZone* zone,
                                               std::function<bool(const Simplifier&)> clean, std::size_t target,
                                               SimplifyResult& r) {
  PhaseClock clock(r);
  auto s = std::make_unique<Simplifier>(h.state);
  EntryList list = h.list;
  auto phases = std::move(r.phases);
  r = h.counters;
  r.phases = std::move(phases);
  clock.lap("handoff copy");
  s->make_scratch();  // (the copy was taken before handoff_ was set: it keeps none)
  if (!region.empty()) s->set_guard_region(std::move(region));
  s->set_contact_zone(zone);
  if (clean) {
    const Simplifier* me = s.get();
    s->set_handoff_check([me, clean = std::move(clean)] { return clean(*me); });
  }
  s->finish(list, h.live, target, r, clock);
  return s;
}

// The guard's grid over the live triangles (cells from their mean area).
void Simplifier::start_guard(std::size_t live) {
  guard_ = true;
  surface_area_ = 0;
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    if (dead_[t]) continue;
    const auto& tr = tris_[t];
    surface_area_ += 0.5 * norm(cross(pos_[tr[1]] - pos_[tr[0]], pos_[tr[2]] - pos_[tr[0]]));
  }
  guard_mark_.assign(tris_.size(), GuardMark{});
  rebuild_grid(live);
}

// The min-heap loop (§4): the cheapest valid candidate is collapsed, its end's edges evaluated
// again. Collapses that would overshoot the budget are kept aside; if the budget cannot be met
// exactly (only 2-triangle collapses left at budget + 1) they are retried to end at budget - 1.
void Simplifier::heap_loop(std::size_t target, std::size_t& live, SimplifyResult& r) {
  Scratch& sc = tls_->local();
  std::vector<HeapEntry> deferred, fresh;
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
    snapshot(a, b, sc);
    if (sc.shared == 0) continue;  // no longer an edge
    Candidate c;
    if (!direction(a, b, sc.seam, c)) continue;  // placement recomputed (same quadrics: same result)
    if (live - static_cast<std::size_t>(sc.shared) < floor) {  // would overshoot the budget
      deferred.push_back(e);
      continue;
    }
    if (!link_ok(a, b, sc)) {
      ++rejected_link_;
      continue;
    }
    if (!flip_ok(a, b, c.p, sc)) {
      ++rejected_flip_;
      continue;
    }
    if (!face_ok(a, sc)) {
      ++rejected_face_;
      continue;
    }
    if (guard_ && guard_refuses(a, b, c.p, sc)) {
      ++rejected_intersection_;
      continue;
    }
    std::size_t died = 0;
    collapse(a, b, c.p, sc, merged_, died);
    set_fan(a, merged_);
    live -= died;
    ++r.collapses;
    report_progress(live);
    if (guard_) {
      if (grid_stale(live)) rebuild_grid(live);
      else
        for (std::uint32_t t : merged_) grid_insert(t);
    }
    fresh.clear();
    candidates_of(a, sc, fresh);
    for (const HeapEntry& f : fresh) heap_.push(f);
  }
}

}  // namespace interfere::qem
