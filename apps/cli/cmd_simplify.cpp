// `interfere simplify IN OUT --target N | --ratio R`: feature-preserving QEM simplification
// (issue #6, items 5-7). IN is a mesh file (STL/OBJ/PLY/OFF; optional per-triangle regions and
// feature regions, or a dihedral-angle mask) or, when built with OpenCASCADE, a STEP file whose
// assembly features are recognised and selected for a process step (--step P --process FILE).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "commands.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/simplify/budget.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"
#include "interfere/simplify/tagged_io.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/pipeline.h"
#endif

namespace interfere::cli {
namespace {

struct SimplifyCliOptions {
  std::string input, output, json, regions, features, step, process, format = "auto", feature_mode = "weight", seams = "all";
  std::string parts_dir;  ///< STEP input: each simplified part (prototype) also written here
  std::string library, rules;  ///< --library, --rules: JSON files instead of the installed ones
  std::size_t target = 0;
  double ratio = 0;
  double sharp_angle = 0;
  double crease_angle = 40;  ///< --crease-angle: glTF normals of a mesh without faces or regions
  double max_error = 0, max_error_rel = 0;  ///< --max-error (model units), --max-error-rel (of the diagonal)
  double linear_deflection = 0, angular_deflection = 0.5;
  std::size_t renderer_max = 0;
  bool lock = false, check_self = false, no_error = false, no_guard = false, strict_guard = false;
  bool deflection_given = false;  ///< --linear-/--angular-deflection on the command line
  bool crease_given = false;      ///< --crease-angle on the command line
  int threads = 0;
};

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

bool is_step(const std::string& file) {
  const std::string e = lower_extension(file);
  return e == ".step" || e == ".stp";
}

#ifdef INTERFERE_HAS_CAD
// A step id or part name as part of a file name (letters, digits, '-' and '_'; others become '_').
std::string file_id(const std::string& name) {
  std::string id;
  for (char c : name) id += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return id;
}

// The report's parts_simplified: one entry per part simplified (a part's self-intersections counted
// with --check-self-intersections, their sum over the instances added to `self_total`).
nlohmann::json parts_report(const cad::Prepared& prep, const cad::AssemblySimplifyResult& a, bool count_self,
                            std::size_t& self_total) {
  nlohmann::json parts = nlohmann::json::array();
  for (std::size_t i = 0; i < prep.parts.size(); ++i) {
    if (a.part_budgets[i] == 0) continue;
    const cad::PreparedPart& p = prep.parts[i];
    const SimplifyResult& d = a.parts[i];
    const auto or_null = [](double x) { return x < 0 ? nlohmann::json(nullptr) : nlohmann::json(x); };
    nlohmann::json j = {{"part", i}, {"model_part", p.model_part}, {"name", p.name}, {"instances", p.instances},
                        {"input_triangles", d.input_triangles}, {"target_triangles", a.part_budgets[i]},
                        {"output_triangles", d.mesh.num_triangles()}, {"one_below", d.one_below},
                        {"feature_triangles", {{"input", d.feature_triangles_in}, {"output", d.feature_triangles_out}}},
                        {"hausdorff", d.hausdorff}, {"error_bound", d.error_bound},
                        {"hausdorff_features", or_null(d.hausdorff_features)}, {"guard_rerun", d.guard_rerun},
                        {"guard_reruns", d.guard_reruns}, {"input_contact_pairs", d.input_contact_pairs},
                        {"inherited_pairs", d.inherited_pairs}, {"seams_relaxed_at", d.seams_relaxed_at},
                        {"max_error_runs", d.max_error_runs}, {"error_limited_budget", d.error_limited_budget}};
    if (count_self) {
      const std::size_t x = count_self_intersections(d.mesh);
      j["self_intersections"] = x;
      self_total += x * p.instances;
    }
    parts.push_back(std::move(j));
  }
  return parts;
}
#endif

#ifdef INTERFERE_HAS_CAD
using ImportedModel = cad::CadModel;
#else
struct ImportedModel {};
#endif

// One run; `model`: the STEP input already imported (--step all imports it once for every step).
int run_simplify(const SimplifyCliOptions& o, [[maybe_unused]] const ImportedModel* model = nullptr) {
  if (o.target == 0 && o.ratio == 0 && o.renderer_max == 0)
    throw InputError("simplify: give --target N (> 0), --ratio R or --renderer-max N");
  if (o.ratio != 0 && !(o.ratio > 0 && o.ratio <= 1)) throw InputError("--ratio must lie in (0, 1]");
  if (!o.step.empty() && o.process.empty()) throw InputError("--step needs --process FILE");
  if (o.step.empty() && !o.process.empty()) throw InputError("--process needs --step ID");
  if (!o.parts_dir.empty() && !is_step(o.input))
    throw InputError("--parts-dir needs a STEP input (one file per part of the assembly)");
  if (!o.parts_dir.empty()) {  // before anything is written
    std::error_code ec;
    std::filesystem::create_directories(o.parts_dir, ec);
    if (ec || !std::filesystem::is_directory(o.parts_dir))
      throw InputError(Error{.file = o.parts_dir, .reason = "--parts-dir: cannot create the directory" +
                                                             (ec ? ": " + ec.message() : std::string())});
  }
  const bool glb_format = o.format == "glb" || o.format == "GLB";
  const MeshFormat out_format = glb_format ? MeshFormat::automatic : mesh_format_from_name(o.format);
  if (out_format == MeshFormat::automatic && o.format != "auto" && o.format != "AUTO" && !glb_format)
    throw InputError("--format: unknown mesh format '" + o.format + "' (stl, stl-ascii, obj, ply, ply-ascii, off, glb)");
  // Outputs checked before any work: a known extension (or --format) and an existing directory.
  check_output(o.output,
               out_format == MeshFormat::automatic && !glb_format
                   ? std::vector<std::string>{".stl", ".ply", ".obj", ".off", ".glb"}
                   : std::vector<std::string>{},
               "OUT (or --format)");
  const bool glb = glb_format || (out_format == MeshFormat::automatic && lower_extension(o.output) == ".glb");
  check_output(o.json, {}, "--json");
  if (o.crease_given) {
    if (!glb) throw InputError("--crease-angle sets the normals of glTF output; OUT is not .glb (or --format glb)");
    if (is_step(o.input) || !o.regions.empty() || o.sharp_angle != 0)
      throw InputError("--crease-angle: the normals follow the faces or regions of IN (a STEP input's B-Rep faces, "
                       "--regions, --sharp-angle); the crease angle is for a mesh without them");
    if (!(o.crease_angle > 0 && o.crease_angle < 180))
      throw InputError("--crease-angle " + short_number(o.crease_angle) + ": give a dihedral angle in degrees, in (0, 180)");
  }
  check_distinct_files({{"IN", o.input}, {"--regions", o.regions}, {"--process", o.process},
                        {"--library", o.library}, {"--rules", o.rules}},
                       {{"OUT", o.output}, {"--json", o.json}});
  set_threads(o.threads);
  Progress total("simplify");
  nlohmann::json report;
  report["command"] = "simplify";
  report["version"] = INTERFERE_VERSION;
  report["input"] = o.input;
  report["output"] = o.output;

  TriMesh mesh;
  SimplifyOptions so;
#ifdef INTERFERE_HAS_CAD
  std::unique_ptr<cad::Prepared> cad_prepared;
#endif
  so.target_triangles = o.target;
  so.ratio = o.ratio;
  if (o.feature_mode == "weight") so.feature_mode = FeatureMode::weight;
  else if (o.feature_mode == "last") so.feature_mode = FeatureMode::last;
  else if (o.feature_mode == "lock") so.feature_mode = FeatureMode::lock;
  else throw InputError("--feature-mode must be weight, last or lock, not '" + o.feature_mode + "'");
  if (o.lock) so.feature_mode = FeatureMode::lock;
  if (o.seams == "all") so.seams = SeamMode::all;
  else if (o.seams == "features") so.seams = SeamMode::features;
  else if (o.seams == "none") so.seams = SeamMode::none;
  else if (o.seams == "auto") so.seams = SeamMode::as_needed;
  else throw InputError("--seams must be all, auto, features or none, not '" + o.seams + "'");
  so.measure_error = !o.no_error;
  so.prevent_self_intersections = !o.no_guard;
  so.inherit_input_contacts = !o.strict_guard;
  if (is_step(o.input)) {
    if (!o.regions.empty() || o.sharp_angle != 0)
      throw InputError("--regions/--sharp-angle are for plain meshes: a STEP input's regions are its B-Rep faces");
#ifdef INTERFERE_HAS_CAD
    cad::PipelineOptions po;
    po.linear_deflection = o.linear_deflection;
    po.angular_deflection = o.angular_deflection;
    po.library_file = o.library;
    po.rules_file = o.rules;
    po.process_file = o.process;
    po.step = o.step;
    Progress progress(model ? "preparing step " + o.step : "importing " + o.input);
    auto prepared = model ? cad::prepare_for_simplify(*model, po) : cad::prepare_for_simplify(o.input, po);
    if (!prepared) throw InputError(prepared.error());
    if (!o.features.empty())  // world face ids, kept on every instance of their part
      if (Status s = cad::add_feature_faces(*prepared, parse_id_list(o.features, "--features")); !s)
        throw InputError("--features: " + s.error().reason);
    mesh = prepared->mesh;
    so.face_ids = prepared->face_ids;
    so.feature_faces = prepared->feature_faces;
    cad_prepared = std::make_unique<cad::Prepared>(std::move(*prepared));
    report["cad"] = nlohmann::json::parse(cad_prepared->report_json);
    for (const auto& w : cad_prepared->warnings)
      warning(w);
#else
    throw InputError(o.input + ": STEP input needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
#endif
  } else {
    if (!o.step.empty() || !o.process.empty() || !o.library.empty() || !o.rules.empty())
      throw InputError("--step/--process/--library/--rules need a STEP input (features are recognised on the B-Rep)");
    if (o.deflection_given)
      throw InputError("--linear-deflection/--angular-deflection tessellate a STEP input; " + o.input + " is a mesh");
    Progress progress("reading " + o.input);
    auto m = read_mesh(o.input);
    if (!m) throw InputError(m.error());
    mesh = std::move(*m);
    if (!o.regions.empty()) {
      auto r = read_region_file(o.regions, mesh.num_triangles());
      if (!r) throw InputError(r.error());
      so.face_ids = std::move(*r);
    } else if (o.sharp_angle != 0) {
      // The regions are made here, not by the simplifier (SimplifyOptions::sharp_angle_deg gives the
      // same run): --features ids are checked against them, --renderer-max counts their feature
      // triangles, and the output carries them as face ids.
      if (!(o.sharp_angle > 0 && o.sharp_angle < 180))
        throw InputError("--sharp-angle " + short_number(o.sharp_angle) + ": give a dihedral angle in degrees, in (0, 180)");
      so.face_ids = sharp_edge_regions(mesh, o.sharp_angle);
    }
    if (!o.features.empty()) {
      if (so.face_ids.empty())
        throw InputError("--features names region ids: give them with --regions FILE or --sharp-angle DEG");
      so.feature_faces = parse_id_list(o.features, "--features");
      const std::string source = o.regions.empty() ? "--sharp-angle " + short_number(o.sharp_angle) + "'s regions of " + o.input
                                                   : o.regions;
      std::vector<std::uint32_t> ids = so.face_ids;  // (a region file's ids may be sparse)
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      for (std::uint32_t id : so.feature_faces)
        if (!std::binary_search(ids.begin(), ids.end(), id))
          throw InputError("--features: no triangle of " + source + " has region id " + std::to_string(id) +
                           (o.regions.empty() ? " (ids 0 to " + std::to_string(ids.back()) + ")" : std::string()));
    }
  }
  // --max-error / --max-error-rel: the largest error bound allowed (the relative one of the whole
  // input's diagonal: an assembly's parts share one limit).
  if (!(o.max_error >= 0 && std::isfinite(o.max_error)))
    throw InputError("--max-error must be a length > 0 (model units), not " + short_number(o.max_error));
  if (!(o.max_error_rel >= 0 && o.max_error_rel <= 1))
    throw InputError("--max-error-rel must be a fraction of the bounding-box diagonal in (0, 1], not " +
                     short_number(o.max_error_rel));
  so.max_error = o.max_error > 0 ? o.max_error : o.max_error_rel * norm(mesh.bounds().extent());
  if (o.max_error_rel > 0 && !(so.max_error > 0))
    throw InputError("--max-error-rel: the input's bounding box has no extent (a point): give --max-error");
  if (o.renderer_max > 0) {  // one part: its budget is the renderer's maximum (docs/simplify.md)
    const auto b = triangle_budgets({{mesh.num_triangles(), count_feature_triangles(so.face_ids, so.feature_faces)}},
                                    o.renderer_max);
    so.target_triangles = std::max<std::size_t>(1, b.budgets[0]);
    so.ratio = 0;
  }
  SimplifyResult r;
  double seconds = 0;
  std::size_t self_parts = 0;
  bool per_part = false;
  std::vector<SimplifyResult> part_results;
  {
    Progress progress("simplifying " + std::to_string(mesh.num_triangles()) + " triangles");
    // On a terminal, the share of the collapses done, rewritten in place (every 10 %).
    bool shown = false;
    if (!Progress::quiet() && ::isatty(::fileno(stderr))) {
      auto last = std::make_shared<int>(-1);
      so.progress = [last, &shown](double f) {
        const int pct = static_cast<int>(f * 10) * 10;
        if (pct == *last) return;
        *last = pct;
        shown = true;
        std::fprintf(stderr, "\r[interfere] simplifying: %3d %%", pct);
        std::fflush(stderr);
      };
      so.stage = [&shown](const char* what) {
        shown = true;
        std::fprintf(stderr, "\r[interfere] simplifying: 100 %%, %s ...", what);
        std::fflush(stderr);
      };
    }
    Expected<SimplifyResult> res = Error{};
#ifdef INTERFERE_HAS_CAD
    if (cad_prepared) {
      auto a = cad::simplify_assembly(*cad_prepared, so);
      if (!a) {
        Error e = a.error();
        e.file = o.input;
        throw InputError(e);
      }
      report["parts_simplified"] = parts_report(*cad_prepared, *a, o.check_self, self_parts);
      report["budget_rounds"] = a->budget_rounds;
      part_results = std::move(a->parts);
      res = std::move(a->merged);
      per_part = true;
    } else {
      res = simplify(mesh, so);
    }
#else
    res = simplify(mesh, so);
#endif
    if (!res) {
      Error e = res.error();
      e.file = o.input;
      throw InputError(e);
    }
    r = std::move(*res);
    seconds = progress.seconds();
    if (shown) std::fprintf(stderr, "\n");
    so.progress = nullptr;
    so.stage = nullptr;
  }
  std::size_t self = 0;
  if (o.check_self) {
    Progress progress("self-intersection check");
    // STEP: per part (an assembly's touching parts are contacts, not self-intersections).
    self = per_part ? self_parts : count_self_intersections(r.mesh);
  }
  {
    Progress progress("writing " + o.output);
    Status s;
    if (glb) {
      // glTF: each part once, placed by its instances (STEP), or the one mesh.
      std::vector<GltfPart> gparts;
      std::vector<GltfInstance> ginst;
#ifdef INTERFERE_HAS_CAD
      if (cad_prepared) {
        std::vector<std::uint32_t> index(cad_prepared->parts.size(), 0xffffffffu);
        for (std::size_t i = 0; i < cad_prepared->parts.size(); ++i) {
          const cad::PreparedPart& p = cad_prepared->parts[i];
          if (part_results[i].mesh.num_triangles() == 0) continue;
          index[i] = static_cast<std::uint32_t>(gparts.size());
          gparts.push_back({p.name, part_results[i].mesh, part_results[i].face_ids, p.feature_faces,
                            part_results[i].error_bound});
        }
        for (const cad::PreparedInstance& in : cad_prepared->instances)
          if (index[in.part] != 0xffffffffu) ginst.push_back({in.name, index[in.part], in.placement});
      }
#endif
      if (gparts.empty()) {
        gparts.push_back({std::filesystem::path(o.input).stem().string(), r.mesh, r.face_ids, so.feature_faces,
                          r.error_bound, o.crease_angle});
        ginst.push_back({gparts[0].name, 0, Transform{}});
      }
      s = write_glb(o.output, gparts, ginst, per_part ? "mm" : "");
    } else {
      s = write_tagged_mesh(o.output, r.mesh, r.face_ids, so.feature_faces, out_format, r.error_bound);
    }
    if (!s) throw InputError(s.error());
  }
#ifdef INTERFERE_HAS_CAD
  // --parts-dir: each part once, in part coordinates, in OUT's format, with its own error bound; the
  // report's cad.instances place them (a renderer instances them instead of the merged OUT).
  if (!o.parts_dir.empty() && cad_prepared) {
    Progress progress("writing the parts to " + o.parts_dir);
    const std::string ext = std::filesystem::path(o.output).extension().string();
    for (auto& jp : report["parts_simplified"]) {
      const std::size_t i = jp["part"].get<std::size_t>();
      const cad::PreparedPart& p = cad_prepared->parts[i];
      const std::string file =
          (std::filesystem::path(o.parts_dir) / fmt::format("{}_{}{}", i, file_id(p.name), ext)).string();
      const SimplifyResult& d = part_results[i];
      const Status s = glb ? write_glb(file, {{p.name, d.mesh, d.face_ids, p.feature_faces, d.error_bound}},
                                       {{p.name, 0, Transform{}}}, "mm")
                           : write_tagged_mesh(file, d.mesh, d.face_ids, p.feature_faces, out_format, d.error_bound);
      if (!s) throw InputError(s.error());
      jp["file"] = file;
    }
  }
#endif
  report["input_triangles"] = r.input_triangles;
  report["target_triangles"] = r.target_triangles;
  report["output_triangles"] = r.mesh.num_triangles();
  report["output_vertices"] = r.mesh.num_vertices();
  report["reached"] = r.reached;
  report["one_below"] = r.one_below;
  report["collapses"] = r.collapses;
  report["rejected"] = {{"link_condition", r.rejected_link}, {"flipped_normal", r.rejected_flip},
                        {"self_intersection", r.rejected_intersection}, {"last_face_triangle", r.rejected_face}};
  report["guard_rerun"] = r.guard_rerun;
  report["guard_reruns"] = r.guard_reruns;
  report["input_contact_pairs"] = r.input_contact_pairs;
  report["inherited_pairs"] = r.inherited_pairs;
  report["degenerate_triangles"] = r.degenerate_triangles;
  report["vertices"] = {{"welded_input", r.input_vertices_welded}, {"seam", r.seam_vertices},
                        {"corner", r.corner_vertices}, {"locked", r.locked_vertices}};
  report["feature_mode"] = so.feature_mode == FeatureMode::lock ? "lock" : so.feature_mode == FeatureMode::last ? "last" : "weight";
  report["seams"] = o.seams;
  report["seams_relaxed_at"] = r.seams_relaxed_at;
  report["max_error"] = so.max_error > 0 ? nlohmann::json(so.max_error) : nlohmann::json(nullptr);
  report["max_error_runs"] = r.max_error_runs;
  report["error_limited_budget"] = r.error_limited_budget;
  std::vector<std::uint32_t> ff = so.feature_faces;
  std::sort(ff.begin(), ff.end());
  ff.erase(std::unique(ff.begin(), ff.end()), ff.end());
  report["feature_faces"] = ff;
  report["sharp_angle"] = o.sharp_angle > 0 ? nlohmann::json(o.sharp_angle) : nlohmann::json(nullptr);
  {
    std::vector<std::uint32_t> ids = so.face_ids;
    std::sort(ids.begin(), ids.end());
    report["regions"] = std::unique(ids.begin(), ids.end()) - ids.begin();  // faces or regions of the input (0: none)
  }
  report["feature_triangles"] = {{"input", r.feature_triangles_in}, {"output", r.feature_triangles_out}};
  report["max_unmodified_cost"] = r.max_unmodified_cost;
  report["bbox_diagonal"] = r.bbox_diagonal;
  report["hausdorff"] = r.hausdorff;
  report["hausdorff_features"] = r.hausdorff_features < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.hausdorff_features);
  report["error_bound"] = r.error_bound;
  if (o.check_self) report["self_intersections"] = self;
  report["seconds"] = {{"simplify", seconds}, {"total", total.seconds()}};
  nlohmann::json phases = nlohmann::json::array();  // wall time per phase of simplify(), in order
  for (const auto& [name, sec] : r.phases) phases.push_back({{"phase", name}, {"seconds", sec}});
  report["seconds"]["phases"] = phases;
  if ((o.lock || o.feature_mode != "weight") && so.feature_faces.empty())
    r.warnings.push_back(std::string(o.lock ? "--lock" : "--feature-mode " + o.feature_mode) +
                         ": there are no feature faces to keep (--features, or --step with --process for a STEP input)");
  report["warnings"] = r.warnings;
  for (const auto& w : r.warnings)
    warning(w);
  if (!o.json.empty()) {
    const Status s = write_file_atomic(o.json, report.dump(2) + "\n");
    if (!s) throw InputError(s.error());
  }
  std::string error = "error not measured";
  if (r.hausdorff >= 0) {
    error = fmt::format("Hausdorff {:.6g}", r.hausdorff);
    if (r.hausdorff_features >= 0) error += fmt::format(" (feature faces {:.6g})", r.hausdorff_features);
    error += fmt::format(", error bound {:.6g}", r.error_bound);
  }
  std::printf("simplified %zu -> %zu triangles (target %zu%s), %s, %.3f s\n", r.input_triangles,
              r.mesh.num_triangles(), r.target_triangles, r.reached ? "" : ", not reached", error.c_str(), seconds);
  return kClear;
}

#ifdef INTERFERE_HAS_CAD
// OUT with "_<step>" before its extension: line.glb -> line_P1.glb.
std::string with_step(const std::string& file, const std::string& step) {
  if (file.empty()) return file;
  const std::filesystem::path p(file);
  return (p.parent_path() / (p.stem().string() + "_" + file_id(step) + p.extension().string())).string();
}

#endif

// --step all: every step of the process in its order, the STEP file imported once; outputs, JSON
// reports and parts directories get the step's id (OUT_<step>.ext, JSON_<step>.json, DIR/<step>/).
int run_all_steps(const SimplifyCliOptions& o) {
#ifdef INTERFERE_HAS_CAD
  if (o.process.empty()) throw InputError("--step all needs --process FILE");
  if (!is_step(o.input)) throw InputError("--step/--process need a STEP input (features are recognised on the B-Rep)");
  // The library, the rules and every step of the process are checked before the import and before
  // any output is written.
  auto sem = cad::load_semantics({.library_file = o.library, .rules_file = o.rules, .process_file = o.process, .step = "all"});
  if (!sem) throw InputError(sem.error());
  const std::optional<cad::Process>& process = sem->process;
  if (process->steps.empty()) throw InputError(Error{.file = o.process, .reason = "the process has no steps"});
  std::vector<SimplifyCliOptions> runs;
  for (const cad::ProcessStep& step : process->steps) {
    // Ids that differ only in characters a file name cannot hold would write one file twice.
    for (const SimplifyCliOptions& r : runs)
      if (file_id(r.step) == file_id(step.id))
        throw InputError(Error{.file = o.process, .reason = "steps '" + r.step + "' and '" + step.id +
                                                            "' would write the same files (OUT_" + file_id(step.id) +
                                                            "...): give them ids that differ in letters, digits, - or _"});
    SimplifyCliOptions r = o;
    r.step = step.id;
    r.output = with_step(o.output, step.id);
    r.json = with_step(o.json, step.id);
    if (!o.parts_dir.empty()) r.parts_dir = (std::filesystem::path(o.parts_dir) / file_id(step.id)).string();
    check_output(r.output, {}, "OUT");
    if (!r.json.empty()) check_output(r.json, {}, "--json");
    check_distinct_files({{"IN", o.input}, {"--process", o.process}, {"--library", o.library}, {"--rules", o.rules}},
                         {{"OUT", r.output}, {"--json", r.json}});
    runs.push_back(std::move(r));
  }
  Expected<cad::CadModel> model = Error{};
  {
    Progress progress("importing " + o.input);
    model = cad::import_step(o.input, {.linear_deflection = o.linear_deflection, .angular_deflection = o.angular_deflection});
  }
  if (!model) throw InputError(model.error());
  for (const SimplifyCliOptions& r : runs) {
    std::printf("step %s: ", r.step.c_str());
    run_simplify(r, &*model);
  }
  return kClear;
#else
  throw InputError(o.input + ": STEP input needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
#endif
}

}  // namespace

void add_simplify_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SimplifyCliOptions>();
  CLI::App* c = app.add_subcommand("simplify", "Feature-preserving QEM simplification to a triangle budget");
  c->add_option("IN", o->input, "input mesh (STL/OBJ/PLY/OFF) or STEP file")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", o->output, "output mesh (.ply/.obj keep face ids, .stl in the attribute word, .off; .glb: glTF, parts instanced)")->required();
  auto* target = c->add_option("--target", o->target, "triangle budget N (> 0, at most the input's count)");
  auto* ratio = c->add_option("--ratio", o->ratio, "budget as a fraction of the input's triangles, in (0, 1]");
  target->excludes(ratio);
  c->add_option("--renderer-max", o->renderer_max,
                "renderer's maximum triangle count: budget from the formula of docs/simplify.md (overrides --target/--ratio)");
  c->add_option("--step", o->step,
                "process step id whose assembly features are kept (STEP input, needs --process); 'all': every step, "
                "the STEP file imported once, outputs named OUT_<step>.ext (and JSON_<step>.json, DIR/<step>/)");
  c->add_option("--process", o->process, "process description JSON (steps, parts, constraint types)");
  c->add_option("--library", o->library, "feature library JSON (default: the installed data/features/library.json)")
      ->check(CLI::ExistingFile);
  c->add_option("--rules", o->rules, "assembly-semantics rules JSON (default: data/features/semantics.json)")
      ->check(CLI::ExistingFile);
  auto* regions = c->add_option("--regions", o->regions, "plain meshes: per-triangle region ids (text, one unsigned integer per triangle)");
  c->add_option("--features", o->features,
                "comma-separated face/region ids to keep (added to the step's features): --regions/--sharp-angle "
                "region ids, or a STEP input's face ids as the output numbers them");
  c->add_flag("--lock", o->lock, "hard-lock feature faces (bit-identical) instead of the paper's cost weighting");
  c->add_option("--seams", o->seams,
                "face seams kept: all (default), auto (all if the budget can be met so, else the borders of "
                "assembly-feature faces only), features (those only: a CAD part of many small faces can go much "
                "lower) or none (face ids as tags only)");
  c->add_option("--feature-mode", o->feature_mode,
                "weight (paper: + maximum unmodified cost), last (feature edges strictly last) or lock");
  c->add_option("--sharp-angle", o->sharp_angle, "plain meshes: keep edges whose dihedral angle exceeds DEG degrees")
      ->excludes(regions);
  c->add_option("--crease-angle", o->crease_angle,
                "glTF output of a mesh without faces or regions: NORMAL is smooth across edges up to DEG degrees, "
                "split across sharper ones (default 40)");
  c->add_option("--linear-deflection", o->linear_deflection, "STEP tessellation: linear deflection (0 = 0.1 % of the diagonal)");
  c->add_option("--angular-deflection", o->angular_deflection, "STEP tessellation: angular deflection in radians");
  c->add_option("--parts-dir", o->parts_dir,
                "STEP input: also write each simplified part once, in part coordinates, to DIR/<part>_<name>.<OUT's "
                "extension> (the report's cad.instances place them)");
  c->add_option("--format", o->format, "output format (stl, stl-ascii, obj, ply, ply-ascii, off, glb; default by extension)");
  c->add_flag("--check-self-intersections", o->check_self, "count self-intersections of the result (engine clash)");
  auto* no_guard = c->add_flag("--no-intersection-guard", o->no_guard,
                               "plain QEM: no self-intersection check of the result and no guarded rerun");
  c->add_flag("--strict-intersection-guard", o->strict_guard,
              "refuse every new intersecting pair, also where the input's own contacts (cracks, touching or "
              "penetrating bodies) move (default: those are inherited within their zone)")
      ->excludes(no_guard);
  auto* no_error = c->add_flag("--no-error", o->no_error, "skip the Hausdorff measurement (error_bound is then -1)");
  auto* max_error = c->add_option("--max-error", o->max_error,
                                  "largest error bound allowed (model units): where the budget would exceed it, the "
                                  "fewest triangles found within it instead (a search over the budget, each step a "
                                  "run with the error measured)");
  c->add_option("--max-error-rel", o->max_error_rel, "--max-error as a fraction of the input's bounding-box diagonal")
      ->excludes(max_error)
      ->excludes(no_error);
  max_error->excludes(no_error);
  c->add_option("--json", o->json, "write the JSON report here");
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  c->callback([o, c, &exit_code] {
    o->deflection_given = c->count("--linear-deflection") + c->count("--angular-deflection") > 0;
    o->crease_given = c->count("--crease-angle") > 0;
    exit_code = o->step == "all" ? run_all_steps(*o) : run_simplify(*o);
  });
}

}  // namespace interfere::cli
