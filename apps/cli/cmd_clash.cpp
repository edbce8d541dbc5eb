// `interfere clash A B`: every intersecting triangle pair, regions, curves, containment, clearance.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "clash_options.h"
#include "interfere/view/scene_document.h"
#include "commands.h"
#include "common.h"
#include "fem_parts.h"
#include "interfere/core/atomic_file.h"
#include "interfere/mesh/polyline.h"
#include "interfere/query/clash.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/report.h"
#include "interfere/simplify/tagged_io.h"
#include "report_json.h"
#include "report_envelope.h"

namespace interfere::cli {
namespace {

TriTest parse_test(const std::string& s) {
  if (s == "exact") return TriTest::exact;
  if (s == "moller") return TriTest::moller;
  if (s == "gd" || s == "guigue_devillers") return TriTest::guigue_devillers;
  throw InputError("--test: unknown test '" + s + "' (exact, moller, gd)");
}

Broadphase parse_broadphase(const std::string& s) {
  if (s == "bvh") return Broadphase::bvh;
  if (s == "brute") return Broadphase::brute_force;
  if (s == "box") return Broadphase::box_pretest;
  throw InputError("--broadphase: unknown broad phase '" + s + "' (bvh, brute, box)");
}

/// The error bound stored in a simplified mesh file; 0 (exact) when it has none.
double stored_error_bound(const std::string& file, const char* part) {
  const Expected<double> e = read_error_bound(file);
  if (!e) throw InputError(e.error());
  if (*e < 0) {
    std::fprintf(stderr, "[interfere] note: part %s (%s) stores no error bound: taken as exact\n", part, file.c_str());
    return 0;
  }
  return *e;
}

/// An upper bound of how much the pose stretches distances: sqrt of the largest row sum of |R^T R|
/// (a matrix norm bounds the largest eigenvalue; 1, up to rounding, for a rotation).
double max_stretch(const std::string& transform) {
  if (transform.empty()) return 1;
  const Expected<Transform> t = Transform::parse(transform);
  if (!t) return 1;  // reported by load_parts
  double worst = 0;
  for (int i = 0; i < 3; ++i) {
    double row = 0;
    for (int j = 0; j < 3; ++j) {
      double m = 0;
      for (int k = 0; k < 3; ++k) m += t->r[k][i] * t->r[k][j];
      row += std::fabs(m);
    }
    worst = std::max(worst, row);
  }
  return std::sqrt(worst) * (1 + 1e-12);
}

// "part A" <-> "part B" in the core's messages (its A is our B when the engine ordered them by id).
std::string swap_part_names(std::string t) {
  for (std::size_t i = 0; (i = t.find("part ", i)) != std::string::npos; i += 6)
    if (i + 5 < t.size() && (t[i + 5] == 'A' || t[i + 5] == 'B')) t[i + 5] = t[i + 5] == 'A' ? 'B' : 'A';
  return t;
}

bool is_triangle_test(const std::string& s) {
  return s == "exact" || s == "moller" || s == "gd" || s == "guigue_devillers";
}

// A scene file with "bodies" (not the two-part {"a", "b"} form).
bool scene_file_has_bodies(const std::string& path) {
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto j = nlohmann::json::parse(text, nullptr, false);
  return !j.is_discarded() && j.is_object() && !j.contains("a") && !j.contains("b");
}

int run_clash(ClashOptions o, const CLI::App& command) {
  // --test: the triangle test's names as before, anything else a clash test (issue #24).
  std::vector<std::string> clash_tests;
  for (const std::string& t : o.test_args) {
    if (is_triangle_test(t)) {
      o.test = t;
    } else {
      clash_tests.push_back(t);
    }
  }
  // A scene: one input (a file that expands to bodies), three or more, a scene file with bodies,
  // or any scene option. Two inputs alone are the two-part clash with its per-pair outputs.
  const bool scene = (!o.a.file.empty() && o.b.file.empty()) || !o.more.empty() || !clash_tests.empty() ||
                     !o.tests_file.empty() || !o.baseline.empty() || !o.csv.empty() || !o.frames_csv.empty() || !o.frame_pairs_csv.empty() ||
                     !o.motion.empty() || command.count("--group-by") > 0 || command.count("--tolerance") > 0 ||
                     (!o.scene.empty() && scene_file_has_bodies(o.scene)) ||
                     (o.scene.empty() && o.a.file.empty());
  check_view_outputs(o.views);
  if (scene) return run_scene_clash(o, command, clash_tests);
  ResolvedParts parts = resolve_two_parts(o, command);
  (void)fail_on(o.fail_on);  // checked before any work
  parts.tessellation.measure_deviation = o.conservative;  // (STEP inputs: the bound below)
  if (!(o.clearance >= 0) || !std::isfinite(o.clearance)) throw InputError("--clearance must be a finite number >= 0");
  // --conservative (issue #6, item 6): two touching originals have points of their simplified
  // versions within the sum of the bounds, so a pair closer than that is a possible clash.
  double bound_a = 0, bound_b = 0;
  if (o.conservative) {
    if (o.fem_requested() || is_fem_file(parts.a.file) || is_fem_file(parts.b.file))
      throw InputError("--conservative takes simplified mesh files (interfere simplify outputs) or STEP files, not FEM input");
    // Bounds in the files' coordinates; a pose that scales stretches them. A STEP input's bound is
    // its tessellation's linear deflection, known once it is read (below).
    if (!is_step_file(parts.a.file)) bound_a = stored_error_bound(parts.a.file, "A") * max_stretch(parts.a.transform);
    if (!is_step_file(parts.b.file)) bound_b = stored_error_bound(parts.b.file, "B") * max_stretch(parts.b.transform);
  }
  ClashRequest request{.test = parse_test(o.test),
                       .broadphase = parse_broadphase(o.broadphase),
                       .parallel = true,
                       .clearance = o.clearance,
                       .regions = true,
                       .containment = !o.no_containment};
  const std::vector<std::string> mesh_ext{".stl", ".ply", ".obj", ".off"};
  check_output(o.json, {}, "--json");
  check_output(o.pairs, {}, "--pairs");
  check_output(o.region_a, mesh_ext, "--region-a");
  check_output(o.region_b, mesh_ext, "--region-b");
  for (const std::string& c : o.curves) check_output(c, {".obj", ".vtk"}, "--curves");
  std::vector<NamedPath> outputs{{"--json", o.json}, {"--pairs", o.pairs}, {"--region-a", o.region_a},
                                 {"--region-b", o.region_b}, {"--regions-vtu", o.regions_vtu}};
  for (const std::string& c : o.curves) outputs.push_back({"--curves", c});
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"A", parts.a.file}, {"B", parts.b.file}, {"--scene", o.scene}}, outputs);
  if (o.fem_requested() || is_fem_file(parts.a.file) || is_fem_file(parts.b.file)) {
    return run_fem_clash(o, parts, request);  // FEM inputs: clash_fem.cpp
  }
  set_threads(o.threads);

  Progress total("clash");
  // Models without statistics (issue #24, item 8): the engine computes a body's statistics only
  // where the query needs its closedness (containment, touching overlap, depth); the report's
  // statistics follow the same rule below.
  LoadedParts loaded = load_parts(parts, false);
  const LoadedPart& pa = loaded.a;
  const LoadedPart& pb = loaded.b;
  if (o.conservative) {
    // A STEP part's bound: BRepMesh's chordal tolerance, or the deviation measured after it where
    // larger (BRepMesh may exceed its tolerance: sampled, not a proven bound; README); already in
    // the working unit. A mesh file's stored bound is in its file's unit: scaled like the part.
    const auto step_bound = [](const LoadedPart& p) { return std::max(p.linear_deflection, p.tessellation_deviation); };
    if (is_step_file(parts.a.file)) bound_a = step_bound(pa) * max_stretch(parts.a.transform);
    else bound_a *= pa.scale;
    if (is_step_file(parts.b.file)) bound_b = step_bound(pb) * max_stretch(parts.b.transform);
    else bound_b *= pb.scale;
  }
  const double margin = bound_a + bound_b;
  request.clearance = o.clearance + margin;
  // The two-part case of the scene engine (issue #24, item 7): two bodies on the models just
  // built, one test; the core's own result comes back through on_pair for the per-pair outputs.
  scene::Scene two;
  two.units = parts.units;
  for (const auto* p : {&pa, &pb}) {
    scene::Body b;
    b.id = scene::make_body_id(std::filesystem::path(p->file).stem().string());
    b.name = std::filesystem::path(p->file).filename().string();
    b.path = "/" + b.name;
    b.source = {scene::SourceKind::mesh_file, p->file, ""};
    b.unit = p->unit.unit;
    b.mesh = std::shared_ptr<const TriMesh>(std::shared_ptr<void>{}, &p->model.mesh);  // (not owned)
    b.world_model = std::shared_ptr<const Model>(std::shared_ptr<void>{}, &p->model);
    b.tessellation_error = p->format == "step" ? std::max(p->linear_deflection, p->tessellation_deviation) : 0;
    two.bodies.push_back(std::move(b));
  }
  if (two.bodies[0].id == two.bodies[1].id) two.bodies[0].id += "#A", two.bodies[1].id += "#B";
  scene::ClashTest test;
  if (request.clearance > 0) test.mode = scene::ClashMode::clearance, test.clearance = request.clearance;
  scene::SceneClashOptions engine{.request = request, .depth = o.depth};
  ClashResult result;
  result.containment = request.containment ? Containment::none : Containment::not_checked;
  bool core_ran = false;  // the bodies' boxes overlap: the exact core decided the pair
  engine.on_pair = [&](std::size_t, std::uint32_t x, std::uint32_t, const ClashResult& r) {
    result = r;
    core_ran = true;
    if (x == 1) {  // B's id sorts first: the engine's pair is (B, A); the outputs speak of A and B
      for (TrianglePair& p : result.pairs) std::swap(p.a, p.b);
      std::sort(result.pairs.begin(), result.pairs.end(), [](const TrianglePair& u, const TrianglePair& v) {
        return std::tie(u.a, u.b) < std::tie(v.a, v.b);
      });
      for (ClashRegion& g : result.regions) std::swap(g.triangles_a, g.triangles_b);
      std::sort(result.regions.begin(), result.regions.end(), [](const ClashRegion& u, const ClashRegion& v) {
        return std::tie(u.triangles_a.front(), u.triangles_b.front()) < std::tie(v.triangles_a.front(), v.triangles_b.front());
      });
      for (ClearancePair& c : result.clearance) std::swap(c.a, c.b), std::swap(c.point_a, c.point_b);
      std::sort(result.clearance.begin(), result.clearance.end(), [](const ClearancePair& u, const ClearancePair& v) {
        return std::tie(u.a, u.b) < std::tie(v.a, v.b);
      });
      for (auto* texts : {&result.warnings, &result.verdict_reasons})
        for (std::string& t : *texts) t = swap_part_names(t);
      if (result.containment == Containment::a_inside_b) result.containment = Containment::b_inside_a;
      else if (result.containment == Containment::b_inside_a) result.containment = Containment::a_inside_b;
    }
  };
  scene::SceneClashResult scene_result;
  double query_seconds = 0;
  {
    Progress progress("clash query (" + std::to_string(active_threads()) + " threads)");
    scene_result = scene::clash_scene(two, {test}, engine);
    query_seconds = progress.seconds();
  }
  {
    // The parts' statistics (and their input warnings) where the verdict depended on closedness:
    // no crossing pair (containment or touching overlap decided it), or --depth of crossing parts.
    const bool needed = core_ran && ((request.containment && result.cross_pairs == 0) || (o.depth && result.cross_pairs > 0));
    if (needed) add_statistics(loaded, true, true);
  }
  for (const std::string& w : result.warnings) warning(w);

  // Outputs (each written atomically; inputs were fully validated above).
  if (!o.pairs.empty()) {
    std::string s;
    s.reserve(result.pairs.size() * 24);
    for (const TrianglePair& p : result.pairs) s += fmt::format("{} {} {}\n", p.a, p.b, kind_name(p.kind));
    write_or_throw(write_output(o.pairs, s));
  }
  auto region_tris = [&](bool part_a) {
    std::vector<std::uint32_t> t;
    for (const ClashRegion& g : result.regions) {
      const auto& v = part_a ? g.triangles_a : g.triangles_b;
      t.insert(t.end(), v.begin(), v.end());
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  // A part without clash region has no mesh to write (mesh formats need a triangle): say so instead.
  auto write_region = [&](const std::string& path, const TriMesh& mesh, bool part_a) {
    if (path.empty()) return;
    const std::vector<std::uint32_t> tris = region_tris(part_a);
    if (tris.empty()) {
      std::fprintf(stderr, "[interfere] note: part %s has no clash region; %s not written\n", part_a ? "A" : "B",
                   path.c_str());
      return;
    }
    write_or_throw(write_mesh(path, submesh(mesh, tris)));
  };
  write_region(o.region_a, pa.model.mesh, true);
  write_region(o.region_b, pb.model.mesh, false);
  if (!o.curves.empty()) {
    std::vector<Polyline> all;
    for (const ClashRegion& g : result.regions) all.insert(all.end(), g.curves.begin(), g.curves.end());
    for (const std::string& c : o.curves) write_or_throw(write_polylines(c, all));
  }
  std::size_t within_margin = 0;
  for (const ClearancePair& c : result.clearance) within_margin += c.distance < margin ? 1 : 0;
  const bool possible = result.interference() || within_margin > 0;
  if (o.conservative && possible && result.verdict != Verdict::clash) {
    // The simplified parts touch or come within their error bounds: the originals may clash or
    // not; neither is proved (issue #23, item 13: never a silent clear, never a clash not seen).
    result.verdict = Verdict::undecided;
    result.verdict_reasons.push_back(fmt::format(
        "{} triangle pairs meet or lie within the error bounds ({:g}): the original parts may clash",
        result.pairs.size() + within_margin, margin));
  }
  const int status = verdict_exit_status(result.verdict, fail_on(o.fail_on));
  if (!o.json.empty()) {
    // One schema for every clash (issue #24, item 7): the scene report of the two bodies, with the
    // two-part details (inputs, options, the core's result) beside it.
    scene::ReportContext ctx{.command = "clash", .tool_version = INTERFERE_VERSION, .inputs = {pa.file, pb.file},
                             .threads = active_threads(), .total_seconds = total.seconds(), .exit_status = status};
    nlohmann::json j = nlohmann::json::parse(scene::report_json(two, {test}, scene_result, ctx));
    j.update(two_part_report("clash", parts.units, loaded, query_seconds, total.seconds()));
    j["options"] = {{"test", o.test}, {"broadphase", o.broadphase}, {"builder", o.builder},
                    {"threads", active_threads()}, {"clearance", o.clearance}, {"containment", !o.no_containment},
                    {"conservative", o.conservative}, {"depth", o.depth}};
    j["result"] = clash_result_json(result, o.max_clearance_pairs);
    if (o.conservative)
      j["conservative"] = {{"error_bound_a", bound_a}, {"error_bound_b", bound_b}, {"margin", margin},
                           {"clearance", o.clearance + margin}, {"pairs_within_margin", within_margin},
                           {"possible_clash", possible}};
    j["verdict"] = verdict_name(result.verdict);
    j["warnings"] = result.warnings;
    j["exit_status"] = status;
    write_or_throw(write_output(o.json, report_text(j)));
  }

  if (o.views.any()) {
    view::Document doc = view::scene_document(two, {test}, scene_result, {});
    doc.verdict = verdict_name(result.verdict);
    doc.units = parts.units;
    write_views(o.views, std::move(doc));
  }

  print_clash_summary(result, parts.units);
  if (o.clearance + margin > 0)
    std::printf(", %zu pairs closer than %g", result.clearance.size(), o.clearance + margin);
  if (o.conservative)
    std::printf("; conservative (error bounds %g + %g): %s", bound_a, bound_b,
                possible ? "possible clash of the original parts" : "the original parts do not clash");
  std::printf("\n");
  return status;
}

}  // namespace

void add_clash_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ClashOptions>();
  CLI::App* c = app.add_subcommand(
      "clash",
      "Clash of a scene of many bodies (one input that expands to bodies, three or more inputs, --scene with "
      "\"bodies\", or --test/--tests/--baseline/--csv/--motion: clash tests, stable clash ids, status between "
      "runs; docs/scene.md), or of two parts A B (every intersecting triangle pair, clash regions with "
      "intersection curves, containment, clearance). Exit status: 0 clear/contact/clearance, 1 clash, 2 input "
      "error, 3 undecided");
  add_two_part_options(*c, *o);
  c->add_option("--pairs", o->pairs, "write 'i j kind' per intersecting pair, sorted");
  c->add_option("--region-a", o->region_a, "write A's clash-region triangles (.stl/.ply/.obj/.off)");
  c->add_option("--region-b", o->region_b, "write B's clash-region triangles (.stl/.ply/.obj/.off)");
  c->add_option("--curves", o->curves, "write intersection curves (.obj polylines or .vtk polydata); repeatable")
      ->allow_extra_args(false);  // one file per --curves, so positionals may follow
  c->add_option("--clearance", o->clearance, "also report non-intersecting pairs closer than this distance");
  c->add_option("MORE", o->more, "further inputs: with one input, or three or more, every input expands to its bodies "
                                 "(a STEP assembly's instances, an FE model's bodies, a glTF scene's nodes) and all are "
                                 "checked as one scene");
  c->add_option("--test", o->test_args,
                "a clash test, repeatable: \"[NAME:] SEL_A [vs SEL_B] [hard|clearance D|duplicates] [tolerance T]\" "
                "(selectors id:, name:, path:, tag:, file:, source: with globs; docs/scene.md); the names exact, moller, "
                "gd select the triangle test of the two-part clash instead")
      ->allow_extra_args(false);
  c->add_option("--tests", o->tests_file, "JSON file of clash tests ({\"tests\": [...]}, as in a scene file)");
  c->add_option("--baseline", o->baseline,
                "an earlier report: clashes are marked new/active, baseline clashes gone are listed once as resolved, "
                "and the user's fields (status approved, assignee, comment) are carried by clash id");
  c->add_option("--csv", o->csv, "write the clash table as CSV");
  c->add_option("--frames-csv", o->frames_csv, "write the frames table (motion, FE steps) as CSV");
  c->add_option("--frame-pairs-csv", o->frame_pairs_csv,
                "write the table frames x body pairs (motion, FE steps: each pair's verdict, contacts, "
                "min distance and max depth per frame) as CSV");
  c->add_flag("!--no-reference", o->reference,
              "FE steps: do not check the undeformed model first (without it, contacts are not told apart "
              "as designed, i.e. touching before the load, or new)");
  c->add_option("--group-by", o->group_by, "group clashes by pair (default), location or none");
  c->add_option("--group-distance", o->group_distance, "--group-by location: clashes closer than this join one group");
  c->add_option("--motion", o->motion, "motion file (CSV or JSON): per-frame body poses (docs/scene.md)");
  c->add_option("--tolerance", o->tolerance,
                "scene default test: penetration tolerance (clashes whose depth bound is at most this are contacts)");
  c->add_option("--broadphase", o->broadphase, "bvh (default), brute, box");
  c->add_option("--tri-test", o->test, "triangle test of the two-part clash: exact (default), moller, gd");
  c->add_option("--max-clearance-pairs", o->max_clearance_pairs, "cap on clearance pairs listed in JSON");
  c->add_flag("--no-containment", o->no_containment, "skip the containment test");
  c->add_flag("--depth", o->depth,
              "two parts: also measure how deep crossing closed parts reach into each other (a sampled depth and a "
              "proven bound per clash; always on for scenes)");
  c->add_flag("--conservative", o->conservative,
              "inputs simplified by 'interfere simplify' (or STEP parts): widen the clearance by their stored error "
              "bounds (a STEP part's: its tessellation's linear deflection); a pair within them is a possible clash "
              "of the originals (exit status 1)");
  add_fem_clash_options(*c, *o);
  add_view_options(*c, o->views);
  c->callback([o, c, &exit_code] { exit_code = run_clash(*o, *c); });
}

}  // namespace interfere::cli
