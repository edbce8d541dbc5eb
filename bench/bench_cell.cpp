// The full inspection cell target of issue #28: "a 6R arm with 7 link meshes of ~5k triangles each,
// fixtures, a 10^6-triangle workpiece, 10^5 path points including between points: <= 5 s". Its
// own executable `interfere_bench_cell` (bench/CMakeLists.txt; this file compiles to nothing inside
// interfere_bench); bench/probe_tables.py runs it and writes the verdict into docs/probe.md.
//
// Generated inputs (not shipped): the example cell of examples/probe (UR5-type arm of arm6r.urdf,
// probe r 8 x 50 and holder r 20 x 80 on tool0, the clamp) with every link mesh refined by midpoint
// subdivision (each triangle into 4, same shape) to within [1/2, 2) x 5,000 triangles, the plate
// with its rib as two finely divided closed boxes (1,017,600 triangles), and two more fixtures
// (boxes of 4,800 triangles) beside the plate. The path: a raster over the plate (y = -150..150 mm, x =
// 350..700 mm), tip 10 mm above the plate, probe pointing down, joints by the numerical inverse
// kinematics (robot/ik.h; untimed setup): it crosses the rib (probe strikes) and passes the clamp
// (holder strikes). INTERFERE_CELL_POINTS overrides the 10^5 points.
//
// Rows (wall time, oneTBB default threads, one iteration each):
//   CellFull/discrete     cell_scene + check_cell_path at every path point (certified distances
//                         carried across points, the engine only where no certificate holds)
//   CellFull/continuous   the same + the conservative check between points (robot/cell.h)
//   CellPlain/2, /3       (INTERFERE_CELL_PLAIN=1 only) the plain run: clash_scene at every point,
//                         check_between_points from scratch
// Counters: points, bodies, triangles, link triangles, colliding points / segments, unresolved,
// seconds per phase, process CPU seconds, certificates (BVH queries), engine pair decisions,
// segments proven clear by the points' certificates alone.
#ifdef INTERFERE_BENCH_CELL
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include "interfere/mesh/generate.h"
#include "interfere/probe/path.h"
#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"

using namespace interfere;
using namespace interfere::robot;

namespace {

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Midpoint subdivision: every triangle into four (shared edge midpoints), same surface.
TriMesh subdivide(const TriMesh& m) {
  TriMesh out;
  out.positions = m.positions;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const auto i = static_cast<std::uint32_t>(out.positions.size());
    out.positions.push_back((m.positions[a] + m.positions[b]) * 0.5);
    mid.emplace(key, i);
    return i;
  };
  out.triangles.reserve(m.triangles.size() * 4);
  for (const Tri& t : m.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

/// Subdivided until the triangle count is nearest to `target` (in ratio).
TriMesh refine_to(TriMesh m, std::size_t target) {
  while (m.num_triangles() * 2 < target) m = subdivide(m);  // 4x per level: stop within [1/2, 2) x target
  return m;
}

/// Both closed boxes in one mesh (two components).
TriMesh merged(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const auto off = static_cast<std::uint32_t>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  return m;
}

struct FullCell {
  Cell cell;
  JointPath path;
  std::size_t link_triangles = 0, total_triangles = 0;
};

const FullCell& full_cell() {
  static std::unique_ptr<FullCell> fc;
  if (fc) return *fc;
  fc = std::make_unique<FullCell>();
  const std::filesystem::path dir = std::filesystem::path(INTERFERE_SOURCE_DIR) / "examples" / "probe";
  Expected<Cell> c = read_cell_json(dir / "cell.json");
  if (!c) throw std::runtime_error(c.error().message());
  fc->cell = std::move(*c);
  Cell& cell = fc->cell;
  for (ChainLink& l : cell.robot.links) {
    if (!l.mesh) continue;
    l.mesh = std::make_shared<const TriMesh>(refine_to(*l.mesh, 5000));
    fc->link_triangles += l.mesh->num_triangles();
  }
  // The example's plate (600 x 400 x 20 mm, top z = 0) and rib (x 480..520, up to z = 40) as two
  // finely divided closed boxes: 940,800 + 76,800 = 1,017,600 triangles.
  cell.workpiece.mesh = std::make_shared<const TriMesh>(
      merged(make_box({250, -200, -20}, {850, 200, 0}, 280), make_box({480, -200, 0}, {520, 200, 40}, 80)));
  CellObject a{.id = "post_a", .file = "", .mesh = std::make_shared<const TriMesh>(make_box({300, 220, -20}, {360, 280, 120}, 20)), .pose = {}};
  CellObject b{.id = "post_b", .file = "", .mesh = std::make_shared<const TriMesh>(make_box({760, -280, -20}, {820, -220, 120}, 20)), .pose = {}};
  cell.fixtures.push_back(a);
  cell.fixtures.push_back(b);
  fc->total_triangles = fc->link_triangles + cell.workpiece.mesh->num_triangles();
  for (const CellObject& f : cell.fixtures) fc->total_triangles += f.mesh->num_triangles();
  // The raster (boustrophedon): lines along x at y = -150..150, tip 10 mm above the plate.
  const std::size_t points = std::getenv("INTERFERE_CELL_POINTS")
                                 ? static_cast<std::size_t>(std::atof(std::getenv("INTERFERE_CELL_POINTS")))
                                 : 100000;
  const std::size_t lines = std::max<std::size_t>(1, points / 1000), per = points / lines;
  probe::ProbePath poses;
  poses.joint_space = false;
  for (std::size_t k = 0; k < lines; ++k) {
    const double y = lines > 1 ? -150.0 + 300.0 * static_cast<double>(k) / static_cast<double>(lines - 1) : 0.0;
    for (std::size_t j = 0; j < per; ++j) {
      const double u = per > 1 ? static_cast<double>(j) / static_cast<double>(per - 1) : 0.0;
      const double x = 350.0 + 350.0 * (k % 2 ? 1.0 - u : u);
      probe::ProbePose p;
      p.tip = {x, y, 10.0};
      p.axis = {0, 0, -1};
      poses.poses.push_back(p);
      poses.lines.push_back(static_cast<std::int64_t>(poses.poses.size()));
    }
  }
  IkOptions o;
  o.start = {-18, -93, 141, -138, -90, 162};  // path.csv's first row: the elbow-up branch
  Expected<PoseIkPath> r = pose_path_to_joints(cell.robot, cell.base, cell_ik_tool(cell), poses, "raster", o);
  if (!r) throw std::runtime_error(r.error().message());
  fc->path = std::move(r->path);
  return *fc;
}

void BM_CellFull(benchmark::State& state) {
  const bool continuous = state.range(0) % 2 != 0;
  const bool plain = state.range(0) >= 2;  // the plain run: clash_scene at every frame, check_between_points
  const FullCell& fc = full_cell();
  double scene_s = 0, discrete_s = 0, between_s = 0, certify_s = 0, cpu = 0;
  std::size_t certificates = 0, queries = 0, engine_pairs = 0, certified_segments = 0;
  std::size_t colliding = 0, seg_collide = 0, seg_unresolved = 0, frames_checked = 0, engine_frames = 0, bodies = 0;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const CellScene cs = cell_scene(fc.cell, fc.path);
    const auto t1 = std::chrono::steady_clock::now();
    scene::SceneClashOptions opt;
    opt.curves = false;
    opt.reference = false;
    opt.depth = false;  // as `interfere cell` without --depth
    PathCheckOptions po;
    po.engine = opt;
    po.between = continuous;
    po.accelerate = !plain;
    PathCheckResult pr = check_cell_path(fc.cell, cs, fc.path, po);
    cpu = process_cpu_seconds() - c0;
    const scene::SceneClashResult& r = pr.frames;
    const std::vector<SegmentResult>& segs = pr.segments;
    scene_s = std::chrono::duration<double>(t1 - t0).count();
    discrete_s = pr.certify_seconds + pr.engine_seconds;
    between_s = pr.between_seconds;
    certify_s = pr.certify_seconds;
    certificates = pr.certificates, queries = pr.bvh_queries, engine_pairs = pr.engine_pair_frames;
    certified_segments = pr.segments_certified;
    colliding = 0;
    for (const scene::FrameRow& f : r.frames) colliding += f.verdict == Verdict::clash;
    seg_collide = seg_unresolved = frames_checked = engine_frames = 0;
    for (const SegmentResult& s : segs) {
      seg_collide += s.state == SegmentState::collides;
      seg_unresolved += s.state == SegmentState::unresolved;
      frames_checked += s.frames;
      engine_frames += s.engine_frames;
    }
    bodies = cs.scene.bodies.size();
    benchmark::DoNotOptimize(colliding);
  }
  state.counters["points"] = static_cast<double>(fc.path.size());
  state.counters["bodies"] = static_cast<double>(bodies);
  state.counters["triangles"] = static_cast<double>(fc.total_triangles);
  state.counters["link_triangles"] = static_cast<double>(fc.link_triangles);
  state.counters["workpiece_triangles"] = static_cast<double>(fc.cell.workpiece.mesh->num_triangles());
  state.counters["colliding_points"] = static_cast<double>(colliding);
  state.counters["colliding_segments"] = static_cast<double>(seg_collide);
  state.counters["unresolved_segments"] = static_cast<double>(seg_unresolved);
  state.counters["between_frames"] = static_cast<double>(frames_checked);
  state.counters["between_engine_frames"] = static_cast<double>(engine_frames);
  state.counters["scene_seconds"] = scene_s;
  state.counters["discrete_seconds"] = discrete_s;
  state.counters["between_seconds"] = between_s;
  state.counters["process_cpu_seconds"] = cpu;
  state.counters["certify_seconds"] = certify_s;
  state.counters["certificates"] = static_cast<double>(certificates);
  state.counters["bvh_queries"] = static_cast<double>(queries);
  state.counters["engine_pair_frames"] = static_cast<double>(engine_pairs);
  state.counters["certified_segments"] = static_cast<double>(certified_segments);
  state.SetLabel(std::string(plain ? "plain " : "") + (continuous ? "continuous" : "discrete"));
}

BENCHMARK(BM_CellFull)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
// The plain run (every frame by the engine, every segment by check_between_points from scratch),
// for comparison, with INTERFERE_CELL_PLAIN=1 only (about half a minute at 10^5 points).
const bool kPlainRows = std::getenv("INTERFERE_CELL_PLAIN") &&
                        benchmark::RegisterBenchmark("BM_CellPlain", BM_CellFull)
                            ->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
#endif  // INTERFERE_BENCH_CELL
