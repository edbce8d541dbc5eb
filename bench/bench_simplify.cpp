// Simplification benchmarks (issue #6, item 8): interfere's feature-preserving QEM against
// meshoptimizer 0.18 (meshopt_simplify) and the OpenMesh 9 Decimater (ModQuadric) in the same run,
// on bumpy spheres of 1e5 and 1e6 triangles to 1 % and 10 % (an equatorial patch x > 0.98, |z| < 0.05
// is the feature region, weighted for interfere, unknown to the peers; interfere_plain ignores it), and on the casing generated
// with OCCT reproducing the paper's 35,548 -> 5,200 case for two process steps; plus feature
// recognition on a 513-face part. Its own executable, interfere_bench_simplify; bench/
// simplify_tables.py runs it and regenerates docs/simplify.md.
//
// Repetitions: interfere and meshoptimizer rows are the mean of 3 (1e6) or 5 (1e5) runs, the casing
// rows (interfere's modes and meshoptimizer on the welded part) of 20, OpenMesh runs once on the
// spheres and 3 times on the casing (plain, and with the feature faces' vertices locked); the
// interfere and meshoptimizer rows make one untimed warm-up call first.
//
// Timed region: simplify() with the options of the row (weld, quadrics, collapses, the result's
// self-intersection check and guarded rerun when needed, output); measure_error is off except in
// `interfere_error`, which also times the report's sampled Hausdorff measurement. CPU time is the
// process's (all threads).
//
// Counters (metrics computed once, outside the timed region): tri_in, tri_out, hausdorff and
// hausdorff_rel (symmetric, sampled, / bounding-box diagonal), feature_err and feature_err_rel (largest
// distance from the original feature-face samples to the simplified surface), self_x (pairs of
// non-adjacent intersecting triangles created).
//
// Real meshes (optional, skipped when absent): public models of ../shared/data/mesh
// (INTERFERE_BENCH_DATA), each to 5 % with interfere (checked and unchecked), meshoptimizer and
// OpenMesh, no features; self_x_in counts the input's own intersecting pairs (self_x includes those
// the result keeps).
//
// Environment: INTERFERE_BENCH_SIMPLIFY_SIZES (default "1e5,1e6"), INTERFERE_BENCH_SIMPLIFY_RATIOS
// (percent, default "1,10"), INTERFERE_BENCH_SIMPLIFY_PEERS (default 1), INTERFERE_BENCH_CASING_TRIANGLES
// (default 35548), INTERFERE_BENCH_CASING_BUDGET (default 5200).
#include <benchmark/benchmark.h>
#include <meshoptimizer.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"
#ifdef INTERFERE_BENCH_HAS_CAD
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/semantics.h"
#endif

namespace {
using namespace interfere;

std::vector<std::size_t> env_list(const char* name, std::vector<std::size_t> fallback) {
  const char* e = std::getenv(name);
  if (!e || !*e) return fallback;
  std::vector<std::size_t> out;
  std::stringstream ss(e);
  std::string tok;
  while (std::getline(ss, tok, ',')) out.push_back(static_cast<std::size_t>(std::stod(tok)));
  return out;
}

struct Case {
  TriMesh mesh;
  std::vector<std::uint32_t> face;  // 1 on the feature cap
  TriMesh feature;                  // the cap's triangles
  double diag = 0;
};

const Case& sphere_case(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<Case>> cache;
  auto& c = cache[n];
  if (!c) {
    c = std::make_unique<Case>();
    c->mesh = make_sphere({.target_triangles = n, .bump_amplitude = 0.05});
    std::vector<std::uint32_t> cap;
    for (std::uint32_t t = 0; t < c->mesh.num_triangles(); ++t) {
      const auto k = c->mesh.corners(t);
      const Vec3 m = (k[0] + k[1] + k[2]) / 3.0;
      const bool f = m.x > 0.98 && std::abs(m.z) < 0.05;  // an equatorial patch: ~0.25 % of the triangles
      c->face.push_back(f ? 1 : 0);
      if (f) cap.push_back(t);
    }
    c->feature = submesh(c->mesh, cap);
    c->diag = norm(c->mesh.bounds().extent());
  }
  return *c;
}

void report(benchmark::State& state, const TriMesh& in, const TriMesh& feature, const TriMesh& out, double diag) {
  const double h = hausdorff(in, out, false).symmetric();
  const double fe = feature.num_triangles() ? one_sided_distance(feature, out) : 0.0;
  state.counters["tri_in"] = double(in.num_triangles());
  state.counters["tri_out"] = double(out.num_triangles());
  state.counters["hausdorff"] = h;
  state.counters["hausdorff_rel"] = h / diag;
  state.counters["feature_err"] = fe;
  state.counters["feature_err_rel"] = fe / diag;
  state.counters["self_x"] = double(count_self_intersections(out));
}

// Wall time of each phase of simplify() in the last iteration (ms): "phase:<name>".
void phase_counters(benchmark::State& state, const SimplifyResult& r) {
  for (const auto& [name, sec] : r.phases) state.counters["phase:" + name] = sec * 1e3;
}

// The timed loop of every interfere row: simplify() per iteration, the last result in `out`;
// false (row skipped with the error) when simplify() fails.
// `last`: where given, the last run's result without its mesh (moved to `out`).
bool timed_simplify(benchmark::State& state, const TriMesh& mesh, const SimplifyOptions& o, TriMesh& out,
                    SimplifyResult* last = nullptr) {
  // One untimed warm-up call (as for meshoptimizer): the timed runs are the steady state of a
  // process that simplifies repeatedly, not its first call (thread pool start, heap growth).
  if (!simplify(mesh, o)) {
    state.SkipWithError("simplify failed");
    return false;
  }
  for (auto _ : state) {
    auto r = simplify(mesh, o);
    if (!r) {
      state.SkipWithError(r.error().reason.c_str());
      return false;
    }
    out = std::move(r->mesh);
    state.counters["guard_rerun"] = r->guard_rerun;
    phase_counters(state, *r);
    if (last) *last = std::move(*r);
  }
  return true;
}

void bm_interfere(benchmark::State& state, std::size_t n, double ratio, bool guard, bool features,
                  bool measure) {
  const Case& c = sphere_case(n);
  const std::size_t target = std::size_t(std::llround(ratio * double(c.mesh.num_triangles()))) & ~std::size_t{1};
  SimplifyOptions o{.target_triangles = target};
  if (features) o.face_ids = c.face, o.feature_faces = {1};
  o.measure_error = measure;  // interfere_error: the report's Hausdorff measurement timed too
  o.prevent_self_intersections = guard;
  TriMesh out;
  if (!timed_simplify(state, c.mesh, o, out)) return;
  report(state, c.mesh, c.feature, out, c.diag);
}

// meshopt_simplify (no error limit) to `target` triangles, timed; the result as a triangle soup.
TriMesh timed_meshopt(benchmark::State& state, const TriMesh& mesh, std::size_t target) {
  std::vector<float> pos;
  for (const Vec3& p : mesh.positions) pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
  std::vector<unsigned> idx;
  for (const Tri& t : mesh.triangles) idx.insert(idx.end(), t.begin(), t.end());
  std::vector<unsigned> dst(idx.size());
  std::size_t count = 0;
  {  // one untimed warm-up call, as for interfere
    float err = 0;
    meshopt_simplify(dst.data(), idx.data(), idx.size(), pos.data(), mesh.num_vertices(), 12, target * 3, 1e30f, 0, &err);
  }
  for (auto _ : state) {
    float err = 0;
    count = meshopt_simplify(dst.data(), idx.data(), idx.size(), pos.data(), mesh.num_vertices(), 12, target * 3,
                             1e30f, 0, &err);
    benchmark::DoNotOptimize(count);
  }
  TriMesh out;
  out.positions = mesh.positions;
  for (std::size_t i = 0; i < count; i += 3) out.triangles.push_back({dst[i], dst[i + 1], dst[i + 2]});
  std::vector<std::uint32_t> all(out.num_triangles());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  return submesh(out, all);
}

void bm_meshopt(benchmark::State& state, std::size_t n, double ratio) {
  const Case& c = sphere_case(n);
  const std::size_t target = std::size_t(std::llround(ratio * double(c.mesh.num_triangles()))) & ~std::size_t{1};
  report(state, c.mesh, c.feature, timed_meshopt(state, c.mesh, target), c.diag);
}

struct OmTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

// The OpenMesh Decimater (ModQuadric, no error limit) to `target` faces, timed (building the
// half-edge structure is not); `locked` (per vertex, optional) marks vertices the Decimater must
// keep: its own way of protecting a region (a collapse never removes a locked vertex, so triangles
// of locked vertices only stay as they are). Triangles OpenMesh refuses as non-manifold are counted
// in the `om_rejected_faces` counter.
TriMesh timed_openmesh(benchmark::State& state, const TriMesh& mesh, std::size_t target,
                       const std::vector<std::uint8_t>* locked = nullptr) {
  TriMesh out;
  std::size_t rejected = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto m = std::make_unique<OmMesh>();
    std::vector<OmMesh::VertexHandle> vh;
    for (const Vec3& p : mesh.positions) vh.push_back(m->add_vertex(OmMesh::Point(p.x, p.y, p.z)));
    rejected = 0;
    for (const Tri& t : mesh.triangles) rejected += !m->add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid();
    if (locked) {
      m->request_vertex_status();
      for (std::size_t v = 0; v < vh.size(); ++v)
        if ((*locked)[v]) m->status(vh[v]).set_locked(true);
    }
    state.ResumeTiming();
    OpenMesh::Decimater::DecimaterT<OmMesh> dec(*m);
    OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle hq;
    dec.add(hq);
    dec.module(hq).unset_max_err();
    dec.initialize();
    dec.decimate_to_faces(0, target);
    m->garbage_collection();
    state.PauseTiming();
    out = TriMesh{};
    for (auto v : m->vertices()) {
      const auto p = m->point(v);
      out.positions.push_back({p[0], p[1], p[2]});
    }
    for (auto f : m->faces()) {
      Tri t;
      int k = 0;
      for (auto v : m->fv_range(f)) t[k++] = static_cast<std::uint32_t>(v.idx());
      out.triangles.push_back(t);
    }
    state.ResumeTiming();
  }
  state.counters["om_rejected_faces"] = double(rejected);
  return out;
}

void bm_openmesh(benchmark::State& state, std::size_t n, double ratio) {
  const Case& c = sphere_case(n);
  const std::size_t target = std::size_t(std::llround(ratio * double(c.mesh.num_triangles()))) & ~std::size_t{1};
  report(state, c.mesh, c.feature, timed_openmesh(state, c.mesh, target), c.diag);
}

// A real mesh of the shared data, welded, with its diagonal and its own intersecting pairs.
struct RealCase {
  std::string name;
  TriMesh mesh, none;  // `none`: no feature triangles
  double diag = 0;
  std::size_t self_in = 0;
};

std::size_t real_target(const RealCase& c) { return std::max<std::size_t>(c.mesh.num_triangles() / 20, 4); }

void real_report(benchmark::State& state, const RealCase& c, const TriMesh& out) {
  report(state, c.mesh, c.none, out, c.diag);
  state.counters["self_x_in"] = double(c.self_in);
}

void bm_real(benchmark::State& state, std::shared_ptr<const RealCase> c, int tool) {
  TriMesh out;
  if (tool <= 1 || tool == 4) {  // 0: interfere (checked), 1: unchecked, 4: checked, strict about own contacts
    SimplifyOptions o{.target_triangles = real_target(*c)};
    o.measure_error = false;
    o.prevent_self_intersections = tool != 1;
    o.inherit_input_contacts = tool != 4;
    if (!timed_simplify(state, c->mesh, o, out)) return;
  } else if (tool == 2) {
    out = timed_meshopt(state, c->mesh, real_target(*c));
  } else {
    out = timed_openmesh(state, c->mesh, real_target(*c));
  }
  real_report(state, *c, out);
}

std::vector<std::shared_ptr<const RealCase>> real_cases() {
  const char* env = std::getenv("INTERFERE_BENCH_DATA");
  const std::filesystem::path dir =
      env && *env ? std::filesystem::path(env) : std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "mesh";
  std::vector<std::shared_ptr<const RealCase>> out;
  for (const char* name : {"bunny_closed_hr_odedstein.obj", "armadillo_closed_odedstein.obj", "rocker_arm.obj",
                           "fandisk.obj", "vtkdata_gears.stl", "teapot_newell.obj", "trimesh_featuretype.STL"}) {
    const auto file = dir / name;
    if (!std::filesystem::exists(file)) continue;
    auto m = read_mesh(file.string());
    if (!m) continue;
    auto c = std::make_shared<RealCase>();
    c->name = std::filesystem::path(name).stem().string();
    c->mesh = weld_positions(*m);
    c->diag = norm(c->mesh.bounds().extent());
    c->self_in = count_self_intersections(c->mesh);
    out.push_back(std::move(c));
  }
  return out;
}

#ifdef INTERFERE_BENCH_HAS_CAD
struct CasingCase {
  cad::CadModel model;
  double deflection = 0;
  std::map<std::string, std::vector<std::uint32_t>> step_faces;
  std::map<std::string, std::vector<std::uint32_t>> step_tris;  ///< annuli (TopFace/BottomFace, issue #29)
  std::map<std::string, TriMesh> step_feature;
  bool ok = false;
};

const CasingCase& casing_case() {
  static CasingCase c;
  static bool done = false;
  if (done) return c;
  done = true;
  const auto dir = std::filesystem::temp_directory_path() / "interfere_bench_simplify";
  std::filesystem::create_directories(dir);
  const auto file = dir / "casing.step";
  if (!cad::write_test_part(cad::TestPart::casing, file)) return c;
  // Linear deflection giving the triangle count closest to the paper's 35,548 (bisection in log d).
  const double want = double(env_list("INTERFERE_BENCH_CASING_TRIANGLES", {35548})[0]);
  double lo = 1e-3, hi = 10, best_err = 1e300;
  for (int it = 0; it < 14; ++it) {
    const double d = std::sqrt(lo * hi);
    auto m = cad::import_step(file, {.linear_deflection = d, .angular_deflection = 0.5});
    if (!m) return c;
    const double n = double(m->parts[0].mesh.num_triangles());
    if (std::abs(n - want) < best_err) best_err = std::abs(n - want), c.model = std::move(*m), c.deflection = d;
    (n > want ? lo : hi) = d;
  }
  auto lib = cad::default_feature_library();
  if (!lib) return c;
  auto rules = cad::default_semantic_rules(*lib);
  auto process = cad::parse_process(
      R"({"steps":[{"id":"P1","parts":["*"],"constraint":"screw"},{"id":"P2","parts":["*"],"constraint":"bolt"}]})");
  if (!rules || !process) return c;
  const cad::Part& part = c.model.parts[0];
  const auto feats = cad::recognize_features(part.aag, *lib);
  for (const char* step : {"P1", "P2"}) {
    auto sel = cad::select_assembly_features(*process, step, *rules, part.name, feats, &part.aag);
    if (!sel) return c;
    c.step_faces[step] = sel->faces;
    c.step_tris[step] = cad::annulus_triangles(part.mesh, part.face_ids, sel->annuli);
    const auto& annulus = c.step_tris[step];
    std::vector<std::uint32_t> tris;
    for (std::uint32_t t = 0; t < part.face_ids.size(); ++t)
      if (std::binary_search(sel->faces.begin(), sel->faces.end(), part.face_ids[t]) ||
          std::binary_search(annulus.begin(), annulus.end(), t))
        tris.push_back(t);
    c.step_feature[step] = submesh(part.mesh, tris);
  }
  c.ok = true;
  return c;
}

// The casing of a row, or nullptr after skipping the row with an error.
const CasingCase* casing_or_skip(benchmark::State& state) {
  const CasingCase& c = casing_case();
  if (c.ok) return &c;
  state.SkipWithError("casing generation/import failed");
  return nullptr;
}

std::size_t casing_budget(const TriMesh& mesh) {
  return std::min<std::size_t>(env_list("INTERFERE_BENCH_CASING_BUDGET", {5200})[0], mesh.num_triangles());
}

void casing_report(benchmark::State& state, const CasingCase& c, const std::string& step, const TriMesh& out) {
  const TriMesh& mesh = c.model.parts[0].mesh;
  report(state, mesh, c.step_feature.at(step), out, norm(mesh.bounds().extent()));
  state.counters["deflection"] = c.deflection;
  state.counters["feature_faces"] = double(c.step_faces.at(step).size());
}

void bm_casing(benchmark::State& state, const std::string& step, bool guard, FeatureMode mode) {
  const CasingCase* c = casing_or_skip(state);
  if (!c) return;
  const cad::Part& part = c->model.parts[0];
  SimplifyOptions o{.target_triangles = casing_budget(part.mesh), .face_ids = part.face_ids,
                    .feature_faces = c->step_faces.at(step), .feature_triangles = c->step_tris.at(step),
                    .feature_mode = mode};
  o.measure_error = false;
  o.prevent_self_intersections = guard;
  TriMesh out;
  if (!timed_simplify(state, part.mesh, o, out)) return;
  casing_report(state, *c, step, out);
}

// The peer on the casing: meshoptimizer on the welded part (it knows neither faces nor features;
// its time is the reference for the casing target on the same machine and load).
void bm_casing_meshopt(benchmark::State& state, const std::string& step) {
  const CasingCase* c = casing_or_skip(state);
  if (!c) return;
  const TriMesh welded = weld_positions(c->model.parts[0].mesh);
  casing_report(state, *c, step, timed_meshopt(state, welded, casing_budget(welded)));
}

// OpenMesh on the welded casing: plain (knowing neither faces nor features) or, `lock`, with every
// vertex of the step's feature faces locked (the Decimater's region protection; it knows no seams).
void bm_casing_openmesh(benchmark::State& state, const std::string& step, bool lock) {
  const CasingCase* c = casing_or_skip(state);
  if (!c) return;
  const cad::Part& part = c->model.parts[0];
  const TriMesh welded = weld_positions(part.mesh);  // triangle order kept
  std::vector<std::uint8_t> locked(welded.num_vertices(), 0);
  const auto& faces = c->step_faces.at(step);
  const auto& annulus = c->step_tris.at(step);
  for (std::size_t t = 0; t < welded.num_triangles(); ++t)
    if (std::binary_search(faces.begin(), faces.end(), part.face_ids[t]) ||
        std::binary_search(annulus.begin(), annulus.end(), std::uint32_t(t)))
      for (std::uint32_t v : welded.triangles[t]) locked[v] = 1;
  casing_report(state, *c, step, timed_openmesh(state, welded, casing_budget(welded), lock ? &locked : nullptr));
}

// CAD parts of many small faces (../shared/data/step, rows only when present), each part to 10 % of
// its triangles, no features: every seam kept (`all`), as needed (`auto`), or the features' only.
struct StepCase {
  std::string name;
  TriMesh mesh;
  std::vector<std::uint32_t> face_ids;
};

std::vector<std::shared_ptr<const StepCase>> step_cases() {
  const char* env = std::getenv("INTERFERE_BENCH_DATA");
  const std::filesystem::path dir = env && *env ? std::filesystem::path(env) / ".." / "step"
                                                : std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step";
  std::vector<std::shared_ptr<const StepCase>> out;
  for (const char* name : {"gmsh_Block.stp", "nist_ftc_08_asme1_rc.stp", "gmsh_Zylkopf.stp", "nist_ctc_01_asme1_rd.stp"}) {
    const auto file = dir / name;
    if (!std::filesystem::exists(file)) continue;
    auto m = cad::import_step(file);
    if (!m || m->parts.size() != 1) continue;
    auto c = std::make_shared<StepCase>();
    c->name = std::filesystem::path(name).stem().string();
    c->mesh = m->parts[0].mesh;
    c->face_ids = m->parts[0].face_ids;
    out.push_back(std::move(c));
  }
  return out;
}

void bm_step_seams(benchmark::State& state, std::shared_ptr<const StepCase> c, SeamMode seams) {
  SimplifyOptions o{.ratio = 0.1, .face_ids = c->face_ids, .seams = seams};
  o.measure_error = false;
  TriMesh out;
  SimplifyResult r;
  if (!timed_simplify(state, c->mesh, o, out, &r)) return;
  report(state, c->mesh, TriMesh{}, out, norm(c->mesh.bounds().extent()));
  state.counters["target"] = double(r.target_triangles);
  state.counters["seams_relaxed_at"] = double(r.seams_relaxed_at);
  state.counters["faces"] = double(std::set<std::uint32_t>(c->face_ids.begin(), c->face_ids.end()).size());
}

void bm_recognition(benchmark::State& state) {
  static cad::CadModel model;
  static bool ok = false;
  if (!ok) {
    const auto file = std::filesystem::temp_directory_path() / "interfere_bench_simplify_plate.step";
    if (!cad::write_test_part(cad::TestPart::perforated_plate, file)) return state.SkipWithError("plate failed");
    auto m = cad::import_step(file);
    if (!m) return state.SkipWithError(m.error().reason.c_str());
    model = std::move(*m);
    ok = true;
  }
  auto lib = cad::default_feature_library();
  if (!lib) return state.SkipWithError("no feature library");
  std::size_t found = 0;
  for (auto _ : state) {
    const auto f = cad::recognize_features(model.parts[0].aag, *lib);
    found = f.size();
    benchmark::DoNotOptimize(found);
  }
  state.counters["faces"] = double(model.parts[0].faces);
  state.counters["features"] = double(found);
}

// Recognition on a real part of ../shared/data/step (issue #29 target: NIST CTC-02, 664 faces,
// <= 100 ms); skipped when the file is absent.
void bm_recognition_file(benchmark::State& state, std::string file) {
  static std::map<std::string, cad::CadModel> models;
  if (!models.count(file)) {
    const auto path = std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step" / file;
    if (!std::filesystem::exists(path)) return state.SkipWithError(("absent: " + path.string()).c_str());
    auto m = cad::import_step(path);
    if (!m) return state.SkipWithError(m.error().reason.c_str());
    models[file] = std::move(*m);
  }
  const cad::CadModel& model = models[file];
  auto lib = cad::default_feature_library();
  if (!lib) return state.SkipWithError("no feature library");
  std::size_t found = 0, faces = 0;
  for (auto _ : state) {
    found = 0;
    for (const auto& part : model.parts) found += cad::recognize_features(part.aag, *lib).size();
    benchmark::DoNotOptimize(found);
  }
  for (const auto& part : model.parts) faces += part.faces;
  state.counters["faces"] = double(faces);
  state.counters["features"] = double(found);
}
#endif

// Sliver meshes (issue #23, item 12): a prism over a regular n-gon of radius 10 whose caps are fans
// from one centre vertex (4n triangles: 2n side slivers, 2n spokes), height 20 ("fan_cylinder",
// n = 8192: 32,768 triangles) or 1 (a thick polygon, n = 10,000 and 20,000). To 10 % with
// interfere's defaults; interfere_error also times the error measurement (what `interfere
// simplify` does without --no-error), whose cost once grew with the spokes' aspect ratio (21.5 s /
// 43 s / over 120 s). Counters: error_bound (the upper bound) and hausdorff (sampled), absolute.
TriMesh fan_prism(int n, double h) { return make_fan_prism(n, 10, h); }

void bm_sliver(benchmark::State& state, int n, double h, bool measure) {
  const TriMesh mesh = fan_prism(n, h);
  SimplifyOptions o{.ratio = 0.1};
  o.measure_error = measure;
  TriMesh out;
  SimplifyResult last;
  if (!timed_simplify(state, mesh, o, out, &last)) return;
  state.counters["tri_in"] = double(mesh.num_triangles());
  state.counters["tri_out"] = double(out.num_triangles());
  if (measure) state.counters["error_bound"] = last.error_bound, state.counters["hausdorff"] = last.hausdorff;
}

std::string label(std::size_t n) {
  if (n == 100000) return "1e5";
  if (n == 1000000) return "1e6";
  return std::to_string(n);
}

}  // namespace

int main(int argc, char** argv) {
  const auto sizes = env_list("INTERFERE_BENCH_SIMPLIFY_SIZES", {100000, 1000000});
  const auto ratios = env_list("INTERFERE_BENCH_SIMPLIFY_RATIOS", {1, 10});
  const bool peers = env_list("INTERFERE_BENCH_SIMPLIFY_PEERS", {1})[0] != 0;
  for (std::size_t n : sizes)
    for (std::size_t pct : ratios) {
      const double r = double(pct) / 100;
      const std::string tag = label(n) + "/" + std::to_string(pct) + "pct";
      // Means over a few runs (single runs on a shared 2-core machine vary by 10 %); OpenMesh, at 40 s
      // a run, once.
      const int reps = n >= 1000000 ? 3 : 5;
      benchmark::RegisterBenchmark(("Simplify/interfere/" + tag).c_str(), bm_interfere, n, r, true, true, false)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(reps);
      benchmark::RegisterBenchmark(("Simplify/interfere_unchecked/" + tag).c_str(), bm_interfere, n, r, false, true, false)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(reps);
      benchmark::RegisterBenchmark(("Simplify/interfere_error/" + tag).c_str(), bm_interfere, n, r, true, true, true)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(reps);
      benchmark::RegisterBenchmark(("Simplify/interfere_plain/" + tag).c_str(), bm_interfere, n, r, true, false, false)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(reps);
      if (peers) {
        benchmark::RegisterBenchmark(("Simplify/meshoptimizer/" + tag).c_str(), bm_meshopt, n, r)
            ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(reps);
        benchmark::RegisterBenchmark(("Simplify/openmesh/" + tag).c_str(), bm_openmesh, n, r)
            ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(1);
      }
    }
  for (const auto& [name, n, h] : {std::tuple{"fan_cylinder", 8192, 20.0}, std::tuple{"polygon_10k", 10000, 1.0},
                                   std::tuple{"polygon_20k", 20000, 1.0}})
    for (bool measure : {false, true})
      benchmark::RegisterBenchmark(
          ((measure ? "Slivers/interfere_error/" : "Slivers/interfere/") + std::string(name)).c_str(), bm_sliver, n,
          h, measure)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
  for (const auto& c : real_cases()) {
    const char* tools[] = {"interfere", "interfere_unchecked", "meshoptimizer", "openmesh", "interfere_strict"};
    for (int t = 0; t < 5; ++t) {
      if ((t == 3 && !peers) || (t == 4 && c->self_in == 0)) continue;  // strict: where the input has contacts
      benchmark::RegisterBenchmark(("Real/" + std::string(tools[t]) + "/" + c->name).c_str(), bm_real, c, t)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(t == 3 ? 1 : 5);
    }
  }
#ifdef INTERFERE_BENCH_HAS_CAD
  for (const char* step : {"P1", "P2"}) {
    benchmark::RegisterBenchmark((std::string("Casing/interfere/") + step).c_str(), bm_casing, std::string(step), true,
                                 FeatureMode::weight)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(20);
    benchmark::RegisterBenchmark((std::string("Casing/interfere_unchecked/") + step).c_str(), bm_casing,
                                 std::string(step), false, FeatureMode::weight)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(20);
    benchmark::RegisterBenchmark((std::string("Casing/interfere_last/") + step).c_str(), bm_casing, std::string(step),
                                 true, FeatureMode::last)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(20);
    benchmark::RegisterBenchmark((std::string("Casing/interfere_lock/") + step).c_str(), bm_casing, std::string(step),
                                 true, FeatureMode::lock)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(20);
    benchmark::RegisterBenchmark((std::string("Casing/meshoptimizer/") + step).c_str(), bm_casing_meshopt,
                                 std::string(step))
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(20);
    if (peers) {  // a few hundred ms a run: 3 runs
      benchmark::RegisterBenchmark((std::string("Casing/openmesh/") + step).c_str(), bm_casing_openmesh,
                                   std::string(step), false)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
      benchmark::RegisterBenchmark((std::string("Casing/openmesh_lock/") + step).c_str(), bm_casing_openmesh,
                                   std::string(step), true)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
    }
  }
  for (const auto& c : step_cases())
    for (const auto& [mode, name] : {std::pair{SeamMode::all, "all"}, std::pair{SeamMode::as_needed, "auto"},
                                     std::pair{SeamMode::features, "features"}})
      benchmark::RegisterBenchmark(("Seams/" + std::string(name) + "/" + c->name).c_str(), bm_step_seams, c, mode)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(5);
  benchmark::RegisterBenchmark("Recognition/perforated_plate", bm_recognition)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
  for (const char* f : {"nist_ctc_02_asme1_rc.stp", "nist_ftc_10_asme1_rb.stp"})
    benchmark::RegisterBenchmark((std::string("Recognition/") + f).c_str(), bm_recognition_file, std::string(f))
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
#endif
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
