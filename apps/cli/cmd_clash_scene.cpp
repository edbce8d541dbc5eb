// `interfere clash` on a scene (issue #24, item 7): one input that expands to bodies, three or
// more inputs, a scene file with "bodies", or scene options (--tests, --baseline, --csv, ...).
// Builds the Scene (scene_input.cpp), the clash tests (command line, --tests file, scene file, or
// the default all-pairs test), runs the scene engine, applies the baseline and writes the report.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "cad_exec.h"
#include "heap.h"
#include "clash_options.h"
#include "interfere/view/scene_document.h"
#include "interfere/scene/report.h"
#include "scene_input.h"
#include "report_envelope.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

std::string read_text(const std::string& path, const char* flag) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(std::string(flag) + ": " + path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

scene::GroupBy parse_group_by(const std::string& s) {
  if (s == "pair") return scene::GroupBy::pair;
  if (s == "location") return scene::GroupBy::location;
  if (s == "none") return scene::GroupBy::none;
  throw InputError("--group-by: unknown grouping '" + s + "' (pair, location, none)");
}

}  // namespace

int run_scene_clash(const ClashOptions& o, const CLI::App& command, const std::vector<std::string>& clash_tests) {
  (void)fail_on(o.fail_on);
  const scene::GroupBy group_by = parse_group_by(o.group_by);
  if (!(o.clearance >= 0) || !std::isfinite(o.clearance)) throw InputError("--clearance must be a finite number >= 0");
  if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance)) throw InputError("--tolerance must be a finite number >= 0");
  if (!(o.group_distance >= 0) || !std::isfinite(o.group_distance)) throw InputError("--group-distance must be a finite number >= 0");
  for (const char* flag : {"--transform-a", "--transform-b", "--units-a", "--units-b", "--pairs", "--region-a", "--region-b",
                           "--curves", "--conservative", "--broadphase", "--regions-vtu", "--disp-a", "--disp-b",
                           "--part-a", "--part-b", "--field-a", "--field-b"})
    if (command.count(flag) > 0)
      throw InputError(std::string(flag) + " belongs to the two-part clash (A B); with a scene, give poses, units and "
                                           "selections in the scene file" +
                       (clash_tests.empty() ? std::string()
                                            : " (--test \"" + clash_tests.front() +
                                                  "\" is a clash test, which makes a scene run; the triangle tests are "
                                                  "exact, moller, gd)"));
  if (o.test != "exact") throw InputError("--test " + o.test + ": scenes use the exact triangle test only");

  // Bodies: the scene file's, then the command line's inputs.
  std::vector<scene::BodySpec> specs;
  scene::SceneSpec file_spec;
  if (!o.scene.empty()) {
    auto s = scene::read_scene_file(o.scene);
    if (!s) throw InputError(s.error());
    file_spec = std::move(*s);
    specs = file_spec.bodies;
  }
  std::vector<std::string> inputs;
  if (!o.a.file.empty()) inputs.push_back(o.a.file);
  if (!o.b.file.empty()) inputs.push_back(o.b.file);
  inputs.insert(inputs.end(), o.more.begin(), o.more.end());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    specs.push_back({.where = "input " + std::to_string(i + 1) + " (" + inputs[i] + ")", .file = inputs[i]});
  if (specs.empty()) throw InputError("clash: no input (files, or --scene with \"bodies\")");
  for (const scene::BodySpec& s : specs) require_cad_for_step_files({s.file});  // (before the first progress line)
  Progress total("clash (scene)");
  std::string units = !o.units.empty() ? o.units : !file_spec.units.empty() ? file_spec.units : "mm";
  check_units(units);

  // Tests: --test texts, then --tests FILE, else the scene file's, else one default test.
  auto selected = scene::select_clash_tests({.texts = clash_tests, .tests_file = o.tests_file, .scene_tests = file_spec.tests,
                                             .clearance = o.clearance, .tolerance = o.tolerance,
                                             .default_options_given = command.count("--clearance") + command.count("--tolerance") > 0});
  if (!selected) throw InputError(selected.error());
  const std::vector<scene::ClashTest> tests = std::move(*selected);

  // Outputs: checked before any work.
  check_output(o.json, {}, "--json");
  check_output(o.csv, {}, "--csv");
  check_output(o.frames_csv, {}, "--frames-csv");
  check_output(o.frame_pairs_csv, {}, "--frame-pairs-csv");
  std::vector<NamedPath> in_paths{{"--scene", o.scene}, {"--tests", o.tests_file}, {"--baseline", o.baseline}, {"--motion", o.motion},
                                 {"--disp", o.disp}};
  for (const scene::BodySpec& s : specs) in_paths.push_back({s.where, s.file});
  std::vector<NamedPath> out_paths{{"--json", o.json}, {"--csv", o.csv}, {"--frames-csv", o.frames_csv},
                                  {"--frame-pairs-csv", o.frame_pairs_csv}};
  for (const NamedPath& v : o.views.paths()) out_paths.push_back(v);
  check_distinct_files(in_paths, out_paths);
  std::string baseline_text;
  if (!o.baseline.empty()) baseline_text = read_text(o.baseline, "--baseline");
  set_threads(o.threads);

  std::vector<std::string> input_warnings;
  scene::LoadedScene in = load_scene(specs,
                                     {.units = units,
                                      .linear_deflection = o.tessellation.linear_deflection,
                                      .angular_deflection = o.tessellation.angular_deflection,
                                      .fem_split = o.split,
                                      .fem_linear_faces = o.linear_faces,
                                      .fem_field = o.field,
                                      .fem_disp = o.disp,
                                      .fem_scale = o.scale},
                                     input_warnings);
  const std::string motion = !o.motion.empty() ? o.motion : file_spec.motion;
  if (!motion.empty()) {
    if (!in.scene.frames.empty()) throw InputError("--motion: the inputs already carry steps (an FE model's); give one motion");
    if (const Status s = scene::read_motion(motion, in.scene); !s) throw InputError(s.error());
    in.files.push_back(motion);
  }

  {
    // The heap for large scenes (heap.h): the results of a scene grow with its instances' triangles
    // (a contact's triangles and source ids per clash), whatever the files hold: 10,000 bodies of
    // five shared part files took 1.3 s with 4 KiB page faults, against 0.7 s with huge pages.
    std::size_t instance_triangles = 0;
    for (const scene::Body& b : in.scene.bodies) instance_triangles += b.mesh->num_triangles();
    prepare_heap(32 * instance_triangles);
  }
  scene::SceneClashOptions eo;
  eo.group_by = group_by;
  eo.group_distance = o.group_distance;
  eo.nominal_fit = in.nominal_fit;
  eo.zero_clearance_fits = in.zero_clearance_fits;  // (issue #29: as assembly-clash classifies them)
  eo.reference = o.reference;
  eo.depth_maps = true;  // (the deepest node per clash and step; the maps drawn by --pvd)
  // Frames: a progress bar with rate and ETA on a terminal, a line per tenth otherwise (progress_bar.h).
  auto frame_bar = in.scene.frames.empty() ? nullptr : std::make_shared<ProgressBar>("frames", in.scene.frames.size(), "frames");
  if (frame_bar) eo.progress = [frame_bar](std::size_t done, std::size_t) { frame_bar->update(done); };
  // A static scene: the body pairs (their count comes with the first call).
  auto pair_bar = in.scene.frames.empty() ? std::make_shared<ProgressBar>("pairs", 1, "pairs") : nullptr;
  if (pair_bar) eo.pair_progress = pair_bar->callback();
  scene::SceneClashResult result;
  {
    Progress progress(fmt::format("scene clash: {} bodies, {} tests{} ({} threads)", in.scene.bodies.size(), tests.size(),
                                  in.scene.frames.empty() ? "" : fmt::format(", {} frames", in.scene.frames.size()),
                                  active_threads()));
    try {
      result = scene::clash_scene(in.scene, tests, eo);
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
    eo.progress = nullptr;
    eo.pair_progress = nullptr;
    frame_bar.reset();  // (ends the bar's line before the timing line)
    pair_bar.reset();
  }
  for (const std::string& w : result.warnings) warning(w);
  if (!o.baseline.empty())
    if (const Status s = scene::apply_baseline(result, baseline_text, o.baseline); !s) throw InputError(s.error());

  const int status = verdict_exit_status(result.verdict, fail_on(o.fail_on));
  scene::ReportContext ctx{.command = "clash", .tool_version = INTERFERE_VERSION, .inputs = in.files,
                           .threads = active_threads(), .total_seconds = total.seconds(), .exit_status = status,
                           .warnings = input_warnings};
  ctx.process_seconds = process_seconds();
  // (scene::report_json writes every command's common keys itself: no second parse of a report
  // that can be hundreds of MB)
  if (!o.json.empty()) write_or_throw(write_output(o.json, scene::report_json(in.scene, tests, result, ctx)));
  if (!o.csv.empty()) write_or_throw(write_output(o.csv, scene::clash_table_csv(in.scene, result)));
  if (!o.frames_csv.empty()) write_or_throw(write_output(o.frames_csv, scene::frames_table_csv(result)));
  if (!o.frame_pairs_csv.empty())
    write_or_throw(write_output(o.frame_pairs_csv, scene::frame_pairs_table_csv(in.scene, tests, result)));
  if (o.views.any()) {
    view::Document doc = view::scene_document(in.scene, tests, result, {});
    doc.units = units;
    write_views(o.views, std::move(doc));
  }

  std::string verdict = verdict_name(result.verdict);
  if (result.verdict == Verdict::clash || result.verdict == Verdict::undecided)
    for (char& ch : verdict) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  std::FILE* out = is_standard_output(o.json) || is_standard_output(o.csv) || is_standard_output(o.frames_csv) ||
                       is_standard_output(o.frame_pairs_csv) ? stderr : stdout;
  std::fprintf(out, "%s: %zu bodies, %zu candidate pairs: %zu clashes, %zu contacts, %zu clearance, %zu undecided",
               verdict.c_str(), result.bodies, result.candidate_pairs, result.clash_count, result.contact_count,
               result.clearance_count, result.undecided_count);
  if (result.suppressed) std::fprintf(out, ", %zu pairs suppressed", result.suppressed);
  if (!o.baseline.empty()) {
    std::size_t fresh = 0;
    for (const scene::SceneClash& c : result.clashes) fresh += c.status == scene::ClashStatus::new_;
    std::fprintf(out, "; %zu new, %zu resolved", fresh, result.resolved.size());
  }
  if (!result.frames.empty()) std::fprintf(out, "; %zu frames", result.frames.size());
  if (result.reference_checked)
    std::fprintf(out, "; against the undeformed model: %zu designed contacts, %zu new contacts, %zu new penetrations",
                 result.designed_contact_count, result.new_contact_count, result.new_penetration_count);
  std::fprintf(out, "\n");
  return status;
}

}  // namespace interfere::cli
