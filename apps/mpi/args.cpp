// interfere-mpi's command line (args.h; issue #31, docs/mpi.md "Options").
#include "args.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "interfere/query/verdict.h"

namespace interfere::mpi {
namespace {

// Options of `interfere clash` that interfere-mpi does not offer, and why (docs/mpi.md, "Options").
const char* not_offered(const std::string& flag) {
  static const std::map<std::string, const char*> why{
      {"--html", "views are drawn from one process's result: run `interfere clash --scene` with --html/--glb/--pvd"},
      {"--glb", "views are drawn from one process's result: run `interfere clash --scene` with --html/--glb/--pvd"},
      {"--pvd", "views are drawn from one process's result: run `interfere clash --scene` with --html/--glb/--pvd"},
      {"--view-budget", "no views are written"},
      {"--pairs", "it belongs to the two-part clash (A B)"},
      {"--region-a", "it belongs to the two-part clash (A B)"},
      {"--region-b", "it belongs to the two-part clash (A B)"},
      {"--curves", "it belongs to the two-part clash (A B)"},
      {"--regions-vtu", "it belongs to the two-part clash (A B)"},
      {"--transform-a", "it belongs to the two-part clash (A B); give poses in the scene file"},
      {"--transform-b", "it belongs to the two-part clash (A B); give poses in the scene file"},
      {"--units-a", "it belongs to the two-part clash (A B); give units in the scene file"},
      {"--units-b", "it belongs to the two-part clash (A B); give units in the scene file"},
      {"--part", "it belongs to the two-part clash (A B); give \"select\" in the scene file"},
      {"--part-a", "it belongs to the two-part clash (A B)"},
      {"--part-b", "it belongs to the two-part clash (A B)"},
      {"--disp-a", "it belongs to the two-part clash (A B); use --disp"},
      {"--disp-b", "it belongs to the two-part clash (A B); use --disp"},
      {"--field-a", "it belongs to the two-part clash (A B); use --field"},
      {"--field-b", "it belongs to the two-part clash (A B); use --field"},
      {"--step", "it belongs to the two-part clash (A B)"},
      {"--broadphase", "it belongs to the two-part clash (A B); scenes use the engine's broad phase"},
      {"--tri-test", "scenes use the exact triangle test only"},
      {"--max-clearance-pairs", "it belongs to the two-part clash (A B)"},
      {"--no-containment", "it belongs to the two-part clash (A B)"},
      {"--depth", "it belongs to the two-part clash (A B); scenes always measure depth"},
      {"--conservative", "it belongs to the two-part clash (A B)"},
  };
  const auto it = why.find(flag);
  return it == why.end() ? nullptr : it->second;
}

}  // namespace

const char* const kUsage =
    "usage: mpirun -n K interfere-mpi clash --scene FILE [--json OUT] [--csv OUT] [--frames-csv OUT]\n"
    "         [--frame-pairs-csv OUT] [--motion FILE] [--baseline FILE] [--units U] [--group-by pair|location|none]\n"
    "         [--group-distance D] [--test TEXT]... [--tests FILE] [--clearance D] [--tolerance T] [--fail-on LIST]\n"
    "         [--field NAME] [--disp FILE] [--scale S] [--split MODE] [--linear-faces] [--no-reference]\n"
    "         [--threads N] [--distribute pairs|frames] [--memory-limit MB] [--cost-model PAIR_S,PAIR_TRI_S,BODY_TRI_S,READ_TRI_S[,MERGE_PAIR_S]] [--quiet]\n"
    "       mpirun -n K interfere-mpi bearing --assembly FILE ... (frames in blocks per rank; `interfere-mpi bearing --help`)\n"
    "The report is the one of `interfere clash --scene FILE` (docs/report.md) plus \"mpi\"; docs/mpi.md.\n"
    "Exit status: 0 clear, contact or clearance; 1 clash (or a verdict named by --fail-on); 2 usage or input error,\n"
    "on any rank (message on stderr, nothing written); 3 undecided.\n";

Options parse_clash(int argc, char** argv) {
  Options o;
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) throw InfoRequest{kUsage};
  if (argc >= 2 && std::string(argv[1]) == "--version") throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
  if (argc < 2 || std::string(argv[1]) != "clash") throw UsageError(std::string("the command is `clash` or `bearing`\n") + kUsage);
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + " needs a value\n" + kUsage);
      return argv[++i];
    };
    const auto number = [&](const std::string& v) {
      try {
        std::size_t used = 0;
        const double d = std::stod(v, &used);
        if (used != v.size() || !std::isfinite(d) || d < 0) throw std::invalid_argument(v);
        return d;
      } catch (const std::exception&) {
        throw UsageError(a + ": '" + v + "' is not a finite number >= 0");
      }
    };
    if (const char* why = not_offered(a)) throw UsageError(a + ": not offered by interfere-mpi: " + why + " (docs/mpi.md, \"Options\")");
    if (a == "--scene") o.scene = value();
    else if (a == "--test") o.test_texts.push_back(value());
    else if (a == "--tests") o.tests_file = value();
    else if (a == "--clearance") o.clearance = number(value()), o.clearance_given = true;
    else if (a == "--tolerance") o.tolerance = number(value()), o.tolerance_given = true;
    else if (a == "--fail-on") o.fail_on = value();
    else if (a == "--field") o.fem_field = value();
    else if (a == "--disp") o.fem_disp = value();
    else if (a == "--scale") {
      const std::string v = value();
      try {
        std::size_t used = 0;
        o.fem_scale = std::stod(v, &used);
        if (used != v.size() || !std::isfinite(o.fem_scale)) throw std::invalid_argument(v);
      } catch (const std::exception&) {
        throw UsageError("--scale: '" + v + "' is not a finite number");
      }
    } else if (a == "--split") o.fem_split = value();
    else if (a == "--linear-faces") o.fem_linear_faces = true;
    else if (a == "--no-reference") o.reference = false;
    else if (a == "--json") o.json = value();
    else if (a == "--csv") o.csv = value();
    else if (a == "--frames-csv") o.frames_csv = value();
    else if (a == "--frame-pairs-csv") o.frame_pairs_csv = value();
    else if (a == "--motion") o.motion = value();
    else if (a == "--baseline") o.baseline = value();
    else if (a == "--units") o.units = value();
    else if (a == "--group-by") o.group_by = value();
    else if (a == "--group-distance") o.group_distance = number(value());
    else if (a == "--threads") o.threads = static_cast<int>(number(value()));
    else if (a == "--memory-limit") o.memory_limit_mb = number(value());
    else if (a == "--distribute") {
      const std::string v = value();
      if (v == "pairs") o.distribute = Distribute::pairs;
      else if (v == "frames") o.distribute = Distribute::frames;
      else throw UsageError("--distribute: '" + v + "' is not pairs or frames");
    }
    else if (a == "--cost-model") {
      const std::string v = value();
      std::vector<double> c;
      std::size_t from = 0;
      while (from <= v.size()) {
        const std::size_t comma = std::min(v.find(',', from), v.size());
        c.push_back(number(v.substr(from, comma - from)));
        from = comma + 1;
      }
      if (c.size() != 4 && c.size() != 5)
        throw UsageError("--cost-model: '" + v + "' is not four or five numbers PAIR_S,PAIR_TRI_S,BODY_TRI_S,READ_TRI_S[,MERGE_PAIR_S]");
      o.cost.pair_s = c[0], o.cost.pair_tri_s = c[1], o.cost.body_tri_s = c[2], o.cost.read_tri_s = c[3];
      if (c.size() == 5) o.cost.merge_pair_s = c[4];
    } else if (a == "--quiet" || a == "-q") o.quiet = true;
    else if (a == "--help" || a == "-h") throw InfoRequest{kUsage};
    else if (a == "--version") throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
    else if (!a.starts_with("-"))
      throw UsageError("'" + a + "': interfere-mpi takes no input files on the command line: list every body in the --scene file");
    else throw UsageError("unknown option " + a + "\n" + kUsage);
  }
  if (o.scene.empty()) throw UsageError(std::string("--scene FILE is required\n") + kUsage);
  if (!o.fail_on.empty() && !parse_fail_on(o.fail_on))
    throw UsageError("--fail-on: '" + o.fail_on + "' is not a list of contact, clearance, undecided (comma-separated)");
  if (o.group_by != "pair" && o.group_by != "location" && o.group_by != "none")
    throw UsageError("--group-by: unknown grouping '" + o.group_by + "' (pair, location, none)");
  return o;
}

}  // namespace interfere::mpi
