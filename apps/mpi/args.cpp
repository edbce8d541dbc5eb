// interfere-mpi's command line (args.h; issue #31, docs/mpi.md "Options"), read with CLI11 as the
// CLI's (apps/cli/main.cpp). Values are taken as text and converted here, so that a bad value is
// reported as before ("--clearance: 'x' is not a finite number >= 0"); options that CLI11 does not
// know are kept as extras and named: an option of `interfere clash` not offered here (its reason),
// any other option ("unknown option --x"), a file on the command line. Usage errors: UsageError
// (exit status 2, the flag named); --help and --version: InfoRequest (stdout, exit status 0).
#include "args.h"

#include <CLI/CLI.hpp>

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

// A CLI11 parser of argv[first..]: no help flag of its own (ours prints the synopsis), extras
// allowed (named by `extras` below), an option given twice takes its last value (as before).
struct Parser {
  CLI::App app;
  std::string usage;
  bool help = false, version = false;

  explicit Parser(std::string text) : app("interfere-mpi"), usage(std::move(text)) {
    app.set_help_flag();
    app.allow_extras();
    app.add_flag("-h,--help", help);
    app.add_flag("--version", version);
  }
  CLI::Option* text(const std::string& name, std::string& into) {
    return app.add_option(name, into)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  bool given(const std::string& name) const { return app.count(name) > 0; }
  void parse(int argc, char** argv, int first) {
    std::vector<std::string> args;  // (CLI11 takes them in reverse order)
    for (int i = argc - 1; i >= first; --i) args.emplace_back(argv[i]);
    try {
      app.parse(args);
    } catch (const CLI::ParseError& e) {
      throw UsageError(std::string(e.what()) + "\n" + usage);  // (CLI11's text names the flag: "--scene: 1 required TEXT missing")
    }
    if (help) throw InfoRequest{usage};
    if (version) throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
  }
  // The first extra: an option not offered, an unknown option, a file on the command line.
  void extras(bool clash) const {
    for (const std::string& a : app.remaining()) {
      const std::string flag = a.substr(0, a.find('='));
      if (clash)
        if (const char* why = not_offered(flag))
          throw UsageError(flag + ": not offered by interfere-mpi: " + why + " (docs/mpi.md, \"Options\")");
      if (!clash && (flag == "--html" || flag == "--glb" || flag == "--pvd" || flag == "--view-budget"))
        throw UsageError(flag + ": not offered by interfere-mpi: views are drawn from one process's result: run `interfere bearing "
                                "--assembly` with --html/--glb/--pvd (docs/mpi.md, \"Options\")");
      if (!a.starts_with("-"))
        throw UsageError("'" + a + "': interfere-mpi takes no input files on the command line" +
                         (clash ? ": list every body in the --scene file" : ""));
      throw UsageError("unknown option " + flag + "\n" + usage);
    }
  }
};

// "--flag: 'v' is not a finite number [>= 0]", "... is not an integer".
double to_number(const std::string& flag, const std::string& v, bool non_negative) {
  try {
    std::size_t used = 0;
    const double d = std::stod(v, &used);
    if (used != v.size() || !std::isfinite(d) || (non_negative && d < 0)) throw std::invalid_argument(v);
    return d;
  } catch (const std::exception&) {
    throw UsageError(flag + ": '" + v + "' is not a finite number" + (non_negative ? " >= 0" : ""));
  }
}

long long to_integer(const std::string& flag, const std::string& v) {
  try {
    std::size_t used = 0;
    const long long n = std::stoll(v, &used);
    if (used != v.size()) throw std::invalid_argument(v);
    return n;
  } catch (const std::exception&) {
    throw UsageError(flag + ": '" + v + "' is not an integer");
  }
}

}  // namespace

const char* const kUsage =
    "usage: mpirun -n K interfere-mpi clash --scene FILE [--json OUT] [--csv OUT] [--frames-csv OUT]\n"
    "         [--frame-pairs-csv OUT] [--motion FILE] [--baseline FILE] [--units U] [--group-by pair|location|none]\n"
    "         [--group-distance D] [--test TEXT]... [--tests FILE] [--clearance D] [--tolerance T] [--fail-on LIST]\n"
    "         [--field NAME] [--disp FILE] [--scale S] [--split MODE] [--linear-faces] [--no-reference]\n"
    "         [--threads N] [--distribute pairs|frames] [--memory-limit MB] [--cost-model PAIR_S,PAIR_TRI_S,BODY_TRI_S,READ_TRI_S[,MERGE_PAIR_S]] [--quiet]\n"
    "       mpirun -n K interfere-mpi bearing --assembly FILE ... (frames in blocks per rank; `interfere-mpi bearing --help`)\n"
    "       mpirun -n K interfere-mpi cell CELL [--path FILE] ... (path points in blocks per rank; `interfere-mpi cell --help`)\n"
    "The report is the one of `interfere clash --scene FILE` (docs/report.md) plus \"mpi\"; docs/mpi.md.\n"
    "Exit status: 0 clear, contact or clearance; 1 clash (or a verdict named by --fail-on); 2 usage or input error,\n"
    "on any rank (message on stderr, nothing written); 3 undecided.\n";

const char* const kBearingUsage =
    "usage: mpirun -n K interfere-mpi bearing --assembly FILE [--motion FILE] [--frames N] [--seed S]\n"
    "         [--clearance D] [--out ROWS.csv] [--json SUMMARY.json] [--fail-on LIST] [--threads N] [--quiet]\n"
    "The outputs are those of `interfere bearing --assembly` (docs/bearing.md) plus \"mpi\" in the JSON; docs/mpi.md.\n";

Options parse_clash(int argc, char** argv) {
  Options o;
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) throw InfoRequest{kUsage};
  if (argc >= 2 && std::string(argv[1]) == "--version") throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
  if (argc < 2 || std::string(argv[1]) != "clash") throw UsageError(std::string("the command is `clash`, `bearing` or `cell`\n") + kUsage);
  Parser p(kUsage);
  std::string clearance, tolerance, scale, group_distance, threads, memory_limit, cost_model, distribute;
  p.text("--scene", o.scene);
  p.app.add_option("--test", o.test_texts)->allow_extra_args(false);  // (repeatable, one text each)
  p.text("--tests", o.tests_file);
  p.text("--clearance", clearance);
  p.text("--tolerance", tolerance);
  p.text("--fail-on", o.fail_on);
  p.text("--field", o.fem_field);
  p.text("--disp", o.fem_disp);
  p.text("--scale", scale);
  p.text("--split", o.fem_split);
  p.app.add_flag("--linear-faces", o.fem_linear_faces);
  bool no_reference = false;
  p.app.add_flag("--no-reference", no_reference);
  p.text("--json", o.json);
  p.text("--csv", o.csv);
  p.text("--frames-csv", o.frames_csv);
  p.text("--frame-pairs-csv", o.frame_pairs_csv);
  p.text("--motion", o.motion);
  p.text("--baseline", o.baseline);
  p.text("--units", o.units);
  p.text("--group-by", o.group_by);
  p.text("--group-distance", group_distance);
  p.text("--threads", threads);
  p.text("--memory-limit", memory_limit);
  p.text("--distribute", distribute);
  p.text("--cost-model", cost_model);
  p.app.add_flag("-q,--quiet", o.quiet);
  p.parse(argc, argv, 2);
  p.extras(true);
  o.reference = !no_reference;
  if (p.given("--clearance")) o.clearance = to_number("--clearance", clearance, true), o.clearance_given = true;
  if (p.given("--tolerance")) o.tolerance = to_number("--tolerance", tolerance, true), o.tolerance_given = true;
  if (p.given("--scale")) o.fem_scale = to_number("--scale", scale, false);
  if (p.given("--group-distance")) o.group_distance = to_number("--group-distance", group_distance, true);
  if (p.given("--threads")) o.threads = static_cast<int>(to_number("--threads", threads, true));
  if (p.given("--memory-limit")) o.memory_limit_mb = to_number("--memory-limit", memory_limit, true);
  if (p.given("--distribute")) {
    if (distribute == "pairs") o.distribute = Distribute::pairs;
    else if (distribute == "frames") o.distribute = Distribute::frames;
    else throw UsageError("--distribute: '" + distribute + "' is not pairs or frames");
  }
  if (p.given("--cost-model")) {
    std::vector<double> c;
    std::size_t from = 0;
    while (from <= cost_model.size()) {
      const std::size_t comma = std::min(cost_model.find(',', from), cost_model.size());
      c.push_back(to_number("--cost-model", cost_model.substr(from, comma - from), true));
      from = comma + 1;
    }
    if (c.size() != 4 && c.size() != 5)
      throw UsageError("--cost-model: '" + cost_model + "' is not four or five numbers PAIR_S,PAIR_TRI_S,BODY_TRI_S,READ_TRI_S[,MERGE_PAIR_S]");
    o.cost.pair_s = c[0], o.cost.pair_tri_s = c[1], o.cost.body_tri_s = c[2], o.cost.read_tri_s = c[3];
    if (c.size() == 5) o.cost.merge_pair_s = c[4];
  }
  if (o.scene.empty()) throw UsageError(std::string("--scene FILE is required\n") + kUsage);
  if (!o.fail_on.empty() && !parse_fail_on(o.fail_on))
    throw UsageError("--fail-on: '" + o.fail_on + "' is not a list of contact, clearance, undecided (comma-separated)");
  if (o.group_by != "pair" && o.group_by != "location" && o.group_by != "none")
    throw UsageError("--group-by: unknown grouping '" + o.group_by + "' (pair, location, none)");
  return o;
}

BearingOptions parse_bearing(int argc, char** argv) {
  BearingOptions o;
  Parser p(kBearingUsage);
  std::string frames, seed, clearance, threads;
  p.text("--assembly", o.assembly);
  p.text("--motion", o.motion);
  p.text("--frames", frames);
  p.text("--seed", seed);
  p.text("--clearance", clearance);
  p.text("--out", o.out);
  p.text("--json", o.json);
  p.text("--fail-on", o.fail_on);
  p.text("--threads", threads);
  p.app.add_flag("-q,--quiet", o.quiet);
  p.parse(argc, argv, 1);
  p.extras(false);
  if (p.given("--frames")) o.frames = static_cast<int>(to_integer("--frames", frames));
  if (p.given("--seed")) {
    const long long s = to_integer("--seed", seed);
    if (s < 0) throw UsageError("--seed must be >= 0");
    o.seed = static_cast<std::uint64_t>(s);
  }
  if (p.given("--clearance")) o.clearance = to_number("--clearance", clearance, false);
  if (p.given("--threads")) o.threads = static_cast<int>(to_integer("--threads", threads));
  if (o.assembly.empty()) throw UsageError(std::string("--assembly FILE is required\n") + kBearingUsage);
  if (o.frames && *o.frames < 1) throw UsageError("--frames must be >= 1, got " + std::to_string(*o.frames));
  if (!o.motion.empty() && o.frames) throw UsageError("--frames cannot be combined with --motion (the file gives the frames)");
  if (!o.fail_on.empty() && !parse_fail_on(o.fail_on))
    throw UsageError("--fail-on: '" + o.fail_on + "' is not a list of contact, clearance, undecided (comma-separated)");
  if (o.threads < 0) throw UsageError("--threads must be >= 0");
  return o;
}

}  // namespace interfere::mpi
