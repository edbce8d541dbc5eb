// Local operations of the QEM edge collapse (Garland & Heckbert, SIGGRAPH 1997): candidate
// evaluation with optimal placement and endpoint/midpoint fallback (§4), the constrained-edge
// (seam) test, the link condition (Dey, Edelsbrunner, Guha & Nekhayev 1999) that keeps the mesh
// manifold, the normal-flip test, and the collapse itself on per-vertex triangle fans. Feature
// weighting after He & Xu (SJTU 2023, §3.3). All but collapse/set_fan only read the mesh.
#include <algorithm>

#include "qem_internal.h"

namespace interfere::qem {

void Simplifier::build_fans() {
  const std::size_t nv = pos_.size();
  fan_start_.assign(nv + 1, 0);
  fan_count_.assign(nv, 0);
  for (const Tri& t : tris_)
    for (std::uint32_t v : t) ++fan_count_[v];
  for (std::size_t v = 0; v < nv; ++v) fan_start_[v + 1] = fan_start_[v] + fan_count_[v];
  // Room for the fans that grow (appended): reserved, so untouched pages cost nothing.
  refs_.reserve(2 * std::size_t{fan_start_[nv]} + 1024);
  refs_.resize(fan_start_[nv]);
  std::vector<std::uint32_t> fill(fan_start_.begin(), fan_start_.end() - 1);
  for (std::uint32_t t = 0; t < tris_.size(); ++t)
    for (std::uint32_t v : tris_[t]) refs_[fill[v]++] = t;
  fan_start_.pop_back();
}

void Simplifier::set_fan(std::uint32_t v, const std::vector<std::uint32_t>& tris) {
  if (tris.size() <= fan_count_[v]) {  // shrinking: reuse the slot
    std::copy(tris.begin(), tris.end(), refs_.begin() + fan_start_[v]);
  } else {
    reserve_fans(tris.size());
    fan_start_[v] = static_cast<std::uint32_t>(refs_.size());
    refs_.insert(refs_.end(), tris.begin(), tris.end());
  }
  fan_count_[v] = static_cast<std::uint32_t>(tris.size());
}

// Grown fans are appended to refs_; when its capacity would be exceeded, the live entries of every
// fan are packed into the spare buffer instead of reallocating (fresh pages cost more than the
// copy: two buffers, each touched once).
void Simplifier::reserve_fans(std::size_t extra) {
  if (refs_.size() + extra <= refs_.capacity()) return;
  refs_spare_.clear();
  refs_spare_.reserve(std::max(refs_.capacity(), 2 * (3 * tris_.size() + extra) + 1024));
  for (std::uint32_t v = 0; v < pos_.size(); ++v) {
    const auto s = static_cast<std::uint32_t>(refs_spare_.size());
    for (std::uint32_t i = 0; i < fan_count_[v]; ++i) {
      const std::uint32_t t = refs_[fan_start_[v] + i];
      if (!dead_[t]) refs_spare_.push_back(t);
    }
    fan_start_[v] = s;
    fan_count_[v] = static_cast<std::uint32_t>(refs_spare_.size() - s);
  }
  refs_.swap(refs_spare_);
}

namespace {
// Where gather_neighbours finds a neighbour beyond the first 16 (neighbour -> its slot in sc.nbr):
// marks over the vertices, or the vertex map on large meshes (see Scratch).
struct MarkIndex {
  Scratch& sc;
  std::uint32_t id = 0;
  void start() { id = ++sc.id; }
  Scratch::Neighbour* find(std::uint32_t w) const { return sc.mark_a[w] == id ? &sc.nbr[sc.slot[w]] : nullptr; }
  void set(std::uint32_t w, std::uint32_t k) { sc.mark_a[w] = id, sc.slot[w] = k; }
};
struct MapIndex {
  Scratch& sc;
  void start() { sc.map.clear(); }
  Scratch::Neighbour* find(std::uint32_t w) const {
    const std::uint32_t* k = sc.map.find(w);
    return k ? &sc.nbr[*k] : nullptr;
  }
  void set(std::uint32_t w, std::uint32_t k) { sc.map.at(w) = k; }
};
}  // namespace

// One sweep over v's fan gathers every neighbour w with the number of live triangles on (v, w) and
// whether their face ids differ (the seam test for all edges at once: an edge is constrained when
// it has not exactly two live triangles, or two with different face ids), in order of
// first appearance.
void Simplifier::gather_neighbours(std::uint32_t v, Scratch& sc) const {
  if (!sc.mark_a.empty()) gather_with(v, sc, MarkIndex{sc});
  else gather_with(v, sc, MapIndex{sc});
}

template <class Index>
void Simplifier::gather_with(std::uint32_t v, Scratch& sc, Index index) const {
  sc.nbr.clear();
  // Small fans: a linear search of the few neighbours found so far; from 16 neighbours on, the
  // index.
  constexpr std::size_t kLinear = 16;
  bool indexed = false;
  const auto add = [&](std::uint32_t w, std::uint32_t f) {
    Scratch::Neighbour* found = nullptr;
    if (!indexed) {
      // (No early exit: the position of a match is data, its branch a guess; the last match is
      // the only one, neighbours being distinct.)
      std::size_t at = sc.nbr.size();
      for (std::size_t i = 0; i < sc.nbr.size(); ++i) at = sc.nbr[i].w == w ? i : at;
      if (at < sc.nbr.size()) found = &sc.nbr[at];
    } else {
      found = index.find(w);
    }
    if (found) {
      ++found->count;
      found->differ = found->differ || found->face != f;
      return;
    }
    sc.nbr.push_back({w, 1, f, false});
    if (indexed) {
      index.set(w, static_cast<std::uint32_t>(sc.nbr.size() - 1));
    } else if (sc.nbr.size() == kLinear) {
      indexed = true;
      index.start();
      for (std::uint32_t k = 0; k < sc.nbr.size(); ++k) index.set(sc.nbr[k].w, k);
    }
  };
  const std::uint32_t* fan = refs_.data() + fan_start_[v];
  for (std::uint32_t i = 0, n = fan_count_[v]; i < n; ++i) {
    const std::uint32_t t = fan[i];
    if (dead_[t]) continue;
    const std::uint32_t f = face_[t];
    const Tri& tr = tris_[t];
    // The two other corners, in the triangle's order after v (v's corner found without branches).
    const int k = (tr[1] == v) + 2 * (tr[2] == v);
    add(tr[k == 2 ? 0 : k + 1], f);
    add(tr[k == 0 ? 2 : k - 1], f);
  }
}

// The candidates of every edge at v (both directions considered, the cheaper kept).
void Simplifier::candidates_of(std::uint32_t v, Scratch& sc, std::vector<HeapEntry>& out) const {
  gather_neighbours(v, sc);
  evaluate_gathered(v, sc, out);
}

bool Simplifier::direction(std::uint32_t keep, std::uint32_t remove, bool seam, Candidate& out) const {
  if (locked_[remove] || cls_[remove] == kCorner) return false;
  if (cls_[remove] == kSeam && (!seam || cls_[keep] == kInterior)) return false;
  Quadric q = quad_[keep];
  q += quad_[remove];
  Vec3 p = pos_[keep];
  double cost;
  if (!(movable(keep) && movable(remove))) {
    cost = q.eval(p);
  } else if (q.optimum(p)) {  // optimal placement (§4)
    cost = q.eval(p);
  } else {  // else the best of the endpoints and the midpoint
    const Vec3 mid = (pos_[keep] + pos_[remove]) * 0.5;
    const Vec3 cand[3] = {pos_[keep], pos_[remove], mid};
    cost = std::numeric_limits<double>::infinity();
    for (const Vec3& c : cand) {
      const double e = q.eval(c);
      if (e < cost) cost = e, p = c;
    }
  }
  out.cost = cost;
  out.p = p;
  out.keep = keep, out.remove = remove;
  out.stamp_keep = stamp_[keep], out.stamp_remove = stamp_[remove];
  out.last_tier = false;
  if (touches_feature_[keep] || touches_feature_[remove]) {
    out.cost += feature_offset_;
    out.last_tier = o_.feature_mode == FeatureMode::last;
  }
  return true;
}

bool Simplifier::evaluate(std::uint32_t a, std::uint32_t b, bool seam, Candidate& out) const {
  Candidate c1, c2;
  const bool ok1 = direction(a, b, seam, c1);
  // Both movable: one symmetric placement, no second direction needed.
  const bool ok2 = !(ok1 && movable(a) && movable(b)) && direction(b, a, seam, c2);
  if (!ok1 && !ok2) return false;
  out = (ok1 && (!ok2 || c1.cost <= c2.cost)) ? c1 : c2;
  return true;
}

std::size_t Simplifier::evaluate_neighbours(std::uint32_t v, const Scratch::Neighbour* first,
                                            const Scratch::Neighbour* last, HeapEntry* out,
                                            const std::uint32_t* mark, std::uint32_t pass) const {
  // The neighbours' quadrics and positions are scattered: fetch them all before the evaluations
  // so that the cache misses overlap.
  for (const Scratch::Neighbour* n = first; n != last; ++n) {
    __builtin_prefetch(&quad_[n->w]);
    __builtin_prefetch(reinterpret_cast<const char*>(&quad_[n->w]) + 64);
    __builtin_prefetch(&pos_[n->w]);
  }
  std::size_t k = 0;
  for (const Scratch::Neighbour* n = first; n != last; ++n) {
    if (mark && mark[n->w] == pass && n->w < v) continue;
    Candidate c;
    if (evaluate(v, n->w, n->count != 2 || n->differ, c)) out[k++] = entry_of(c);
  }
  return k;
}

// The live triangles of a's and b's fans with their corners, read once for all the checks and the
// collapse; the triangles on ab are those of b's fan holding a (the seam test as in
// gather_neighbours).
// Scratch::fragile (the face rule in the batched passes) concerns collapses along seams only: an
// inner edge of a face removes an interior vertex, whose closed fan of three or more triangles lies
// in that face, and two of them die, so the face keeps one. A
// batched pass's collapses have disjoint ends: in a disc face with i inner and l border vertices
// (2i + l - 2 triangles) it makes at most (i + l) / 2, each removing two triangles with an inner
// vertex (at most i of them) or one with a border vertex, so at least min((i + l) / 2, i) - 2
// triangles remain, one or more for a face of 8 or more; below kFragileFace (a margin for other
// shapes) the seam collapses go to the serial sweep. The count at the pass's start decides: the
// same for any thread count.
bool Simplifier::snapshot(std::uint32_t a, std::uint32_t b, Scratch& sc, std::uint32_t range) const {
  const auto foreign = [&](const Tri& tr) {
    if (range == kNone) return false;
    for (std::uint32_t w : tr)
      if (owner_[w].pass == owner_pass_ && owner_[w].range != range) return true;
    return false;
  };
  sc.fan_a.clear();
  sc.fan_b.clear();
  for (std::uint32_t i = 0, n = fan_count_[a]; i < n; ++i) {
    const std::uint32_t t = refs_[fan_start_[a] + i];
    if (dead_[t]) continue;
    if (foreign(tris_[t])) return false;
    sc.fan_a.push_back({t, tris_[t]});
  }
  int shared = 0;
  std::uint32_t f0 = kNone;
  bool differ = false, fragile = false;
  for (std::uint32_t i = 0, n = fan_count_[b]; i < n; ++i) {
    const std::uint32_t t = refs_[fan_start_[b] + i];
    if (dead_[t]) continue;
    const Tri& tr = tris_[t];
    if (foreign(tr)) return false;
    sc.fan_b.push_back({t, tr});
    if (!((tr[0] == a) | (tr[1] == a) | (tr[2] == a))) continue;
    ++shared;
    const std::uint32_t f = face_[t];
    if (f0 == kNone) f0 = f;
    else if (f != f0) differ = true;
    if (!face_pass_.empty()) fragile = fragile || face_pass_[f] < kFragileFace;
  }
  sc.shared = shared;
  sc.seam = shared != 2 || differ;
  sc.fragile = sc.seam && fragile;
  return true;
}

namespace {
// The link condition's per-vertex state (in a's fan; already counted from b's): marks over the
// vertices, or the vertex map on large meshes (see Scratch), like MarkIndex and MapIndex above.
struct MarkLink {
  Scratch& sc;
  std::uint32_t id;
  void put_a(std::uint32_t w) { sc.mark_a[w] = id; }
  /// 1 when w, met in b's fan for the first time, is in a's fan.
  int common_from_b(std::uint32_t w) {
    if (sc.mark_b[w] == id) return 0;
    sc.mark_b[w] = id;
    return sc.mark_a[w] == id;
  }
};
struct MapLink {  // per vertex: bit 1 = in a's fan, bit 2 = counted from b's
  Scratch& sc;
  void put_a(std::uint32_t w) { sc.map.at(w) = 1; }
  int common_from_b(std::uint32_t w) {
    std::uint32_t& m = sc.map.at(w);
    if (m & 2) return 0;
    m |= 2;
    return static_cast<int>(m & 1);
  }
};

template <class Link>
int common_neighbours(std::uint32_t a, std::uint32_t b, const Scratch& sc, Link link) {
  for (const Scratch::FanTri& f : sc.fan_a)
    for (std::uint32_t w : f.tr) link.put_a(w);
  int common = 0;
  for (const Scratch::FanTri& f : sc.fan_b)
    for (std::uint32_t w : f.tr)
      if (!((w == a) | (w == b))) common += link.common_from_b(w);
  return common;
}
}  // namespace

// Link condition: the common neighbours of a and b are exactly the apexes of the triangles on ab.
bool Simplifier::link_ok(std::uint32_t a, std::uint32_t b, Scratch& sc) const {
  if (!sc.mark_a.empty()) return common_neighbours(a, b, sc, MarkLink{sc, ++sc.id}) == sc.shared;
  sc.map.clear();
  return common_neighbours(a, b, sc, MapLink{sc}) == sc.shared;
}

// The triangles on ab (those of b's fan that hold a) die; each one's face must keep another.
// At most a few: a face is counted once per dying triangle of it.
bool Simplifier::face_ok(std::uint32_t a, const Scratch& sc) const {
  if (face_live_.empty()) return true;
  std::uint32_t seen[4];
  std::int32_t dying[4];
  int n = 0;
  for (const Scratch::FanTri& f : sc.fan_b) {
    if (!((f.tr[0] == a) | (f.tr[1] == a) | (f.tr[2] == a))) continue;
    const std::uint32_t face = face_[f.t];
    int i = 0;
    while (i < n && seen[i] != face) ++i;
    if (i == n) {
      if (n == 4) return false;  // (a non-manifold edge of many faces: not collapsed)
      seen[n] = face, dying[n++] = 0;
    }
    if (face_live_[face] <= ++dying[i]) return false;
  }
  return true;
}


namespace {
bool normal_ok(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& pa, const Vec3& pb, const Vec3& pc,
               double min_cos) {
  const Vec3 n0 = cross(b - a, c - a);
  const Vec3 n1 = cross(pb - pa, pc - pa);
  const double l0 = squared_norm(n0), l1 = squared_norm(n1);
  if (!(l1 > 0)) return false;
  if (!(l0 > 0)) return true;  // a degenerate triangle becoming non-degenerate is no flip
  const double d = dot(n0, n1);
  if (d <= 0) return false;
  return d * d >= min_cos * min_cos * l0 * l1 || min_cos <= 0;
}
}  // namespace

// Every live triangle moved by the collapse (those of `remove` that do not contain `keep`, and, if
// `keep` moves, those of `keep` that do not contain `remove`) keeps its orientation.
bool Simplifier::flip_ok(std::uint32_t keep, std::uint32_t remove, const Vec3& p, const Scratch& sc) const {
  const double mc = o_.min_normal_cos;
  for (int side = 0; side < 2; ++side) {
    const std::uint32_t v = side == 0 ? remove : keep;
    const std::uint32_t other = side == 0 ? keep : remove;
    if (side == 1 && p == pos_[keep]) break;
    for (const Scratch::FanTri& f : side == 0 ? sc.fan_b : sc.fan_a) {
      const Tri& tr = f.tr;
      if ((tr[0] == other) | (tr[1] == other) | (tr[2] == other)) continue;
      Vec3 q[3];
      for (int k = 0; k < 3; ++k) q[k] = tr[k] == v ? p : pos_[tr[k]];
      if (!normal_ok(pos_[tr[0]], pos_[tr[1]], pos_[tr[2]], q[0], q[1], q[2], mc)) return false;
    }
  }
  return true;
}

void Simplifier::collapse(std::uint32_t a, std::uint32_t b, const Vec3& p, const Scratch& sc,
                          std::vector<std::uint32_t>& merged, std::size_t& died,
                          std::vector<std::uint32_t>* died_faces) {
  merged.clear();
  bool feat = false;
  for (const Scratch::FanTri& f : sc.fan_b) {
    if ((f.tr[0] == a) | (f.tr[1] == a) | (f.tr[2] == a)) {
      dead_[f.t] = 1;
      ++died;
      if (face_live_.empty()) continue;
      if (died_faces) died_faces->push_back(face_[f.t]);
      else --face_live_[face_[f.t]];
      continue;
    }
    for (std::uint32_t& w : tris_[f.t])
      if (w == b) w = a;
    merged.push_back(f.t);
    feat = feat || feature_tri_[f.t];
  }
  for (const Scratch::FanTri& f : sc.fan_a) {
    if ((f.tr[0] == b) | (f.tr[1] == b) | (f.tr[2] == b)) continue;  // on ab: died above
    merged.push_back(f.t);
    feat = feat || feature_tri_[f.t];
  }
  fan_count_[b] = 0;
  vdead_[b] = 1;
  pos_[a] = p;
  quad_[a] += quad_[b];
  touches_feature_[a] = feat;
  ++stamp_[a];
}

}  // namespace interfere::qem
