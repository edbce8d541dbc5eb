// `interfere features PART.step`: machining features recognised on the B-Rep (issue #6, items 2-4,
// 7): the AAG of every part, the features of the library with their face ids, axes and radii, and,
// with --process/--step, the assembly-feature faces that step selects.
#include <cmath>
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstdio>

#include "commands.h"
#include "cad_exec.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/view/mesh_document.h"
#include "view_output.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/aag_dot.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/pipeline.h"
#include "interfere/cad/semantics.h"
#include "report_envelope.h"
#endif

namespace interfere::cli {
namespace {

struct FeaturesCliOptions {
  std::string input, json, dot, library, rules, process, step;
  StepTessellation tessellation;
  bool aag = false;
  ViewOutputs views;  ///< --html, --glb, --pvd (issue #25): faces coloured by feature type
};

#ifdef INTERFERE_HAS_CAD
nlohmann::json vec_json(const Vec3& v) { return {v.x, v.y, v.z}; }

int run_features(const FeaturesCliOptions& o) {
  using namespace interfere::cad;
  if (!o.step.empty() && o.process.empty()) throw InputError("--step needs --process FILE");
  if (o.step.empty() && !o.process.empty()) throw InputError("--process needs --step ID");
  check_output(o.json, {}, "--json");
  check_output(o.dot, {}, "--dot");
  check_view_outputs(o.views);
  if (o.step == "all" && o.views.any())
    throw InputError("--html/--glb/--pvd with --step all: give one step (its assembly-feature faces are highlighted)");
  std::vector<NamedPath> outputs{{"--json", o.json}, {"--dot", o.dot}};
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"IN", o.input}, {"--library", o.library}, {"--rules", o.rules}, {"--process", o.process}},
                       outputs);
  Progress total("features");
  auto sem = load_semantics({.library_file = o.library, .rules_file = o.rules, .process_file = o.process, .step = o.step});
  if (!sem) throw InputError(sem.error());
  const FeatureLibrary* lib = &sem->library;
  const SemanticRules* rules = &sem->rules;
  const std::optional<Process>& process = sem->process;
  Expected<CadModel> model = CadModel{};
  {
    Progress progress("importing " + o.input);
    model = import_step(o.input, {.linear_deflection = o.tessellation.linear_deflection,
                                  .angular_deflection = o.tessellation.angular_deflection});
    if (!model) throw InputError(model.error());
  }
  // --step all: every step of the process, in its order.
  std::vector<std::string> steps;
  if (process) {
    if (o.step == "all") {
      for (const ProcessStep& st : process->steps) steps.push_back(st.id);
    } else {
      steps.push_back(o.step);
    }
  }
  for (const std::string& step : steps)
    for (auto& w : unknown_step_names(*process, step, *model)) model->warnings.push_back(std::move(w));
  for (const auto& w : model->warnings)
    warning(w);
  {
    std::string declared;
    for (const auto& u : model->file_length_units) declared += (declared.empty() ? "" : ", ") + u;
    std::printf("lengths in %s%s%s%s\n", model->units.c_str(), declared.empty() ? "" : " (the file declares ",
                declared.c_str(), declared.empty() ? "" : ")");
  }
  nlohmann::json report{{"command", "features"}, {"version", INTERFERE_VERSION}, {"input", o.input}};
  report["parts"] = nlohmann::json::array();
  double recognition_seconds = 0;
  std::vector<DotPart> dot_parts;  // --dot: each part's graph, features and (one step) assembly faces
  // --html/--glb/--pvd: per part and triangle, the feature type of its B-Rep face (legend index),
  // the step's assembly-feature faces above every type.
  std::vector<std::string> type_names;
  std::vector<std::vector<std::uint32_t>> part_labels;
  const auto type_index = [&](const std::string& t) {
    const auto it = std::find(type_names.begin(), type_names.end(), t);
    if (it != type_names.end()) return static_cast<std::uint32_t>(it - type_names.begin() + 1);
    type_names.push_back(t);
    return static_cast<std::uint32_t>(type_names.size());
  };
  for (const Part& part : model->parts) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto feats = recognize_features(part.aag, *lib);
    recognition_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json jp{{"name", part.name}, {"solids", part.solids}, {"faces", part.faces},
                      {"triangles", part.mesh.num_triangles()}, {"untessellated_faces", part.untessellated_faces}};
    jp["features"] = nlohmann::json::array();
    std::printf("part '%s': %u faces, %zu triangles, %zu features\n", part.name.c_str(), part.faces,
                part.mesh.num_triangles(), feats.size());
    for (const Feature& f : feats) {
      nlohmann::json jf{{"type", f.type}, {"faces", f.faces}, {"roles", f.roles}, {"radii", f.radii}};
      if (norm(f.axis) > 0) jf["axis"] = {{"point", vec_json(f.axis_point)}, {"direction", vec_json(f.axis)}};
      jp["features"].push_back(jf);
      const std::string faces = fmt::format("{}", fmt::join(f.faces, ","));
      std::vector<std::string> radius_texts;
      for (double r : f.radii) radius_texts.push_back(short_number(r));
      const std::string radii = fmt::format("{}", fmt::join(radius_texts, ","));
      // The axis as a point and a direction (display: components within 1e-12 of 0 shown as 0).
      std::string axis;
      if (norm(f.axis) > 0) {
        const auto v = [](const Vec3& p) {
          const auto c = [](double x) { return short_number(std::fabs(x) < 1e-12 ? 0.0 : x); };
          return "(" + c(p.x) + ", " + c(p.y) + ", " + c(p.z) + ")";
        };
        axis = " axis " + v(f.axis_point) + " dir " + v(f.axis);
      }
      std::printf("  %-18s faces [%s]%s%s%s\n", f.type.c_str(), faces.c_str(), radii.empty() ? "" : " radii ",
                  radii.c_str(), axis.c_str());
    }
    if (!o.dot.empty()) dot_parts.push_back({part.name, &part.aag, feats, {}});
    std::vector<std::uint32_t> face_label;  // by B-Rep face id (label 0: assembly-feature face)
    if (o.views.any()) {
      for (const Feature& f : feats)
        for (std::uint32_t face : f.faces) {
          if (face >= face_label.size()) face_label.resize(face + 1, view::kNoLabel);
          if (face_label[face] == view::kNoLabel) face_label[face] = type_index(f.type);
        }
    }
    for (const std::string& step : steps) {
      // In the step when it names the part or one of its instances (then only those instances
      // keep the features when simplified: `instances[].in_step` of the simplify report).
      const auto sel = part_step_selection(*process, step, *rules, *model,
                                           static_cast<std::uint32_t>(&part - model->parts.data()), feats);
      if (!sel) throw InputError(o.process + ": " + sel.error().reason);
      for (const std::string& w : sel->warnings) warning(w);
      // The clamped annuli of TopFace/BottomFace (issue #29): face, radius, axis.
      nlohmann::json annuli = nlohmann::json::array();
      for (const Annulus& a : sel->annuli)
        annuli.push_back({{"face", a.face}, {"radius", a.radius},
                          {"axis", {{"point", vec_json(a.axis_point)}, {"direction", vec_json(a.axis)}}}});
      if (o.step == "all") {
        jp["steps"][step] = {{"assembly_feature_faces", sel->faces}, {"assembly_feature_annuli", annuli},
                             {"semantics_warnings", sel->warnings}};
      } else {
        jp["assembly_feature_faces"] = sel->faces;
        jp["assembly_feature_annuli"] = annuli;
        jp["semantics_warnings"] = sel->warnings;
      }
      if (!o.dot.empty() && o.step != "all") dot_parts.back().assembly_faces = sel->faces;
      if (o.views.any())
        for (std::uint32_t face : sel->faces) {
          if (face >= face_label.size()) face_label.resize(face + 1, view::kNoLabel);
          face_label[face] = 0;
        }
      const std::string faces = fmt::format("{}", fmt::join(sel->faces, ","));
      std::printf("  step %s: %zu assembly-feature faces [%s]", step.c_str(), sel->faces.size(), faces.c_str());
      if (!sel->annuli.empty()) {
        std::string an;
        for (const Annulus& a : sel->annuli) an += fmt::format("{}{} r {:g}", an.empty() ? "" : ", ", a.face, a.radius);
        std::printf(" and %zu clamped annuli [%s]", sel->annuli.size(), an.c_str());
      }
      std::printf("\n");
    }
    if (o.aag) {
      nlohmann::json nodes = nlohmann::json::array(), arcs = nlohmann::json::array();
      for (const AagNode& n : part.aag.nodes) {
        nlohmann::json jn{{"face", n.face}, {"type", surface_type_name(n.type)}, {"from_bspline", n.from_bspline},
                          {"area", n.area}, {"outer_loops", n.outer_loops}, {"inner_loops", n.inner_loops},
                          {"triangles", n.triangles}};
        if (n.type == SurfaceType::plane) jn["normal"] = vec_json(n.normal);
        else if (n.type != SurfaceType::bspline && n.type != SurfaceType::other) {
          jn["axis"] = {{"point", vec_json(n.axis_point)}, {"direction", vec_json(n.axis)}};
          jn["radius"] = n.radius;
          jn["hole"] = n.hole;
          if (n.type == SurfaceType::cone) jn["half_angle"] = n.half_angle;
          if (n.type == SurfaceType::torus) jn["minor_radius"] = n.minor_radius;
        }
        nodes.push_back(jn);
      }
      for (const AagArc& a : part.aag.arcs)
        arcs.push_back({{"faces", {a.a, a.b}}, {"edge", a.edge}, {"curve", curve_type_name(a.curve)},
                        {"convexity", convexity_name(a.convexity)}, {"angle", a.angle}, {"length", a.length},
                        {"inner_loop", {a.inner_loop_a, a.inner_loop_b}}});
      jp["aag"] = {{"nodes", nodes}, {"arcs", arcs}, {"minimal_subgraphs", minimal_subgraphs(part.aag)}};
    }
    report["parts"].push_back(jp);
    if (o.views.any()) {
      std::vector<std::uint32_t> labels(part.mesh.num_triangles(), view::kNoLabel);
      for (std::size_t t = 0; t < labels.size() && t < part.face_ids.size(); ++t)
        if (part.face_ids[t] < face_label.size()) labels[t] = face_label[part.face_ids[t]];
      part_labels.push_back(std::move(labels));
    }
  }
  report["instances"] = nlohmann::json::array();
  for (const Instance& i : model->instances) {
    report["instances"].push_back(
        {{"name", i.name}, {"part", i.part}, {"path", i.path}, {"placement", i.placement.to_rows()}});
  }
  report["units"] = model->units;
  report["file_length_units"] = model->file_length_units;
  report["warnings"] = model->warnings;
  report["seconds"] = {{"recognition", recognition_seconds}, {"total", total.seconds()}};
  if (!o.dot.empty()) {
    const Status s = write_output(o.dot, aag_dot(dot_parts));
    if (!s) throw InputError(s.error());
  }
  if (!o.json.empty()) {
    const Status s = write_output(o.json, report_text(report));
    if (!s) throw InputError(s.error());
  }
  if (o.views.any()) {
    std::vector<view::LegendEntry> legend{{"assembly-feature face (step " + o.step + ")", {0.90f, 0.10f, 0.10f}}};
    if (o.step.empty()) legend[0].label = "assembly-feature face (no step given)";
    for (std::size_t i = 0; i < type_names.size(); ++i) legend.push_back({type_names[i], view::label_color(i)});
    std::vector<view::MeshLayer> layers;
    const auto layer = [&](std::uint32_t part, const std::string& name, const std::string& path, const Transform& pose) {
      view::MeshLayer l;
      l.id = "b" + std::to_string(layers.size());
      l.name = name, l.path = path, l.role = model->parts[part].name, l.pose = pose;
      l.mesh = model->parts[part].mesh;
      l.labels = part_labels[part];
      layers.push_back(std::move(l));
    };
    for (const Instance& i : model->instances) layer(i.part, i.name, i.path, i.placement);
    if (model->instances.empty())
      for (std::uint32_t p = 0; p < model->parts.size(); ++p) layer(p, model->parts[p].name, "/" + model->parts[p].name, {});
    view::Document doc = view::meshes_document("interfere features: " + std::filesystem::path(o.input).filename().string(),
                                               std::move(layers), std::move(legend));
    doc.units = model->units;
    write_views(o.views, std::move(doc));
  }
  return kClear;
}
#else
int run_features(const FeaturesCliOptions& o) {
  require_cad("`interfere features " + o.input + "`");  // (does not return here)
  return kInputError;
}
#endif

}  // namespace

void add_features_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<FeaturesCliOptions>();
  CLI::App* c = app.add_subcommand("features", "Machining features of a STEP part (AAG + feature library)");
  c->add_option("IN", o->input, "STEP file")->required()->check(CLI::ExistingFile);
  c->add_option("--json", o->json, "write the JSON report here");
  c->add_flag("--aag", o->aag, "include the attributed adjacency graph in the JSON report");
  c->add_option("--dot", o->dot,
                "write the attributed adjacency graph as Graphviz DOT (faces filled per feature, the step's "
                "assembly-feature faces in red; convex arcs solid, concave dashed, smooth dotted)");
  c->add_option("--library", o->library, "feature library JSON (default: the installed data/features/library.json)");
  c->add_option("--rules", o->rules, "assembly-semantics rules JSON (default: data/features/semantics.json)");
  c->add_option("--process", o->process, "process description JSON (steps, parts, constraint types)");
  c->add_option("--step", o->step,
                "process step whose assembly-feature faces are listed ('all': every step; JSON parts[].steps)");
  add_step_tessellation_options(*c, o->tessellation);
  add_view_options(*c, o->views);
  c->callback([o, &exit_code] { exit_code = run_features(*o); });
}

}  // namespace interfere::cli
