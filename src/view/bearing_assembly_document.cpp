// A bearing assembly's run as a viewer document (view/bearing_assembly_document.h).
#include "interfere/view/bearing_assembly_document.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>

namespace interfere::view {
namespace {

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Rgb colour(const bearing::AssemblyPart& p) {
  switch (p.kind) {
    case bearing::PartKind::inner: return {0.45f, 0.55f, 0.70f};
    case bearing::PartKind::outer: return {0.55f, 0.60f, 0.66f};
    case bearing::PartKind::cage: return {0.72f, 0.60f, 0.30f};
    case bearing::PartKind::roller: return p.scarred ? Rgb{0.85f, 0.45f, 0.30f} : Rgb{0.70f, 0.72f, 0.78f};
  }
  return {0.6f, 0.6f, 0.6f};
}

}  // namespace

Expected<Document> bearing_assembly_document(const bearing::Assembly& as, const bearing::AssemblyMotion& motion,
                                             const bearing::AssemblyResult& r) {
  const std::size_t frames = motion.poses.size(), np = as.pairs.size();
  if (r.rows.size() != frames * np) return Error{.reason = "bearing assembly view: rows and motion differ"};
  Document doc;
  doc.title = "interfere bearing --assembly: " + std::to_string(as.spec.bearings.size()) + " bearings, " +
              std::to_string(as.parts.size()) + " parts x " + std::to_string(frames) + " frames";
  doc.verdict = verdict_name(r.verdict);
  std::map<const TriMesh*, std::uint32_t> meshes;  // parts share meshes (unscarred rollers)
  for (std::size_t i = 0; i < as.parts.size(); ++i) {
    const bearing::AssemblyPart& p = as.parts[i];
    auto [it, fresh] = meshes.emplace(p.mesh.get(), static_cast<std::uint32_t>(doc.meshes.size()));
    if (fresh) {
      ViewMesh m;
      m.mesh = *p.mesh;
      m.source_triangles = m.mesh.num_triangles();
      doc.meshes.push_back(std::move(m));
    }
    ViewBody b;
    b.id = p.id;
    b.name = p.id;
    b.path = "/" + as.spec.bearings[p.bearing].id + "/" + bearing::part_kind_name(p.kind) +
             (p.kind == bearing::PartKind::roller ? std::to_string(p.index) : "");
    b.mesh = it->second;
    b.color = colour(p);
    b.role = p.scarred ? "scarred roller" : bearing::part_kind_name(p.kind);
    b.tags = {as.spec.bearings[p.bearing].id, bearing::part_kind_name(p.kind)};
    for (std::size_t f = 0; f < frames; ++f) b.frame_poses.push_back(motion.poses[f][i]);
    b.pose = frames ? b.frame_poses.front() : p.rest;
    doc.bodies.push_back(std::move(b));
  }
  doc.frames.labels.resize(frames);
  doc.frames.verdicts.assign(frames, "clear");
  for (std::size_t f = 0; f < frames; ++f) {
    Verdict v = Verdict::clear;
    for (std::size_t k = 0; k < np; ++k) v = worst(v, r.rows[f * np + k].result.verdict);
    doc.frames.labels[f] = "frame " + std::to_string(f);
    doc.frames.verdicts[f] = verdict_name(v);
  }
  for (std::size_t k = 0; k < np; ++k) {
    const bearing::AssemblyPair& pair = as.pairs[k];
    std::size_t f = 0;
    while (f < frames) {
      const bearing::AssemblyRow& first = r.rows[f * np + k];
      if (first.result.verdict == Verdict::clear) {
        ++f;
        continue;
      }
      ViewClash c;
      c.verdict = verdict_name(first.result.verdict);
      c.kind = bearing::assembly_pair_kind_name(pair.kind);
      c.body_a = pair.a, c.body_b = pair.b;
      const bearing::AssemblyRow* deepest = &first;
      std::size_t g = f;
      for (; g < frames && r.rows[g * np + k].result.verdict == first.result.verdict; ++g) {
        c.frames.push_back(static_cast<std::uint32_t>(g));
        if (r.rows[g * np + k].result.distance < deepest->result.distance) deepest = &r.rows[g * np + k];
      }
      const bearing::AssemblyPairResult& d = deepest->result;
      c.point = d.point_a;
      if (d.distance < 0) c.depth = c.depth_bound = -d.distance;
      else c.distance = d.distance;
      c.has_witness = true;
      c.witness_a = d.point_a, c.witness_b = d.point_b;
      const double pad = 0.05 * as.spec.bearings[as.parts[pair.a].bearing].rollers.radius;
      c.box_min = min(d.point_a, d.point_b) - Vec3{pad, pad, pad};
      c.box_max = max(d.point_a, d.point_b) + Vec3{pad, pad, pad};
      c.id = "P" + std::to_string(k) + "F" + std::to_string(f);
      c.note = std::string(bearing::assembly_pair_kind_name(pair.kind)) + " " + as.parts[pair.a].id + " / " +
               as.parts[pair.b].id + ", frames " + std::to_string(f) + "-" + std::to_string(g - 1) +
               (d.distance < 0 ? ", max interference " + fmt(-d.distance) : ", distance " + fmt(d.distance)) +
               " at frame " + std::to_string(deepest->frame) + (d.scar ? " (scar)" : "") + (d.exact ? "" : " (bound)");
      doc.clashes.push_back(std::move(c));
      f = g;
    }
  }
  return doc;
}

}  // namespace interfere::view
