// `interfere bearing --assembly FILE.json [--motion poses.csv] [--frames N] [--seed S] --out rows.csv
// --json summary.json` (issue #27; docs/bearing.md, "Bearing assemblies"): reads and validates the
// description, builds the parts and pairs, generates the motion (or reads it), solves every pair of
// every frame and writes one CSV row per (frame, pair) and the JSON summary (schema_version 1).
// Outputs are written atomically and only after every input is validated.
#include "bearing_assembly.h"
#include "bearing_assembly_report.h"

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "common.h"
#include "interfere/bearing/assembly.h"
#include "interfere/view/bearing_assembly_document.h"
#include "report_envelope.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

using namespace interfere::bearing;

}  // namespace

int run_bearing_assembly(const BearingAssemblyOptions& o) {
  Expected<AssemblySpec> spec = read_assembly_file(o.assembly);
  if (!spec) throw InputError(spec.error());
  if (o.frames) spec->frames = *o.frames;
  if (o.seed) spec->seed = *o.seed;
  if (o.clearance) spec->clearance = *o.clearance;
  if (o.frames && *o.frames < 1) throw InputError("--frames must be >= 1, got " + std::to_string(*o.frames));
  if (!o.motion.empty() && o.frames) throw InputError("--frames cannot be combined with --motion (the file gives the frames)");
  if (Status s = validate_assembly(*spec); !s) {
    Error e = s.error();
    if (e.file.empty()) e.file = o.assembly;
    throw InputError(e);
  }
  const FailOn fail = fail_on(o.fail_on);
  check_output(o.out, {}, "--out");
  check_output(o.json, {}, "--json");
  check_view_outputs(o.views);
  std::vector<NamedPath> outputs{{"--out", o.out}, {"--json", o.json}};
  for (const NamedPath& v : o.views.paths()) outputs.push_back(v);
  check_distinct_files({{"--assembly", o.assembly}, {"--motion", o.motion}}, outputs);
  set_threads(o.threads.value_or(0));

  Progress total("bearing assembly");
  Expected<Assembly> as = build_assembly(*spec);
  if (!as) throw InputError(as.error());
  AssemblyMotion motion;
  if (!o.motion.empty()) {
    Expected<AssemblyMotion> m = read_assembly_motion(*as, o.motion);
    if (!m) throw InputError(m.error());
    motion = std::move(*m);
  } else {
    motion = generate_motion(*as, spec->frames, spec->seed);
  }
  AssemblyResult res;
  {
    Progress progress("solving " + std::to_string(as->pairs.size()) + " pairs x " +
                      std::to_string(motion.poses.size()) + " frames");
    ProgressBar bar("frames", motion.poses.size(), "frames");  // (progress_bar.h)
    res = run_assembly(*as, motion, bar.callback());
  }
  const int status = verdict_exit_status(res.verdict, fail);
  if (!o.out.empty()) write_or_throw(write_output(o.out, [&](std::FILE* f) { return write_assembly_csv(f, *as, res); }));
  if (!o.json.empty()) write_or_throw(write_output(o.json, report_text(assembly_summary(*as, motion, res, spec->seed, status, active_threads()))));
  if (o.views.any()) {
    Expected<view::Document> doc = view::bearing_assembly_document(*as, motion, res);
    if (!doc) throw InputError(doc.error());
    write_views(o.views, std::move(*doc));
  }
  const AssemblyRow& w = res.rows[res.worst];
  std::printf("%s: %zu bearings, %zu parts, %zu pairs x %d frames, %llu interfering pair-frames, worst %s %s-%s "
              "distance %.17g (frame %d)\n",
              verdict_name(res.verdict), as->spec.bearings.size(), as->parts.size(), as->pairs.size(), res.frames,
              static_cast<unsigned long long>(res.interfering_rows), assembly_pair_kind_name(as->pairs[w.pair].kind),
              as->parts[as->pairs[w.pair].a].id.c_str(), as->parts[as->pairs[w.pair].b].id.c_str(), w.result.distance,
              w.frame);
  std::printf("  pair-frames: %llu clash, %llu contact, %llu clearance, %llu undecided, %llu clear\n",
              static_cast<unsigned long long>(res.verdicts[4]), static_cast<unsigned long long>(res.verdicts[2]),
              static_cast<unsigned long long>(res.verdicts[1]), static_cast<unsigned long long>(res.verdicts[3]),
              static_cast<unsigned long long>(res.verdicts[0]));
  return status;
}

}  // namespace interfere::cli
