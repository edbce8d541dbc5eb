// Probe path checking benchmarks (issue #5, item 6 and targets), its own executable
// `interfere_bench_probe` (bench/CMakeLists.txt, last block; the file compiles to nothing inside
// interfere_bench). bench/probe_tables.py runs it and regenerates docs/probe.md's tables.
//
// Cases: the three generated panels and paths of probe/generate.h (576 / 1,152 / 2,784 triangles,
// 872 / 1,430 / 2,366 points), a probe of radius 5 and length 40 with a holder (radius 12, length
// 30). Rows (all wall time, oneTBB default threads unless the name says threads:1):
//   ProbeDiscrete/<case>/<hierarchy>    all path points, decisions only (the paper's measurement)
//   ProbeContinuous/<case>              decisions + continuous check between points (BVH)
//   ProbeFull/<case>                    decisions + continuous + clearance of every point (BVH)
//   ProbeBuild/<case>/<hierarchy>       building the hierarchy
//   ProbePatches/<case>/<ratio>         the paper's patches at box/probe volume 8, 33, 100
//   ProbePaperLevels/<case>/<level>/<path>/<ratio>  the paper's Table 1 levels timed one at a time
//                                       (issue #28): 1 = §3.2 probe box vs patch boxes (box volume =
//                                       ratio 8, 33 or 100 x probe volume, as Table 1) at every
//                                       point, 2 = §3.3 triangle/box for the triangles of the patches
//                                       that passed, 3 = §3.4 three projections for the triangles that
//                                       passed, 0 = the exact cylinder-triangle test on those same
//                                       triangles; path 0 = the standard path (stand-off 10 mm = 2
//                                       probe radii), 1 = a near path (stand-off 1 mm, the probe
//                                       tilted 30 degrees about its tip) where most points reach
//                                       level 3. Probe only (the paper has no holder).
//   ProbeReplan/<case>/<standoff>       re-planning every colliding point (probe/replan.h; issue #28,
//                                       deliverable 4): tilt cone 15 degrees, stand-off range
//                                       0..<standoff> mm; counters: colliding points, found, ms each
//   ProbeNear/<case>/<hierarchy>        Tables 2-3 on near-surface paths (issue #28, deliverable
//                                       5): the same rasters with the tip 2 mm from the surface and
//                                       the probe tilted 20 degrees about its tip (within 2 probe
//                                       radii; most points have a triangle in the probe's or the
//                                       holder's box), probe + holder, decisions only; the patches at
//                                       the paper's Table 2 ratios (31, 35, 32)
//   ProbeNearContinuous/<case>          the same + the continuous check between points (BVH)
//   ProbeScaling                        10^6-triangle saddle, 10^5 points: build + decisions +
//                                       continuous check (INTERFERE_PROBE_SCALING_TRIANGLES /
//                                       _POINTS override the sizes)
#ifdef INTERFERE_BENCH_PROBE
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>

#include "interfere/probe/generate.h"
#include "interfere/probe/paper_tests.h"
#include "interfere/probe/replan.h"
#include "interfere/probe/sweep.h"

using namespace interfere;
using namespace interfere::probe;

namespace {

const ProbeShape kProbe{.radius = 5, .length = 40, .holder_radius = 12, .holder_length = 30};

struct Case {
  PanelCase spec;
  TriMesh mesh;
  ProbePath path;
  Robot robot;
};

const Case& get_case(int i) {
  static std::map<int, std::unique_ptr<Case>> cache;
  auto& c = cache[i];
  if (!c) {
    c = std::make_unique<Case>();
    c->spec = paper_cases()[i];
    c->mesh = make_panel(c->spec.kind, c->spec.nu, c->spec.nv);
    c->path = make_panel_path(c->spec.kind, c->spec.path);
    c->robot = pivot_machine(c->spec.path.pivot_to_tip);
  }
  return *c;
}

const Workpiece& get_workpiece(int i, Hierarchy h, double ratio = 33) {
  static std::map<std::tuple<int, int, double>, std::unique_ptr<Workpiece>> cache;
  auto& w = cache[{i, static_cast<int>(h), ratio}];
  if (!w) {
    w = std::make_unique<Workpiece>(
        prepare_workpiece(get_case(i).mesh, kProbe, {.hierarchy = h, .patch_volume_ratio = ratio}));
  }
  return *w;
}

void counters(benchmark::State& state, const Case& c, const Workpiece& w, const SweepResult& r) {
  state.counters["triangles"] = static_cast<double>(c.mesh.num_triangles());
  state.counters["points"] = static_cast<double>(c.path.size());
  state.counters["colliding_points"] = static_cast<double>(r.colliding_points);
  state.counters["colliding_segments"] = static_cast<double>(r.colliding_segments);
  state.counters["between_samples"] = static_cast<double>(r.between_samples_segments);
  state.counters["candidate_tests"] = static_cast<double>(r.candidate_tests);
  state.counters["patches"] = static_cast<double>(w.patches.size());
  state.counters["exact_fallbacks"] = static_cast<double>(cylinder_exact_fallbacks());
}

void BM_ProbeDiscrete(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const auto h = static_cast<Hierarchy>(state.range(1));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, h);
  SweepResult r;
  for (auto _ : state) {
    r = sweep(w, c.path, &c.robot, {.probe = kProbe, .continuous = false, .clearance = false});
    benchmark::DoNotOptimize(r.colliding_points);
  }
  counters(state, c, w, r);
  state.SetLabel(c.spec.name + "/" + hierarchy_name(h));
}

void BM_ProbeContinuous(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::bvh);
  SweepResult r;
  for (auto _ : state) {
    r = sweep(w, c.path, &c.robot, {.probe = kProbe, .continuous = true, .clearance = false});
    benchmark::DoNotOptimize(r.colliding_segments);
  }
  counters(state, c, w, r);
  state.SetLabel(c.spec.name);
}

void BM_ProbeFull(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::bvh);
  SweepResult r;
  for (auto _ : state) {
    r = sweep(w, c.path, &c.robot, {.probe = kProbe, .continuous = true, .clearance = true});
    benchmark::DoNotOptimize(r.colliding_segments);
  }
  counters(state, c, w, r);
  double min_clear = INFINITY;
  for (const PointResult& p : r.points) min_clear = std::min(min_clear, p.collides ? 0.0 : p.clearance);
  state.counters["clearance_seconds"] = r.clearance_seconds;
  state.SetLabel(c.spec.name);
}

void BM_ProbeReplan(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::bvh);
  const SweepResult r = sweep(w, c.path, &c.robot, {.probe = kProbe, .continuous = false, .clearance = false});
  const ReplanRequest rq{.max_tilt_deg = 15, .standoff_min = 0, .standoff_max = static_cast<double>(state.range(1))};
  ReplanResult p;
  for (auto _ : state) {
    p = replan(w, c.path, &c.robot, kProbe, r, rq);
    benchmark::DoNotOptimize(p.found);
  }
  std::size_t tested = 0;
  for (const ReplannedPoint& q : p.points) tested += q.poses_tested;
  state.counters["colliding_points"] = static_cast<double>(p.points.size());
  state.counters["found"] = static_cast<double>(p.found);
  state.counters["poses_tested"] = static_cast<double>(tested);
  state.counters["ms_per_point"] = p.points.empty() ? 0.0 : 1e3 * p.seconds / static_cast<double>(p.points.size());
  state.SetLabel(c.spec.name);
}

void BM_ProbeBuild(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const auto h = static_cast<Hierarchy>(state.range(1));
  const Case& c = get_case(i);
  for (auto _ : state) {
    Workpiece w = prepare_workpiece(c.mesh, kProbe, {.hierarchy = h});
    benchmark::DoNotOptimize(w.bvh.nodes.data());
  }
  state.SetLabel(c.spec.name + "/" + hierarchy_name(h));
}

void BM_ProbePatches(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const double ratio = static_cast<double>(state.range(1));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::patches, ratio);
  SweepResult r;
  for (auto _ : state) {
    r = sweep(w, c.path, &c.robot, {.probe = kProbe, .continuous = false, .clearance = false});
    benchmark::DoNotOptimize(r.colliding_points);
  }
  counters(state, c, w, r);
  state.counters["ratio"] = ratio;
  double tris = 0;
  for (const auto& t : w.patches.tris) tris += static_cast<double>(t.size());
  state.counters["triangles_per_patch"] = tris / static_cast<double>(std::max<std::size_t>(1, w.patches.size()));
  state.SetLabel(c.spec.name + "/" + std::to_string(state.range(1)));
}

/// The inputs of each paper level for one case and path, computed once (untimed).
struct LevelInputs {
  std::vector<Cylinder> probes;
  std::vector<Aabb> probe_boxes;
  std::vector<std::vector<std::uint32_t>> patches;    ///< per point: patches passing level 1
  std::vector<std::vector<std::uint32_t>> triangles;  ///< per point: triangles passing level 2
  std::size_t level3_passed = 0, exact_hits = 0, points_reaching_3 = 0;
};

/// The near path: stand-off 1 mm, each pose's axis tilted by 30 degrees about the tip.
ProbePath near_path(const Case& c) {
  PanelPathOptions o = c.spec.path;
  o.standoff = 1.0;
  ProbePath p = make_panel_path(c.spec.kind, o);
  p.joint_space = false;
  p.joints.clear();
  for (ProbePose& q : p.poses) {
    const Vec3 a = q.axis;
    Vec3 e = cross(a, std::fabs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    e = e / norm(e);
    q.axis = a * std::cos(M_PI / 6) + e * std::sin(M_PI / 6);
  }
  return p;
}

const LevelInputs& level_inputs(int i, int near, double ratio) {
  static std::map<std::tuple<int, int, double>, std::unique_ptr<LevelInputs>> cache;
  auto& in = cache[{i, near, ratio}];
  if (in) return *in;
  in = std::make_unique<LevelInputs>();
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::patches, ratio);
  const ProbePath path = near ? near_path(c) : c.path;
  for (const ProbePose& q : path.poses) {
    const Cylinder cyl = cylinder_from_tip(q.tip, q.axis, kProbe.length, kProbe.radius);
    const Aabb box = paper_cylinder_box(cyl);
    in->probes.push_back(cyl);
    in->probe_boxes.push_back(box);
    std::vector<std::uint32_t> ps, ts;
    for (std::uint32_t p = 0; p < w.patches.size(); ++p) {
      if (paper_box_test(box, w.patches.boxes[p]) || paper_box_test(w.patches.boxes[p], box)) ps.push_back(p);
    }
    for (std::uint32_t p : ps) {
      for (std::uint32_t t : w.patches.tris[p]) {
        if (paper_triangle_box_test(w.mesh.corners(t), box)) ts.push_back(t);
      }
    }
    bool any3 = false;
    for (std::uint32_t t : ts) {
      const bool pass = paper_projections(cyl, w.mesh.corners(t)).all();
      in->level3_passed += pass;
      any3 = any3 || pass;
      in->exact_hits += cylinder_triangle_intersect(cyl, w.mesh.corners(t));
    }
    in->points_reaching_3 += !ts.empty();
    in->patches.push_back(std::move(ps));
    in->triangles.push_back(std::move(ts));
  }
  return *in;
}

void BM_ProbePaperLevels(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0)), level = static_cast<int>(state.range(1));
  const int near = static_cast<int>(state.range(2));
  const double ratio = static_cast<double>(state.range(3));
  const Workpiece& w = get_workpiece(i, Hierarchy::patches, ratio);
  const LevelInputs& in = level_inputs(i, near, ratio);
  std::size_t passed = 0, work = 0;
  for (auto _ : state) {
    passed = 0, work = 0;
    for (std::size_t k = 0; k < in.probes.size(); ++k) {
      if (level == 1) {
        for (std::uint32_t p = 0; p < w.patches.size(); ++p) {
          ++work;
          passed += paper_box_test(in.probe_boxes[k], w.patches.boxes[p]) ||
                    paper_box_test(w.patches.boxes[p], in.probe_boxes[k]);
        }
      } else if (level == 2) {
        for (std::uint32_t p : in.patches[k]) {
          for (std::uint32_t t : w.patches.tris[p]) {
            ++work;
            passed += paper_triangle_box_test(w.mesh.corners(t), in.probe_boxes[k]);
          }
        }
      } else {
        for (std::uint32_t t : in.triangles[k]) {
          ++work;
          passed += level == 3 ? paper_projections(in.probes[k], w.mesh.corners(t)).all()
                               : cylinder_triangle_intersect(in.probes[k], w.mesh.corners(t));
        }
      }
    }
    benchmark::DoNotOptimize(passed);
  }
  state.counters["tests"] = static_cast<double>(work);
  state.counters["passed"] = static_cast<double>(passed);
  state.counters["points"] = static_cast<double>(in.probes.size());
  state.counters["points_reaching_3"] = static_cast<double>(in.points_reaching_3);
  state.counters["patches"] = static_cast<double>(w.patches.size());
  state.counters["ratio"] = ratio;
  state.SetLabel(get_case(i).spec.name + "/" + std::to_string(level) + (near ? "/near/" : "/standard/") +
                 std::to_string(state.range(3)));
}

/// CPU seconds of the whole process (every thread, user + system): on a shared machine the wall
/// time includes waiting for the cores, this does not.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Table 2's box / probe volume ratios of the paper, per case (31, 35, 32).
double paper_ratio(int i) {
  static const double r[] = {31, 35, 32};
  return r[i];
}

/// The near-surface path of Tables 2-3 (issue #28): the standard raster's poses with the tip 2 mm
/// from the surface along its normal (the colliding points keep their depth) and the axis tilted
/// 20 degrees about the tip; a pose path (straight pose interpolation between points).
const ProbePath& near_surface_path(int i) {
  static std::map<int, std::unique_ptr<ProbePath>> cache;
  auto& p = cache[i];
  if (p) return *p;
  const Case& c = get_case(i);
  PanelPathOptions o = c.spec.path;
  o.standoff = 2.0;
  p = std::make_unique<ProbePath>(make_panel_path(c.spec.kind, o));
  p->joint_space = false;
  p->joints.clear();
  for (ProbePose& q : p->poses) {
    const Vec3 a = q.axis;
    Vec3 e = cross(a, std::fabs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    e = e / norm(e);
    q.axis = a * std::cos(M_PI / 9) + e * std::sin(M_PI / 9);
  }
  return *p;
}

/// Points of `path` with a triangle whose box meets the box of the probe or of the holder: the
/// points where any candidate search must run at least one exact test (method-independent).
std::size_t points_reaching_exact(const TriMesh& mesh, const ProbePath& path) {
  std::vector<Aabb> boxes(mesh.num_triangles());
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    for (const Vec3& v : mesh.corners(t)) boxes[t].expand(v);
  }
  std::size_t n = 0;
  for (const ProbePose& q : path.poses) {
    const Cylinder probe = cylinder_from_tip(q.tip, q.axis, kProbe.length, kProbe.radius);
    const Cylinder holder = cylinder_from_tip(q.tip - q.axis * kProbe.length, q.axis, kProbe.holder_length,
                                              kProbe.holder_radius);
    const Aabb bp = paper_cylinder_box(probe), bh = paper_cylinder_box(holder);
    bool any = false;
    for (std::uint32_t t = 0; t < mesh.num_triangles() && !any; ++t) any = boxes[t].overlaps(bp) || boxes[t].overlaps(bh);
    n += any;
  }
  return n;
}

void BM_ProbeNear(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const auto h = static_cast<Hierarchy>(state.range(1));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, h, h == Hierarchy::patches ? paper_ratio(i) : 33);
  const ProbePath& path = near_surface_path(i);
  SweepResult r;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    r = sweep(w, path, nullptr, {.probe = kProbe, .continuous = false, .clearance = false});
    benchmark::DoNotOptimize(r.colliding_points);
  }
  state.counters["process_cpu_ms"] = 1e3 * (process_cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
  counters(state, c, w, r);
  state.counters["points"] = static_cast<double>(path.size());
  static std::map<int, std::size_t> reaching;
  if (!reaching.count(i)) reaching[i] = points_reaching_exact(c.mesh, path);
  state.counters["reaching_exact"] = static_cast<double>(reaching[i]);
  state.counters["ratio"] = h == Hierarchy::patches ? paper_ratio(i) : 0;
  double tris = 0;
  for (const auto& t : w.patches.tris) tris += static_cast<double>(t.size());
  state.counters["triangles_per_patch"] = tris / static_cast<double>(std::max<std::size_t>(1, w.patches.size()));
  state.SetLabel(c.spec.name + "/near/" + hierarchy_name(h));
}

void BM_ProbeNearBuild(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const auto h = static_cast<Hierarchy>(state.range(1));
  const Case& c = get_case(i);
  for (auto _ : state) {
    Workpiece w = prepare_workpiece(
        c.mesh, kProbe, {.hierarchy = h, .patch_volume_ratio = h == Hierarchy::patches ? paper_ratio(i) : 33});
    benchmark::DoNotOptimize(w.bvh.nodes.data());
  }
  state.SetLabel(c.spec.name + "/" + hierarchy_name(h));
}

void BM_ProbeNearContinuous(benchmark::State& state) {
  const int i = static_cast<int>(state.range(0));
  const Case& c = get_case(i);
  const Workpiece& w = get_workpiece(i, Hierarchy::bvh);
  const ProbePath& path = near_surface_path(i);
  SweepResult r;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    r = sweep(w, path, nullptr, {.probe = kProbe, .continuous = true, .clearance = false});
    benchmark::DoNotOptimize(r.colliding_segments);
  }
  state.counters["process_cpu_ms"] = 1e3 * (process_cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
  counters(state, c, w, r);
  state.counters["points"] = static_cast<double>(path.size());
  state.counters["unresolved_segments"] = static_cast<double>(r.unresolved_segments);
  state.SetLabel(c.spec.name + "/near");
}

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v ? static_cast<std::size_t>(std::atof(v)) : fallback;
}

void BM_ProbeScaling(benchmark::State& state) {
  const std::size_t tris = env_size("INTERFERE_PROBE_SCALING_TRIANGLES", 1000000);
  const std::size_t pts = env_size("INTERFERE_PROBE_SCALING_POINTS", 100000);
  // Saddle of 2 nu nv triangles with nu = nv; raster of 100 lines.
  const int nu = static_cast<int>(std::lround(std::sqrt(tris / 2.0)));
  const TriMesh mesh = make_panel(PanelKind::saddle, nu, nu);
  const int lines = 100;
  const ProbePath path = make_panel_path(
      PanelKind::saddle, {.lines = lines, .points_per_line = static_cast<int>(pts / lines), .collide_every = 997});
  const Robot robot = pivot_machine(150);
  double build = 0, discrete = 0, continuous = 0;
  SweepResult r;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    Workpiece w = prepare_workpiece(mesh, kProbe);
    build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r = sweep(w, path, &robot, {.probe = kProbe, .continuous = true, .clearance = false});
    discrete = r.discrete_seconds, continuous = r.continuous_seconds;
    benchmark::DoNotOptimize(r.colliding_points);
  }
  state.counters["triangles"] = static_cast<double>(mesh.num_triangles());
  state.counters["points"] = static_cast<double>(path.size());
  state.counters["build_seconds"] = build;
  state.counters["discrete_seconds"] = discrete;
  state.counters["continuous_seconds"] = continuous;
  state.counters["colliding_points"] = static_cast<double>(r.colliding_points);
  state.counters["colliding_segments"] = static_cast<double>(r.colliding_segments);
}

void register_all() {
  const Hierarchy hs[] = {Hierarchy::bvh, Hierarchy::patches, Hierarchy::grid, Hierarchy::distance_field,
                          Hierarchy::brute_force};
  for (int i = 0; i < 3; ++i) {
    for (Hierarchy h : hs) {
      benchmark::RegisterBenchmark("ProbeDiscrete", BM_ProbeDiscrete)
          ->Args({i, static_cast<long>(h)})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(0.3);
    }
    benchmark::RegisterBenchmark("ProbeContinuous", BM_ProbeContinuous)->Arg(i)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.3);
    benchmark::RegisterBenchmark("ProbeFull", BM_ProbeFull)->Arg(i)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.3);
    for (Hierarchy h : hs) {
      benchmark::RegisterBenchmark("ProbeBuild", BM_ProbeBuild)
          ->Args({i, static_cast<long>(h)})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(h == Hierarchy::distance_field ? 1 : 20);
    }
    for (long ratio : {8L, 33L, 100L}) {
      benchmark::RegisterBenchmark("ProbePatches", BM_ProbePatches)->Args({i, ratio})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.2);
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (long near : {0L, 1L}) {
      for (long ratio : {8L, 33L, 100L}) {
        for (long level : {1L, 2L, 3L, 0L}) {
          benchmark::RegisterBenchmark("ProbePaperLevels", BM_ProbePaperLevels)
              ->Args({i, level, near, ratio})
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime()
              ->MinTime(0.05);
        }
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (Hierarchy h : hs) {
      benchmark::RegisterBenchmark("ProbeNear", BM_ProbeNear)
          ->Args({i, static_cast<long>(h)})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(0.3);
      benchmark::RegisterBenchmark("ProbeNearBuild", BM_ProbeNearBuild)
          ->Args({i, static_cast<long>(h)})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(h == Hierarchy::distance_field ? 1 : 20);
    }
    benchmark::RegisterBenchmark("ProbeNearContinuous", BM_ProbeNearContinuous)
        ->Arg(i)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(0.3);
  }
  for (long standoff : {0L, 3L})
    benchmark::RegisterBenchmark("ProbeReplan", BM_ProbeReplan)->Args({2, standoff})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.3);
  benchmark::RegisterBenchmark("ProbeScaling", BM_ProbeScaling)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
}

const bool registered = (register_all(), true);

}  // namespace
#endif  // INTERFERE_BENCH_PROBE
