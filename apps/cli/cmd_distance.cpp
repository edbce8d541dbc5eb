// `interfere distance A B`: minimum distance between two parts with the two witness points.
#include <CLI/CLI.hpp>

#include "commands.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "report_json.h"

namespace interfere::cli {
namespace {

int run_distance(const TwoPartOptions& o, const CLI::App& command) {
  const ResolvedParts parts = resolve_two_parts(o, command);
  const FailOn failing = fail_on(o.fail_on);
  check_output(o.json, {}, "--json");
  check_distinct_files({{"A", parts.a.file}, {"B", parts.b.file}, {"--scene", o.scene}}, {{"--json", o.json}});
  set_threads(o.threads);
  Progress total("distance");
  const LoadedParts loaded = load_parts(parts);
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
    const Status s = write_output(o.json, j.dump(2) + "\n");
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
  return status;
}

}  // namespace

void add_distance_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<TwoPartOptions>();
  CLI::App* c = app.add_subcommand("distance", "Minimum distance between parts A and B, with witness points");
  add_two_part_options(*c, *o);
  c->callback([o, c, &exit_code] { exit_code = run_distance(*o, *c); });
}

}  // namespace interfere::cli
