// `interfere assembly-clash ASSEMBLY.step`: every pair of instances of a STEP assembly checked for
// interference, as a CAD package's clash module checks a product (cad/assembly_clash.h: the exact
// clash of paper 1 on each pair whose boxes meet). Each meeting pair is a clash (crossing surfaces,
// containment, or touching faces of overlapping solids), a contact (touching only) or, with
// --clearance, a pair closer than the clearance. Exit status 1 when some pair clashes.
#include <CLI/CLI.hpp>
#include <filesystem>

#include <algorithm>
#include <cstdio>

#include "view_output.h"
#include "commands.h"
#include "cad_exec.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/mesh/polyline.h"
#include "interfere/simplify/tagged_io.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/model.h"
#include "report_envelope.h"
#include "progress_bar.h"
#endif

namespace interfere::cli {
namespace {

struct AssemblyClashCliOptions {
  std::string input, json, regions;
  std::vector<std::string> curves;
  double clearance = 0;
  StepTessellation tessellation;
  std::size_t depth_bound_splits = 5000;
  int threads = 0;
  std::string fail_on;
  ViewOutputs views;  ///< --html, --glb, --pvd (issue #25)
};

#ifdef INTERFERE_HAS_CAD
// --regions: the clash-region triangles of every clashing pair, each instance's once, in world
// coordinates, tagged with the instance's index (face id: PLY face_id, OBJ groups, STL attribute
// word); --curves: every clashing pair's intersection curves. Nothing to write (no clash): a note.
void write_clash_geometry(const AssemblyClashCliOptions& o, const cad::CadModel& model,
                          const cad::AssemblyClashResult& r) {
  if (o.regions.empty() && o.curves.empty()) return;
  std::vector<std::vector<std::uint32_t>> tris(model.instances.size());
  std::vector<Polyline> curves;
  for (const cad::InstancePairResult& p : r.pairs) {
    tris[p.a].insert(tris[p.a].end(), p.region_triangles_a.begin(), p.region_triangles_a.end());
    tris[p.b].insert(tris[p.b].end(), p.region_triangles_b.begin(), p.region_triangles_b.end());
    curves.insert(curves.end(), p.curves.begin(), p.curves.end());
  }
  if (!o.regions.empty()) {
    TriMesh all;
    std::vector<std::uint32_t> instance_of;
    for (std::uint32_t i = 0; i < tris.size(); ++i) {
      std::sort(tris[i].begin(), tris[i].end());
      tris[i].erase(std::unique(tris[i].begin(), tris[i].end()), tris[i].end());
      if (tris[i].empty()) continue;
      const cad::Instance& in = model.instances[i];
      const TriMesh m = transformed(submesh(model.parts[in.part].mesh, tris[i]), in.placement);
      const auto base = static_cast<std::uint32_t>(all.positions.size());
      all.positions.insert(all.positions.end(), m.positions.begin(), m.positions.end());
      for (const Tri& t : m.triangles) all.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      instance_of.insert(instance_of.end(), m.num_triangles(), i);
    }
    if (all.triangles.empty()) {
      std::fprintf(stderr, "[interfere] note: no pair clashes; %s not written\n", o.regions.c_str());
    } else {
      const Status s = write_tagged_mesh(o.regions, all, instance_of, {});
      if (!s) throw InputError(s.error());
    }
  }
  for (const std::string& c : o.curves) {
    if (curves.empty()) {
      std::fprintf(stderr, "[interfere] note: no pair clashes with crossing surfaces; %s not written\n", c.c_str());
      continue;
    }
    const Status s = write_polylines(c, curves);
    if (!s) throw InputError(s.error());
  }
}

// The viewer's document (issue #25): every instance placed (each part's mesh stored once), one row
// per pair that is not clear with its regions (world) and curves.
view::Document assembly_document(const AssemblyClashCliOptions& o, const cad::CadModel& model,
                                 const cad::AssemblyClashResult& r) {
  view::Document doc;
  doc.title = "interfere assembly-clash: " + std::filesystem::path(o.input).filename().string();
  doc.units = model.units;
  doc.verdict = verdict_name(r.verdict);
  for (const cad::Part& p : model.parts) {
    view::ViewMesh m;
    m.mesh = p.mesh;
    m.source_triangles = p.mesh.num_triangles();
    doc.meshes.push_back(std::move(m));
  }
  for (std::size_t i = 0; i < model.instances.size(); ++i) {
    const cad::Instance& in = model.instances[i];
    view::ViewBody b;
    b.id = "i" + std::to_string(i), b.name = in.name, b.path = in.path, b.role = model.parts[in.part].name;
    b.mesh = in.part, b.pose = in.placement;
    doc.bodies.push_back(std::move(b));
  }
  for (const cad::InstancePairResult& p : r.pairs) {
    view::ViewClash c;
    c.verdict = cad::instance_meeting_name(p.meeting);
    c.kind = p.nominal_fit ? "nominal fit" : p.zero_clearance_fit ? "zero-clearance fit" : containment_name(p.containment);
    c.body_a = p.a, c.body_b = p.b;
    c.id = "I" + std::to_string(p.a) + "_" + std::to_string(p.b);
    if (p.cross_pairs > 0) c.depth = p.depth;
    if (p.depth_bound > 0) c.depth_bound = p.depth_bound;
    if (p.clearance_pairs > 0) c.distance = p.min_clearance;
    TriMesh region;
    const auto add = [&](std::uint32_t inst, const std::vector<std::uint32_t>& tris) {
      if (tris.empty()) return;
      const cad::Instance& in = model.instances[inst];
      const TriMesh m = transformed(submesh(model.parts[in.part].mesh, tris), in.placement);
      const auto base = static_cast<std::uint32_t>(region.positions.size());
      region.positions.insert(region.positions.end(), m.positions.begin(), m.positions.end());
      for (const Tri& t : m.triangles) region.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    };
    add(p.a, p.region_triangles_a);
    add(p.b, p.region_triangles_b);
    Aabb box;
    for (const Polyline& curve : p.curves) {
      c.curves.push_back(curve.points);
      if (curve.closed && !curve.points.empty()) c.curves.back().push_back(curve.points.front());
      for (const Vec3& q : curve.points) box.expand(q);
    }
    if (box.empty()) box = region.bounds();
    if (box.empty()) {  // no geometry kept: the two instances' boxes' overlap
      const Aabb ba = transformed(model.parts[model.instances[p.a].part].mesh, model.instances[p.a].placement).bounds();
      const Aabb bb = transformed(model.parts[model.instances[p.b].part].mesh, model.instances[p.b].placement).bounds();
      box.expand(ba.center()), box.expand(bb.center());
    }
    c.box_min = box.lo, c.box_max = box.hi;
    c.point = !p.curves.empty() && !p.curves[0].points.empty() ? p.curves[0].points[0] : box.center();
    if (!region.triangles.empty()) {
      view::ViewMesh m;
      m.source_triangles = region.num_triangles();
      m.mesh = std::move(region);
      doc.meshes.push_back(std::move(m));
      c.region_mesh = static_cast<std::int64_t>(doc.meshes.size() - 1);
    }
    for (const std::string& why : p.verdict_reasons) c.note += (c.note.empty() ? "" : "; ") + why;
    doc.clashes.push_back(std::move(c));
  }
  return doc;
}

int run_assembly_clash(const AssemblyClashCliOptions& o) {
  if (!is_step_file(o.input)) throw InputError(o.input + ": assembly-clash takes a STEP file (.step, .stp)");
  const FailOn failing = fail_on(o.fail_on);
  if (!(o.clearance >= 0 && std::isfinite(o.clearance)))
    throw InputError("--clearance must be a distance >= 0 (mm), not " + short_number(o.clearance));
  check_output(o.json, {}, "--json");
  check_output(o.regions, {".stl", ".ply", ".obj", ".off"}, "--regions");
  for (const std::string& c : o.curves) check_output(c, {".obj", ".vtk"}, "--curves");
  std::vector<NamedPath> outputs{{"--json", o.json}, {"--regions", o.regions}};
  for (const std::string& c : o.curves) outputs.push_back({"--curves", c});
  check_view_outputs(o.views);
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"IN", o.input}}, outputs);
  set_threads(o.threads);
  Progress total("assembly-clash");
  Expected<cad::CadModel> model = Error{};
  {
    Progress progress("importing " + o.input);
    model = cad::import_step(o.input, {.linear_deflection = o.tessellation.linear_deflection,
                                       .angular_deflection = o.tessellation.angular_deflection,
                                       .measure_deviation = true});  // (tessellation_error)
    if (!model) throw InputError(model.error());
  }
  for (const std::string& w : model->warnings) warning(w);
  cad::AssemblyClashResult r;
  {
    Progress progress("clashing the pairs of " + std::to_string(model->instances.size()) + " instances");
    ProgressBar bar("pairs", 1, "pairs");  // (the count comes with the first call; progress_bar.h)
    r = cad::assembly_clash(*model, {.clearance = o.clearance,
                                     .geometry = !o.regions.empty() || !o.curves.empty() || o.views.any(),
                                     .depth_bound_splits = o.depth_bound_splits,
                                     .progress = bar.callback()});
  }
  write_clash_geometry(o, *model, r);
  for (const std::string& w : r.warnings) warning(w);
  const auto name = [&](std::uint32_t i) { return model->instances[i].name; };
  // Pairs print by full instance path (issue #29, item 5: six different bolt x bracket pairs all
  // read "bolt_1 x l-bracket_1"); the name where a model has no paths.
  const auto path = [&](std::uint32_t i) {
    return model->instances[i].path.empty() ? model->instances[i].name : model->instances[i].path;
  };
  nlohmann::json pairs = nlohmann::json::array();
  std::size_t shallow = 0;  // clashes by crossing surfaces no deeper than the tessellation error
  for (const cad::InstancePairResult& p : r.pairs) {
    const bool inside = p.containment == Containment::a_inside_b || p.containment == Containment::b_inside_a;
    shallow += p.meeting == cad::InstanceMeeting::clash && p.cross_pairs > 0 && !inside && !p.touching_overlap &&
               p.depth <= p.tessellation_error;
    pairs.push_back({{"a", p.a}, {"b", p.b}, {"a_name", name(p.a)}, {"b_name", name(p.b)},
                     {"a_path", path(p.a)}, {"b_path", path(p.b)},
                     {"meeting", cad::instance_meeting_name(p.meeting)}, {"cross_pairs", p.cross_pairs},
                     {"touch_pairs", p.touch_pairs}, {"touching_overlap", p.touching_overlap},
                     {"containment", containment_name(p.containment)}, {"regions", p.regions},
                     {"curve_length", p.curve_length}, {"clearance_pairs", p.clearance_pairs},
                     {"min_clearance", p.clearance_pairs > 0 ? nlohmann::json(p.min_clearance) : nlohmann::json(nullptr)},
                     {"depth", p.cross_pairs > 0 ? nlohmann::json(p.depth) : nlohmann::json(nullptr)},
                     {"depth_bound", p.depth_bound > 0 ? nlohmann::json(p.depth_bound) : nlohmann::json(nullptr)},
                     {"tessellation_error", p.tessellation_error}, {"nominal_fit", p.nominal_fit},
                     {"zero_clearance_fit", p.zero_clearance_fit},
                     {"verdict", cad::instance_meeting_name(p.meeting)}, {"verdict_reasons", p.verdict_reasons}});
    std::string what = std::to_string(p.cross_pairs) + " crossing, " + std::to_string(p.touch_pairs) + " touching pairs";
    if (p.containment == Containment::a_inside_b || p.containment == Containment::b_inside_a)
      what = std::string(containment_name(p.containment));
    if (p.touching_overlap) what += ", the solids overlap behind touching faces";
    if (p.nominal_fit)
      what += ", a nominal fit: the crossings lie on coincident B-Rep faces (depth " + short_number(p.depth) +
              " mm, tessellation error " + short_number(p.tessellation_error) + " mm)";
    else if (p.cross_pairs > 0)
      what += ", depth " + short_number(p.depth) + " mm" +
              (p.depth_bound > 0 ? ", at most " + short_number(p.depth_bound) + " mm" : std::string()) +
              " (tessellation error " + short_number(p.tessellation_error) + " mm" +
              (p.depth <= p.tessellation_error ? ": a nominal fit?)" : ")");
    if (p.meeting == cad::InstanceMeeting::clearance) what = "closest " + short_number(p.min_clearance) + " mm";
    if (p.zero_clearance_fit)  // (issue #29: classified from the B-Rep, whatever the tessellation)
      what += ", a zero-clearance fit: coincident B-Rep faces, their tessellations " + short_number(p.min_clearance) +
              " mm apart";
    for (const std::string& why : p.verdict_reasons) what += "; undecided: " + why;
    std::printf("%-9s %s x %s: %s\n", cad::instance_meeting_name(p.meeting), path(p.a).c_str(), path(p.b).c_str(),
                what.c_str());
  }
  nlohmann::json instances = nlohmann::json::array();
  for (const cad::Instance& i : model->instances)
    instances.push_back({{"name", i.name}, {"part", model->parts[i.part].name}, {"path", i.path},
                         {"triangles", model->parts[i.part].mesh.num_triangles()}, {"placement", i.placement.to_rows()}});
  std::printf("%zu instances, %zu candidate pairs: %zu clashes (%zu no deeper than the tessellation error), %zu contacts, "
              "%zu within the clearance, %zu undecided: verdict %s\n",
              model->instances.size(), r.candidate_pairs, r.clashes, shallow, r.contacts, r.within_clearance,
              r.undecided, verdict_name(r.verdict));
  const int status = verdict_exit_status(r.verdict, failing);
  if (!o.json.empty()) {
    std::vector<std::string> warnings = model->warnings;
    warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
    const nlohmann::json j = {{"command", "assembly-clash"}, {"version", INTERFERE_VERSION}, {"input", o.input},
                              {"units", model->units}, {"clearance", o.clearance}, {"instances", instances},
                              {"candidate_pairs", r.candidate_pairs}, {"clashes", r.clashes},
                              {"clashes_within_tessellation_error", shallow}, {"contacts", r.contacts},
                              {"within_clearance", r.within_clearance}, {"undecided", r.undecided},
                              {"verdict", verdict_name(r.verdict)}, {"exit_status", status}, {"pairs", pairs},
                              {"warnings", warnings}, {"seconds", total.seconds()}};
    const Status s = write_output(o.json, report_text(j));
    if (!s) throw InputError(s.error());
  }
  if (o.views.any()) write_views(o.views, assembly_document(o, *model, r));
  return status;
}
#else
int run_assembly_clash(const AssemblyClashCliOptions& o) {
  require_cad("`interfere assembly-clash " + o.input + "`");  // (does not return here)
  return kInputError;
}
#endif

}  // namespace

void add_assembly_clash_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AssemblyClashCliOptions>();
  CLI::App* c = app.add_subcommand("assembly-clash",
                                   "Every pair of instances of a STEP assembly: clashes, contacts, pairs within a clearance");
  c->add_option("IN", o->input, "STEP assembly (or part)")->required()->check(CLI::ExistingFile);
  c->add_option("--clearance", o->clearance, "also list pairs of instances closer than this (mm)");
  c->add_option("--json", o->json, "write the JSON report here");
  c->add_option("--regions", o->regions,
                "write the clash-region triangles of every clashing pair, in world coordinates, each tagged with its "
                "instance's index (.ply/.obj/.stl face ids; .off untagged)");
  c->add_option("--curves", o->curves, "write the clashing pairs' intersection curves (.obj polylines or .vtk); repeatable")
      ->allow_extra_args(false);
  c->add_option("--depth-bound-splits", o->depth_bound_splits,
                "splits per clashing pair for the upper bound of its depth (default 5000; more: tighter and slower; "
                "0: none)");
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  add_fail_on_option(*c, o->fail_on);
  add_step_tessellation_options(*c, o->tessellation);
  add_view_options(*c, o->views);
  c->callback([o, &exit_code] { exit_code = run_assembly_clash(*o); });
}

}  // namespace interfere::cli
