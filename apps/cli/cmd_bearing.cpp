// `interfere bearing`: dynamic interference of cylindrical roller bearings with scars (issue #4;
// Jia & Zheng, J. System Simulation 31(3), 2019). Parses options and the parameters file, runs the
// simulation (bearing/simulation.h), writes the per-frame CSV and the JSON summary
// (docs/bearing.md). Outputs are written atomically and only after every input is validated.
// Every row and every pair of parts of different bearings that the broad phase reports carries a
// verdict (query/verdict.h; bearing/part_pair.h); the exit status is verdict_exit_status's.
#include <CLI/CLI.hpp>

#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "bearing_assembly.h"
#include "commands.h"
#include "common.h"
#include "interfere/bearing/analytic.h"
#include "interfere/bearing/simulation.h"
#include "interfere/core/atomic_file.h"
#include "interfere/view/bearing_document.h"
#include "view_output.h"
#include "bearing_scar_import.h"
#include "report_envelope.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

using namespace interfere::bearing;

struct BearingOptions {
  std::string params_file, out, json, broad_phase, scar, fail_on;
  std::string assembly, motion;  ///< --assembly, --motion (bearing_assembly.cpp)
  std::optional<int> pairs, frames, vertices, threads_opt, border;
  std::optional<double> tilt, radius, top_radius, height, partner_radius, partner_height, gap, spin, tilt_step,
      scar_fraction, roughness, spacing, clearance;
  std::optional<std::uint64_t> seed, scar_seed;
  bool no_scar = false;
  bool raised = false;                ///< --raised (issue #27)
  ScarImportOptions scar_import;      ///< --scar-map, --scar-points (issue #27)
  ViewOutputs views;
};

// ---- parameters file (JSON, the paper's bearing.parameters) ----

[[noreturn]] void file_error(const std::string& file, const std::string& reason) {
  throw InputError(Error{.file = file, .reason = reason});
}

double number(const nlohmann::json& j, const std::string& file, const std::string& key) {
  if (!j.is_number()) file_error(file, "'" + key + "' must be a number");
  return j.get<double>();
}
int integer(const nlohmann::json& j, const std::string& file, const std::string& key) {
  if (!j.is_number_integer()) file_error(file, "'" + key + "' must be an integer");
  const auto v = j.get<std::int64_t>();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    file_error(file, "'" + key + "' is out of range");
  return static_cast<int>(v);
}
std::uint64_t unsigned_integer(const nlohmann::json& j, const std::string& file, const std::string& key) {
  if (!j.is_number_unsigned()) file_error(file, "'" + key + "' must be a non-negative integer");
  return j.get<std::uint64_t>();
}

void apply_params_file(const std::string& file, SceneParams& p) {
  std::ifstream in(file, std::ios::binary);
  if (!in) file_error(file, "cannot open the parameters file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(Error{.file = file, .byte = static_cast<std::int64_t>(e.byte), .reason = "invalid JSON"});
  } catch (const nlohmann::json::exception& e) {  // a number beyond double ("9e308")
    throw InputError(Error{.file = file, .reason = std::string("invalid JSON: ") + e.what()});
  }
  if (!j.is_object()) file_error(file, "the parameters file must hold a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "pairs") p.pairs = integer(v, file, k);
    else if (k == "frames") p.frames = integer(v, file, k);
    else if (k == "seed") p.seed = unsigned_integer(v, file, k);
    else if (k == "gap") p.gap = number(v, file, k);
    else if (k == "max_tilt_deg") p.max_tilt_deg = number(v, file, k);
    else if (k == "tilt_step") p.tilt_step = number(v, file, k);
    else if (k == "spin_deg_per_frame") p.spin_deg_per_frame = number(v, file, k);
    else if (k == "spacing") p.spacing = number(v, file, k);
    else if (k == "clearance") p.clearance = number(v, file, k);
    else if (k == "broad_phase") {
      if (!v.is_string() || !parse_broad_phase(v.get<std::string>(), p.broad_phase))
        file_error(file, "'broad_phase' must be one of \"brute\", \"sap\", \"octree\", \"bvh\"");
    } else if (k == "roller") {
      if (!v.is_object()) file_error(file, "'roller' must be an object");
      for (auto r = v.begin(); r != v.end(); ++r) {
        const std::string key = "roller." + r.key();
        if (r.key() == "radius") p.roller.radius = number(*r, file, key);
        else if (r.key() == "top_radius") p.roller.top_radius = number(*r, file, key);
        else if (r.key() == "height") p.roller.height = number(*r, file, key);
        else if (r.key() == "radial_segments") p.roller.radial_segments = integer(*r, file, key);
        else if (r.key() == "height_segments") p.roller.height_segments = integer(*r, file, key);
        else file_error(file, "unknown key '" + key + "'");
      }
    } else if (k == "partner") {
      if (!v.is_object()) file_error(file, "'partner' must be an object");
      for (auto r = v.begin(); r != v.end(); ++r) {
        const std::string key = "partner." + r.key();
        if (r.key() == "radius") p.partner_radius = number(*r, file, key);
        else if (r.key() == "height") p.partner_height = number(*r, file, key);
        else file_error(file, "unknown key '" + key + "'");
      }
    } else if (k == "scar") {
      if (v.is_null()) { p.scar_fraction = 0; continue; }
      if (!v.is_object()) file_error(file, "'scar' must be an object or null");
      for (auto r = v.begin(); r != v.end(); ++r) {
        const std::string key = "scar." + r.key();
        if (r.key() == "fraction") p.scar_fraction = number(*r, file, key);
        else if (r.key() == "angle_center_deg") p.scar.angle_center_deg = number(*r, file, key);
        else if (r.key() == "angle_width_deg") p.scar.angle_width_deg = number(*r, file, key);
        else if (r.key() == "z_min") p.scar.z_min = number(*r, file, key);
        else if (r.key() == "z_max") p.scar.z_max = number(*r, file, key);
        else if (r.key() == "depth") p.scar.depth = number(*r, file, key);
        else if (r.key() == "roughness") p.scar.roughness = number(*r, file, key);
        else if (r.key() == "border") p.scar.border = integer(*r, file, key);
        else if (r.key() == "seed") p.scar.seed = unsigned_integer(*r, file, key);
        else if (r.key() == "raised") {
          if (!r->is_boolean()) file_error(file, "'" + key + "' must be true or false");
          p.scar.raised = r->get<bool>();
        }
        else file_error(file, "unknown key '" + key + "'");
      }
    } else {
      file_error(file, "unknown key '" + k + "'");
    }
  }
}

void parse_scar_spec(const std::string& spec, ScarParams& s) {
  // CENTER,WIDTH,ZMIN,ZMAX,DEPTH (degrees, degrees, length, length, length)
  std::vector<double> v;
  std::stringstream ss(spec);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double d = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(d))
      throw InputError("--scar: '" + item + "' is not a number (expected CENTER,WIDTH,ZMIN,ZMAX,DEPTH)");
    v.push_back(d);
  }
  if (v.size() != 5) throw InputError("--scar: expected 5 numbers CENTER,WIDTH,ZMIN,ZMAX,DEPTH, got " + std::to_string(v.size()));
  s.angle_center_deg = v[0], s.angle_width_deg = v[1], s.z_min = v[2], s.z_max = v[3], s.depth = v[4];
}

nlohmann::json vec_json(const Vec3& v) { return {v.x, v.y, v.z}; }

/// Part index 2k (roller of pair k) or 2k + 1 (its partner).
nlohmann::json scene_part_json(std::uint32_t part) {
  return {{"pair", part / 2}, {"part", part % 2 == 0 ? "roller" : "partner"}};
}

nlohmann::json verdict_counts(const std::array<std::uint64_t, 5>& counts) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t v = 0; v < counts.size(); ++v) j[verdict_name(static_cast<Verdict>(v))] = counts[v];
  return j;
}

nlohmann::json params_json(const SceneParams& p) {
  return {{"pairs", p.pairs},
          {"frames", p.frames},
          {"seed", p.seed},
          {"roller",
           {{"radius", p.roller.radius},
            {"top_radius", p.roller.top()},
            {"height", p.roller.height},
            {"radial_segments", p.roller.radial_segments},
            {"height_segments", p.roller.height_segments}}},
          {"partner", {{"radius", p.partner_radius}, {"height", p.partner_height}}},
          {"gap", p.gap},
          {"max_tilt_deg", p.max_tilt_deg},
          {"tilt_step", p.tilt_step},
          {"spin_deg_per_frame", p.spin_deg_per_frame},
          {"scar",
           {{"fraction", p.scar_fraction},
            {"angle_center_deg", p.scar.angle_center_deg},
            {"angle_width_deg", p.scar.angle_width_deg},
            {"z_min", p.scar.z_min},
            {"z_max", p.scar.z_max},
            {"depth", p.scar.depth},
            {"roughness", p.scar.roughness},
            {"border", p.scar.border},
            {"seed", p.scar.seed},
            {"raised", p.scar.raised}}},
          {"broad_phase", broad_phase_name(p.broad_phase)},
          {"spacing", p.spacing},
          {"clearance", p.clearance}};
}

int write_csv(std::FILE* f, const SimulationResult& r) {
  std::fputs("frame,pair,distance,interference,ax,ay,az,bx,by,bz,solver,path,scarred,scar_in_range,box_overlap,"
             "tilt_deg,azimuth_deg,spin_deg,evaluated,verdict\n", f);
  for (const PairFrame& row : r.rows) {
    std::fprintf(f, "%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%s,%d,%d,%d,%.17g,%.17g,%.17g,%u,%s\n",
                 row.frame, row.pair, row.distance, row.distance < 0 ? -row.distance : 0.0, row.point_a.x,
                 row.point_a.y, row.point_a.z, row.point_b.x, row.point_b.y, row.point_b.z,
                 row.solver == 1 ? "scarred" : "standard",
                 row.solver == 1 ? "mesh" : analytic_path_name(static_cast<AnalyticPath>(row.path)),
                 row.scarred_roller ? 1 : 0, row.scar_in_range ? 1 : 0, row.box_overlap ? 1 : 0, row.tilt_deg,
                 row.azimuth_deg, row.spin_deg, row.evaluated, verdict_name(row.verdict));
  }
  return std::ferror(f) ? 1 : 0;
}

int run_bearing(const BearingOptions& o) {
  if (!o.assembly.empty() || !o.motion.empty()) {
    if (o.assembly.empty()) throw InputError("--motion needs --assembly");
    if (!o.params_file.empty() || o.pairs) throw InputError("--assembly cannot be combined with --params or --pairs");
    return run_bearing_assembly({.assembly = o.assembly, .motion = o.motion, .out = o.out, .json = o.json,
                                 .fail_on = o.fail_on, .frames = o.frames, .threads = o.threads_opt, .seed = o.seed,
                                 .clearance = o.clearance, .views = o.views});
  }
  SceneParams p;
  if (!o.params_file.empty()) apply_params_file(o.params_file, p);
  if (o.pairs) p.pairs = *o.pairs;
  if (o.frames) p.frames = *o.frames;
  if (o.vertices) {
    if (*o.vertices < 3) throw InputError("--vertices must be >= 3, got " + std::to_string(*o.vertices));
    p.roller.radial_segments = *o.vertices, p.roller.height_segments = *o.vertices - 1;
  }
  if (o.tilt) p.max_tilt_deg = *o.tilt;
  if (o.radius) p.roller.radius = *o.radius;
  if (o.top_radius) p.roller.top_radius = *o.top_radius;
  if (o.height) p.roller.height = *o.height;
  if (o.partner_radius) p.partner_radius = *o.partner_radius;
  if (o.partner_height) p.partner_height = *o.partner_height;
  if (o.gap) p.gap = *o.gap;
  if (o.spin) p.spin_deg_per_frame = *o.spin;
  if (o.tilt_step) p.tilt_step = *o.tilt_step;
  if (o.spacing) p.spacing = *o.spacing;
  if (o.clearance) p.clearance = *o.clearance;
  if (o.seed) p.seed = *o.seed;
  if (!o.scar.empty()) parse_scar_spec(o.scar, p.scar);
  if (o.scar_fraction) p.scar_fraction = *o.scar_fraction;
  if (o.roughness) p.scar.roughness = *o.roughness;
  if (o.border) p.scar.border = *o.border;
  if (o.scar_seed) p.scar.seed = *o.scar_seed;
  if (o.no_scar) p.scar_fraction = 0;
  if (o.raised) p.scar.raised = true;
  const nlohmann::json scar_import = apply_scar_import(o.scar_import, p);  // after the roller grid is final
  if (!o.broad_phase.empty() && !parse_broad_phase(o.broad_phase, p.broad_phase))
    throw InputError("--broad-phase: unknown broad phase '" + o.broad_phase + "' (brute, sap, octree, bvh)");
  if (Status s = validate(p); !s) throw InputError(s.error());
  const FailOn fail = fail_on(o.fail_on);
  check_output(o.out, {}, "--out");
  check_output(o.json, {}, "--json");
  check_view_outputs(o.views);
  std::vector<NamedPath> outputs{{"--out", o.out}, {"--json", o.json}};
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  std::vector<NamedPath> inputs{{"--params", o.params_file}};
  for (const std::string& f : scar_import_inputs(o.scar_import))
    inputs.push_back({f == o.scar_import.map ? "--scar-map" : "--scar-points", f});
  check_distinct_files(inputs, outputs);
  set_threads(o.threads_opt.value_or(0));

  Progress total("bearing");
  Expected<SimulationResult> r = Error{.reason = "not run"};
  {
    Progress progress("simulating " + std::to_string(p.pairs) + " pairs x " + std::to_string(p.frames) + " frames");
    // Frames: a bar with rate and ETA on a terminal, a line per tenth otherwise (progress_bar.h).
    ProgressBar bar("frames", static_cast<std::size_t>(p.frames), "frames");
    r = simulate(p, !o.out.empty() || o.views.any(), bar.callback());
  }
  if (!r) throw InputError(r.error());
  const SimulationResult& res = *r;
  const int status = verdict_exit_status(res.verdict, fail);
  if (!o.out.empty()) {
    const Status s = write_output(o.out, [&](std::FILE* f) { return write_csv(f, res); });
    if (!s) throw InputError(s.error());
  }
  if (!o.json.empty()) {
    nlohmann::json j;
    j["version"] = INTERFERE_VERSION;
    j["command"] = "bearing";
    j["parameters"] = params_json(p);
    j["spacing"] = res.spacing;
    j["theta_deg"] = res.theta * 180 / std::numbers::pi;
    j["scar_import"] = scar_import;
    j["threads"] = active_threads();
    j["results"] = {{"rows", static_cast<std::uint64_t>(p.pairs) * static_cast<std::uint64_t>(p.frames)},
                    {"colliders", 2 * p.pairs},
                    {"interfering_rows", res.interfering_rows},
                    {"min_distance", res.min_distance},
                    {"max_interference", res.min_distance < 0 ? -res.min_distance : 0.0},
                    {"scarred_rollers", res.scarred_rollers},
                    {"scarred_solves", res.scarred_solves},
                    {"general_solves", res.general_solves},
                    {"broad_pairs_total", res.broad_pairs_total},
                    {"cross_pairs", res.cross_pairs},
                    {"verdicts", verdict_counts(res.row_verdicts)},
                    {"cross_verdicts", verdict_counts(res.cross_verdicts)}};
    nlohmann::json cross = nlohmann::json::array();
    for (const CrossPair& c : res.cross_results)
      cross.push_back({{"frame", c.frame},
                       {"a", scene_part_json(c.part_a)},
                       {"b", scene_part_json(c.part_b)},
                       {"distance", c.distance},
                       {"interference", c.distance < 0 && c.solver != PartPairSolver::bound ? -c.distance : 0.0},
                       {"point_a", vec_json(c.point_a)},
                       {"point_b", vec_json(c.point_b)},
                       {"solver", part_pair_solver_name(c.solver)},
                       {"verdict", verdict_name(c.verdict)}});
    j["cross"] = std::move(cross);
    j["verdict"] = verdict_name(res.verdict);
    j["undecided_reasons"] = res.undecided_reasons;
    j["worst"] = {{"frame", res.worst.frame},
                  {"pair", res.worst.pair},
                  {"distance", res.worst.distance},
                  {"point_a", vec_json(res.worst.point_a)},
                  {"point_b", vec_json(res.worst.point_b)},
                  {"solver", res.worst.solver == 1 ? "scarred" : "standard"},
                  {"verdict", verdict_name(res.worst.verdict)}};
    j["timing"] = {{"setup_seconds", res.setup_seconds},
                   {"broad_seconds", res.broad_seconds},
                   {"narrow_seconds", res.narrow_seconds},
                   {"total_seconds", res.total_seconds},
                   {"frames_per_second", res.frames_per_second},
                   {"cpu_seconds", res.cpu_seconds}};
    j["exit_status"] = status;
    const Status s = write_output(o.json, report_text(j, 2, {{"parameters", o.params_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.params_file)}, {"scar_import", j["scar_import"]}}));
    if (!s) throw InputError(s.error());
  }
  if (o.views.any()) {
    Expected<view::Document> doc = view::bearing_document(p, res);
    if (!doc) throw InputError(doc.error());
    write_views(o.views, std::move(*doc));
  }
  const auto count = [](const std::array<std::uint64_t, 5>& c, Verdict v) {
    return static_cast<unsigned long long>(c[static_cast<std::size_t>(v)]);
  };
  std::printf("%s: %d pairs x %d frames, %llu interfering pair-frames, max interference %.17g, min distance %.17g, "
              "%.1f frames/s\n",
              verdict_name(res.verdict), p.pairs, p.frames, static_cast<unsigned long long>(res.interfering_rows),
              res.min_distance < 0 ? -res.min_distance : 0.0, res.min_distance, res.frames_per_second);
  std::printf("  pair-frames: %llu clash, %llu contact, %llu clearance, %llu undecided\n",
              count(res.row_verdicts, Verdict::clash), count(res.row_verdicts, Verdict::contact),
              count(res.row_verdicts, Verdict::clearance), count(res.row_verdicts, Verdict::undecided));
  std::printf("  parts of different pairs: %llu box overlaps: %llu clash, %llu contact, %llu clearance, %llu undecided\n",
              static_cast<unsigned long long>(res.cross_pairs), count(res.cross_verdicts, Verdict::clash),
              count(res.cross_verdicts, Verdict::contact), count(res.cross_verdicts, Verdict::clearance),
              count(res.cross_verdicts, Verdict::undecided));
  for (const std::string& reason : res.undecided_reasons) std::printf("  undecided: %s\n", reason.c_str());
  return status;
}

}  // namespace

void add_bearing_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<BearingOptions>();
  CLI::App* c = app.add_subcommand(
      "bearing", "Dynamic interference of cylindrical roller bearings with scars (per-frame maximum interference)");
  c->add_option("--assembly", o->assembly, "bearing assembly description (JSON; docs/bearing.md, \"Bearing assemblies\")");
  c->add_option("--motion", o->motion, "with --assembly: per-frame part poses (CSV frame,body,12 numbers, or JSON)");
  c->add_option("--params", o->params_file, "parameters file (JSON, like the paper's bearing.parameters)");
  c->add_option("--pairs", o->pairs, "number of roller/partner pairs N (colliders = 2N)");
  c->add_option("--frames", o->frames, "number of frames F");
  c->add_option("--vertices", o->vertices, "side vertices per ring and rings per roller (n x n)");
  c->add_option("--scar", o->scar, "scar window CENTER_DEG,WIDTH_DEG,ZMIN,ZMAX,DEPTH");
  c->add_option("--scar-fraction", o->scar_fraction, "fraction of scarred rollers (default 0.25)");
  c->add_option("--roughness", o->roughness, "diamond-square roughness in (0, 1]");
  c->add_option("--border", o->border, "median-filter border band in grid cells");
  c->add_option("--scar-seed", o->scar_seed, "seed of the scar height maps");
  c->add_flag("--no-scar", o->no_scar, "no scarred rollers");
  c->add_flag("--raised", o->raised, "generated scars are raised (outward) instead of inward");
  c->add_option("--scar-map", o->scar_import.map,
                "imported scar height map for the scarred rollers: .csv grid or 16-bit grayscale .png (docs/bearing.md)");
  c->add_option("--scar-map-scale", o->scar_import.scale, "PNG map: mm per pixel unit (height = scale * value + offset)");
  c->add_option("--scar-map-offset", o->scar_import.offset, "PNG map: height offset in mm (default 0)");
  c->add_option("--scar-points", o->scar_import.points,
                "imported scar from a point cloud in the roller's body frame: x y z text, or .stl/.ply/.obj/.off");
  c->add_option("--scar-points-window", o->scar_import.window, "point cloud search radius in mm (default 0 = one grid cell)");
  c->add_option("--tilt", o->tilt, "maximum tilt alpha in degrees (default 1)");
  c->add_option("--tilt-step", o->tilt_step, "tilt random-walk step, fraction of alpha (default 0.25)");
  c->add_option("--spin", o->spin, "roller spin per frame in degrees (default 3)");
  c->add_option("--radius", o->radius, "roller radius r (default 10)");
  c->add_option("--top-radius", o->top_radius, "roller top radius (tapered roller; default = radius)");
  c->add_option("--height", o->height, "roller length h_b (default 40)");
  c->add_option("--partner-radius", o->partner_radius, "partner radius R (default 30)");
  c->add_option("--partner-height", o->partner_height, "partner height (default 60)");
  c->add_option("--gap", o->gap, "nominal surface gap between roller and partner (default 0; < 0 = preload)");
  c->add_option("--spacing", o->spacing, "grid pitch between pairs (default 0 = automatic)");
  c->add_option("--clearance", o->clearance, "pairs apart but closer than this get the verdict clearance (default 0 = none)");
  add_fail_on_option(*c, o->fail_on);
  c->add_option("--seed", o->seed, "seed of the tilt random walk and spin phases (default 1)");
  c->add_option("--broad-phase", o->broad_phase, "brute, sap (default), octree or bvh");
  c->add_option("--threads", o->threads_opt, "worker threads (0 = all cores)");
  c->add_option("--out", o->out, "per-frame CSV (one row per pair and frame)");
  c->add_option("--json", o->json, "JSON summary");
  add_view_options(*c, o->views);
  c->callback([o, &exit_code] { exit_code = run_bearing(*o); });
}

}  // namespace interfere::cli
