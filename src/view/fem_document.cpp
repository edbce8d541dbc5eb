// Two deforming parts over load steps as a viewer document (include/interfere/view/fem_document.h;
// issue #25, item 1, "FE series").
#include "interfere/view/fem_document.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "interfere/view/scene_document.h"

namespace interfere::view {
namespace {

std::string step_label(const FemSeriesStep& s) {
  char time[64];
  std::snprintf(time, sizeof time, "%g", s.time);
  return "step " + std::to_string(s.step) + " (time " + time + ")";
}

std::string row_kind(const FemSeriesStep& s) {
  std::size_t cross = 0, touch = 0;
  for (const ClashRegion& g : s.regions) cross += g.cross_pairs, touch += g.touch_pairs;
  if (cross > 0) return "crossing";
  if (touch > 0) return "touch";
  if (s.containment == Containment::a_inside_b || s.containment == Containment::b_inside_a) return "inside";
  return "";
}

bool positions_fit(const FemSeriesBody& b, const std::vector<Vec3>& p) {
  return b.surface != nullptr && p.size() == b.surface->num_vertices();
}

Aabb box_of(const std::vector<Vec3>& p) {
  Aabb box;
  for (const Vec3& v : p) box.expand(v);
  return box;
}

}  // namespace

FemSeriesStep fem_series_step(std::size_t step, double time, const ClashResult& r) {
  FemSeriesStep s;
  s.step = step;
  s.time = time;
  s.verdict = r.verdict;
  s.regions = r.regions;
  s.containment = r.containment;
  s.reasons = r.verdict_reasons;
  if (!r.clearance.empty()) {
    s.has_clearance = true;
    s.closest = *std::min_element(r.clearance.begin(), r.clearance.end(),
                                  [](const ClearancePair& x, const ClearancePair& y) { return x.distance < y.distance; });
  }
  return s;
}

Document fem_series_document(FemSeriesInput in, const FemSeriesDocumentOptions& options) {
  Document doc;
  doc.units = in.units;
  doc.verdict = verdict_name(in.verdict);
  const std::size_t nf = in.steps.size();
  doc.title = !options.title.empty() ? options.title
                                     : "interfere clash: FE series, " + std::to_string(in.num_steps) + " steps";
  if (nf < in.num_steps)
    doc.notes.push_back(std::to_string(nf) + " of the series' " + std::to_string(in.num_steps) + " steps checked");

  // Frames.
  for (const FemSeriesStep& s : in.steps) {
    doc.frames.labels.push_back(step_label(s));
    doc.frames.times.push_back(s.time);
    doc.frames.verdicts.push_back(verdict_name(s.verdict));
  }

  // Rows: one per checked step that is not clear.
  Verdict previous = Verdict::clear;
  for (std::size_t f = 0; f < nf; ++f) {
    const FemSeriesStep& s = in.steps[f];
    const Verdict was = previous;
    previous = s.verdict;
    if (s.verdict == Verdict::clear) continue;
    ViewClash c;
    c.id = "step " + std::to_string(s.step);
    c.verdict = verdict_name(s.verdict);
    c.status = was == s.verdict ? "active" : "new";
    c.kind = row_kind(s);
    c.body_a = 0, c.body_b = 1;
    c.frames = {static_cast<std::uint32_t>(f)};
    Aabb box;
    double curve_length = 0;
    for (const ClashRegion& g : s.regions) {
      if (!g.box.empty()) box.expand(g.box);
      curve_length += g.curve_length;
      for (const Polyline& l : g.curves) {
        std::vector<Vec3> pts = l.points;
        if (l.closed && !pts.empty()) pts.push_back(pts.front());
        if (pts.size() >= 2) c.curves.push_back(std::move(pts));
      }
    }
    if (s.verdict == Verdict::clearance && s.has_clearance) {
      c.distance = s.closest.distance;
      c.has_witness = true;
      c.witness_a = s.closest.point_a, c.witness_b = s.closest.point_b;
      box.expand(s.closest.point_a);
      box.expand(s.closest.point_b);
    } else if (c.kind == "touch") {
      c.distance = 0;
    }
    if (box.empty()) {  // a containment without regions: the inner body
      const int inner = s.containment == Containment::a_inside_b ? 0 : s.containment == Containment::b_inside_a ? 1 : -1;
      if (inner >= 0 && positions_fit(in.bodies[static_cast<std::size_t>(inner)], s.positions[static_cast<std::size_t>(inner)]))
        box = box_of(s.positions[static_cast<std::size_t>(inner)]);
    }
    if (!box.empty()) c.point = box.center(), c.box_min = box.lo, c.box_max = box.hi;
    // The region triangles of both bodies at the step's positions.
    if (options.regions && !s.regions.empty()) {
      ViewMesh region;
      for (std::size_t side = 0; side < 2; ++side) {
        const FemSeriesBody& body = in.bodies[side];
        if (!positions_fit(body, s.positions[side])) continue;
        const TriMesh& mesh = *body.surface;
        std::map<std::uint32_t, std::uint32_t> vertex;  // surface -> region mesh
        for (const ClashRegion& g : s.regions)
          for (const std::uint32_t t : side == 0 ? g.triangles_a : g.triangles_b) {
            if (t >= mesh.num_triangles()) continue;
            Tri tri{};
            for (std::size_t k = 0; k < 3; ++k) {
              const std::uint32_t v = mesh.triangles[t][k];
              auto [it, fresh] = vertex.emplace(v, static_cast<std::uint32_t>(region.mesh.positions.size()));
              if (fresh) region.mesh.positions.push_back(s.positions[side][v]);
              tri[k] = it->second;
            }
            region.mesh.triangles.push_back(tri);
            if (!body.source_ids.empty() && body.source_ids.size() == mesh.num_triangles())
              region.source_ids.push_back(body.source_ids[t]);
          }
      }
      if (region.source_ids.size() != region.mesh.num_triangles()) region.source_ids.clear();
      region.source_triangles = region.mesh.num_triangles();
      if (region.mesh.num_triangles() > 0) {
        doc.meshes.push_back(std::move(region));
        c.region_mesh = static_cast<std::int64_t>(doc.meshes.size() - 1);
      }
    }
    std::string note = step_label(s);
    if (!s.regions.empty()) {
      char len[64];
      std::snprintf(len, sizeof len, "%g", curve_length);
      note += "; " + std::to_string(s.regions.size()) + (s.regions.size() == 1 ? " region" : " regions") +
              ", curve length " + len;
    }
    if (s.containment == Containment::a_inside_b) note += "; " + in.bodies[0].id + " inside " + in.bodies[1].id;
    if (s.containment == Containment::b_inside_a) note += "; " + in.bodies[1].id + " inside " + in.bodies[0].id;
    for (const std::string& r : s.reasons) note += "; " + r;
    c.note = std::move(note);
    doc.clashes.push_back(std::move(c));
  }
  // Bodies: per step a mesh at the step's positions with the step's clash flags, shared with the
  // previous step's when both are equal (after the rows: the positions move into the meshes).
  for (std::size_t side = 0; side < 2; ++side) {
    const FemSeriesBody& body = in.bodies[side];
    ViewBody vb;
    vb.id = body.id, vb.name = body.name, vb.path = body.path, vb.role = body.role;
    vb.color = body_color(side);
    const std::size_t nt = body.surface ? body.surface->num_triangles() : 0;
    const bool ids = body.source_ids.size() == nt && nt > 0;
    if (!body.surface) doc.notes.push_back("body '" + body.id + "' has no geometry: nothing to draw");
    if (!body.source_ids.empty() && !ids)
      doc.notes.push_back("body '" + body.id + "': " + std::to_string(body.source_ids.size()) + " element ids for " +
                          std::to_string(nt) + " triangles, not shown");
    // Penetration depth per vertex (issue #26, item 3): on every step's mesh when any step has it.
    const std::size_t nv = body.surface ? body.surface->num_vertices() : 0;
    const bool any_depth = nv > 0 && std::any_of(in.steps.begin(), in.steps.end(), [&](const FemSeriesStep& s) {
      return !s.depth[side].empty();
    });
    std::int64_t last = -1;
    for (std::size_t f = 0; f < nf; ++f) {
      FemSeriesStep& s = in.steps[f];
      std::vector<std::uint8_t> flags;
      std::vector<std::int32_t> regions;
      bool flagged = false;
      if (nt > 0) {
        flags.assign(nt, 0);
        regions.assign(nt, -1);
        for (std::size_t g = 0; g < s.regions.size(); ++g)
          for (const std::uint32_t t : side == 0 ? s.regions[g].triangles_a : s.regions[g].triangles_b)
            if (t < nt) {
              flags[t] = 1, flagged = true;
              if (regions[t] < 0) regions[t] = static_cast<std::int32_t>(g);
            }
      }
      const bool fits = positions_fit(body, s.positions[side]);
      if (body.surface && !fits)
        doc.notes.push_back("body '" + body.id + "', " + step_label(s) + ": " + std::to_string(s.positions[side].size()) +
                            " positions for " + std::to_string(body.surface->num_vertices()) + " vertices, not drawn");
      std::vector<double> depth;
      if (any_depth && fits) {
        if (s.depth[side].size() == nv) {
          depth = std::move(s.depth[side]);
        } else if (!s.depth[side].empty()) {  // none drawn (the .pvd writes NaN), never a made-up 0
          doc.notes.push_back("body '" + body.id + "', " + step_label(s) + ": " + std::to_string(s.depth[side].size()) +
                              " depths for " + std::to_string(nv) + " vertices, not drawn");
        } else {  // not measured at this step: not a clash, nothing inside
          depth.assign(nv, 0.0);
        }
      }
      if (last >= 0) {
        const ViewMesh& prev = doc.meshes[static_cast<std::size_t>(last)];
        const bool same_flags = flagged ? prev.clash_flags == flags && prev.clash_region == regions : prev.clash_flags.empty();
        const bool same_shape = fits ? prev.mesh.num_triangles() == nt && prev.mesh.positions == s.positions[side]
                                     : prev.mesh.num_triangles() == 0;
        if (same_flags && same_shape && prev.point_depth == depth) {
          vb.frame_meshes.push_back(static_cast<std::uint32_t>(last));
          continue;
        }
      }
      ViewMesh vm;
      if (fits) {
        vm.mesh.positions = std::move(s.positions[side]);
        vm.mesh.triangles = body.surface->triangles;
        if (ids) vm.source_ids = body.source_ids;
        if (flagged) vm.clash_flags = std::move(flags), vm.clash_region = std::move(regions);
        vm.point_depth = std::move(depth);
      }
      vm.source_triangles = vm.mesh.num_triangles();
      doc.meshes.push_back(std::move(vm));
      last = static_cast<std::int64_t>(doc.meshes.size() - 1);
      vb.frame_meshes.push_back(static_cast<std::uint32_t>(last));
    }
    if (nf == 0) {  // nothing checked: the body without geometry
      ViewMesh vm;
      doc.meshes.push_back(std::move(vm));
      vb.frame_meshes.push_back(static_cast<std::uint32_t>(doc.meshes.size() - 1));
    }
    vb.mesh = vb.frame_meshes.front();
    if (std::all_of(vb.frame_meshes.begin(), vb.frame_meshes.end(), [&](std::uint32_t m) { return m == vb.mesh; }))
      vb.frame_meshes.clear();
    doc.bodies.push_back(std::move(vb));
  }

  return doc;
}

}  // namespace interfere::view
