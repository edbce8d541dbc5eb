// `interfere simplify IN OUT --target N | --ratio R`: feature-preserving QEM simplification
// (issue #6, items 5-7). IN is a mesh file (STL/OBJ/PLY/OFF/glTF; optional per-triangle regions and
// feature regions, or a dihedral-angle mask) or, when built with OpenCASCADE, a STEP file whose
// assembly features are recognised and selected for a process step (--step P --process FILE).
// This file: the run, its outputs, --step all and the command line; the options' checks and the
// input are in simplify_input.cpp, the report in simplify_report.cpp.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <unistd.h>

#include "interfere/view/mesh_document.h"
#include "commands.h"
#include "cad_exec.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"
#include "interfere/simplify/tagged_io.h"
#include "simplify_cli.h"
#include "report_envelope.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

#ifdef INTERFERE_HAS_CAD
// A step id or part name as part of a file name (letters, digits, '-' and '_'; others become '_').
std::string file_id(const std::string& name) {
  std::string id;
  for (char c : name) id += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return id;
}

#endif

// One run; `model`: the STEP input already imported (--step all imports it once for every step).
// The viewer's document (issue #25): the simplified mesh over the original (hidden at first), the
// feature faces kept in their own colour.
view::Document simplify_document(const SimplifyCliOptions& o, const TriMesh& original, const SimplifyResult& r,
                                 const SimplifyOptions& so) {
  std::vector<std::uint32_t> features = so.feature_faces;
  std::sort(features.begin(), features.end());
  const auto labels = [&](const std::vector<std::uint32_t>& face_ids, std::size_t n) {
    std::vector<std::uint32_t> l(n, view::kNoLabel);
    for (std::size_t t = 0; t < face_ids.size() && t < n; ++t)
      if (std::binary_search(features.begin(), features.end(), face_ids[t])) l[t] = 0;
    return l;
  };
  const std::string name = std::filesystem::path(o.input).stem().string();
  view::MeshLayer simplified{.id = "simplified", .name = name + " (simplified)", .path = "/simplified",
                             .role = "simplified", .mesh = r.mesh, .pose = {},
                             .labels = labels(r.face_ids, r.mesh.num_triangles()), .visible = true,
                             .color = {0.35f, 0.62f, 0.85f}};
  view::MeshLayer input{.id = "original", .name = name + " (original)", .path = "/original", .role = "original",
                        .mesh = original, .pose = {}, .labels = labels(so.face_ids, original.num_triangles()),
                        .visible = false, .color = {0.70f, 0.70f, 0.70f}};
  view::Document doc = view::meshes_document(
      fmt::format("interfere simplify: {} -> {} triangles", original.num_triangles(), r.mesh.num_triangles()),
      {std::move(simplified), std::move(input)}, {{"feature faces (kept)", view::label_color(1)}});
  if (r.error_bound >= 0) doc.notes.push_back(fmt::format("error bound of the simplification: {:.6g}", r.error_bound));
  if (r.hausdorff >= 0) doc.notes.push_back(fmt::format("Hausdorff distance: {:.6g}", r.hausdorff));
  return doc;
}

int run_simplify(const SimplifyCliOptions& o, [[maybe_unused]] const ImportedModel* model = nullptr) {
  const SimplifyOutput output = check_simplify_options(o);
  // The input's unit (issue #23, item 6): a glTF output is written in metres, as its
  // specification says, so mesh coordinates in mm are scaled by the root node.
  const PartUnit input_unit = part_unit({.file = o.input, .units = o.units, .units_flag = "--units"});
  const bool glb = output.glb;
  const MeshFormat out_format = output.format;
  if (!o.parts_dir.empty()) {  // after the checks, before any work
    std::error_code ec;
    std::filesystem::create_directories(o.parts_dir, ec);
    if (ec || !std::filesystem::is_directory(o.parts_dir))
      throw InputError(Error{.file = o.parts_dir, .reason = "--parts-dir: cannot create the directory" +
                                                             (ec ? ": " + ec.message() : std::string())});
  }
  set_threads(o.threads);
  Progress total("simplify");
  nlohmann::json report;
  report["command"] = "simplify";
  report["version"] = INTERFERE_VERSION;
  report["input"] = o.input;
  report["output"] = o.output;
  SimplifyOptions so = simplify_options(o);
  SimplifyInput input = load_simplify_input(o, model, so, report);
  const TriMesh& mesh = input.mesh;
#ifdef INTERFERE_HAS_CAD
  const std::unique_ptr<cad::Prepared>& cad_prepared = input.cad;
#endif
  SimplifyResult r;
  double seconds = 0;
  std::size_t self_parts = 0;
  bool per_part = false;
  std::vector<SimplifyResult> part_results;
  {
    Progress progress("simplifying " + std::to_string(mesh.num_triangles()) + " triangles");
    // The share of the collapses done: a bar with ETA on a terminal, a line per tenth otherwise
    // (progress_bar.h); a long stage after the collapses is announced on its own line.
    auto bar = std::make_shared<std::unique_ptr<ProgressBar>>(std::make_unique<ProgressBar>("simplifying", 1000));
    so.progress = [bar](double f) {
      if (*bar) (*bar)->update(static_cast<std::size_t>(std::clamp(f, 0.0, 1.0) * 1000));
    };
    so.stage = [bar](const char* what) {
      bar->reset();
      if (!Progress::quiet()) std::fprintf(stderr, "[interfere] simplifying: %s ...\n", what);
    };
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
      double tessellation_error = 0;  // (relative to the B-Rep, add it to error_bound)
      for (const cad::PreparedPart& p : cad_prepared->parts) tessellation_error = std::max(tessellation_error, p.tessellation_error);
      report["tessellation_error"] = tessellation_error;
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
    bar->reset();
    so.progress = nullptr;
    so.stage = nullptr;
  }
  // --lod: coarser levels of detail for the glTF (issue #29, item 6), each the same simplification to
  // a fraction of the budget, written as MSFT_lod levels of every instance.
  std::vector<double> lod_ratios;
  for (std::size_t a = 0; a < o.lod.size();) {
    const std::size_t b = std::min(o.lod.find(',', a), o.lod.size());
    const std::string tok = o.lod.substr(a, b - a);
    char* end = nullptr;
    const double x = std::strtod(tok.c_str(), &end);
    if (tok.empty() || end != tok.c_str() + tok.size() || !(x > 0 && x < 1) ||
        (!lod_ratios.empty() && !(x < lod_ratios.back())))
      throw InputError("--lod: '" + tok + "': give decreasing fractions of the budget in (0, 1), e.g. 0.5,0.1");
    lod_ratios.push_back(x);
    a = b + 1;
  }
  if (!lod_ratios.empty() && !glb) throw InputError("--lod writes MSFT_lod levels of a glTF output: OUT is not .glb/.gltf");
  std::vector<std::vector<SimplifyResult>> lod_parts;  // per level: per part (STEP) or the one mesh
  nlohmann::json lod_report = nlohmann::json::array();
  for (double x : lod_ratios) {
    Progress progress("simplifying level of detail " + short_number(x));
    SimplifyOptions lo = so;
    lo.target_triangles = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(x * double(r.target_triangles))));
    lo.ratio = 0;
    lo.measure_error = so.measure_error;
#ifdef INTERFERE_HAS_CAD
    if (cad_prepared) {
      auto a = cad::simplify_assembly(*cad_prepared, lo);
      if (!a) throw InputError(a.error());
      lod_report.push_back({{"fraction", x}, {"target_triangles", lo.target_triangles},
                            {"output_triangles", a->merged.mesh.num_triangles()}, {"error_bound", a->merged.error_bound}});
      lod_parts.push_back(std::move(a->parts));
      continue;
    }
#endif
    auto one = simplify(mesh, lo);
    if (!one) throw InputError(one.error());
    lod_report.push_back({{"fraction", x}, {"target_triangles", lo.target_triangles},
                          {"output_triangles", one->mesh.num_triangles()}, {"error_bound", one->error_bound}});
    lod_parts.push_back({std::move(*one)});
  }
  if (!lod_ratios.empty()) report["lods"] = lod_report;
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
                            part_results[i].error_bound, 40, part_results[i].feature_flags});
          gparts.back().has_color = p.has_color;  // (the STEP file's colour: issue #29)
          std::copy(p.color, p.color + 3, gparts.back().color);
          for (std::size_t k = 0; k < lod_parts.size(); ++k) {
            const SimplifyResult& l = lod_parts[k][i];
            if (l.mesh.num_triangles() == 0) break;
            gparts.back().lods.push_back({p.name + " LOD" + std::to_string(k + 1), l.mesh, l.face_ids, p.feature_faces,
                                          l.error_bound, 40, l.feature_flags});
            gparts.back().lods.back().has_color = p.has_color;
            std::copy(p.color, p.color + 3, gparts.back().lods.back().color);
          }
        }
        for (const cad::PreparedInstance& in : cad_prepared->instances)  // (the product tree: issue #29)
          if (index[in.part] != 0xffffffffu) ginst.push_back({in.name, index[in.part], in.placement, in.path});
      }
#endif
      if (gparts.empty()) {
        gparts.push_back({std::filesystem::path(o.input).stem().string(), r.mesh, r.face_ids, so.feature_faces,
                          r.error_bound, o.crease_angle});
        for (std::size_t k = 0; k < lod_parts.size(); ++k)
          gparts.back().lods.push_back({gparts[0].name + " LOD" + std::to_string(k + 1), lod_parts[k][0].mesh,
                                        lod_parts[k][0].face_ids, so.feature_faces, lod_parts[k][0].error_bound,
                                        o.crease_angle});
        ginst.push_back({gparts[0].name, 0, Transform{}});
      }
      s = write_glb(o.output, gparts, ginst, per_part ? "mm" : input_unit.unit, output.container);
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
                                       {{p.name, 0, Transform{}}}, "mm", output.container)
                           : write_tagged_mesh(file, d.mesh, d.face_ids, p.feature_faces, out_format, d.error_bound);
      if (!s) throw InputError(s.error());
      jp["file"] = file;
    }
  }
#endif
  add_result_report(report, r, so, o);
  if (!report.contains("units")) report["units"] = input_unit.unit;
  report["units_source"] = input_unit.source;
  if (o.check_self) report["self_intersections"] = self;
  report["seconds"] = {{"simplify", seconds}, {"total", total.seconds()}};
  nlohmann::json phases = nlohmann::json::array();  // wall time per phase of simplify(), in order
  for (const auto& [name, sec] : r.phases) phases.push_back({{"phase", name}, {"seconds", sec}});
  report["seconds"]["phases"] = phases;
  if ((o.lock || o.feature_mode != "weight") && so.feature_faces.empty())
    r.warnings.push_back(std::string(o.lock ? "--lock" : "--feature-mode " + o.feature_mode) +
                         ": there are no feature faces to keep (--features, or for a STEP input --step with --process or an assembly's "
                         "mates)");
  report["warnings"] = r.warnings;
  for (const auto& w : r.warnings)
    warning(w);
  if (!o.json.empty()) {
    const Status s = write_output(o.json, report_text(report));
    if (!s) throw InputError(s.error());
  }
  if (o.views.any()) {
    view::Document doc = simplify_document(o, mesh, r, so);
    if (report["units"].is_string()) doc.units = report["units"].get<std::string>();
    write_views(o.views, std::move(doc));
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
  if (o.json == "-") throw InputError("--json -: --step all writes one report per step (JSON_<step>.json): give a file name");
  if (!is_step_file(o.input)) throw InputError("--step/--process need a STEP input (features are recognised on the B-Rep)");
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
    r.views.html = with_step(o.views.html, step.id);
    r.views.glb = with_step(o.views.glb, step.id);
    r.views.pvd = with_step(o.views.pvd, step.id);
    if (!o.parts_dir.empty()) r.parts_dir = (std::filesystem::path(o.parts_dir) / file_id(step.id)).string();
    check_simplify_options(r);  // (every run's options and outputs, before the import)
    runs.push_back(std::move(r));
  }
  Expected<cad::CadModel> model = Error{};
  {
    Progress progress("importing " + o.input);
    model = cad::import_step(o.input, {.linear_deflection = o.tessellation.linear_deflection,
                                       .angular_deflection = o.tessellation.angular_deflection,
                                       .measure_deviation = true,  // (the parts' tessellation_error)
                                       .delabella = o.mesher == "delabella"});
  }
  if (!model) throw InputError(model.error());
  for (const SimplifyCliOptions& r : runs) {
    std::printf("step %s: ", r.step.c_str());
    run_simplify(r, &*model);
  }
  return kClear;
#else
  require_cad("`interfere simplify " + o.input + " --step all`");  // (does not return here)
  return kInputError;
#endif
}

}  // namespace

void add_simplify_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SimplifyCliOptions>();
  CLI::App* c = app.add_subcommand("simplify", "Feature-preserving QEM simplification to a triangle budget");
  c->add_option("IN", o->input, "input mesh (STL/OBJ/PLY/OFF) or STEP file")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", o->output, "output mesh (.ply/.obj keep face ids, .stl in the attribute word, .off; .glb/.gltf: glTF, parts instanced)")->required();
  auto* target = c->add_option("--target", o->target, "triangle budget N (> 0, at most the input's count)");
  auto* ratio = c->add_option("--ratio", o->ratio, "budget as a fraction of the input's triangles, in (0, 1]");
  target->excludes(ratio);
  c->add_option("--renderer-max", o->renderer_max,
                "renderer's maximum triangle count: budget from the formula of docs/simplify.md (overrides --target/--ratio)");
  c->add_option("--step", o->step,
                "process step id whose assembly features are kept (STEP input, needs --process); 'all': every step, "
                "the STEP file imported once, outputs named OUT_<step>.ext (and JSON_<step>.json, DIR/<step>/)");
  c->add_option("--process", o->process, "process description JSON (steps, parts, constraint types)");
  c->add_option("--mates", o->mates,
                "STEP input without --process: auto (default) keeps the assembly features the mates inferred from "
                "the geometry pick (a bolt or rod in a hole of its diameter, a nut on a bolt, planar faces back to "
                "back; report cad.mates), off keeps none");
  c->add_option("--mesher", o->mesher,
                "STEP input: default (BRepMesh's algorithm) or delabella (OCCT's Delabella Delaunay per face: the "
                "same deflections, about a third less tessellation time on the casing, slightly different triangles)");
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
                "face seams kept: auto (default: all if the budget can be met so, else the borders of "
                "assembly-feature faces only, with a warning), all (every seam: a CAD part of many small faces "
                "may stop above the budget), features (those only) or none (face ids as tags only)");
  c->add_option("--feature-mode", o->feature_mode,
                "weight (paper: + maximum unmodified cost), last (feature edges strictly last) or lock");
  c->add_option("--sharp-angle", o->sharp_angle, "plain meshes: keep edges whose dihedral angle exceeds DEG degrees")
      ->excludes(regions);
  c->add_option("--units", o->units,
                "unit of a mesh input's coordinates (mm, cm, m, um, in, ft; default: m for glTF, mm otherwise; a STEP "
                "file's is its own): a glTF output is scaled to metres");
  c->add_option("--crease-angle", o->crease_angle,
                "glTF output of a mesh without faces or regions: NORMAL is smooth across edges up to DEG degrees, "
                "split across sharper ones (default 40)");
  add_step_tessellation_options(*c, o->tessellation);
  c->add_option("--parts-dir", o->parts_dir,
                "STEP input: also write each simplified part once, in part coordinates, to DIR/<part>_<name>.<OUT's "
                "extension> (the report's cad.instances place them)");
  c->add_option("--format", o->format, "output format (stl, stl-ascii, obj, ply, ply-ascii, off, glb, gltf; default by extension)");
  c->add_flag("--check-self-intersections", o->check_self, "count self-intersections of the result (engine clash)");
  auto* no_guard = c->add_flag("--no-intersection-guard", o->no_guard,
                               "plain QEM: no self-intersection check of the result and no guarded rerun");
  c->add_flag("--strict-intersection-guard", o->strict_guard,
              "refuse every new intersecting pair, also where the input's own contacts (cracks, touching or "
              "penetrating bodies) move (default: those are inherited within their zone)")
      ->excludes(no_guard);
  auto* no_error = c->add_flag("--no-error", o->no_error, "skip the Hausdorff measurement (error_bound is then -1)");
  c->add_option("--lod", o->lod,
                "glTF output: coarser levels of detail as decreasing fractions of the budget (e.g. 0.5,0.1), each "
                "simplified the same way and written as MSFT_lod levels of every instance");
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
  add_view_options(*c, o->views);
  c->callback([o, c, &exit_code] {
    resolve_step_tessellation(*c, o->tessellation, {o->input});  // (an error on a mesh input)
    o->crease_given = c->count("--crease-angle") > 0;
    exit_code = o->step == "all" ? run_all_steps(*o) : run_simplify(*o);
  });
}

}  // namespace interfere::cli
