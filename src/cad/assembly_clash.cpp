// Instance-pair interference of an assembly (include/interfere/cad/assembly_clash.h): the scene
// clash engine (scene/engine.h: the exact core of paper 1 on every pair of instances whose world
// boxes come within the clearance) on the assembly's scene.
#include "interfere/cad/assembly_clash.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <tuple>

#include "assembly_clash_internal.h"
#include "interfere/cad/assembly_scene.h"
#include "interfere/scene/engine.h"

namespace interfere::cad {

const char* instance_meeting_name(InstanceMeeting m) {
  switch (m) {
    case InstanceMeeting::clash:
      return "clash";
    case InstanceMeeting::contact:
      return "contact";
    case InstanceMeeting::clearance:
      return "clearance";
    case InstanceMeeting::undecided:
      return "undecided";
  }
  return "?";
}

// A user of the scene engine (issue #24, item 3: one code path): the assembly as a scene
// (assembly_scene.cpp), one all-pairs test (clearance mode when a clearance is asked for), the
// nominal-fit rule as the engine's hook; the engine's clashes are folded back into instance pairs.
AssemblyClashResult assembly_clash(const CadModel& model, const AssemblyClashOptions& options) {
  AssemblyClashResult out;
  const scene::Scene s = assembly_scene(model);
  scene::ClashTest test;
  test.name = "assembly";
  if (options.clearance > 0) test.mode = scene::ClashMode::clearance, test.clearance = options.clearance;
  scene::SceneClashOptions eo;
  eo.depth_bound_splits = options.depth_bound_splits;
  eo.curves = options.geometry;
  eo.triangles = options.geometry;
  eo.group_by = scene::GroupBy::none;
  eo.nominal_fit = nominal_fit_check(model, s);
  // Zero-clearance fits classified from the B-Rep (issue #29, item 4): pairs of instances whose
  // tessellations the core shows apart, or not at all (placements rounded a hair apart: the AS1
  // AP203 export's bracket 1.3e-12 mm above its plate), with coincident B-Rep faces whose triangles
  // come within the fit tolerance are contacts: the engine's hook, as for clash --scene.
  eo.zero_clearance_fits = zero_clearance_fit_check(model, s);
  eo.pair_progress = options.progress;
  // The core's per-pair figures (counts, containment), by instance pair.
  struct Raw {
    std::size_t cross = 0, touch = 0, clearance = 0, regions = 0;
    double min_clearance = 0, curve_length = 0;
    Containment containment = Containment::not_checked;
    bool touching_overlap = false;
  };
  std::mutex mutex;
  std::map<std::pair<std::uint32_t, std::uint32_t>, Raw> raw;
  eo.on_pair = [&](std::size_t, std::uint32_t a, std::uint32_t b, const ClashResult& r) {
    Raw x{.cross = r.cross_pairs, .touch = r.touch_pairs, .clearance = r.clearance.size(), .regions = r.regions.size()};
    if (!r.clearance.empty()) {
      x.min_clearance = r.clearance.front().distance;
      for (const ClearancePair& c : r.clearance) x.min_clearance = std::min(x.min_clearance, c.distance);
    }
    for (const ClashRegion& g : r.regions) x.curve_length += g.curve_length;
    x.containment = r.containment;
    if (a > b) {  // instance order, a < b
      std::swap(a, b);
      if (x.containment == Containment::a_inside_b) x.containment = Containment::b_inside_a;
      else if (x.containment == Containment::b_inside_a) x.containment = Containment::a_inside_b;
    }
    x.touching_overlap = r.touching_overlap;
    const std::lock_guard lock(mutex);
    raw[{a, b}] = x;
  };
  const scene::SceneClashResult r = scene::clash_scene(s, {test}, eo);
  out.candidate_pairs = r.candidate_pairs;
  for (const scene::PairSummary& ps : r.pairs) {
    InstancePairResult p;
    const bool swapped = ps.a > ps.b;
    p.a = std::min(ps.a, ps.b), p.b = std::max(ps.a, ps.b);
    const auto seen = raw.find({p.a, p.b});
    const Raw x = seen != raw.end() ? seen->second : Raw{};
    p.cross_pairs = x.cross, p.touch_pairs = x.touch, p.clearance_pairs = x.clearance;
    p.min_clearance = x.min_clearance, p.containment = x.containment, p.touching_overlap = x.touching_overlap;
    p.regions = x.regions, p.curve_length = x.curve_length;
    p.tessellation_error = model.parts[model.instances[p.a].part].tessellation_error() +
                           model.parts[model.instances[p.b].part].tessellation_error();
    p.depth = ps.depth;
    switch (ps.verdict) {
      case Verdict::clash: p.meeting = InstanceMeeting::clash; break;
      case Verdict::undecided: p.meeting = InstanceMeeting::undecided; break;
      case Verdict::clearance: p.meeting = InstanceMeeting::clearance; break;
      default: p.meeting = InstanceMeeting::contact; break;
    }
    if (p.meeting == InstanceMeeting::clash && x.cross > 0 && options.depth_bound_splits > 0) p.depth_bound = ps.depth_bound;
    for (const std::uint32_t k : ps.clashes) {
      const scene::SceneClash& c = r.clashes[k];
      p.nominal_fit = p.nominal_fit || c.kind == "nominal_fit";
      if (c.kind == "zero_clearance_fit") {
        p.zero_clearance_fit = true;
        if (seen == raw.end()) p.min_clearance = c.distance;  // (a pair the core never saw: the fit's gap)
      }
      if (c.verdict == Verdict::undecided)
        p.verdict_reasons.insert(p.verdict_reasons.end(), c.reasons.begin(), c.reasons.end());
      if (options.geometry && p.meeting == InstanceMeeting::clash) {
        p.curves.insert(p.curves.end(), c.curves.begin(), c.curves.end());
        auto& ta = swapped ? p.region_triangles_b : p.region_triangles_a;
        auto& tb = swapped ? p.region_triangles_a : p.region_triangles_b;
        ta.insert(ta.end(), c.triangles_a.begin(), c.triangles_a.end());
        tb.insert(tb.end(), c.triangles_b.begin(), c.triangles_b.end());
      }
    }
    for (auto* v : {&p.region_triangles_a, &p.region_triangles_b}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    out.clashes += p.meeting == InstanceMeeting::clash;
    out.contacts += p.meeting == InstanceMeeting::contact;
    out.within_clearance += p.meeting == InstanceMeeting::clearance;
    out.undecided += p.meeting == InstanceMeeting::undecided;
    out.verdict = worst(out.verdict, ps.verdict);
    out.pairs.push_back(std::move(p));
  }
  std::sort(out.pairs.begin(), out.pairs.end(),
            [](const InstancePairResult& x, const InstancePairResult& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  out.warnings = r.warnings;
  return out;
}

}  // namespace interfere::cad
