// Instance-pair interference of an assembly (include/interfere/cad/assembly_clash.h): the clash
// engine of paper 1 (exact triangle tests, regions, containment; query/clash.h) on every pair of
// instances whose world boxes overlap, found by sorting the boxes along x and sweeping.
#include "interfere/cad/assembly_clash.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "assembly_clash_internal.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/model.h"

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

AssemblyClashResult assembly_clash(const CadModel& model, const AssemblyClashOptions& options) {
  AssemblyClashResult out;
  const std::size_t n = model.instances.size();
  // Each instance in the world, welded (faces meeting along shared edges: a closed solid is
  // closed).
  std::vector<Model> world(n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    const Instance& in = model.instances[i];
    TriMesh m = transformed(model.parts[in.part].mesh, in.placement);
    weld_exact(m);
    world[i] = make_model(std::move(m));
  });
  // Candidates: boxes within the clearance of each other on every axis (sweep along x; growing the
  // low corners alone by it is the same test).
  const double grow = std::max(0.0, options.clearance);
  std::vector<Aabb> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    box[i] = world[i].mesh.bounds();
    box[i].lo = box[i].lo - Vec3{grow, grow, grow};
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return box[x].lo.x < box[y].lo.x || (box[x].lo.x == box[y].lo.x && x < y);
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  for (std::size_t k = 0; k < n; ++k) {
    const Aabb& a = box[order[k]];
    for (std::size_t l = k + 1; l < n && box[order[l]].lo.x <= a.hi.x; ++l) {
      const Aabb& b = box[order[l]];
      if (a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z && b.lo.z <= a.hi.z)
        candidates.emplace_back(std::min(order[k], order[l]), std::max(order[k], order[l]));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  out.candidate_pairs = candidates.size();
  // The exact clash of each candidate (in parallel; each result is the same on any thread count).
  std::vector<InstancePairResult> result(candidates.size());
  std::vector<char> meets(candidates.size(), 0);
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t c) {
    const auto [a, b] = candidates[c];
    const ClashResult r = clash(world[a], world[b], {.clearance = options.clearance});
    InstancePairResult& p = result[c];
    p.tessellation_error = model.parts[model.instances[a].part].tessellation_error() +
                           model.parts[model.instances[b].part].tessellation_error();
    p.a = a, p.b = b;
    p.cross_pairs = r.cross_pairs, p.touch_pairs = r.touch_pairs;
    p.clearance_pairs = r.clearance.size();
    if (!r.clearance.empty())
      p.min_clearance =
          std::min_element(r.clearance.begin(), r.clearance.end(),
                           [](const auto& x, const auto& y) { return x.distance < y.distance; })
              ->distance;
    p.containment = r.containment;
    p.regions = r.regions.size();
    for (const ClashRegion& g : r.regions) p.curve_length += g.curve_length;
    p.touching_overlap = r.touching_overlap;
    const bool inside =
        r.containment == Containment::a_inside_b || r.containment == Containment::b_inside_a;
    std::vector<char> pa, pb;              // the triangles of each that cross or touch the other
    std::vector<signed char> sa, sb;       // and the side of the other the rest lies on
    if (r.cross_pairs > 0) {
      pa.assign(world[a].mesh.num_triangles(), 0), pb.assign(world[b].mesh.num_triangles(), 0);
      for (const TrianglePair& q : r.pairs) pa[q.a] = 1, pb[q.b] = 1;
      sa = interfere::detail::untouched_sides(world[a], world[b], pa), sb = interfere::detail::untouched_sides(world[b], world[a], pb);
      p.depth = std::max(interfere::detail::depth_into(world[a], world[b], pa, sa),
                         interfere::detail::depth_into(world[b], world[a], pb, sb));
    }
    if (r.cross_pairs > 0 && !inside && !r.touching_overlap)
      p.nominal_fit = detail::nominal_fit(model, a, b, world, r, p.depth, p.tessellation_error);
    if ((r.cross_pairs > 0 && !p.nominal_fit) || inside || r.touching_overlap) {
      p.meeting = InstanceMeeting::clash;
      // A clash's depth, bounded (branch and bound on the crossing triangles' pieces; not for
      // nominal fits, whose coincident faces it could only bound by their chordal errors, slowly).
      if (r.cross_pairs > 0 && options.depth_bound_splits > 0) {
        const std::size_t n = options.depth_bound_splits;
        p.depth_bound = std::max({p.depth, interfere::detail::depth_bound(world[a], world[b], pa, sa, p.depth, n),
                                  interfere::detail::depth_bound(world[b], world[a], pb, sb, p.depth, n)});
      }
      if (options.geometry)
        for (const ClashRegion& g : r.regions) {
          p.curves.insert(p.curves.end(), g.curves.begin(), g.curves.end());
          p.region_triangles_a.insert(p.region_triangles_a.end(), g.triangles_a.begin(), g.triangles_a.end());
          p.region_triangles_b.insert(p.region_triangles_b.end(), g.triangles_b.begin(), g.triangles_b.end());
        }
      // One instance inside the other: all of it is the clash region.
      const auto all = [&](std::uint32_t i, std::vector<std::uint32_t>& v) {
        v.resize(world[i].mesh.num_triangles());
        std::iota(v.begin(), v.end(), 0u);
      };
      if (options.geometry && r.containment == Containment::a_inside_b) all(a, p.region_triangles_a);
      if (options.geometry && r.containment == Containment::b_inside_a) all(b, p.region_triangles_b);
      for (auto* v : {&p.region_triangles_a, &p.region_triangles_b}) {
        std::sort(v->begin(), v->end());
        v->erase(std::unique(v->begin(), v->end()), v->end());
      }
    }
    else if (r.verdict == Verdict::undecided) {
      p.meeting = InstanceMeeting::undecided;  // never a silent contact or clear (issue #23)
      p.verdict_reasons = r.verdict_reasons;
    } else if (r.touch_pairs > 0)
      p.meeting = InstanceMeeting::contact;
    else if (!r.clearance.empty())
      p.meeting = InstanceMeeting::clearance;
    else
      return;
    meets[c] = 1;
  });
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!meets[c]) continue;
    const InstancePairResult& p = result[c];
    out.clashes += p.meeting == InstanceMeeting::clash;
    out.contacts += p.meeting == InstanceMeeting::contact;
    out.within_clearance += p.meeting == InstanceMeeting::clearance;
    out.undecided += p.meeting == InstanceMeeting::undecided;
    const Verdict v = p.meeting == InstanceMeeting::clash       ? Verdict::clash
                      : p.meeting == InstanceMeeting::contact   ? Verdict::contact
                      : p.meeting == InstanceMeeting::clearance ? Verdict::clearance
                                                                : Verdict::undecided;
    out.verdict = worst(out.verdict, v);
    out.pairs.push_back(p);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!world[i].stats.closed())
      out.warnings.push_back("instance '" + model.instances[i].name +
                             "' is not closed: containment in it is not checked");
  return out;
}

}  // namespace interfere::cad
