// STEP -> AAG -> features -> assembly features of a process step -> mesh with face ids (issue #6):
// the glue of `interfere simplify` (STEP input) and `interfere features`.
#include "interfere/cad/pipeline.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>

#include "interfere/cad/mates.h"

namespace interfere::cad {
namespace {
constexpr std::uint32_t kNoPart = 0xffffffffu;
}  // namespace

bool instance_in_step(const Process& process, const std::string& step, const CadModel& model, std::size_t k) {
  const Instance& inst = model.instances[k];
  return step_includes(process, step, model.parts[inst.part].name) || step_includes(process, step, inst.name);
}

bool part_in_step(const Process& process, const std::string& step, const CadModel& model, std::uint32_t part) {
  if (step_includes(process, step, model.parts[part].name)) return true;
  for (std::size_t k = 0; k < model.instances.size(); ++k)
    if (model.instances[k].part == part && instance_in_step(process, step, model, k)) return true;
  return false;
}

Expected<Selection> part_step_selection(const Process& process, const std::string& step, const SemanticRules& rules,
                                        const CadModel& model, std::uint32_t part,
                                        const std::vector<Feature>& features) {
  auto sel = select_step_features(process, step, rules, model.parts[part].name, features, &model.parts[part].aag);
  if (sel && !part_in_step(process, step, model, part)) return Selection{};
  return sel;
}

std::vector<std::string> unknown_step_names(const Process& process, const std::string& step, const CadModel& model) {
  std::vector<std::string> names;
  for (const Part& part : model.parts) names.push_back(part.name);
  for (const Instance& inst : model.instances) names.push_back(inst.name);
  return unknown_step_parts(process, step, names);
}

Expected<Semantics> load_semantics(const PipelineOptions& o) {
  auto lib = o.library_file.empty() ? default_feature_library() : load_feature_library(o.library_file);
  if (!lib) return lib.error();
  Semantics sem{std::move(*lib), {}, std::nullopt};
  if (o.process_file.empty()) {
    if (o.mates) {  // the rules the inferred mates' constraints apply
      auto rules = o.rules_file.empty() ? default_semantic_rules(sem.library) : load_semantic_rules(o.rules_file, sem.library);
      if (!rules) return rules.error();
      sem.rules = std::move(*rules);
      return sem;
    }
    if (!o.rules_file.empty())
      return Error{.file = o.rules_file, .reason = "semantic rules apply to the steps of a process (or to the mates inferred "
                                                   "from an assembly): give a process too"};
    return sem;
  }
  auto rules = o.rules_file.empty() ? default_semantic_rules(sem.library)
                                    : load_semantic_rules(o.rules_file, sem.library);
  if (!rules) return rules.error();
  sem.rules = std::move(*rules);
  auto p = load_process(o.process_file);
  if (!p) return p.error();
  sem.process = std::move(*p);
  if (o.step.empty()) return Error{.file = o.process_file, .reason = "a process needs the id of its step (or 'all')"};
  std::vector<std::string> steps{o.step};
  if (o.step == "all") {
    steps.clear();
    for (const ProcessStep& s : sem.process->steps) steps.push_back(s.id);
  }
  for (const std::string& step : steps)
    if (auto s = select_step_features(*sem.process, step, sem.rules, "", {}); !s)
      return Error{.file = o.process_file, .reason = s.error().reason};
  return sem;
}

namespace {
// The parts' feature faces as world ids: each instance's part's, shifted by its face offset.
std::vector<std::uint32_t> world_feature_faces(const Prepared& prep) {
  std::vector<std::uint32_t> out;
  for (const PreparedInstance& in : prep.instances)
    for (std::uint32_t f : prep.parts[in.part].feature_faces) out.push_back(f + in.face_offset);
  return out;
}
}  // namespace

Status add_feature_faces(Prepared& prep, const std::vector<std::uint32_t>& world_ids) {
  std::vector<std::vector<std::uint32_t>> added(prep.parts.size());
  std::uint32_t faces = 0;  // the world's face count
  for (const PreparedInstance& in : prep.instances)
    faces = std::max(faces, in.face_offset + prep.parts[in.part].faces);
  for (std::uint32_t id : world_ids) {
    const auto in = std::find_if(prep.instances.begin(), prep.instances.end(), [&](const PreparedInstance& i) {
      return id >= i.face_offset && id - i.face_offset < prep.parts[i.part].faces;
    });
    if (in == prep.instances.end())
      return Error{.reason = "face id " + std::to_string(id) + " is on no part: the model's faces are 0.." +
                             std::to_string(faces == 0 ? 0 : faces - 1)};
    added[in->part].push_back(id - in->face_offset);
  }
  for (std::size_t i = 0; i < prep.parts.size(); ++i) {
    std::vector<std::uint32_t>& f = prep.parts[i].feature_faces;
    f.insert(f.end(), added[i].begin(), added[i].end());
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
  }
  prep.feature_faces = world_feature_faces(prep);
  return {};
}

namespace {

Expected<Prepared> prepare(const CadModel& imported, const PipelineOptions& o, const Semantics& sem);

}  // namespace

Expected<Prepared> prepare_for_simplify(const std::string& step_file, const PipelineOptions& o) {
  auto sem = load_semantics(o);
  if (!sem) return sem.error();
  auto imported = import_step(step_file, {.linear_deflection = o.linear_deflection,
                                          .angular_deflection = o.angular_deflection,
                                          .measure_deviation = true,
                                          .delabella = o.delabella});  // (PreparedPart::tessellation_error)
  if (!imported) return imported.error();
  return prepare(*imported, o, *sem);
}

Expected<Prepared> prepare_for_simplify(const CadModel& model, const PipelineOptions& o) {
  auto sem = load_semantics(o);
  if (!sem) return sem.error();
  return prepare(model, o, *sem);
}

namespace {

Expected<Prepared> prepare(const CadModel& imported, const PipelineOptions& o, const Semantics& sem) {
  const CadModel* model = &imported;
  const FeatureLibrary* lib = &sem.library;
  const SemanticRules* rules = &sem.rules;
  const std::optional<Process>& process = sem.process;
  Prepared out;
  out.warnings = model->warnings;
  // Which instances take part in the step: those it names, by part or by instance name ("*": all).
  std::vector<std::uint8_t> in_step(model->instances.size(), 0);
  std::vector<std::uint8_t> part_in_step(model->parts.size(), 0), part_out_of_step(model->parts.size(), 0);
  if (process)
    for (auto& w : unknown_step_names(*process, o.step, *model)) out.warnings.push_back(std::move(w));
  // Without a process: the features the mates inferred from the geometry pick (issue #29, item 4);
  // the instances in a mate take part, as in a step.
  std::optional<MateSelection> mates;
  if (!process && o.mates) mates = select_mate_features(*model, *lib, *rules);
  const std::string step_label = process ? o.step : "mates";
  for (std::size_t k = 0; k < model->instances.size(); ++k) {
    in_step[k] = process ? instance_in_step(*process, o.step, *model, k) : mates && mates->instances[k] != 0;
    (in_step[k] ? part_in_step : part_out_of_step)[model->instances[k].part] = 1;
  }
  nlohmann::json rep;
  rep["parts"] = nlohmann::json::array();
  std::vector<std::vector<std::uint32_t>> part_features(model->parts.size()), part_annulus_tris(model->parts.size());
  // Each part once per kind of its instances: with the step's features (instances in the step) and
  // without (the others), so a step that names one of six identical bolts keeps only that bolt's.
  std::vector<std::uint32_t> with_features(model->parts.size(), kNoPart), without(model->parts.size(), kNoPart);
  for (std::size_t i = 0; i < model->parts.size(); ++i) {
    const Part& part = model->parts[i];
    const double tessellation_error = part.tessellation_error();
    const auto feats = recognize_features(part.aag, *lib);
    nlohmann::json jp{{"name", part.name}, {"faces", part.faces}, {"triangles", part.mesh.num_triangles()},
                      {"features", nlohmann::json::array()}};
    for (const Feature& f : feats) jp["features"].push_back({{"type", f.type}, {"faces", f.faces}});
    if (process || mates) {
      Expected<Selection> sel = mates ? Expected<Selection>(mates->parts[i])
                                      : select_step_features(*process, o.step, *rules, part.name, feats, &part.aag);
      if (!sel) return Error{.file = o.process_file, .reason = sel.error().reason};
      if (part_in_step[i]) {
        part_features[i] = sel->faces;
        part_annulus_tris[i] = annulus_triangles(part.mesh, part.face_ids, sel->annuli);
        for (const auto& w : sel->warnings) out.warnings.push_back(w);
        for (const Annulus& a : sel->annuli)
          jp["assembly_feature_annuli"].push_back({{"face", a.face}, {"radius", a.radius},
                                                   {"axis", {{"point", {a.axis_point.x, a.axis_point.y, a.axis_point.z}},
                                                             {"direction", {a.axis.x, a.axis.y, a.axis.z}}}}});
      }
      jp["assembly_feature_faces"] = part_features[i];
      if (!jp.contains("assembly_feature_annuli")) jp["assembly_feature_annuli"] = nlohmann::json::array();
      jp["assembly_feature_annulus_triangles"] = part_annulus_tris[i].size();
    }
    rep["parts"].push_back(jp);
    const bool split = part_in_step[i] && part_out_of_step[i] && (!part_features[i].empty() || !part_annulus_tris[i].empty());
    if (part_in_step[i] || !part_out_of_step[i]) {
      with_features[i] = static_cast<std::uint32_t>(out.parts.size());
      out.parts.push_back({split ? part.name + " [" + step_label + "]" : part.name, part.mesh, part.face_ids,
                           part_features[i], part.faces, 0, static_cast<std::uint32_t>(i), tessellation_error,
                           part_annulus_tris[i], part.has_color, {part.color[0], part.color[1], part.color[2]}});
    }
    if (part_out_of_step[i] && (split || !part_in_step[i])) {
      without[i] = static_cast<std::uint32_t>(out.parts.size());
      out.parts.push_back({part.name, part.mesh, part.face_ids, {}, part.faces, 0, static_cast<std::uint32_t>(i),
                           tessellation_error, {}, part.has_color, {part.color[0], part.color[1], part.color[2]}});
    }
    if (!split && part_in_step[i]) without[i] = with_features[i];
  }
  // World mesh; feature face ids shifted like world_mesh shifts the instance's faces.
  out.mesh = world_mesh(*model, &out.face_ids);
  std::uint32_t base = 0;
  rep["instances"] = nlohmann::json::array();
  for (std::size_t k = 0; k < model->instances.size(); ++k) {
    const Instance& inst = model->instances[k];
    const std::uint32_t variant = in_step[k] ? with_features[inst.part] : without[inst.part];
    out.instances.push_back({inst.name, variant, inst.placement, base, inst.path});
    ++out.parts[variant].instances;
    rep["instances"].push_back({{"name", inst.name}, {"part", inst.part}, {"path", inst.path}, {"face_id_offset", base},
                                {"placement", inst.placement.to_rows()}, {"in_step", in_step[k] != 0},
                                {"simplified_part", variant}});
    base += model->parts[inst.part].faces;
  }
  out.feature_faces = world_feature_faces(out);
  if (!o.step.empty()) rep["step"] = o.step;
  if (mates) {
    for (const auto& w : mates->warnings) out.warnings.push_back(w);
    rep["features_from"] = "mates";
    rep["mates"] = nlohmann::json::array();
    for (const Mate& m : mates->mates)
      rep["mates"].push_back({{"kind", mate_kind_name(m.kind)}, {"a", m.instance_a}, {"b", m.instance_b},
                              {"a_path", model->instances[m.instance_a].path}, {"b_path", model->instances[m.instance_b].path},
                              {"feature_type", m.feature_type}, {"constraint", m.constraint},
                              {"faces_a", m.faces_a}, {"faces_b", m.faces_b}});
  } else {
    rep["features_from"] = process ? "process" : "none";
  }
  rep["units"] = model->units;
  rep["file_length_units"] = model->file_length_units;
  rep["warnings"] = out.warnings;
  out.report_json = rep.dump();
  return out;
}

}  // namespace
}  // namespace interfere::cad
