// Batched passes for large meshes, before the heap finishes with the exact budget: the scheme of
// meshoptimizer's simplifier (Kapoulkine, meshopt_simplify): candidates sorted by cost (stable
// parallel radix sort), walked from the cheapest up to an error limit of 1.5x the cost at half the
// pass's goal, a collapse selected when neither end was used by an earlier selection of the pass
// (independent-set decimation, Franc & Skala 2001). The selected collapses are checked against the
// current mesh (link condition, flips) and applied in vertex order, in parallel over a fixed number
// of contiguous vertex ranges: a collapse whose triangles touch an end of another range's collapse
// is deferred to a serial sweep afterwards, so the ranges own disjoint triangle fans. Candidates of
// edges whose ends did not change are kept; those of the changed ends are evaluated again (in
// parallel). Every step is a fixed function of the mesh: results do not depend on the thread count
// or on timing.
#include <functional>

#include <tbb/parallel_reduce.h>

#include "interfere/core/morton.h"
#include "qem_internal.h"
#include "radix_sort.h"

namespace interfere::qem {
namespace {
constexpr std::size_t kRanges = 16;      ///< vertex ranges applied in parallel (fixed: deterministic)
constexpr std::size_t kMinRange = 1024;  ///< collapses per range at least (but see range_length)

/// Collapses per range of apply_selected (fixed by their count: deterministic): ranges of about
/// kMinRange, up to kRanges, of equal length and an even number of them from kMinRange / 2
/// collapses on, so that two threads share them evenly (casing: its late passes of 800 to 2,300
/// collapses made one range or 1024 + 1024 + 218, the apply phase 3.7 -> 3.2 ms with even ranges;
/// from 16 * 1024 collapses on, kRanges ranges as before).
std::size_t range_length(std::size_t n) {
  std::size_t ranges = std::max<std::size_t>(1, std::min(kRanges, (n + kMinRange - 1) / kMinRange));
  if (ranges % 2 == 1 && n >= kMinRange / 2) ++ranges;
  return std::max<std::size_t>(1, (n + ranges - 1) / ranges);  // (n = 0: 1)
}

}  // namespace

// Applies the selected collapses (sorted by kept end); returns how many were applied. Ranges run in
// parallel; a collapse whose triangles hold an end of another range's collapse is deferred (so no
// triangle is read by one range while another writes it: the writer would have been deferred too),
// and the deferred ones are applied serially afterwards, in vertex order.
std::size_t Simplifier::apply_selected(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& selected,
                                       std::size_t& live, std::vector<std::uint32_t>& changed) {
  const std::size_t n = selected.size();
  const std::size_t per = range_length(n);
  const std::size_t ranges = (n + per - 1) / per;
  ++owner_pass_;
  face_pass_ = face_live_;  // (Scratch::fragile's counts: the pass's start)
  std::vector<std::size_t> bound(ranges + 1, 0);  // refs_ space for the grown fans of each range
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ranges, 1), [&](const tbb::blocked_range<std::size_t>& rg) {
    for (std::size_t c = rg.begin(); c < rg.end(); ++c)
      for (std::size_t k = c * per; k < std::min(n, (c + 1) * per); ++k) {
        const auto [a, b] = selected[k];
        owner_[a] = owner_[b] = {owner_pass_, static_cast<std::uint32_t>(c)};
        bound[c + 1] += fan_count_[a] + fan_count_[b];
      }
  });
  for (std::size_t c = 0; c < ranges; ++c) bound[c + 1] += bound[c];
  reserve_fans(bound[ranges]);
  const std::size_t base = refs_.size();
  refs_.resize(base + bound[ranges]);
  struct RangeResult {
    std::size_t died = 0, link = 0, flip = 0, intersection = 0, face = 0;
    std::vector<std::uint32_t> changed, deferred, died_faces;
  };
  std::vector<RangeResult> res(ranges + 1);
  // One collapse: checks, then b into a; a's grown fan goes to `*end` (the range's own space). The
  // self-intersection guard runs only in the serial sweep (end == nullptr): it reads and extends
  // the shared grid. False: deferred (a triangle holds an end of another range's collapse).
  auto apply_one = [&](std::uint32_t a, std::uint32_t b, Scratch& sc, std::vector<std::uint32_t>& merged,
                       RangeResult& out, std::size_t* end, std::uint32_t range) {
    if (!snapshot(a, b, sc, range)) return false;
    if (sc.shared == 0) return true;
    Candidate c;
    if (!direction(a, b, sc.seam, c)) return true;
    // Guarded collapses go to the serial sweep, and those that may remove a small face's last
    // triangle (Scratch::fragile).
    if (end && guard_ && guarded(moved_box(a, b, c.p, sc))) return false;
    if (end && sc.fragile) return false;
    if (!link_ok(a, b, sc)) {
      ++out.link;
      return true;
    }
    if (!flip_ok(a, b, c.p, sc)) {
      ++out.flip;
      return true;
    }
    if (!end && !face_ok(a, sc)) {
      ++out.face;
      return true;
    }
    if (!end && guard_ && guard_refuses(a, b, c.p, sc)) {
      ++out.intersection;
      return true;
    }
    collapse(a, b, c.p, sc, merged, out.died, end ? &out.died_faces : nullptr);
    if (end && merged.size() > fan_count_[a]) {
      fan_start_[a] = static_cast<std::uint32_t>(*end);
      std::copy(merged.begin(), merged.end(), refs_.begin() + *end);
      fan_count_[a] = static_cast<std::uint32_t>(merged.size());
      *end += merged.size();
    } else {
      set_fan(a, merged);
    }
    out.changed.push_back(a);
    return true;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ranges, 1), [&](const tbb::blocked_range<std::size_t>& rg) {
    Scratch& sc = tls_->local();
    std::vector<std::uint32_t> merged;
    for (std::size_t c = rg.begin(); c < rg.end(); ++c) {
      std::size_t end = base + bound[c];
      const std::uint32_t range = ranges > 1 ? static_cast<std::uint32_t>(c) : kNone;
      const std::size_t last = std::min(n, (c + 1) * per);
      for (std::size_t k = c * per; k < last; ++k) {
        // The data of later collapses is fetched ahead: their vertices are scattered, and the
        // misses then overlap with this collapse's work.
        if (k + 8 < last) {
          const auto [pa, pb] = selected[k + 8];
          __builtin_prefetch(&quad_[pa]), __builtin_prefetch(&quad_[pb]);
          __builtin_prefetch(&pos_[pb]), __builtin_prefetch(&fan_start_[pb]), __builtin_prefetch(&fan_count_[pb]);
        }
        if (k + 4 < last) {
          const auto [pa, pb] = selected[k + 4];
          __builtin_prefetch(&refs_[fan_start_[pa]]), __builtin_prefetch(&refs_[fan_start_[pb]]);
        }
        const auto [a, b] = selected[k];
        if (!apply_one(a, b, sc, merged, res[c], &end, range))
          res[c].deferred.push_back(static_cast<std::uint32_t>(k));
      }
    }
  });
  Scratch& sc = tls_->local();
  for (std::size_t c = 0; c < ranges; ++c)  // (the serial sweep's face_ok reads the counts)
    for (std::uint32_t f : res[c].died_faces) --face_live_[f];
  if (guard_) {  // the triangles moved in parallel enter the grid before the guarded checks
    for (std::size_t c = 0; c < ranges; ++c)
      for (std::uint32_t v : res[c].changed) grid_insert_fan(v);
  }
  for (std::size_t c = 0; c < ranges; ++c)
    for (std::uint32_t k : res[c].deferred) {
      const std::size_t before = res[ranges].changed.size();
      apply_one(selected[k].first, selected[k].second, sc, merged_, res[ranges], nullptr, kNone);
      if (guard_ && res[ranges].changed.size() > before) grid_insert_fan(res[ranges].changed.back());
    }
  std::size_t applied = 0;
  changed.clear();
  for (RangeResult& r : res) {
    live -= r.died;
    rejected_link_ += r.link, rejected_flip_ += r.flip, rejected_intersection_ += r.intersection;
    rejected_face_ += r.face;
    applied += r.changed.size();
    changed.insert(changed.end(), r.changed.begin(), r.changed.end());
  }
  return applied;
}

void Simplifier::batched_passes(EntryList& list, std::size_t handoff, std::size_t& live,
                                SimplifyResult& r, PhaseClock& clock) {
  EntryList tmp;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> selected;  // (keep, remove)
  struct Selected {
    std::uint32_t code, keep, remove;
  };
  std::vector<Selected> sel, sel_tmp;
  // Per vertex: the pass that used it as an end, and (spatial ranges) its Morton code.
  struct VertexSel {
    std::uint32_t taken, code;
  };
  std::vector<VertexSel> vsel;
  // Ranges of vertex numbers are compact regions when neighbours have near numbers (generated
  // grids, most scanned meshes); a CAD tessellation numbers each B-Rep face on its own, and half of
  // a pass's collapses then touched another range and were deferred to the serial sweep (casing:
  // 2,488 of 5,131). Where more than 2 % of the edges join vertices far apart in number, the ranges
  // are cut along a Morton curve instead (casing: 245 deferred in 6 ranges of 1024, 339 in the 6
  // equal ranges of range_length), each still applied in vertex order.
  const std::size_t far_limit = std::max<std::size_t>(1024, pos_.size() / 64);
  const std::size_t far_edges = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, list.size(), 1 << 16), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& rg, std::size_t n) {
        for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
          const HeapEntry& e = list[i];
          n += (e.keep > e.remove ? e.keep - e.remove : e.remove - e.keep) > far_limit ? 1 : 0;
        }
        return n;
      },
      std::plus<>());
  const bool spatial = far_edges * 50 > list.size();
  // The Morton grid (128^3): the input's box (positions stay near it; outliers are clamped); a
  // vertex's code is taken when the passes start or the arrays are compacted (any fixed spatial
  // code will do).
  Aabb box;
  for (const Vec3& p : pos_) box.expand(p);
  const double box_ext = std::max({box.extent().x, box.extent().y, box.extent().z});
  const double box_scale = box_ext > 0 ? 127.0 / box_ext : 0.0;
  const auto init_vsel = [&] {
    vsel.resize(pos_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pos_.size(), 1 << 14), [&](const tbb::blocked_range<std::size_t>& rg) {
      for (std::size_t v = rg.begin(); v < rg.end(); ++v) {
        const Vec3& p = pos_[v];
        auto q = [&](double x, double lo) { return static_cast<std::uint32_t>(std::clamp((x - lo) * box_scale, 0.0, 127.0)); };
        // A 128^3 grid: 21-bit codes, two radix passes.
        vsel[v] = {0, spatial ? morton30(q(p.z, box.lo.z), q(p.y, box.lo.y), q(p.x, box.lo.x)) : 0};
      }
    });
  };
  init_vsel();
  std::vector<std::uint32_t> changed, mark(pos_.size(), 0);
  owner_.assign(pos_.size(), Owner{});
  std::uint32_t pass = 0;
  std::size_t sorted = 0;  // list[0, sorted) is in key order (the entries kept from the last pass)
  EntryList fresh_list, fresh_tmp;
  // The sort key: the cost's bits without the 10 lowest of the mantissa (a relative resolution of
  // 2^-13, far below what separates one collapse from another in quality), so two radix passes of
  // 11 bits instead of three; equal keys keep their order (stable).
  const auto key = [](const HeapEntry& e) { return key_bits(e) >> 10; };
  // The last few percent are left to the heap (small passes cost a sort and a sweep each).
  while (live > handoff + handoff / 8 && !list.empty()) {
    ++pass;
    if (sorted == 0) {
      radix_sort_u32<22>(list, tmp, key);
    } else {
      // Only the fresh entries are sorted, then merged after the kept ones (a stable merge, the
      // kept entries first among equal keys): the same order as a stable sort of the list.
      fresh_list.assign(list.begin() + static_cast<std::ptrdiff_t>(sorted), list.end());
      radix_sort_u32<22>(fresh_list, fresh_tmp, key);
      tmp.resize(list.size());
      parallel_merge(list.data(), sorted, fresh_list.data(), fresh_list.size(), tmp.data(),
                     [&](const HeapEntry& x, const HeapEntry& y) { return key(x) < key(y); });
      list.swap(tmp);
    }
    clock.lap("passes: sort");
    const std::size_t goal = live - handoff;
    // meshoptimizer's error limit: 1.5x the cost at half the goal (no limit in the last tier).
    const HeapEntry& at = list[std::min(list.size() - 1, goal / 2)];
    std::uint32_t limit = std::numeric_limits<std::uint32_t>::max();
    if (!(key_bits(at) & 0x80000000u)) {
      const float lim = at.cost * 1.5f;
      std::memcpy(&limit, &lim, 4);
      if (!std::isfinite(lim)) limit = 0x7fffffffu;
    }
    sel.clear();
    std::size_t planned = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const HeapEntry& e = list[i];
      if (planned >= goal || key_bits(e) > limit) break;
      if (i + 16 < list.size()) {  // scattered vertices: fetched ahead
        __builtin_prefetch(&vsel[list[i + 16].keep]);
        __builtin_prefetch(&vsel[list[i + 16].remove]);
      }
      if (vsel[e.keep].taken == pass || vsel[e.remove].taken == pass) continue;
      vsel[e.keep].taken = vsel[e.remove].taken = pass;
      sel.push_back({vsel[e.keep].code, e.keep, e.remove});
      planned += 2;
    }
    // Vertex order (memory locality, contiguous ranges for the parallel application); spatial
    // ranges: Morton order of the kept end, then vertex order within each range.
    if (!spatial) {
      radix_sort_u32(sel, sel_tmp, [](const Selected& x) { return x.keep; });
    } else {
      radix_sort_u32<21>(sel, sel_tmp, [](const Selected& x) { return x.code; });
      const std::size_t per = range_length(sel.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (sel.size() + per - 1) / per, 1), [&](const tbb::blocked_range<std::size_t>& rg) {
        for (std::size_t c = rg.begin(); c < rg.end(); ++c)
          std::sort(sel.begin() + c * per, sel.begin() + std::min(sel.size(), (c + 1) * per),
                    [](const Selected& x, const Selected& y) { return x.keep < y.keep; });
      });
    }
    selected.resize(sel.size());
    for (std::size_t i = 0; i < sel.size(); ++i) selected[i] = {sel[i].keep, sel[i].remove};
    clock.lap("passes: select");
    const std::size_t applied = apply_selected(selected, live, changed);
    r.collapses += applied;
    report_progress(live);
    if (guard_ && grid_stale(live)) rebuild_grid(live);
    clock.lap("passes: apply");
    if (applied == 0) break;
    // Next list: the entries whose ends did not change (same cost), then the edges of the changed
    // ends, each edge once (from its smaller end when both changed), in a fixed order.
    for (std::uint32_t v : changed) mark[v] = pass;
    const auto stale = [&](const HeapEntry& e) {
      return vdead_[e.keep] || vdead_[e.remove] || mark[e.keep] == pass || mark[e.remove] == pass;
    };
    // In parallel over fixed blocks: each copies its kept entries to the start of its own span of
    // tmp, then the spans are joined in order.
    {
      const std::size_t n = list.size();
      const std::size_t kFilterBlock = parallel_block_length(n);
      const std::size_t nb = (n + kFilterBlock - 1) / kFilterBlock;
      tmp.resize(n);
      std::vector<std::size_t> kept(nb + 1, 0);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& rg) {
        for (std::size_t b = rg.begin(); b < rg.end(); ++b) {
          std::size_t k = b * kFilterBlock;
          for (std::size_t i = b * kFilterBlock; i < std::min(n, (b + 1) * kFilterBlock); ++i)
            if (!stale(list[i])) tmp[k++] = list[i];
          kept[b + 1] = k - b * kFilterBlock;
        }
      });
      for (std::size_t b = 0; b < nb; ++b) kept[b + 1] += kept[b];
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& rg) {
        for (std::size_t b = rg.begin(); b < rg.end(); ++b)
          std::copy_n(tmp.begin() + b * kFilterBlock, kept[b + 1] - kept[b], list.begin() + kept[b]);
      });
      list.resize(kept[nb]);
    }
    sorted = list.size();
    clock.lap("passes: filter");
    // Chunks of the changed vertices, joined in order (the result does not depend on their size;
    // 256 rather than 1024 keeps both threads busy in the small late passes: casing -0.3 ms).
    constexpr std::size_t kChunk = 256;
    std::vector<std::vector<HeapEntry>> fresh((changed.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fresh.size(), 1), [&](const tbb::blocked_range<std::size_t>& rg) {
      Scratch& sc = tls_->local();
      for (std::size_t ci = rg.begin(); ci < rg.end(); ++ci)
        for (std::size_t k = ci * kChunk; k < std::min(changed.size(), (ci + 1) * kChunk); ++k) {
          if (k + 4 < changed.size()) __builtin_prefetch(&refs_[fan_start_[changed[k + 4]]]);
          const std::uint32_t v = changed[k];
          gather_neighbours(v, sc);
          evaluate_gathered(v, sc, fresh[ci], mark.data(), pass);
        }
    });
    for (const auto& f : fresh) list.insert(list.end(), f.begin(), f.end());
    clock.lap("passes: evaluate");
    // Most of the arrays dead: renumbered densely (same results, far fewer cache misses).
    // (Inputs of SimplifyOptions::compact_min_triangles and more, down to the handoff: a casing of
    // 35,516 triangles ran about 3 % more instructions with it, for no fewer cache misses; a large
    // input compacted throughout also keeps a small copy at the handoff, see Simplifier::run.)
    if (input_triangles_ >= o_.compact_min_triangles && live * 2 < tris_.size()) {
      compact_mesh(list, sorted, live);
      init_vsel();
      mark.assign(pos_.size(), 0);
      clock.lap("passes: compact");
    }
  }
}

}  // namespace interfere::qem
