// One body pair of a clash test (include/interfere/scene/engine.h, issue #24 items 3-4): the exact
// two-part core (query/clash.h) decides; its regions become clashes with tight boxes,
// representative points, source ids and depth bounds (query/depth.h); the test's mode, penetration
// tolerance and nominal-fit rule turn them into verdicts.
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine_internal.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"
#include "interfere/query/distance.h"

namespace interfere::scene::detail {

const MeshStats& WorldBody::stats() {
  // Isolated: a thread waiting inside its parallel loop must not pick up another pair's task that
  // asks for this body's statistics (it would wait on itself).
  std::call_once(*stats_once, [&] {
    if (prebuilt && prebuilt->stats.triangles > 0) lazy_stats = prebuilt->stats;
    else tbb::this_task_arena::isolate([&] { lazy_stats = mesh_stats(model().mesh); });
  });
  return lazy_stats;
}

namespace {

Aabb intersection(const Aabb& x, const Aabb& y) {
  Aabb r;
  r.lo = max(x.lo, y.lo), r.hi = min(x.hi, y.hi);
  return r;
}

// The body pair's duplicates test: the same triangle count, boxes within the tolerance, and every
// vertex of each within the tolerance of the other's surface (the symmetric vertex-to-surface
// distance bounds the placement error of one geometry placed twice).
bool duplicates(const Model& x, const Aabb& box_x, const Model& y, const Aabb& box_y, double tol) {
  if (x.mesh.num_triangles() != y.mesh.num_triangles()) return false;
  for (int k = 0; k < 3; ++k)
    if (std::fabs(box_x.lo[k] - box_y.lo[k]) > tol || std::fabs(box_x.hi[k] - box_y.hi[k]) > tol) return false;
  const auto near = [tol](const Model& from, const Model& to) {
    for (const Vec3& p : from.mesh.positions)
      if (surface_distance(to, p) > tol) return false;
    return true;
  };
  return near(x, y) && near(y, x);
}

// A representative point of a crossing region: the curve point nearest the middle of its box
// (ties: the first in curve order), so it lies on the intersection.
Vec3 curve_point(const std::vector<Polyline>& curves, const Aabb& box) {
  const Vec3 mid = box.center();
  Vec3 best = mid;
  double d = std::numeric_limits<double>::infinity();
  for (const Polyline& l : curves)
    for (const Vec3& p : l.points)
      if (const double e = squared_norm(p - mid); e < d) d = e, best = p;
  return best;
}

}  // namespace

void set_sources(SceneClash& c, const Body& a, const Body& b) {
  for (const auto& [tris, body, out] : {std::tuple{&c.triangles_a, &a, &c.source_ids_a},
                                       std::tuple{&c.triangles_b, &b, &c.source_ids_b}}) {
    out->reserve(tris->size());
    for (const std::uint32_t t : *tris) out->push_back(body->source_id(t));
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
  }
}

std::string inside_reason(const Body& inner, const Body& outer) {
  return "body '" + inner.id + "' (or a component of it) lies inside body '" + outer.id + "'";
}

PairCore core_pair(const PairContext& c, const PairFrame& f, std::uint32_t a, std::uint32_t b, double clearance) {
  PairCore core;
  const Model& ma = *f.a;
  const Model& mb = *f.b;
  ClashRequest request = c.options.request;
  request.clearance = clearance;
  request.stats = f.stats;
  if (c.many_pairs && ma.mesh.num_triangles() + mb.mesh.num_triangles() < 100000)
    request.parallel = false;
  // Clearance pairs matter only for bodies whose surfaces do not meet and neither lies inside the
  // other (verdict clear without them; derive_pair reports regions, containment or undecided
  // first). So the core first runs without clearance, and again with it only for such a pair: a
  // seated contact's many near triangle pairs get no distance computed. The second run is the run
  // at that clearance (the same surface pairs; containment and warnings are the first run's, as
  // its tests do not depend on the clearance). Not where a caller sees the core result (on_pair),
  // nor without regions (then clearance pairs are reported beside surface pairs), nor with a
  // non-exact triangle test (the core switches to the exact one for a clearance).
  const bool two_step = clearance > 0 && !c.options.on_pair && request.regions && request.test == TriTest::exact;
  if (two_step) request.clearance = 0;
  core.r = clash(ma, mb, request);
  if (two_step && core.r.verdict == Verdict::clear) {
    request.clearance = clearance;
    request.containment = false;
    ClashResult second = clash(ma, mb, request);
    second.containment = core.r.containment;
    second.warnings = std::move(core.r.warnings);
    core.r = std::move(second);
  }
  core.clearance = clearance;
  if (c.options.on_pair && f.world) c.options.on_pair(c.test_index, a, b, core.r);  // (else per member: engine.cpp)
  // Depth of crossing (or touching but overlapping) closed solids (the statistics are computed
  // here when not yet known: the depth needs inside/outside).
  const bool crossing = core.r.cross_pairs > 0 || core.r.touching_overlap;
  const bool inside = core.r.containment == Containment::a_inside_b || core.r.containment == Containment::b_inside_a;
  if (c.options.depth && (crossing || (inside && c.options.depth_maps)) && f.stats(0).closed() && f.stats(1).closed()) {
    // (containment: the maps only; the pair's depth stays unmeasured as before)
    const PenetrationDepth d = penetration_depth(ma, mb, core.r, c.depth_bound_splits,
                                                 c.options.depth_maps ? &core.maps : nullptr);
    if (crossing) core.depth = d, core.depth_known = true;
    core.maps_known = c.options.depth_maps;
  }
  return core;
}

void narrow_clearance(PairCore& core, double clearance) {
  if (clearance >= core.clearance) return;
  ClashResult& r = core.r;
  std::erase_if(r.clearance, [&](const ClearancePair& p) { return !(p.distance < clearance); });
  if (r.verdict == Verdict::clearance && r.clearance.empty()) r.verdict = Verdict::clear;
  core.clearance = clearance;
}

std::vector<SceneClash> derive_pair(const PairContext& c, const PairFrame& f, std::uint32_t a, std::uint32_t b,
                                    double clearance, PairCore* core, std::vector<std::array<Vec3, 2>>& locations) {
  std::vector<SceneClash> out;
  locations.clear();
  // Id locations (engine_internal.h) in a's and in b's local frame, from the clash's own geometry
  // (curves, touching triangles, witness segments), so that they follow the clash, not the
  // triangles, and change when it moves on either body.
  const std::array<std::uint32_t, 2> ab{a, b};
  const std::array<Transform, 2>& to = f.to_local;
  const auto local_box_center = [&](int side) {
    Aabb box;
    for (const Vec3& v : c.local_positions(ab[side])) box.expand(v);
    std::array<Vec3, 2> out;
    for (int k = 0; k < 2; ++k) out[k] = k == side ? box.center() : to[k].apply(f.to_frame[side].apply(box.center()));
    return out;
  };
  const Model& ma = *f.a;
  const Model& mb = *f.b;
  const bool keep_curves = c.options.curves || !f.world;
  const Body& ba = c.scene.bodies[a];
  const Body& bb = c.scene.bodies[b];
  const auto base = [&](Verdict v, const char* kind) {
    SceneClash s;
    s.test = c.test.name;
    s.a = a, s.b = b;
    s.verdict = v;
    s.kind = kind;
    return s;
  };
  if (c.test.mode == ClashMode::duplicates) {
    if (!duplicates(ma, f.box_a, mb, f.box_b, c.test.tolerance)) return out;
    SceneClash s = base(Verdict::clash, "duplicate");
    s.box = f.box_a;
    s.box.expand(f.box_b);
    s.point = f.box_a.center();
    s.reasons.push_back("the same geometry placed twice (within " + short_number(c.test.tolerance) + ")");
    out.push_back(std::move(s));
    locations.push_back(local_box_center(0));
    return out;
  }
  narrow_clearance(*core, clearance);
  const ClashResult& r = core->r;
  if (r.verdict == Verdict::clear) return out;

  const bool inside = r.containment == Containment::a_inside_b || r.containment == Containment::b_inside_a;
  const PenetrationDepth& depth = core->depth;
  const bool depth_known = core->depth_known;
  bool nominal = false;
  if (r.cross_pairs > 0 && !inside && !r.touching_overlap && c.test.nominal_fits_are_contacts && c.options.nominal_fit)
    nominal = c.options.nominal_fit(a, b, ma, mb, r, depth.depth);
  // Penetration tolerance (hard mode): the upper bound decides, so no deeper clash is hidden.
  const bool shallow = r.cross_pairs > 0 && !inside && !r.touching_overlap && c.test.tolerance > 0 &&
                       c.test.mode != ClashMode::duplicates && depth_known && depth.depth_bound <= c.test.tolerance;

  if (inside) {
    const bool a_in = r.containment == Containment::a_inside_b;
    SceneClash s = base(Verdict::clash, "inside");
    s.box = a_in ? f.box_a : f.box_b;
    s.point = s.box.center();
    if (c.options.triangles) {
      auto& tris = a_in ? s.triangles_a : s.triangles_b;
      tris.resize((a_in ? ma : mb).mesh.num_triangles());
      for (std::uint32_t t = 0; t < tris.size(); ++t) tris[t] = t;
      set_sources(s, ba, bb);
    }
    s.reasons.push_back(a_in ? inside_reason(ba, bb) : inside_reason(bb, ba));
    out.push_back(std::move(s));
    locations.push_back(local_box_center(a_in ? 0 : 1));
    return out;
  }
  // The pairs of each region (those whose triangle of a is one of the region's), in pair order:
  // built once, not searched per region.
  std::vector<std::vector<std::uint32_t>> region_pairs(r.regions.size());
  {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> owner;  // (triangle of a, region)
    for (std::uint32_t k = 0; k < r.regions.size(); ++k)
      for (const std::uint32_t t : r.regions[k].triangles_a) owner.emplace_back(t, k);
    std::sort(owner.begin(), owner.end());
    for (std::uint32_t i = 0; i < r.pairs.size(); ++i) {
      auto it = std::lower_bound(owner.begin(), owner.end(), std::pair{r.pairs[i].a, std::uint32_t{0}});
      for (; it != owner.end() && it->first == r.pairs[i].a; ++it)
        if (region_pairs[it->second].empty() || region_pairs[it->second].back() != i) region_pairs[it->second].push_back(i);
    }
  }
  for (std::size_t gi = 0; gi < r.regions.size(); ++gi) {
    const ClashRegion& g = r.regions[gi];
    SceneClash s = base(Verdict::contact, "touch");
    if (g.cross_pairs > 0) {
      if (nominal) {
        s.kind = "nominal_fit";
        s.reasons.push_back("crossings only where B-Rep faces coincide within the tessellation error");
      } else if (shallow) {
        s.kind = "within_tolerance";
        s.reasons.push_back("depth bound " + short_number(depth.depth_bound) + " <= tolerance " +
                            short_number(c.test.tolerance));
      } else {
        s.verdict = Verdict::clash, s.kind = "crossing";
      }
    } else if (r.touching_overlap) {
      s.verdict = Verdict::clash, s.kind = "touching_overlap";
    } else if (r.verdict == Verdict::undecided) {
      s.verdict = Verdict::undecided, s.kind = "undecided";
      s.reasons = r.verdict_reasons;
    }
    if (r.cross_pairs > 0 && !depth_known && s.verdict == Verdict::clash)
      s.reasons.push_back(c.options.depth ? "depth not measured: a body is not closed" : "depth not measured (not requested)");
    s.cross_pairs = g.cross_pairs, s.touch_pairs = g.touch_pairs;
    s.curve_length = g.curve_length;
    s.depth = depth.depth, s.depth_bound = depth.depth_bound;
    // Tight box: the curves, and where only touching, the common part of the touching triangles'
    // boxes (it holds the triangles' common points).
    for (const Polyline& l : g.curves)
      for (const Vec3& p : l.points) s.box.expand(p);
    if (g.cross_pairs == 0 || s.box.empty()) {
      for (const std::uint32_t i : region_pairs[gi]) {
        const TrianglePair& p = r.pairs[i];
        const Aabb common = intersection(ma.mesh.triangle_box(p.a), mb.mesh.triangle_box(p.b));
        if (!common.empty()) s.box.expand(common);
      }
    }
    s.point = g.curves.empty() ? s.box.center() : curve_point(g.curves, s.box);
    std::array<Vec3, 2> loc;
    for (int k = 0; k < 2; ++k) {
      Aabb where;
      for (const Polyline& l : g.curves)
        for (const Vec3& p : l.points) where.expand(to[k].apply(p));
      if (where.empty()) {  // touching only: the common parts of the touching triangles, in this frame
        const std::vector<Vec3>& own = c.local_positions(ab[k]);
        const TriMesh& mesh_own = *c.scene.bodies[ab[k]].mesh;
        const TriMesh& other = (k == 0 ? mb : ma).mesh;
        for (const std::uint32_t i : region_pairs[gi]) {
          const TrianglePair& p = r.pairs[i];
          Aabb t_own, t_other;
          for (const std::uint32_t v : mesh_own.triangles[k == 0 ? p.a : p.b]) t_own.expand(own[v]);
          for (const Vec3& v : other.corners(k == 0 ? p.b : p.a)) t_other.expand(to[k].apply(v));
          if (const Aabb common = intersection(t_own, t_other); !common.empty()) where.expand(common);
          else where.expand(t_own);  // (rounding of the other's corners: this triangle stands for the contact)
        }
      }
      loc[k] = where.center();
    }
    locations.push_back(loc);
    if (keep_curves) s.curves = g.curves;
    if (c.options.triangles) {
      s.triangles_a = g.triangles_a, s.triangles_b = g.triangles_b;
      set_sources(s, ba, bb);
    }
    out.push_back(std::move(s));
  }
  if (!out.empty()) return out;
  if (r.verdict == Verdict::undecided) {  // no surface pair: containment could not be decided
    SceneClash s = base(Verdict::undecided, "undecided");
    s.box = intersection(f.box_a, f.box_b);
    if (s.box.empty()) s.box = f.box_a, s.box.expand(f.box_b);
    s.point = s.box.center();
    s.reasons = r.verdict_reasons;
    out.push_back(std::move(s));
    locations.push_back(local_box_center(0));
    return out;
  }
  if (!r.clearance.empty()) {
    const ClearancePair* m = &r.clearance.front();
    for (const ClearancePair& p : r.clearance)
      if (p.distance < m->distance) m = &p;
    SceneClash s = base(Verdict::clearance, "clearance");
    s.distance = m->distance;
    s.witness_a = m->point_a, s.witness_b = m->point_b;
    s.box.expand(m->point_a), s.box.expand(m->point_b);
    s.point = (m->point_a + m->point_b) * 0.5;
    s.reasons.push_back("closer than the required clearance " + short_number(clearance));
    if (c.options.triangles) {
      s.triangles_a = {m->a}, s.triangles_b = {m->b};
      set_sources(s, ba, bb);
    }
    out.push_back(std::move(s));
    std::array<Vec3, 2> loc;  // every pair within the clearance (continuous: no tie between witnesses)
    for (int k = 0; k < 2; ++k) {
      Aabb where;
      for (const ClearancePair& p : r.clearance) where.expand(to[k].apply(p.point_a)), where.expand(to[k].apply(p.point_b));
      loc[k] = where.center();
    }
    locations.push_back(loc);
  }
  return out;
}

}  // namespace interfere::scene::detail
