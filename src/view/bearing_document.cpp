// The bearing simulation as a viewer document (view/bearing_document.h).
#include "interfere/view/bearing_document.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "interfere/bearing/roller.h"
#include "interfere/query/verdict.h"
#include <cstdio>

namespace interfere::view {
namespace {

std::uint32_t add_mesh(Document& doc, TriMesh mesh) {
  ViewMesh m;
  m.source_triangles = mesh.num_triangles();
  m.mesh = std::move(mesh);
  doc.meshes.push_back(std::move(m));
  return static_cast<std::uint32_t>(doc.meshes.size() - 1);
}

std::string fmt_mm(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

Expected<Document> bearing_document(const bearing::SceneParams& p, const bearing::SimulationResult& r) {
  const auto pairs = static_cast<std::size_t>(p.pairs), frames = static_cast<std::size_t>(p.frames);
  if (r.roller_poses.size() != pairs * frames || r.rows.size() != pairs * frames || r.pair_variant.size() != pairs)
    return Error{.reason = "bearing view: the simulation kept no per-frame poses (simulate with keep_rows)"};
  Document doc;
  doc.title = "interfere bearing: " + std::to_string(p.pairs) + " pairs x " + std::to_string(p.frames) + " frames";
  doc.verdict = verdict_name(r.verdict);
  // Meshes: the unscarred roller, each scarred variant, the partner (body frames).
  Expected<bearing::Roller> plain = bearing::make_roller(p.roller);
  if (!plain) return plain.error();
  const std::uint32_t plain_mesh = add_mesh(doc, plain->mesh);
  std::vector<std::uint32_t> scar_mesh;
  for (const TriMesh& m : r.scar_meshes) scar_mesh.push_back(add_mesh(doc, m));
  bearing::RollerParams partner = p.roller;
  partner.radius = p.partner_radius, partner.top_radius = -1, partner.height = p.partner_height;
  partner.height_segments = 1;
  Expected<bearing::Roller> partner_roller = bearing::make_roller(partner);
  if (!partner_roller) return partner_roller.error();
  const std::uint32_t partner_mesh = add_mesh(doc, partner_roller->mesh);

  for (std::size_t k = 0; k < pairs; ++k) {
    ViewBody roller;
    roller.id = "roller_" + std::to_string(k);
    roller.name = "roller " + std::to_string(k);
    roller.path = "/pair " + std::to_string(k) + "/roller";
    const std::int32_t v = r.pair_variant[k];
    roller.mesh = v >= 0 ? scar_mesh.at(static_cast<std::size_t>(v)) : plain_mesh;
    roller.role = v >= 0 ? "scarred roller" : "roller";
    roller.color = v >= 0 ? Rgb{0.80f, 0.62f, 0.35f} : Rgb{0.70f, 0.72f, 0.78f};
    roller.frame_poses.reserve(frames);
    for (std::size_t f = 0; f < frames; ++f) roller.frame_poses.push_back(r.roller_poses[f * pairs + k]);
    roller.pose = roller.frame_poses.front();
    doc.bodies.push_back(std::move(roller));
    ViewBody b;
    b.id = "partner_" + std::to_string(k);
    b.name = "partner " + std::to_string(k);
    b.path = "/pair " + std::to_string(k) + "/partner";
    b.mesh = partner_mesh;
    b.role = "partner";
    b.color = Rgb{0.45f, 0.55f, 0.70f};
    b.pose = bearing::partner_pose(p, r.spacing, static_cast<int>(k));
    doc.bodies.push_back(std::move(b));
  }

  // Frames: the worst verdict of each frame's rows and cross pairs.
  doc.frames.labels.resize(frames);
  doc.frames.verdicts.assign(frames, "clear");
  std::vector<Verdict> frame_verdict(frames, Verdict::clear);
  for (const bearing::PairFrame& row : r.rows) {
    auto& fv = frame_verdict[static_cast<std::size_t>(row.frame)];
    fv = worst(fv, row.verdict);
  }
  for (const bearing::CrossPair& c : r.cross_results) {
    auto& fv = frame_verdict[static_cast<std::size_t>(c.frame)];
    fv = worst(fv, c.verdict);
  }
  for (std::size_t f = 0; f < frames; ++f) {
    doc.frames.labels[f] = "frame " + std::to_string(f);
    doc.frames.verdicts[f] = verdict_name(frame_verdict[f]);
  }

  // Clash rows: per pair, each run of consecutive frames with the same non-clear verdict; its
  // point is the deepest frame's point on the roller, its depth the largest interference.
  for (std::size_t k = 0; k < pairs; ++k) {
    std::size_t f = 0;
    while (f < frames) {
      const bearing::PairFrame& first = r.rows[f * pairs + k];
      if (first.verdict == Verdict::clear) {
        ++f;
        continue;
      }
      ViewClash c;
      c.verdict = verdict_name(first.verdict);
      c.kind = first.solver == 1 ? "scarred roller" : "roller";
      c.body_a = static_cast<std::uint32_t>(2 * k), c.body_b = static_cast<std::uint32_t>(2 * k + 1);
      const bearing::PairFrame* deepest = &first;
      std::size_t g = f;
      for (; g < frames && r.rows[g * pairs + k].verdict == first.verdict; ++g) {
        const bearing::PairFrame& row = r.rows[g * pairs + k];
        c.frames.push_back(static_cast<std::uint32_t>(g));
        if (row.distance < deepest->distance) deepest = &row;
      }
      c.point = deepest->point_a;
      if (deepest->distance < 0) c.depth = c.depth_bound = -deepest->distance;
      else c.distance = deepest->distance;
      c.has_witness = deepest->distance > 0;
      c.witness_a = deepest->point_a, c.witness_b = deepest->point_b;
      const Vec3 lo{std::min(deepest->point_a.x, deepest->point_b.x), std::min(deepest->point_a.y, deepest->point_b.y),
                    std::min(deepest->point_a.z, deepest->point_b.z)};
      const Vec3 hi{std::max(deepest->point_a.x, deepest->point_b.x), std::max(deepest->point_a.y, deepest->point_b.y),
                    std::max(deepest->point_a.z, deepest->point_b.z)};
      const double pad = 0.05 * p.roller.radius;
      c.box_min = lo - Vec3{pad, pad, pad}, c.box_max = hi + Vec3{pad, pad, pad};
      c.id = std::string("P").append(std::to_string(k)).append("F").append(std::to_string(f));
      c.note = "pair " + std::to_string(k) + ", frames " + std::to_string(f) + "-" + std::to_string(g - 1) +
               (deepest->distance < 0 ? ", max interference " + fmt_mm(-deepest->distance)
                                      : ", distance " + fmt_mm(deepest->distance)) +
               " at frame " + std::to_string(deepest->frame) + (deepest->scar_in_range ? " (scar in range)" : "");
      doc.clashes.push_back(std::move(c));
      f = g;
    }
  }
  // Parts of different pairs (cross pairs): one row each.
  for (const bearing::CrossPair& cp : r.cross_results) {
    ViewClash c;
    c.verdict = verdict_name(cp.verdict);
    c.kind = "parts of different pairs";
    c.body_a = cp.part_a, c.body_b = cp.part_b;
    c.point = cp.point_a;
    if (cp.distance < 0) c.depth = -cp.distance;
    else c.distance = cp.distance;
    c.has_witness = cp.distance > 0;
    c.witness_a = cp.point_a, c.witness_b = cp.point_b;
    c.box_min = c.box_max = cp.point_a;
    c.frames = {static_cast<std::uint32_t>(cp.frame)};
    c.id = "X" + std::to_string(cp.part_a) + "_" + std::to_string(cp.part_b) + "F" + std::to_string(cp.frame);
    doc.clashes.push_back(std::move(c));
  }
  return doc;
}

}  // namespace interfere::view
