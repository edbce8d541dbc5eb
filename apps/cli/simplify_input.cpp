// `interfere simplify`: the options checked before any file is read, and the input loaded (a mesh
// with its regions and features, or a STEP model prepared for a process step; issue #6, items 1-5).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "cad_exec.h"
#include "common.h"
#include "interfere/simplify/budget.h"
#include "interfere/simplify/tagged_io.h"
#include "simplify_cli.h"

namespace interfere::cli {
namespace {

std::vector<std::uint32_t> parse_id_list(const std::string& s, const std::string& flag) {
  std::vector<std::uint32_t> out;
  std::stringstream ss(s);
  std::string tok;
  while (std::getline(ss, tok, ',')) {
    if (tok.empty()) continue;
    try {
      std::size_t used = 0;
      const unsigned long v = std::stoul(tok, &used);
      if (used != tok.size() || v > 0xffffffffUL) throw std::invalid_argument(tok);
      out.push_back(static_cast<std::uint32_t>(v));
    } catch (const std::exception&) {
      throw InputError(flag + ": not a face/region id: '" + tok + "'");
    }
  }
  return out;
}

bool valid_angle(double deg) { return deg > 0 && deg < 180; }

// --features ids of a plain mesh: each must be a region some triangle has.
void check_region_ids(const SimplifyCliOptions& o, const SimplifyOptions& so) {
  const std::string source =
      o.regions.empty() ? "--sharp-angle " + short_number(o.sharp_angle) + "'s regions of " + o.input : o.regions;
  std::vector<std::uint32_t> ids = so.face_ids;  // (a region file's ids may be sparse)
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (std::uint32_t id : so.feature_faces)
    if (!std::binary_search(ids.begin(), ids.end(), id))
      throw InputError("--features: no triangle of " + source + " has region id " + std::to_string(id) +
                       (o.regions.empty() ? " (ids 0 to " + std::to_string(ids.back()) + ")" : std::string()));
}

}  // namespace

SimplifyOptions simplify_options(const SimplifyCliOptions& o) {
  SimplifyOptions so;
  so.target_triangles = o.target;
  so.ratio = o.ratio;
  const auto mode = feature_mode_from_name(o.feature_mode);
  if (!mode) throw InputError("--feature-mode must be weight, last or lock, not '" + o.feature_mode + "'");
  so.feature_mode = o.lock ? FeatureMode::lock : *mode;
  const auto seams = seam_mode_from_name(o.seams);
  if (!seams) throw InputError("--seams must be all, auto, features or none, not '" + o.seams + "'");
  so.seams = *seams;
  so.measure_error = !o.no_error;
  so.prevent_self_intersections = !o.no_guard;
  so.inherit_input_contacts = !o.strict_guard;
  return so;
}

SimplifyOutput check_simplify_options(const SimplifyCliOptions& o) {
  if (o.target == 0 && o.ratio == 0 && o.renderer_max == 0)
    throw InputError("simplify: give --target N (> 0), --ratio R or --renderer-max N");
  if (o.ratio != 0 && !(o.ratio > 0 && o.ratio <= 1)) throw InputError("--ratio must lie in (0, 1]");
  if (!o.step.empty() && o.process.empty()) throw InputError("--step needs --process FILE");
  if (o.step.empty() && !o.process.empty()) throw InputError("--process needs --step ID");
  const bool step_input = is_step_file(o.input);
  if (!o.parts_dir.empty() && !step_input)
    throw InputError("--parts-dir needs a STEP input (one file per part of the assembly)");
  if (step_input && (!o.regions.empty() || o.sharp_angle != 0))
    throw InputError("--regions/--sharp-angle are for plain meshes: a STEP input's regions are its B-Rep faces");
  if (o.mates != "auto" && o.mates != "off") throw InputError("--mates must be auto or off, not '" + o.mates + "'");
  if (o.mesher != "default" && o.mesher != "delabella")
    throw InputError("--mesher must be default or delabella, not '" + o.mesher + "'");
  if (o.mesher != "default" && !step_input) throw InputError("--mesher tessellates a STEP input; " + o.input + " is a mesh");
  if (!step_input && (!o.step.empty() || !o.process.empty() || !o.library.empty() || !o.rules.empty()))
    throw InputError("--step/--process/--library/--rules need a STEP input (features are recognised on the B-Rep)");
  if (o.sharp_angle != 0 && !valid_angle(o.sharp_angle))
    throw InputError("--sharp-angle " + short_number(o.sharp_angle) + ": give a dihedral angle in degrees, in (0, 180)");
  if (!step_input && !o.features.empty() && o.regions.empty() && o.sharp_angle == 0)
    throw InputError("--features names region ids: give them with --regions FILE or --sharp-angle DEG");
  parse_id_list(o.features, "--features");
  simplify_options(o);  // (the modes' names)
  if (!(o.max_error >= 0 && std::isfinite(o.max_error)))
    throw InputError("--max-error must be a length > 0 (model units), not " + short_number(o.max_error));
  if (!(o.max_error_rel >= 0 && o.max_error_rel <= 1))
    throw InputError("--max-error-rel must be a fraction of the bounding-box diagonal in (0, 1], not " +
                     short_number(o.max_error_rel));
  SimplifyOutput out;
  const MeshFormat named = mesh_format_from_name(o.format);
  const bool gltf_format = named == MeshFormat::glb || named == MeshFormat::gltf;
  out.format = gltf_format ? MeshFormat::automatic : named;
  if (named == MeshFormat::automatic && o.format != "auto" && o.format != "AUTO")
    throw InputError("--format: unknown mesh format '" + o.format + "' (stl, stl-ascii, obj, ply, ply-ascii, off, glb, gltf)");
  // Outputs: a known extension (or --format) and an existing directory.
  check_output(o.output,
               out.format == MeshFormat::automatic && !gltf_format
                   ? std::vector<std::string>{".stl", ".ply", ".obj", ".off", ".glb", ".gltf"}
                   : std::vector<std::string>{},
               "OUT (or --format)");
  if (is_standard_output(o.output))  // (a mesh: standard output carries text reports only)
    throw InputError("OUT: " + o.output + ": standard output is for text reports; give a mesh file name");
  const std::string out_ext = lower_extension(o.output);
  out.glb = gltf_format || (out.format == MeshFormat::automatic && (out_ext == ".glb" || out_ext == ".gltf"));
  out.container = named == MeshFormat::gltf || (!gltf_format && out_ext == ".gltf") ? GltfContainer::gltf
                                                                                     : GltfContainer::glb;
  check_output(o.json, {}, "--json");
  if (o.crease_given) {
    if (!out.glb) throw InputError("--crease-angle sets the normals of glTF output; OUT is not .glb/.gltf (or --format glb/gltf)");
    if (step_input || !o.regions.empty() || o.sharp_angle != 0)
      throw InputError("--crease-angle: the normals follow the faces or regions of IN (a STEP input's B-Rep faces, "
                       "--regions, --sharp-angle); the crease angle is for a mesh without them");
    if (!valid_angle(o.crease_angle))
      throw InputError("--crease-angle " + short_number(o.crease_angle) + ": give a dihedral angle in degrees, in (0, 180)");
  }
  check_view_outputs(o.views);
  std::vector<NamedPath> outputs{{"OUT", o.output}, {"--json", o.json}};
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"IN", o.input}, {"--regions", o.regions}, {"--process", o.process},
                        {"--library", o.library}, {"--rules", o.rules}},
                       outputs);
  return out;
}

SimplifyInput load_simplify_input(const SimplifyCliOptions& o, [[maybe_unused]] const ImportedModel* model,
                                  SimplifyOptions& so, [[maybe_unused]] nlohmann::json& report) {
  SimplifyInput in;
  if (is_step_file(o.input)) {
    require_cad("STEP input " + o.input);  // (returns in interfere-cad only)
#ifdef INTERFERE_HAS_CAD
    cad::PipelineOptions po;
    po.linear_deflection = o.tessellation.linear_deflection;
    po.angular_deflection = o.tessellation.angular_deflection;
    po.library_file = o.library;
    po.rules_file = o.rules;
    po.process_file = o.process;
    po.step = o.step;
    po.mates = o.mates == "auto";
    po.delabella = o.mesher == "delabella";  // (issue #29: without --process, the mates inferred from the assembly)
    Progress progress(model ? "preparing step " + o.step : "importing " + o.input);
    auto prepared = model ? cad::prepare_for_simplify(*model, po) : cad::prepare_for_simplify(o.input, po);
    if (!prepared) throw InputError(prepared.error());
    if (!o.features.empty())  // world face ids, kept on every instance of their part
      if (Status s = cad::add_feature_faces(*prepared, parse_id_list(o.features, "--features")); !s)
        throw InputError("--features: " + s.error().reason);
    in.mesh = prepared->mesh;
    so.face_ids = prepared->face_ids;
    so.feature_faces = prepared->feature_faces;
    in.cad = std::make_unique<cad::Prepared>(std::move(*prepared));
    report["cad"] = nlohmann::json::parse(in.cad->report_json);
    for (const auto& w : in.cad->warnings)
      warning(w);
#endif
  } else {
    Progress progress("reading " + o.input);
    auto m = read_mesh(o.input);
    if (!m) throw InputError(m.error());
    in.mesh = std::move(*m);
    if (!o.regions.empty()) {
      auto r = read_region_file(o.regions, in.mesh.num_triangles());
      if (!r) throw InputError(r.error());
      so.face_ids = std::move(*r);
    } else if (o.sharp_angle != 0) {
      // The regions are made here, not by the simplifier (SimplifyOptions::sharp_angle_deg gives the
      // same run): --features ids are checked against them, --renderer-max counts their feature
      // triangles, and the output carries them as face ids.
      so.face_ids = sharp_edge_regions(in.mesh, o.sharp_angle);
    }
    if (!o.features.empty()) {
      so.feature_faces = parse_id_list(o.features, "--features");
      check_region_ids(o, so);
    }
  }
  // --max-error / --max-error-rel: the largest error bound allowed (the relative one of the whole
  // input's diagonal: an assembly's parts share one limit).
  // The diagonal only when asked for (0 * an overflowed diagonal was NaN: issue #23, item 7).
  so.max_error = o.max_error > 0 ? o.max_error : 0;
  if (o.max_error_rel > 0) {
    const double diagonal = norm(in.mesh.bounds().extent());
    if (!(diagonal > 0) || !std::isfinite(diagonal))
      throw InputError("--max-error-rel: the input's bounding box diagonal is " +
                       std::string(diagonal > 0 ? "not a finite number" : "0 (a point)") + ": give --max-error");
    so.max_error = o.max_error_rel * diagonal;
  }
  if (o.renderer_max > 0) {  // the total is the renderer's maximum, the features reserved (docs/simplify.md)
    const std::size_t f = count_feature_triangles(so.face_ids, so.feature_faces);
    const auto b = triangle_budgets({{in.mesh.num_triangles(), f}}, o.renderer_max);
    so.target_triangles = std::max<std::size_t>(1, b.budgets[0]);
    // The cap holds (issue #29): feature triangles beyond it are simplified too, and said so (a STEP
    // input's parts are named by simplify_assembly).
    if (b.features_exceed_budget && !is_step_file(o.input))
      warning("--renderer-max " + std::to_string(o.renderer_max) + " is below the " + std::to_string(f) +
              " triangles of the feature faces or regions: the cap holds, so they are simplified too");
    so.ratio = 0;
  }
  return in;
}

}  // namespace interfere::cli
