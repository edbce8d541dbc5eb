// Static clash query (issue #2, item 5): broad phase (tree vs tree, or the paper's brute-force
// strategies), exact narrow phase with classification, clearance pairs, regions and containment.
#include "interfere/query/clash.h"

#include <tuple>
#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_sort.h>
#include <tbb/parallel_for.h>

#include "clash_internal.h"
#include "interfere/mesh/validate.h"
#include "interfere/bvh/traverse.h"
#include "interfere/np/distance.h"

namespace interfere {

int point_in_solid(const Model& solid, const Vec3& p) { return detail::point_in_closed_mesh(solid, p); }

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

using detail::Segment;

struct ByAb {
  template <class X>
  bool operator()(const X& x, const X& y) const {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  }
};

/// Narrow phase: appends intersecting pairs to the traversal's output and keeps the bulkier
/// by-products (crossing segments, clearance pairs) in per-thread side buffers; everything is
/// sorted by (a, b) afterwards, so no order depends on the thread count.
class NarrowPhase {
 public:
  NarrowPhase(const TriMesh& a, const TriMesh& b, const ClashRequest& r) : a_(a), b_(b), r_(r) {}

  void operator()(std::uint32_t ia, std::uint32_t ib, std::vector<TrianglePair>& out) const {
    ++candidates_.local();  // per-thread counter: no shared cache line in the hot loop
    const auto ta = a_.corners(ia), tb = b_.corners(ib);
    ContactKind kind = ContactKind::none;
    switch (r_.test) {
      case TriTest::exact:
        if (r_.regions) {
          const TriTriResult res = tri_tri_exact(ta, tb);
          kind = res.kind;
          if (kind == ContactKind::cross) {
            segments_.local().push_back(
                {.a = ia, .b = ib, .points = res.segment, .feature_a = res.feature_a, .feature_b = res.feature_b});
          }
        } else {
          kind = tri_tri_exact_kind(ta, tb);
        }
        break;
      case TriTest::moller:
        kind = tri_tri_moller(ta, tb) ? ContactKind::cross : ContactKind::none;
        break;
      case TriTest::guigue_devillers:
        kind = tri_tri_guigue_devillers(ta, tb) ? ContactKind::cross : ContactKind::none;
        break;
    }
    if (kind != ContactKind::none) {
      out.push_back({ia, ib, kind});
      return;
    }
    if (r_.clearance > 0) {
      const ClosestPoints cp = triangle_triangle_closest(ta, tb);
      if (cp.distance < r_.clearance) {
        clearance_.local().push_back({.a = ia, .b = ib, .distance = cp.distance, .point_a = cp.p, .point_b = cp.q});
      }
    }
  }

  std::size_t candidates() const { return candidates_.combine(std::plus<>()); }
  template <class T>
  static std::vector<T> gather(tbb::enumerable_thread_specific<std::vector<T>>& parts) {
    std::vector<T> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    tbb::parallel_sort(all.begin(), all.end(), ByAb{});
    return all;
  }
  std::vector<Segment> segments() { return gather(segments_); }
  std::vector<ClearancePair> clearance() { return gather(clearance_); }

 private:
  const TriMesh& a_;
  const TriMesh& b_;
  const ClashRequest& r_;
  mutable tbb::combinable<std::size_t> candidates_{[] { return std::size_t{0}; }};
  mutable tbb::enumerable_thread_specific<std::vector<Segment>> segments_;
  mutable tbb::enumerable_thread_specific<std::vector<ClearancePair>> clearance_;
};

/// All |A|·|B| pairs (optionally box-pretested), rows of A split across threads; rows are
/// concatenated in order, so the output does not depend on the thread count.
std::vector<TrianglePair> all_pairs(const Model& a, const Model& b, const ClashRequest& r,
                                     const NarrowPhase& np, bool box_pretest) {
  const std::size_t na = a.mesh.num_triangles(), nb = b.mesh.num_triangles();
  std::vector<Aabb> boxes_b;
  if (box_pretest) {
    boxes_b.reserve(nb);
    for (std::size_t j = 0; j < nb; ++j) boxes_b.push_back(b.mesh.triangle_box(j));
  }
  std::vector<std::vector<TrianglePair>> rows(na);
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
  std::vector<TrianglePair> out;
  for (auto& v : rows) out.insert(out.end(), v.begin(), v.end());
  return out;
}


// One vertex of each connected component of a mesh (triangles joined by shared vertices), in the
// order of their lowest triangle: containment must test every component, as a part of several
// (a bolt and its nut in one file) may have one inside the other part and one outside.
std::vector<std::uint32_t> component_vertices(const TriMesh& m) {
  const std::vector<std::uint32_t> set = connected_sets(m, std::vector<char>(m.num_triangles(), 1));
  std::vector<std::uint32_t> out;
  for (std::uint32_t t = 0; t < set.size(); ++t)
    if (set[t] == t) out.push_back(m.triangles[t][0]);  // the set's smallest triangle
  return out;
}

// Whether some component of `part` (one vertex of each: `vertices`) lies inside the closed `solid`:
// 1 yes, 0 no, -1 undecided (every ray direction degenerate for a component, none inside).
int some_component_inside(const Model& solid, const TriMesh& part, const std::vector<std::uint32_t>& vertices) {
  int result = 0;
  for (const std::uint32_t v : vertices) {
    const int in = detail::point_in_closed_mesh(solid, part.positions[v]);
    if (in == 1) return 1;
    if (in < 0) result = -1;
  }
  return result;
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
  if (r.broadphase == Broadphase::bvh) {
    const float margin = r.clearance > 0 ? round_up(r.clearance) : 0.0f;
    if (r.parallel) {
      result.pairs = collide_parallel<TrianglePair>(
          a.bvh, b.bvh, ParallelTraversalOptions{.margin = margin},
          [&](std::uint32_t ia, std::uint32_t ib, std::vector<TrianglePair>& out) { np(ia, ib, out); });
    } else {
      for_each_overlap(a.bvh, b.bvh, margin, [&](std::uint32_t ia, std::uint32_t ib) { np(ia, ib, result.pairs); });
    }
  } else {
    result.pairs = all_pairs(a, b, r, np, r.broadphase == Broadphase::box_pretest);
  }
  result.candidate_pairs = np.candidates();
  tbb::parallel_sort(result.pairs.begin(), result.pairs.end(), ByAb{});
  result.clearance = np.clearance();
  for (const TrianglePair& p : result.pairs) (p.kind == ContactKind::cross ? result.cross_pairs : result.touch_pairs)++;
  if (r.regions) result.regions = detail::build_regions(a.mesh, b.mesh, result.pairs, np.segments());

  // Containment (no surface pair can exist when one closed part lies wholly inside the other).
  // Statistics only where a branch needs them (ClashRequest::stats may compute them lazily).
  const auto stats_of = [&](int side) -> const MeshStats& {
    if (r.stats) return r.stats(side);
    return side == 0 ? a.stats : b.stats;
  };
  const auto closed = [&](int side) { return stats_of(side).closed(); };
  auto open_reason = [&](const char* name, const MeshStats& s) {
    if (s.triangles == 0)
      return std::string("part ") + name + ": mesh statistics not computed (make_model with_stats = false)";
    return std::string("part ") + name + " is not closed (" + std::to_string(s.open_edges) + " open, " +
           std::to_string(s.nonmanifold_edges) + " non-manifold, " + std::to_string(s.inconsistent_edges) +
           " inconsistently oriented edges)";
  };
  std::vector<std::string> undecided;  // what could not be decided (the verdict's reasons)
  if (!r.containment) {
    result.containment = Containment::not_checked;
  } else if (!result.pairs.empty()) {
    result.containment = Containment::none;
    if (result.cross_pairs == 0) {
      if (closed(0) && closed(1)) {
        const int overlap = detail::touching_overlap(a, b, result.pairs);
        result.touching_overlap = overlap == 1;
        if (overlap < 0) {
          result.warnings.push_back("touching overlap undecided: every ray direction was degenerate");
          undecided.push_back("whether the touching solids overlap: every ray direction was degenerate");
        }
      } else {
        // Touching surfaces of an open part: whether the solids' interiors overlap (coincident
        // faces of overlapping solids) needs both closed.
        for (const auto& [name, side] : {std::pair{"A", 0}, std::pair{"B", 1}})
          if (!closed(side)) {
            result.warnings.push_back(open_reason(name, stats_of(side)) + ": whether the touching parts overlap is not checked");
            undecided.push_back(open_reason(name, stats_of(side)) + ": whether the touching parts overlap");
          }
      }
    }
  } else if (a.mesh.triangles.empty() || b.mesh.triangles.empty()) {
    result.containment = Containment::none;
  } else {
    // A closed part may contain the other (open or not): one point of each of the other's
    // components decides, as no surface pair exists. An open part encloses nothing provably, so
    // the reverse stays undecided.
    // A component lies inside the other part only if its vertices lie in that part's box (the
    // tree's root box contains it): components with a vertex outside are skipped exactly, and only
    // where one remains are the other part's statistics needed (ClashRequest::stats: lazy).
    const auto candidates = [](const Model& pm, const Bvh& other) {
      const TriMesh& part = pm.mesh;
      const AabbF& o = other.nodes[0].box;
      std::vector<std::uint32_t> out;
      const auto in_box = [&](const Vec3& p) {
        return p.x >= o.lo[0] && p.x <= o.hi[0] && p.y >= o.lo[1] && p.y <= o.hi[1] && p.z >= o.lo[2] && p.z <= o.hi[2];
      };
      // A component in that box has every triangle in it: for a large part, first look for one
      // such triangle through the part's own tree (only triangles whose boxes meet the box are
      // visited); none, no candidate, and the connected-components pass over the whole part is
      // skipped (issue #28: a 10^6-triangle workpiece against a robot link, per pair and frame).
      if (part.num_triangles() > 4096 && !pm.bvh.empty()) {
        bool any = false;
        for_each_in_box(pm.bvh, o, [&](std::uint32_t t) {
          if (!any) {
            const Tri& f = part.triangles[t];
            any = in_box(part.positions[f[0]]) && in_box(part.positions[f[1]]) && in_box(part.positions[f[2]]);
          }
        });
        if (!any) return out;
      }
      for (const std::uint32_t v : component_vertices(part)) {
        const Vec3& p = part.positions[v];
        if (p.x >= o.lo[0] && p.x <= o.hi[0] && p.y >= o.lo[1] && p.y <= o.hi[1] && p.z >= o.lo[2] && p.z <= o.hi[2])
          out.push_back(v);
      }
      return out;
    };
    const std::vector<std::uint32_t> ca = candidates(a, b.bvh), cb = candidates(b, a.bvh);
    const int a_in_b = ca.empty() ? 0 : closed(1) ? some_component_inside(b, a.mesh, ca) : -2;
    const int b_in_a = cb.empty() ? 0 : closed(0) ? some_component_inside(a, b.mesh, cb) : -2;
    const bool a_closed = b_in_a != -2, b_closed = a_in_b != -2;  // (as far as needed)
    if (a_in_b == 1) {
      result.containment = Containment::a_inside_b;
    } else if (b_in_a == 1) {
      result.containment = Containment::b_inside_a;
    } else if (a_in_b == -1 || b_in_a == -1) {
      result.warnings.push_back("containment undecided: every ray direction was degenerate");
      undecided.push_back("containment: every ray direction was degenerate");
      result.containment = Containment::not_checked;
    } else if (a_closed && b_closed) {
      result.containment = Containment::none;
    } else {
      for (const auto& [name, side, c] : {std::tuple{"A", 0, a_closed}, std::tuple{"B", 1, b_closed}})
        if (!c) {
          result.warnings.push_back(open_reason(name, stats_of(side)) + ": containment not checked");
          undecided.push_back(open_reason(name, stats_of(side)) + ": whether the other part lies inside it");
        }
      result.containment = Containment::not_checked;
    }
  }

  // The verdict (query/verdict.h).
  if (result.cross_pairs > 0 || result.containment == Containment::a_inside_b ||
      result.containment == Containment::b_inside_a || result.touching_overlap) {
    result.verdict = Verdict::clash;
  } else if (!undecided.empty()) {
    result.verdict = Verdict::undecided;
    result.verdict_reasons = std::move(undecided);
  } else if (result.touch_pairs > 0) {
    result.verdict = Verdict::contact;
  } else if (!result.clearance.empty()) {
    result.verdict = Verdict::clearance;
  } else {
    result.verdict = Verdict::clear;
  }
  return result;
}

}  // namespace interfere
