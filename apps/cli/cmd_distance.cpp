// `interfere distance A B`: minimum distance between two parts with the two witness points. A part
// may be an FE model (issue #26, item 5): one body's boundary surface at one step (fem_surfaces.h).
#include <CLI/CLI.hpp>

#include <tuple>

#include "commands.h"
#include "common.h"
#include "fem_surfaces.h"
#include "interfere/core/atomic_file.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "report_json.h"
#include "report_envelope.h"

namespace interfere::cli {
namespace {

struct DistanceOptions : TwoPartOptions {
  FemFlags fem;  ///< FE inputs (issue #26, item 5)
};

// FE inputs: the flags go with the parts; a flag for no FE file is an error (it would do nothing).
void resolve_fem(const DistanceOptions& o, const CLI::App& command, ResolvedParts& parts) {
  const bool fa = is_fem_file(parts.a.file), fb = is_fem_file(parts.b.file);
  if (!fa && !fb) {
    if (const std::string flag = given_fem_flag(command); !flag.empty())
      throw InputError(flag + ": neither A nor B is an FE file (" + parts.a.file + ", " + parts.b.file + ")");
    return;
  }
  for (const auto& [fe, side, file] : {std::tuple{fa, 'a', &parts.a.file}, std::tuple{fb, 'b', &parts.b.file}}) {
    if (fe) continue;
    for (const std::string flag : {"--part-", "--disp-", "--field-"}) {
      if (command.count(flag + side) > 0)
        throw InputError(flag + side + ": " + *file + " is not an FE file");
    }
  }
  parts.fem = std::make_shared<const FemFlags>(o.fem);
}

// "A: body 'right' of model.msh at step 9 of 10 (field 'disp' of model.msh, scale 1)"
void print_fem_part(const char* label, const LoadedPart& p) {
  if (!p.fem) return;
  const FemPart& f = p.fem->part;
  std::printf("%s: body '%s' of %s", label, f.part().name.c_str(), p.file.c_str());
  if (f.displacement)
    std::printf(" at step %zu of %zu (%s, scale %g)", p.fem->step, f.num_steps(), displacement_source_text(f).c_str(),
                p.fem->scale);
  std::printf("\n");
}

int run_distance(const DistanceOptions& o, const CLI::App& command) {
  ResolvedParts parts = resolve_two_parts(o, command);
  resolve_fem(o, command, parts);
  const FailOn failing = fail_on(o.fail_on);
  check_output(o.json, {}, "--json");
  check_distinct_files({{"A", parts.a.file}, {"B", parts.b.file}, {"--scene", o.scene}}, {{"--json", o.json}});
  set_threads(o.threads);
  Progress total("distance");
  const LoadedParts loaded = load_parts(parts);
  if (loaded.a.fem && loaded.b.fem) check_step_counts(loaded.a.fem->part, loaded.b.fem->part);
  if (parts.fem) {
    const auto moved = [](const LoadedPart& p) { return p.fem && p.fem->part.displacement; };
    if (!moved(loaded.a) && !moved(loaded.b))
      check_no_steps(o.fem.step, "A (" + parts.a.file + ") and B (" + parts.b.file + ") have no displacements");
  }
  const LoadedPart& pa = loaded.a;
  const LoadedPart& pb = loaded.b;
  DistanceResult r;
  ClashResult verdict;  // clash, contact, containment: the one clash engine decides (issue #23, item 13)
  double query_seconds = 0;
  {
    Progress progress("distance query");
    r = distance(pa.model, pb.model);
    verdict = clash(pa.model, pb.model, ClashRequest{.regions = false, .containment = true});
    query_seconds = progress.seconds();
  }
  for (const std::string& w : verdict.warnings) warning(w);
  const int status = verdict_exit_status(verdict.verdict, failing);
  if (!o.json.empty()) {
    nlohmann::json j = two_part_report("distance", parts.units, loaded, query_seconds, total.seconds());
    j["result"] = distance_result_json(r);
    j["result"]["verdict"] = verdict_name(verdict.verdict);
    j["result"]["verdict_reasons"] = verdict.verdict_reasons;
    j["result"]["containment"] = containment_name(verdict.containment);
    j["verdict"] = verdict_name(verdict.verdict);
    j["warnings"] = verdict.warnings;
    j["exit_status"] = status;
    const Status s = write_output(o.json, report_text(j));
    if (!s) throw InputError(s.error());
  }
  if (r.intersecting) {
    std::printf("%s: surfaces %s (triangles %u of A and %u of B), distance 0\n",
                verdict.verdict == Verdict::clash ? "CLASH" : verdict.verdict == Verdict::undecided ? "UNDECIDED" : "contact",
                verdict.cross_pairs > 0 ? "cross" : "touch", r.triangle_a, r.triangle_b);
  } else {
    const char* head = verdict.verdict == Verdict::clash       ? "CLASH (one part lies inside the other): "
                       : verdict.verdict == Verdict::undecided ? "UNDECIDED (containment not decided): "
                                                               : "";
    std::printf("%sdistance %.17g %s between A (%.17g %.17g %.17g) and B (%.17g %.17g %.17g), triangles %u and %u\n",
                head, r.distance, parts.units.c_str(), r.point_a.x, r.point_a.y, r.point_a.z, r.point_b.x,
                r.point_b.y, r.point_b.z, r.triangle_a, r.triangle_b);
  }
  print_fem_part("A", pa);
  print_fem_part("B", pb);
  return status;
}

}  // namespace

void add_distance_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DistanceOptions>();
  CLI::App* c = app.add_subcommand("distance", "Minimum distance between parts A and B, with witness points (an FE "
                                               "model: the boundary surface of one body, at one step)");
  add_two_part_options(*c, *o);
  add_fem_flags(*c, o->fem, true);
  c->callback([o, c, &exit_code] { exit_code = run_distance(*o, *c); });
}

}  // namespace interfere::cli
