// Static clash query (issue #2, item 5): broad phase (tree vs tree, or the paper's brute-force
// strategies), exact narrow phase with classification, clearance pairs, regions and containment.
#include "interfere/query/clash.h"

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "clash_internal.h"
#include "interfere/bvh/traverse.h"
#include "interfere/np/distance.h"

namespace interfere {

const char* containment_name(Containment c) {
  switch (c) {
    case Containment::none: return "none";
    case Containment::a_inside_b: return "a_inside_b";
    case Containment::b_inside_a: return "b_inside_a";
    case Containment::not_checked: return "not_checked";
  }
  return "?";
}

namespace {

using detail::Hit;

/// A narrow-phase output: either an intersecting pair or a clearance pair.
struct Found {
  Hit hit;
  bool is_clearance = false;
  ClearancePair near;
};

class NarrowPhase {
 public:
  NarrowPhase(const TriMesh& a, const TriMesh& b, const ClashRequest& r) : a_(a), b_(b), r_(r) {}

  void operator()(std::uint32_t ia, std::uint32_t ib, std::vector<Found>& out) const {
    ++candidates_.local();  // per-thread counter: no shared cache line in the hot loop
    const auto ta = a_.corners(ia), tb = b_.corners(ib);
    Found f;
    f.hit.a = ia, f.hit.b = ib;
    switch (r_.test) {
      case TriTest::exact: {
        if (r_.regions) {
          const TriTriResult res = tri_tri_exact(ta, tb);
          f.hit.kind = res.kind;
          if (res.kind == ContactKind::cross) {
            f.hit.has_segment = true;
            f.hit.segment = res.segment;
            f.hit.feature_a = res.feature_a;
            f.hit.feature_b = res.feature_b;
          }
        } else {
          f.hit.kind = tri_tri_exact_kind(ta, tb);
        }
        break;
      }
      case TriTest::moller:
        f.hit.kind = tri_tri_moller(ta, tb) ? ContactKind::cross : ContactKind::none;
        break;
      case TriTest::guigue_devillers:
        f.hit.kind = tri_tri_guigue_devillers(ta, tb) ? ContactKind::cross : ContactKind::none;
        break;
    }
    if (f.hit.kind != ContactKind::none) {
      out.push_back(f);
      return;
    }
    if (r_.clearance > 0) {
      const ClosestPoints cp = triangle_triangle_closest(ta, tb);
      if (cp.distance < r_.clearance) {
        f.is_clearance = true;
        f.near = {.a = ia, .b = ib, .distance = cp.distance, .point_a = cp.p, .point_b = cp.q};
        out.push_back(f);
      }
    }
  }

  std::size_t candidates() const { return candidates_.combine(std::plus<>()); }

 private:
  const TriMesh& a_;
  const TriMesh& b_;
  const ClashRequest& r_;
  mutable tbb::combinable<std::size_t> candidates_{[] { return std::size_t{0}; }};
};

/// All |A|·|B| pairs (optionally box-pretested), rows of A split across threads; rows are
/// concatenated in order, so the output does not depend on the thread count.
std::vector<Found> all_pairs(const Model& a, const Model& b, const ClashRequest& r,
                             const NarrowPhase& np, bool box_pretest) {
  const std::size_t na = a.mesh.num_triangles(), nb = b.mesh.num_triangles();
  std::vector<Aabb> boxes_b;
  if (box_pretest) {
    boxes_b.reserve(nb);
    for (std::size_t j = 0; j < nb; ++j) boxes_b.push_back(b.mesh.triangle_box(j));
  }
  std::vector<std::vector<Found>> rows(na);
  auto row = [&](std::size_t i) {
    Aabb box_a;
    if (box_pretest) {
      box_a = a.mesh.triangle_box(i);
      box_a.lo -= Vec3{r.clearance, r.clearance, r.clearance};
      box_a.hi += Vec3{r.clearance, r.clearance, r.clearance};
    }
    for (std::size_t j = 0; j < nb; ++j) {
      if (box_pretest && !box_a.overlaps(boxes_b[j])) continue;
      np(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), rows[i]);
    }
  };
  if (r.parallel) {
    tbb::parallel_for(std::size_t{0}, na, row);
  } else {
    for (std::size_t i = 0; i < na; ++i) row(i);
  }
  std::vector<Found> out;
  for (auto& v : rows) out.insert(out.end(), v.begin(), v.end());
  return out;
}

}  // namespace

ClashResult clash(const Model& a, const Model& b, const ClashRequest& request) {
  ClashResult result;
  if (request.clearance < 0 || !std::isfinite(request.clearance)) {
    result.warnings.push_back("clearance must be a finite number >= 0; ignored");
  }
  ClashRequest r = request;
  if (!(r.clearance >= 0) || !std::isfinite(r.clearance)) r.clearance = 0;
  if (r.clearance > 0 && r.test != TriTest::exact) {
    // Clearance needs an exact intersection decision first (a pair is either a clash or near).
    result.warnings.push_back("clearance uses the exact test to separate clashes from near pairs");
    r.test = TriTest::exact;
  }

  NarrowPhase np(a.mesh, b.mesh, r);
  std::vector<Found> found;
  if (r.broadphase == Broadphase::bvh) {
    const float margin = r.clearance > 0 ? round_up(r.clearance) : 0.0f;
    if (r.parallel) {
      found = collide_parallel<Found>(
          a.bvh, b.bvh, ParallelTraversalOptions{.margin = margin},
          [&](std::uint32_t ia, std::uint32_t ib, std::vector<Found>& out) { np(ia, ib, out); });
    } else {
      for_each_overlap(a.bvh, b.bvh, margin,
                       [&](std::uint32_t ia, std::uint32_t ib) { np(ia, ib, found); });
    }
  } else {
    found = all_pairs(a, b, r, np, r.broadphase == Broadphase::box_pretest);
  }
  result.candidate_pairs = np.candidates();

  std::vector<Hit> hits;
  hits.reserve(found.size());
  for (Found& f : found) {
    if (f.is_clearance) {
      result.clearance.push_back(f.near);
    } else {
      hits.push_back(f.hit);
    }
  }
  auto by_ab = [](const auto& x, const auto& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
  std::sort(hits.begin(), hits.end(), by_ab);
  std::sort(result.clearance.begin(), result.clearance.end(), by_ab);

  result.pairs.reserve(hits.size());
  for (const Hit& h : hits) {
    result.pairs.push_back({h.a, h.b, h.kind});
    (h.kind == ContactKind::cross ? result.cross_pairs : result.touch_pairs)++;
  }
  if (r.regions) result.regions = detail::build_regions(a.mesh, b.mesh, hits);

  // Containment (no surface pair can exist when one closed part lies wholly inside the other).
  if (!r.containment) {
    result.containment = Containment::not_checked;
  } else if (!result.pairs.empty()) {
    result.containment = Containment::none;
  } else if (a.mesh.triangles.empty() || b.mesh.triangles.empty()) {
    result.containment = Containment::none;
  } else {
    auto open_warning = [&](const char* name, const MeshStats& s) {
      result.warnings.push_back(std::string("part ") + name + " is not closed (" +
                                std::to_string(s.open_edges) + " open, " +
                                std::to_string(s.nonmanifold_edges) + " non-manifold, " +
                                std::to_string(s.inconsistent_edges) +
                                " inconsistently oriented edges): containment not checked");
    };
    const bool a_closed = a.stats.closed(), b_closed = b.stats.closed();
    if (!a_closed) open_warning("A", a.stats);
    if (!b_closed) open_warning("B", b.stats);
    if (a_closed && b_closed) {
      const Vec3 pa = a.mesh.positions[a.mesh.triangles[0][0]];
      const Vec3 pb = b.mesh.positions[b.mesh.triangles[0][0]];
      const int a_in_b = detail::point_in_closed_mesh(b, pa);
      const int b_in_a = detail::point_in_closed_mesh(a, pb);
      if (a_in_b < 0 || b_in_a < 0) {
        result.warnings.push_back("containment undecided: every ray direction was degenerate");
        result.containment = Containment::not_checked;
      } else if (a_in_b == 1) {
        result.containment = Containment::a_inside_b;
      } else if (b_in_a == 1) {
        result.containment = Containment::b_inside_a;
      } else {
        result.containment = Containment::none;
      }
    } else {
      result.containment = Containment::not_checked;
    }
  }
  return result;
}

}  // namespace interfere
