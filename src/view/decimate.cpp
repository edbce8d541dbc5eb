// Display decimation (include/interfere/view/budget.h; issue #25, item 1).
#include "interfere/view/budget.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <utility>

#include "interfere/core/error.h"
#include "interfere/simplify/budget.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace interfere::view {
namespace {

/// One mesh's decimation: the simplified mesh and its carried attributes, or why it was kept.
struct Outcome {
  std::optional<ViewMesh> mesh;
  std::vector<std::string> warnings;
};

Outcome decimate_mesh(const ViewMesh& in, std::size_t index, std::size_t budget, const DisplayOptions& options) {
  Outcome out;
  const std::size_t nt = in.mesh.num_triangles();
  SimplifyOptions so;
  so.target_triangles = budget;
  so.prevent_self_intersections = false;  // drawn only: the guard's checks are not worth their time here
  so.measure_error = false;  // measured below, as DisplayOptions::error says
  // Each distinct (face colour, clash flag) is one face of the simplification, so that every output
  // triangle can be given the attributes of the input triangle it comes from.
  const bool colours = in.face_colors.size() == nt, flags = in.clash_flags.size() == nt;
  std::vector<std::pair<std::uint32_t, std::uint8_t>> classes;
  if (colours || flags) {
    std::map<std::pair<std::uint32_t, std::uint8_t>, std::uint32_t> id;
    so.face_ids.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) {
      const std::pair<std::uint32_t, std::uint8_t> key{colours ? in.face_colors[t] : 0u, flags ? in.clash_flags[t] : std::uint8_t{0}};
      const auto [it, fresh] = id.emplace(key, static_cast<std::uint32_t>(classes.size()));
      if (fresh) classes.push_back(key);
      so.face_ids[t] = it->second;
    }
    so.seams = SeamMode::as_needed;
  }
  Expected<SimplifyResult> r = simplify(in.mesh, so);
  const std::string name = "mesh " + std::to_string(index);
  if (!r) {
    out.warnings.push_back(name + " kept at full resolution (" + std::to_string(nt) + " triangles): " + r.error().message());
    return out;
  }
  for (const std::string& w : r->warnings)
    if (w != one_below_warning(budget)) out.warnings.push_back(name + ": " + w);  // (one below: harmless here)
  ViewMesh m;
  m.mesh = std::move(r->mesh);
  const std::size_t mt = m.mesh.num_triangles();
  if (colours || flags) {
    if (r->face_ids.size() != mt) {
      out.warnings.push_back(name + " kept at full resolution: the simplifier returned no face per triangle");
      return out;
    }
    if (colours) m.face_colors.resize(mt);
    if (flags) m.clash_flags.resize(mt);
    for (std::size_t t = 0; t < mt; ++t) {
      const auto& [c, f] = classes[r->face_ids[t]];
      if (colours) m.face_colors[t] = c;
      if (flags) m.clash_flags[t] = f;
    }
  }
  m.source_triangles = std::max(in.source_triangles, nt);
  if (options.error != DisplayError::none) {
    const OneSidedDistance e = one_sided(in.mesh, m.mesh, options.error == DisplayError::bound);
    m.decimation_error = options.error == DisplayError::bound ? std::max(e.bound, e.sampled) : e.sampled;
  }
  out.mesh = std::move(m);
  return out;
}

}  // namespace

std::string grouped_count(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

DisplayDecimation decimate_for_display(Document& doc, const DisplayOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  DisplayDecimation d;
  // The bodies' meshes (local), each once; clash regions are never among them.
  std::vector<bool> region(doc.meshes.size(), false), drawn(doc.meshes.size(), false);
  for (const ViewClash& c : doc.clashes)
    if (c.region_mesh >= 0 && static_cast<std::size_t>(c.region_mesh) < doc.meshes.size())
      region[static_cast<std::size_t>(c.region_mesh)] = true;
  for (const ViewBody& b : doc.bodies) {
    if (b.mesh < doc.meshes.size()) drawn[b.mesh] = true;
    for (const std::uint32_t m : b.frame_meshes)
      if (m < doc.meshes.size()) drawn[m] = true;
  }
  std::vector<std::size_t> parts_mesh;
  std::vector<PartBudgetInput> parts;
  for (std::size_t m = 0; m < doc.meshes.size(); ++m) {
    if (!drawn[m] || region[m]) continue;
    const std::size_t nt = doc.meshes[m].mesh.num_triangles();
    parts_mesh.push_back(m);
    parts.push_back({nt, std::min(nt, options.min_mesh_triangles)});
    d.triangles_before += nt;
  }
  d.triangles_after = d.triangles_before;
  if (options.triangle_budget == 0 || d.triangles_before <= options.triangle_budget) return d;

  const BudgetResult budgets = triangle_budgets(parts, options.triangle_budget);
  std::vector<Outcome> outcomes(parts.size());
  tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t i) {
    const std::size_t m = parts_mesh[i], budget = budgets.budgets[i];
    if (budget >= parts[i].triangles || budget == 0) return;
    outcomes[i] = decimate_mesh(doc.meshes[m], m, budget, options);
  });
  std::size_t after = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Outcome& o = outcomes[i];
    d.warnings.insert(d.warnings.end(), o.warnings.begin(), o.warnings.end());
    if (o.mesh) {
      ViewMesh& target = doc.meshes[parts_mesh[i]];
      target = std::move(*o.mesh);
      ++d.meshes_decimated;
      d.largest_error = std::max(d.largest_error, target.decimation_error);
    }
    after += doc.meshes[parts_mesh[i]].mesh.num_triangles();
  }
  d.triangles_after = after;
  d.over_budget = after > options.triangle_budget;

  std::string note = "bodies decimated for display: " + grouped_count(d.triangles_before) + " -> " +
                     grouped_count(d.triangles_after) + " triangles";
  switch (options.error) {
    case DisplayError::none: note += ", error not measured"; break;
    case DisplayError::sampled: note += ", largest deviation " + short_number(d.largest_error) + " " + doc.units + " (sampled)"; break;
    case DisplayError::bound: note += ", error bound " + short_number(d.largest_error) + " " + doc.units; break;
  }
  if (d.over_budget) note += " (above the budget of " + grouped_count(options.triangle_budget) + ")";
  std::size_t kept = 0;
  for (const Outcome& o : outcomes)
    if (!o.mesh && !o.warnings.empty()) ++kept;
  if (kept > 0) note += "; " + std::to_string(kept) + " mesh(es) could not be simplified and are shown in full";
  doc.notes.push_back(note);
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

}  // namespace interfere::view
