// Compaction of the QEM simplifier's arrays between batched passes (issue #6, item 5, speed): once
// many vertices and triangles are dead, the live ones lie sparsely in arrays sized for the input and
// the collapses of the late passes miss the caches (a collapse of pass 10 on a 10^6-triangle sphere
// cost 4.5x one of pass 1). Renumbering the live vertices and triangles densely, in their order,
// keeps every later decision the same (orders and tie-breaks are by index, and the renumbering is
// monotone), so results stay bit-identical; it runs in parallel over fixed blocks.
#include <atomic>

#include <tbb/parallel_invoke.h>

#include "qem_internal.h"

namespace interfere::qem {
namespace {

/// New numbers of the kept items of [0, n) (kept(i) true), in order, in parallel over fixed blocks;
/// kNone for the others. Returns the kept count.
template <class Kept>
std::uint32_t renumber(std::size_t n, std::vector<std::uint32_t>& out, Kept kept) {
  out.resize(n);
  std::vector<std::uint32_t> offset(num_blocks(n) + 1, 0);
  for_blocks(n, [&](std::uint32_t i0, std::uint32_t i1, std::size_t b) {
    std::uint32_t c = 0;
    for (std::uint32_t i = i0; i < i1; ++i) c += kept(i) ? 1 : 0;
    offset[b + 1] = c;
  });
  for (std::size_t b = 1; b < offset.size(); ++b) offset[b] += offset[b - 1];
  for_blocks(n, [&](std::uint32_t i0, std::uint32_t i1, std::size_t b) {
    std::uint32_t k = offset[b];
    for (std::uint32_t i = i0; i < i1; ++i) out[i] = kept(i) ? k++ : kNone;
  });
  return offset.back();
}

/// a[map[i]] = a[i] for the mapped i, in place (map[i] <= i, ascending: no item is overwritten
/// before it is read; fresh storage would cost more in page faults than the copy).
template <class Vector>
void gather(Vector& a, const std::vector<std::uint32_t>& map, std::size_t m) {
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map[i] != kNone) a[map[i]] = a[i];
  a.resize(m);
}

}  // namespace

void Simplifier::compact_mesh(EntryList& list, std::size_t& sorted, std::size_t live) {
  const std::size_t nv = pos_.size(), nt = tris_.size();
  std::vector<std::uint32_t> vnew, tnew;
  const std::uint32_t mv = renumber(nv, vnew, [&](std::uint32_t v) { return !vdead_[v]; });
  const std::uint32_t mt = renumber(nt, tnew, [&](std::uint32_t t) { return !dead_[t]; });
  // Fans: the live triangles of each live vertex, in fan order, under their new numbers (counted,
  // then placed at the block offsets).
  std::vector<std::uint32_t> start(mv), count(mv);
  std::vector<std::size_t> offset(num_blocks(nv) + 1, 0);
  for_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t b) {
    std::size_t sum = 0;
    for (std::uint32_t v = v0; v < v1; ++v) {
      if (vnew[v] == kNone) continue;
      std::uint32_t c = 0;
      for (std::uint32_t i = 0; i < fan_count_[v]; ++i) c += dead_[refs_[fan_start_[v] + i]] ? 0 : 1;
      count[vnew[v]] = c;
      sum += c;
    }
    offset[b + 1] = sum;
  });
  for (std::size_t b = 1; b < offset.size(); ++b) offset[b] += offset[b - 1];
  Refs& refs = refs_spare_;
  refs.clear();
  refs.reserve(2 * offset.back() + 1024);  // room for grown fans (reserve_fans)
  refs.resize(offset.back());
  for_blocks(nv, [&](std::uint32_t v0, std::uint32_t v1, std::size_t b) {
    std::size_t k = offset[b];
    for (std::uint32_t v = v0; v < v1; ++v) {
      if (vnew[v] == kNone) continue;
      start[vnew[v]] = static_cast<std::uint32_t>(k);
      for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
        const std::uint32_t t = refs_[fan_start_[v] + i];
        if (!dead_[t]) refs[k++] = tnew[t];
      }
    }
  });
  refs_.swap(refs);
  fan_start_.swap(start);
  fan_count_.swap(count);
  // Vertex and triangle data, the arrays in parallel; the input index of each triangle is kept for
  // the output.
  if (tri_origin_.empty()) {
    tri_origin_.resize(nt);
    for (std::uint32_t t = 0; t < nt; ++t) tri_origin_[t] = t;
  }
  tbb::parallel_invoke(
      [&] { gather(quad_, vnew, mv); },
      [&] {
        gather(pos_, vnew, mv), gather(cls_, vnew, mv), gather(locked_, vnew, mv);
        gather(touches_feature_, vnew, mv), gather(stamp_, vnew, mv);
      },
      [&] {
        for (Tri& tr : tris_)
          for (std::uint32_t& w : tr) w = w < nv ? vnew[w] : w;
        gather(tris_, tnew, mt);
      },
      [&] { gather(face_, tnew, mt), gather(feature_tri_, tnew, mt), gather(tri_origin_, tnew, mt); });
  dead_.assign(mt, 0);
  vdead_.assign(mv, 0);
  // The candidates (their ends are live: stale ones were filtered out before; any other would be
  // dropped, the sorted prefix shortened to match).
  std::atomic<bool> drop{false};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, list.size(), 1 << 14), [&](const tbb::blocked_range<std::size_t>& rg) {
    for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
      HeapEntry& e = list[i];
      e.keep = vnew[e.keep], e.remove = vnew[e.remove];
      if (e.keep == kNone || e.remove == kNone) drop.store(true, std::memory_order_relaxed);
    }
  });
  if (drop.load()) {
    std::size_t k = 0, kept_sorted = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (list[i].keep == kNone || list[i].remove == kNone) continue;
      kept_sorted += i < sorted ? 1 : 0;
      list[k++] = list[i];
    }
    list.resize(k);
    sorted = kept_sorted;
  }
  owner_.assign(mv, Owner{});
  if (guard_) {  // the grid holds triangle numbers: built again (the guard's answers are exact either way)
    guard_mark_.assign(mt, GuardMark{});
    rebuild_grid(live);
  }
}

// Back to the input's triangle numbering (the caller reads dead_ and tris_ by input triangle).
void Simplifier::uncompact_triangles(std::size_t input_triangles) {
  if (tri_origin_.empty()) return;
  std::vector<Tri> tris(input_triangles, Tri{0, 0, 0});
  std::vector<std::uint8_t> dead(input_triangles, 1);
  for (std::size_t u = 0; u < tris_.size(); ++u) {
    tris[tri_origin_[u]] = tris_[u];
    dead[tri_origin_[u]] = dead_[u];
  }
  tris_.swap(tris);
  dead_.swap(dead);
  tri_origin_.clear();
}

// The live triangles as a mesh of their own (unused vertices dropped) and, per triangle, its input
// number (through tri_origin_ when compacted): the mesh at the handoff of a heap-guarded rerun.
TriMesh Simplifier::live_mesh(std::vector<std::uint32_t>& origin) const {
  TriMesh m;
  origin.clear();
  std::vector<std::uint32_t> used(pos_.size(), kNone);
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    if (dead_[t]) continue;
    Tri tr = tris_[t];
    for (std::uint32_t& v : tr) {
      if (used[v] == kNone) {
        used[v] = static_cast<std::uint32_t>(m.positions.size());
        m.positions.push_back(pos_[v]);
      }
      v = used[v];
    }
    m.triangles.push_back(tr);
    origin.push_back(tri_origin_.empty() ? static_cast<std::uint32_t>(t) : tri_origin_[t]);
  }
  return m;
}

}  // namespace interfere::qem
