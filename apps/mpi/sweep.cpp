// interfere-mpi sweep (issue #31, item 3; docs/mpi.md, "Sweep path points"). probe::sweep decides
// every path point alone (pose_state and clearance_of at that pose) and every segment from its two
// end points alone (refine on path segment s, with the points' own verdicts): nothing is carried
// from point 0 (src/probe/sweep.cpp), so the path splits exactly in blocks. Rank k of K takes points
// [k n / K, (k + 1) n / K) and runs sweep on that sub-path with the request of `interfere sweep`;
// with the check between points the segment from a block's last point to the next block's first is
// the earlier rank's: its sub-path runs to that border point, whose own row is dropped (it is the
// next rank's) and whose candidate tests are taken off (sweep on that point alone). Rank 0 renumbers
// the segments, recounts the totals as sweep does, and writes the report through the CLI's writer
// (apps/cli/sweep_report.h).
//
// What is carried along the path is done whole on every rank before the blocks: a pose path's
// inverse kinematics (the paper's machine: the branch of the previous point; --interpolate joint on
// a DH arm: each point seeded with the previous point's solution), exactly as `interfere sweep`.
//
// Not offered (usage error, exit 2): re-planning (--replan-tilt, --replan-standoff,
// --replanned-path: the re-planned path is checked again whole after the sweep), --paper-levels
// (not split yet), the views (--html, --glb, --pvd), STEP workpieces (read by the CLI's CAD reader,
// which interfere-mpi does not link) and STEP tessellation options.
#include "sweep.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "args.h"
#include "block_outputs.h"
#include "driver.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/core/units.h"
#include "interfere/mesh/io.h"
#include "interfere/probe/export.h"
#include "interfere/probe/paper_machine.h"
#include "interfere/probe/sweep.h"
#include "interfere/robot/ik.h"
#include "report_envelope.h"
#include "sweep_inputs.h"
#include "sweep_report.h"
#include "usage.h"

namespace interfere::mpi {
namespace {

using namespace interfere::probe;
using Clock = std::chrono::steady_clock;

const char* const kSweepUsage =
    "usage: mpirun -n K interfere-mpi sweep --workpiece MESH --path FILE --probe-radius R --probe-length L\n"
    "         [the other options of `interfere sweep`] [--quiet]\n"
    "The path's points split in blocks per rank; the outputs are those of `interfere sweep` (docs/probe.md)\n"
    "plus \"mpi\" in the JSON. Not offered: --replan-tilt, --replan-standoff, --replanned-path, --paper-levels,\n"
    "--html, --glb, --pvd, STEP workpieces (docs/mpi.md, \"Sweep path points\").\n";

struct SweepArgs {
  cli::SweepOptions o;
  bool quiet = false;
};

SweepArgs parse_sweep(int argc, char** argv) {
  SweepArgs a;
  cli::SweepOptions& o = a.o;
  CLI::App app("interfere-mpi sweep");
  app.set_help_flag();
  bool help = false, version = false;
  std::string budget;
  app.add_flag("-h,--help", help);
  app.add_flag("--version", version);
  app.add_option("--workpiece", o.workpiece);
  app.add_option("--robot", o.robot);
  app.add_option("--path", o.path);
  app.add_option("--d1", o.d1);
  app.add_option("--d2", o.d2);
  app.add_option("--interpolate", o.interpolate);
  app.add_option("--probe-radius", o.probe_radius);
  app.add_option("--probe-length", o.probe_length);
  app.add_option("--holder-radius", o.holder_radius);
  app.add_option("--holder-length", o.holder_length);
  app.add_option("--holder-box", o.holder_box);
  app.add_option("--json", o.json);
  app.add_option("--csv", o.csv);
  app.add_option("--hits-obj", o.hits_obj);
  app.add_option("--probes-vtk", o.probes_vtk);
  app.add_option("--hierarchy", o.hierarchy);
  app.add_option("--patch-size", o.patch_size);
  app.add_option("--patch-rule", o.patch_rule);
  app.add_flag("--paper-levels", o.paper_levels);
  app.add_flag("--no-continuous", o.no_continuous);
  app.add_flag("--no-clearance", o.no_clearance);
  app.add_option("--max-clearance", o.max_clearance);
  app.add_option("--depth", o.depth);
  app.add_option("--max-poses", o.max_poses);
  app.add_option("--clearance", o.clearance);
  app.add_option("--replan-tilt", o.replan_tilt);
  app.add_option("--replan-standoff", o.replan_standoff);
  app.add_option("--replanned-path", o.replanned_path);
  app.add_option("--fail-on", o.fail_on);
  app.add_option("--threads", o.threads);
  app.add_option("--units", o.units);
  app.add_option("--units-workpiece", o.units_workpiece);
  app.add_option("--html", o.views.html);
  app.add_option("--glb", o.views.glb);
  app.add_option("--pvd", o.views.pvd);
  app.add_option("--view-budget", budget);
  app.add_flag("-q,--quiet", a.quiet);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    throw UsageError(std::string(e.what()) + "\n" + kSweepUsage);
  }
  if (help) throw InfoRequest{kSweepUsage};
  if (version) throw InfoRequest{std::string("interfere-mpi ") + INTERFERE_VERSION + "\n"};
  for (const char* flag : {"--replan-tilt", "--replan-standoff", "--replanned-path"})
    if (app.count(flag))
      throw UsageError(std::string(flag) +
                       ": not offered by interfere-mpi sweep: re-planning checks the re-planned path again, whole, "
                       "after the sweep: run `interfere sweep` (docs/mpi.md, \"Sweep path points\")");
  if (o.paper_levels)
    throw UsageError("--paper-levels: not offered by interfere-mpi sweep (not split across ranks yet): run `interfere "
                     "sweep --paper-levels` (docs/mpi.md, \"Sweep path points\")");
  for (const char* flag : {"--html", "--glb", "--pvd", "--view-budget"})
    if (app.count(flag))
      throw UsageError(std::string(flag) +
                       ": not offered by interfere-mpi sweep: views are drawn from one process's result: run `interfere "
                       "sweep` with --html/--glb/--pvd (docs/mpi.md, \"Options\")");
  if (o.workpiece.empty() || o.path.empty() || !app.count("--probe-radius") || !app.count("--probe-length"))
    throw UsageError(std::string("--workpiece, --path, --probe-radius and --probe-length are required\n") + kSweepUsage);
  if (!o.fail_on.empty() && !parse_fail_on(o.fail_on))
    throw UsageError("--fail-on: '" + o.fail_on + "' is not a list of contact, clearance, undecided (comma-separated)");
  if (o.threads < 0) throw UsageError("--threads must be >= 0");
  return a;
}

std::string lower_ext(const std::string& f) {
  std::string e = std::filesystem::path(f).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

double mm_per(const std::string& unit, const char* flag) {
  const std::optional<double> m = millimetres_per_unit(unit);
  if (!m) throw InputError(std::string(flag) + ": unknown unit '" + unit + "' (" + known_units() + ")");
  return *m;
}

// ---- the rows on the wire (plain bytes: every rank is the same build on the same kind of machine) ----
struct Writer {
  std::string b;
  template <class T> void put(const T& v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); }
  template <class T> void vec(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    b.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
};
struct Reader {
  std::string_view b;
  std::size_t at = 0;
  template <class T> void get(T& v) {
    if (at + sizeof v > b.size()) throw std::logic_error("interfere-mpi sweep: short rank message");
    std::memcpy(&v, b.data() + at, sizeof v);
    at += sizeof v;
  }
  template <class T> void vec(std::vector<T>& v) {
    std::uint64_t n = 0;
    get(n);
    if (at + n * sizeof(T) > b.size()) throw std::logic_error("interfere-mpi sweep: short rank message");
    v.resize(n);
    if (n) std::memcpy(v.data(), b.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
};

struct SweepHeader {
  std::uint64_t lo = 0, hi = 0, points = 0, segments = 0, candidate_tests = 0;
  double seconds = 0, cpu_seconds = 0, discrete = 0, clearance = 0, continuous = 0;
};

void put_point(Writer& w, const PointResult& p) {
  w.put(p.collides), w.put(p.inside), w.put(p.undecided), w.put(p.verdict), w.put(p.holder), w.put(p.clearance);
  w.put(p.triangle), w.put(p.patch), w.vec(p.hits), w.put(p.point_probe), w.put(p.point_workpiece);
}
void get_point(Reader& r, PointResult& p) {
  r.get(p.collides), r.get(p.inside), r.get(p.undecided), r.get(p.verdict), r.get(p.holder), r.get(p.clearance);
  r.get(p.triangle), r.get(p.patch), r.vec(p.hits), r.get(p.point_probe), r.get(p.point_workpiece);
}
void put_segment(Writer& w, const SegmentResult& s) {
  w.put(s.from), w.put(s.state), w.put(s.verdict), w.vec(s.intervals), w.vec(s.unresolved), w.put(s.smallest_gap);
  w.put(s.unresolved_motion), w.put(s.clearance_state), w.vec(s.clearance_intervals), w.vec(s.clearance_unresolved);
  w.put(s.between_samples), w.vec(s.triangles), w.put(s.poses_tested);
}
void get_segment(Reader& r, SegmentResult& s) {
  r.get(s.from), r.get(s.state), r.get(s.verdict), r.vec(s.intervals), r.vec(s.unresolved), r.get(s.smallest_gap);
  r.get(s.unresolved_motion), r.get(s.clearance_state), r.vec(s.clearance_intervals), r.vec(s.clearance_unresolved);
  r.get(s.between_samples), r.vec(s.triangles), r.get(s.poses_tested);
}

/// Points [lo, hi) of `path` (its poses, lines and joint rows).
ProbePath sub_path(const ProbePath& path, std::size_t lo, std::size_t hi) {
  ProbePath s;
  s.joint_space = path.joint_space;
  s.columns = path.columns;
  for (std::size_t i = lo; i < hi; ++i) {
    s.poses.push_back(path.poses[i]);
    s.lines.push_back(path.lines[i]);
    if (i < path.joints.size()) s.joints.push_back(path.joints[i]);
  }
  return s;
}

int run_checked(const World& world, const SweepArgs& a) {
  const auto t_total = Clock::now();
  const cli::SweepOptions& o = a.o;
  // ---- the inputs, as `interfere sweep` reads them: every rank, the ranks agreeing on any error ----
  std::string error;
  std::optional<Robot> robot;
  ProbePath path;
  TriMesh mesh;
  MeshReadInfo info;
  ProbeShape shape;
  Hierarchy hierarchy = Hierarchy::bvh;
  bool pose_input = false, joint_motion = false;
  std::string unit, unit_source;
  double workpiece_scale = 1, read_seconds = 0;
  FailOn failing;
  try {
    shape = cli::check_sweep_probe(o);
    if (!o.fail_on.empty()) failing = *parse_fail_on(o.fail_on);
    if (o.depth < 1 || o.depth > 40) throw InputError("--depth: must be in [1, 40]");
    const double working_mm = mm_per(o.units, "--units");
    for (const std::string* f : {&o.workpiece, &o.path, &o.robot})
      if (!f->empty() && !std::filesystem::is_regular_file(*f)) throw InputError(*f + ": no such file");
    const std::string ext = lower_ext(o.workpiece);
    if (ext == ".step" || ext == ".stp")
      throw InputError("--workpiece " + o.workpiece +
                       ": STEP workpieces are not offered by interfere-mpi sweep (the CLI's CAD reader is not linked "
                       "in): write it as a mesh (`interfere surface`) or run `interfere sweep`");
    if (!o.units_workpiece.empty()) {
      (void)mm_per(o.units_workpiece, "--units-workpiece");
      unit = o.units_workpiece, unit_source = "given (--units-workpiece)";
    } else if (ext == ".glb" || ext == ".gltf") {
      unit = "m", unit_source = "glTF (metres by its specification)";
    } else {
      unit = "mm", unit_source = "default (mm; give --units-a/--units-b when not)";
    }
    workpiece_scale = mm_per(unit, "--units-workpiece") / working_mm;
    hierarchy = cli::check_sweep_machine(o);
    // Outputs: their folders must exist, no output may be an input or another output.
    std::vector<std::pair<const char*, const std::string*>> outs{
        {"--json", &o.json}, {"--csv", &o.csv}, {"--hits-obj", &o.hits_obj}, {"--probes-vtk", &o.probes_vtk}};
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const auto& [flag, out] = outs[i];
      if (out->empty() || *out == "-") continue;
      const std::filesystem::path abs = std::filesystem::absolute(*out);
      if (!std::filesystem::is_directory(abs.parent_path()))
        throw InputError(std::string(flag) + " " + *out + ": no folder " + abs.parent_path().string());
      for (const std::string* input : {&o.workpiece, &o.path, &o.robot})
        if (!input->empty() && std::filesystem::absolute(*input) == abs)
          throw InputError(std::string(flag) + " " + *out + ": is an input file");
      for (std::size_t k = 0; k < i; ++k)
        if (!outs[k].second->empty() && *outs[k].second != "-" && std::filesystem::absolute(*outs[k].second) == abs)
          throw InputError(std::string(flag) + " and " + outs[k].first + " name the same file " + *out);
    }
    for (const std::string* f : {&o.hits_obj, &o.probes_vtk})
      if (!f->empty() && lower_ext(*f) != ".obj" && lower_ext(*f) != ".vtk")
        throw InputError(*f + ": unsupported extension (give .obj or .vtk)");
    const auto t_read = Clock::now();
    robot = cli::read_sweep_robot(o);
    // The motion between points and the inverse kinematics of a pose path: the whole path on every
    // rank (each point's solution follows the previous point's), as `interfere sweep`.
    cli::SweepPath swept = cli::read_sweep_path(o, robot ? &*robot : nullptr, shape);
    path = std::move(swept.path);
    pose_input = swept.pose_input, joint_motion = swept.joint_motion;
    auto m = read_mesh(o.workpiece, {}, &info);
    if (!m) throw InputError(m.error().message());
    mesh = std::move(*m);
    if (workpiece_scale != 1) cli::scale_workpiece(mesh.positions, workpiece_scale, o);
    read_seconds = std::chrono::duration<double>(Clock::now() - t_read).count();
  } catch (const InputError& e) {
    error = e.what();
  } catch (const cli::InputError& e) {  // (the checks and reads shared with interfere sweep: sweep_inputs.h)
    error = e.what();
  }
  for (const std::string& e : allgather(error))
    if (!e.empty()) throw InputError(e);
  std::unique_ptr<tbb::global_control> threads;
  if (o.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  const int thread_count = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  const Robot* motion_robot = joint_motion && robot ? &*robot : nullptr;

  // ---- this rank's block (every rank builds the whole workpiece's hierarchy) ----
  const Workpiece w = prepare_workpiece(std::move(mesh), shape,
                                        {.hierarchy = hierarchy, .patch_volume_ratio = o.patch_rule, .patch_volume = o.patch_size});
  const std::size_t n = path.size(), k = static_cast<std::size_t>(world.size), rank = static_cast<std::size_t>(world.rank);
  const std::size_t lo = rank * n / k, hi = (rank + 1) * n / k;
  if (world.rank == 0 && k > n && !a.quiet)
    std::fprintf(stderr, "[interfere-mpi] warning: %d ranks for %zu path points: %zu ranks idle\n", world.size, n, k - n);
  const bool border = !o.no_continuous && lo < hi && hi < n;
  const SweepRequest request = cli::sweep_request(o, shape);
  const auto t_run = Clock::now();
  SweepHeader head;
  head.lo = lo, head.hi = hi;
  Writer out;
  if (lo < hi) {
    const SweepResult r = sweep(w, sub_path(path, lo, hi + (border ? 1 : 0)), motion_robot, request);
    head.points = hi - lo, head.segments = r.segments.size();
    head.candidate_tests = r.candidate_tests;
    head.discrete = r.discrete_seconds, head.clearance = r.clearance_seconds, head.continuous = r.continuous_seconds;
    if (border) {
      // The border point's row is the next rank's: its exact tests are taken off (the same tests
      // at the same pose: sweep on that point alone, discrete pass only).
      SweepRequest one = request;
      one.continuous = false, one.clearance = false, one.clearance_limit = 0;
      head.candidate_tests -= sweep(w, sub_path(path, hi, hi + 1), motion_robot, one).candidate_tests;
    }
    for (std::size_t i = 0; i < hi - lo; ++i) put_point(out, r.points[i]);
    for (SegmentResult s : r.segments) {
      s.from += static_cast<std::uint32_t>(lo);
      put_segment(out, s);
    }
  }
  head.seconds = std::chrono::duration<double>(Clock::now() - t_run).count();
  head.cpu_seconds = cpu_seconds();
  const std::vector<std::string> all = gather_blocks(head, out.b);

  int status = 0;
  if (world.rank == 0) {
    // ---- merge in rank order (= point order), the totals counted as sweep counts them ----
    SweepResult r;
    nlohmann::json ranks = nlohmann::json::array();
    for (std::size_t q = 0; q < all.size(); ++q) {
      SweepHeader h;
      Reader in{block_rows(all[q], h)};
      for (std::uint64_t i = 0; i < h.points; ++i) get_point(in, r.points.emplace_back());
      for (std::uint64_t i = 0; i < h.segments; ++i) get_segment(in, r.segments.emplace_back());
      r.candidate_tests += h.candidate_tests;
      r.discrete_seconds += h.discrete, r.clearance_seconds += h.clearance, r.continuous_seconds += h.continuous;
      ranks.push_back({{"rank", q},
                       {"points", {h.lo, h.hi}},
                       {"seconds", h.seconds},
                       {"cpu_seconds", h.cpu_seconds}});
    }
    if (r.points.size() != n)
      throw std::logic_error("gathered " + std::to_string(r.points.size()) + " point rows, expected " + std::to_string(n));
    for (const PointResult& p : r.points) {
      r.colliding_points += p.collides, r.inside_points += p.inside, r.undecided_points += p.undecided;
      r.verdict = worst(r.verdict, p.verdict);
    }
    for (std::size_t s = 0; s < r.segments.size(); ++s) {
      const SegmentResult& g = r.segments[s];
      if (s > 0 && g.from <= r.segments[s - 1].from) throw std::logic_error("segment rows out of order");
      r.verdict = worst(r.verdict, g.verdict);
      r.colliding_segments += g.state == SegmentState::collides;
      r.unresolved_segments += g.state == SegmentState::unresolved;
      r.between_samples_segments += g.between_samples;
    }
    for (const std::string& text : w.warnings)
      if (!a.quiet) std::fprintf(stderr, "interfere: warning: %s\n", text.c_str());
    status = verdict_exit_status(r.verdict, failing);
    const std::vector<PaperPointCheck> paper;
    const ReplanRequest replan_request;
    const ReplanResult replanned;
    const SweepResult after;
    const cli::SweepRun run{.o = o,
                            .format = mesh_format_name(info.format),
                            .unit = unit,
                            .unit_source = unit_source,
                            .workpiece_scale = workpiece_scale,
                            .linear_deflection = 0,
                            .w = w,
                            .path = path,
                            .pose_input = pose_input,
                            .robot = robot ? &*robot : nullptr,
                            .shape = shape,
                            .hierarchy = hierarchy,
                            .joint_motion = joint_motion,
                            .threads = thread_count,
                            .r = r,
                            .paper = paper,
                            .replanning = false,
                            .replan_request = replan_request,
                            .replanned = replanned,
                            .after = after,
                            .read_seconds = read_seconds,
                            .total_seconds = std::chrono::duration<double>(Clock::now() - t_total).count(),
                            .status = status};
    const BlockOutputs outputs{.json = o.json, .csv = o.csv, .quiet = a.quiet, .start = t_total};
    write_block_reports(world, outputs, std::move(ranks), [&] { return cli::sweep_report_json(run); },
                        [&] { return cli::sweep_report_csv(path, r); });
    if (const Status s = cli::write_sweep_geometry(o, w, path, motion_robot, shape, r); !s)
      throw std::runtime_error(s.error().message());
    print_block_summary(world, outputs, [&] { cli::print_sweep_summary(run); });
  }
  return broadcast(status);
}

}  // namespace

int run_sweep(const World& w, int argc, char** argv) {
  return run_guarded(w, [&] { return run_checked(w, parse_sweep(argc, argv)); });
}

}  // namespace interfere::mpi
