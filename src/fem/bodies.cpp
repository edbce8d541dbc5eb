// FE models as scenes (include/interfere/fem/bodies.h, issue #24 item 1).
#include "interfere/fem/bodies.h"

#include <tbb/parallel_for.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "interfere/core/coordinate_range.h"
#include "interfere/fem/io.h"
#include "interfere/scene/clash_test.h"

namespace interfere {
namespace {

Error fail(const std::string& file, std::string reason) {
  return Error{.file = file, .reason = std::move(reason)};
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s.empty() ? "none" : s;
}

bool displacement_like(const std::string& name) {
  if (name == "u" || name == "U") return true;
  std::string l;
  for (const char c : name) l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return l.find("disp") != std::string::npos;
}

// The series the frames come from (null: none), or an error.
Expected<const NodalSeries*> choose_series(const FemMesh& mesh, const std::string& file,
                                           const FemSceneOptions& o,
                                           std::optional<NodalSeries>& csv,
                                           std::vector<std::string>& warnings) {
  if (!o.steps) return static_cast<const NodalSeries*>(nullptr);
  std::vector<std::string> names;
  for (const NodalSeries& f : mesh.fields) names.push_back(f.name);
  if (!o.displacement_csv.empty()) {
    if (!o.field.empty())
      return fail(file, "displacements from CSV (" + o.displacement_csv + ") and field '" +
                            o.field + "': give one of them");
    CsvDisplacementInfo info;
    auto u = read_displacements_csv(o.displacement_csv, mesh, &info);
    if (!u) return u.error();
    csv = std::move(*u);
    if (info.missing_nodes > 0)
      warnings.push_back(o.displacement_csv + ": " + std::to_string(info.missing_nodes) +
                         " (node, step) displacements missing, set to zero");
    return &*csv;
  }
  if (!o.field.empty()) {
    for (const NodalSeries& f : mesh.fields)
      if (f.name == o.field) return &f;
    return fail(file, "no nodal field '" + o.field + "' (fields: " + quoted_list(names) + ")");
  }
  const NodalSeries* found = nullptr;
  std::vector<std::string> like;
  for (const NodalSeries& f : mesh.fields) {
    if (!displacement_like(f.name)) continue;
    found = &f;
    like.push_back(f.name);
  }
  if (like.size() > 1)
    return fail(file, "several displacement fields (" + quoted_list(like) + "): name one (field)");
  if (!found && !mesh.fields.empty())
    warnings.push_back(
        file + ": nodal fields " + quoted_list(names) +
        " not taken as displacements (none is named like one): no steps; name one (field)");
  return found;
}

}  // namespace

Expected<scene::Scene> fem_scene(const FemMesh& input, const std::string& file_arg,
                                 const FemSceneOptions& o) {
  const std::string file = file_arg.empty() ? input.file : file_arg;
  PartSplit split{};
  if (!part_split_from_name(o.split, split))
    return fail(file, "split: unknown split '" + o.split + "' (auto, group, connectivity, single)");
  if (!(std::isfinite(o.unit_scale) && o.unit_scale > 0))
    return fail(file,
                "unit scale " + short_number(o.unit_scale) + ": must be a positive finite number");
  if (o.unit_scale != 1 && o.working_unit.empty())
    return fail(file, "unit scale " + short_number(o.unit_scale) + " without a working unit");
  if (!std::isfinite(o.displacement_scale))
    return fail(file,
                "displacement scale " + short_number(o.displacement_scale) + ": must be finite");

  scene::Scene sc;
  sc.units = o.working_unit.empty() ? o.unit : o.working_unit;
  for (const std::string& w : input.warnings) sc.warnings.push_back(file + ": " + w);

  std::optional<NodalSeries> csv;
  auto chosen = choose_series(input, file, o, csv, sc.warnings);
  if (!chosen) return chosen.error();
  const NodalSeries* series = *chosen;
  if (series) {
    for (const auto& step : series->values)
      if (step.size() != input.num_nodes())
        return fail(file, "displacement '" + series->name + "': " + std::to_string(step.size()) +
                              " values for " + std::to_string(input.num_nodes()) + " nodes");
  }

  // Nodes into the working unit before the extraction, as the CLI does (apps/cli/fem_parts.cpp):
  // the surface (orientation votes, quad diagonals) is the one of the converted coordinates.
  std::optional<FemMesh> scaled;
  if (o.unit_scale != 1) {
    scaled.emplace();  // what extract_surface reads (not the fields, sets, warnings)
    scaled->file = input.file;
    scaled->nodes = input.nodes;
    for (Vec3& v : scaled->nodes) v = v * o.unit_scale;
    scaled->node_ids = input.node_ids;
    scaled->elem_types = input.elem_types;
    scaled->elem_ids = input.elem_ids;
    scaled->elem_groups = input.elem_groups;
    scaled->elem_offsets = input.elem_offsets;
    scaled->elem_nodes = input.elem_nodes;
    scaled->groups = input.groups;
  }
  const FemMesh& mesh = scaled ? *scaled : input;

  auto extracted = extract_surface(
      mesh, {.subdivide_quadratic = !o.linear_faces, .split = split, .parallel = o.parallel});
  if (!extracted) return extracted.error();
  SurfaceResult& surface = *extracted;
  if (surface.parts.empty()) return fail(file, "no surface or volume elements");
  for (const std::string& w : surface_warnings(surface)) sc.warnings.push_back(file + ": " + w);

  std::vector<std::size_t> parts;  // surface.parts taken, in order
  {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < surface.parts.size(); ++i) {
      names.push_back(surface.parts[i].name);
      if (o.select.empty() || scene::glob_match(o.select, surface.parts[i].name))
        parts.push_back(i);
    }
    if (parts.empty())
      return fail(file, "no body matches '" + o.select + "' (bodies: " + quoted_list(names) + ")");
  }

  const std::string stem = std::filesystem::path(file).stem().string();
  std::vector<std::size_t> body_part;  // Scene::bodies -> surface.parts
  for (const std::size_t i : parts) {
    SurfacePart& sp = surface.parts[i];
    const std::string who = file + ", body '" + sp.name + "': ";
    if (sp.mesh.num_triangles() == 0) {
      sc.warnings.push_back(who + "no surface triangles; left out");
      continue;
    }
    if (const std::size_t bad = first_out_of_range(sp.mesh.positions);
        bad < sp.mesh.positions.size())
      return fail(
          file, "node " + std::to_string(mesh.node_ids[sp.vertex_node[bad]]) +
                    (o.unit_scale != 1 ? ", once converted from " + o.unit : std::string()) + ": " +
                    coordinate_range_reason(sp.mesh.positions[bad]));
    for (const std::string& w : surface_part_warnings(sp)) sc.warnings.push_back(who + w);
    scene::Body b;
    b.id = scene::make_body_id(sp.name);
    b.name = sp.name;
    b.path = "/" + stem + "/" + sp.name;
    b.source = {.kind = scene::SourceKind::fe_body, .file = file, .detail = sp.name};
    b.unit = o.unit;
    b.source_id_kind = scene::SourceIdKind::fe_element_face;
    auto ids = std::make_shared<std::vector<std::int64_t>>(sp.tri_element.size());
    auto faces = std::make_shared<std::vector<std::int8_t>>(sp.tri_face.size());
    for (std::size_t t = 0; t < sp.tri_element.size(); ++t) {
      (*ids)[t] = mesh.elem_ids[sp.tri_element[t]];
      (*faces)[t] = static_cast<std::int8_t>(sp.tri_face[t]);
    }
    b.source_ids = std::move(ids);
    b.source_faces = std::move(faces);
    auto nodes = std::make_shared<std::vector<std::int64_t>>(sp.vertex_node.size());
    for (std::size_t v = 0; v < sp.vertex_node.size(); ++v) (*nodes)[v] = mesh.node_ids[sp.vertex_node[v]];
    b.vertex_ids = std::move(nodes);
    b.mesh = std::make_shared<const TriMesh>(sp.mesh);  // a copy: vertex_node stays with the part
    sc.bodies.push_back(std::move(b));
    body_part.push_back(i);
  }
  scene::make_ids_unique(sc);
  if (!series) return sc;

  // Frames: every step, every body. A body whose nodes' displacements equal the previous step's
  // shares that step's positions (decided first, so that no memory is spent on them).
  const std::size_t nb = sc.bodies.size(), ns = series->num_steps();
  const double s = o.displacement_scale * o.unit_scale;
  std::vector<std::shared_ptr<const std::vector<Vec3>>> shape(ns * nb);
  std::vector<std::size_t> first_bad(ns * nb, ~std::size_t{0});
  auto one = [&](std::size_t k) {
    const std::size_t step = k / nb, body = k % nb;
    const SurfacePart& sp = surface.parts[body_part[body]];
    const std::vector<Vec3>& u = series->values[step];
    if (step > 0) {
      const std::vector<Vec3>& prev = series->values[step - 1];
      bool same = true;
      for (const std::uint32_t n : sp.vertex_node) {
        if (!(u[n] == prev[n])) {
          same = false;
          break;
        }
      }
      if (same) return;  // shape[k] stays null: the previous step's, filled in below
    }
    auto pos = std::make_shared<std::vector<Vec3>>(sp.vertex_node.size());
    for (std::size_t v = 0; v < pos->size(); ++v) {
      const std::uint32_t n = sp.vertex_node[v];
      (*pos)[v] = mesh.nodes[n] + u[n] * s;
      if (first_bad[k] == ~std::size_t{0} && !coordinates_in_range((*pos)[v])) first_bad[k] = v;
    }
    shape[k] = std::move(pos);
  };
  if (o.parallel) {
    tbb::parallel_for(std::size_t{0}, ns * nb, one);
  } else {
    for (std::size_t k = 0; k < ns * nb; ++k) one(k);
  }
  for (std::size_t k = 0; k < ns * nb; ++k) {
    if (first_bad[k] == ~std::size_t{0}) continue;
    const std::size_t step = k / nb, body = k % nb;
    const std::uint32_t n = surface.parts[body_part[body]].vertex_node[first_bad[k]];
    return fail(file, "step " + std::to_string(step) + ", node " +
                          std::to_string(mesh.node_ids[n]) + " displaced (" + series->name +
                          "): " + coordinate_range_reason((*shape[k])[first_bad[k]]));
  }
  sc.frames.resize(ns);
  for (std::size_t step = 0; step < ns; ++step) {
    scene::Frame& f = sc.frames[step];
    f.time = step < series->times.size() ? series->times[step] : static_cast<double>(step);
    f.label = "step " + std::to_string(step) + " (time " + short_number(f.time) + ")";
    f.shapes.resize(nb);
    for (std::size_t body = 0; body < nb; ++body) {
      std::shared_ptr<const std::vector<Vec3>>& p = shape[step * nb + body];
      if (!p) p = shape[(step - 1) * nb + body];  // step > 0 here
      f.shapes[body] = {.body = static_cast<std::uint32_t>(body), .positions = p};
    }
  }
  return sc;
}

Expected<scene::Scene> read_fem_scene(const std::string& file, const FemSceneOptions& options) {
  auto mesh = read_fem(file);
  if (!mesh) return mesh.error();
  return fem_scene(*mesh, file, options);
}

}  // namespace interfere
