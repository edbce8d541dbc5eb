// The scene clash engine (include/interfere/scene/engine.h; issue #24, items 3, 4, 6): per frame,
// conservative world boxes of the bodies (a rigid pose maps the local box's corners, so a body's
// geometry is only moved when a candidate pair needs it), a tree over them refitted per frame,
// candidate pairs per test, then the exact two-part core on every candidate in parallel
// (engine_pair.cpp). Results are sorted by ids, so they depend neither on the thread count nor on
// the order of the bodies.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <unordered_map>

#include "engine_internal.h"
#include "interfere/bvh/traverse.h"
#include "interfere/core/units.h"

namespace interfere::scene {

const char* clash_status_name(ClashStatus s) {
  switch (s) {
    case ClashStatus::new_: return "new";
    case ClashStatus::active: return "active";
    case ClashStatus::resolved: return "resolved";
  }
  return "?";
}

std::vector<Model> world_models(const Scene& scene) {
  std::vector<Model> out(scene.bodies.size());
  tbb::parallel_for(std::size_t{0}, scene.bodies.size(), [&](std::size_t i) {
    const Body& b = scene.bodies[i];
    out[i] = make_model(transformed(*b.mesh, b.pose), {}, false);
  });
  return out;
}

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The state of every body in the current frame.
struct State {
  std::vector<Transform> pose;
  std::vector<std::shared_ptr<const std::vector<Vec3>>> shape;  // local positions (null: the mesh's)
  std::vector<Aabb> local_box;                                   // of the local positions
  std::vector<AabbF> broad_box;                                  // conservative world box
  std::vector<char> stale;                                       // world geometry out of date
  std::vector<char> built;                                       // world model exists
  std::vector<signed char> sign;                                 // of the pose the world model has
};

const std::vector<Vec3>& local_positions(const Scene& s, const State& st, std::size_t i) {
  return st.shape[i] ? *st.shape[i] : s.bodies[i].mesh->positions;
}

Aabb bounds_of(const std::vector<Vec3>& ps) {
  Aabb b;
  for (const Vec3& p : ps) b.expand(p);
  return b;
}

// Brings the world model of body i to its current pose and shape: built once, then moved in place
// and refitted (same topology).
void refresh(const Scene& s, State& st, std::vector<detail::WorldBody>& world, std::size_t i) {
  const std::vector<Vec3>& local = local_positions(s, st, i);
  detail::WorldBody& w = world[i];
  if (s.bodies[i].world_model && !st.shape[i] && st.pose[i] == s.bodies[i].pose) {
    w.prebuilt = s.bodies[i].world_model.get();  // the caller's model, as it is
    w.box = w.prebuilt->mesh.bounds();
    st.stale[i] = 0;
    return;
  }
  if (w.prebuilt) {  // moved away from the caller's model: from now on the engine's own
    w.prebuilt = nullptr;
    st.built[i] = 0;
  }
  Model& own = w.own;
  // A mirroring pose turns the winding around: swap two corners so that outward stays outward
  // (as transformed() does); refits keep the swap in step with the pose's sign.
  const signed char sign = st.pose[i].determinant_sign() < 0 ? -1 : 1;
  if (!st.built[i]) {
    TriMesh m;
    m.triangles = s.bodies[i].mesh->triangles;
    if (sign < 0)
      for (Tri& f : m.triangles) std::swap(f[1], f[2]);
    st.sign[i] = sign;
    m.positions.resize(local.size());
    for (std::size_t v = 0; v < local.size(); ++v) m.positions[v] = st.pose[i].apply(local[v]);
    own.bvh = build_bvh(m);
    own.mesh = std::move(m);
    st.built[i] = 1;
  } else {
    if (sign != st.sign[i]) {
      for (Tri& f : own.mesh.triangles) std::swap(f[1], f[2]);
      st.sign[i] = sign;
    }
    for (std::size_t v = 0; v < local.size(); ++v) own.mesh.positions[v] = st.pose[i].apply(local[v]);
    refit_bvh(own.bvh, own.mesh);
  }
  w.box = own.mesh.bounds();
  st.stale[i] = 0;
}

using Candidate = CandidatePair;  // (a's id < b's id)

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// What makes two units one problem in their first body's frame: the two meshes, b's pose in a's
// frame (bit for bit) and the tests with their clearances, in the unit's order.
struct ClassKey {
  std::uintptr_t a = 0, b = 0;  // the meshes
  std::array<double, 12> t{};
  std::vector<std::pair<std::uint32_t, double>> tests;
  bool operator<(const ClassKey& o) const { return std::tie(a, b, t, tests) < std::tie(o.a, o.b, o.t, o.tests); }
};

// A class of units decided once (its first unit), in the first body's local frame.
struct FrameClass {
  std::size_t unit = 0;  // the unit decided
  Transform t;           // b's pose in a's frame
  std::vector<std::vector<SceneClash>> found;               // per candidate of the unit, in the frame
  std::vector<std::vector<std::array<Vec3, 2>>> where;      // their id locations
  DepthMaps maps;
  bool has_maps = false;
  ClashResult core;  // the core's result in the frame (SceneClashOptions::on_pair)
};

FramePairRow frame_pair_row(std::uint32_t frame, const Candidate& c, const std::vector<SceneClash>& list) {
  FramePairRow r{.frame = frame, .test = c.test, .a = c.a, .b = c.b};
  for (const SceneClash& s : list) {
    r.verdict = worst(r.verdict, s.verdict);
    switch (s.verdict) {
      case Verdict::clash:
        ++r.clashes, r.min_distance = 0;
        r.max_depth = std::max(r.max_depth, s.depth), r.max_depth_bound = std::max(r.max_depth_bound, s.depth_bound);
        break;
      case Verdict::contact: ++r.contacts, r.min_distance = 0; break;
      case Verdict::clearance:
        ++r.clearances;
        r.min_distance = r.min_distance < 0 ? s.distance : std::min(r.min_distance, s.distance);
        break;
      case Verdict::undecided: ++r.undecided; break;
      case Verdict::clear: break;
    }
  }
  return r;
}

}  // namespace

namespace detail {

void sort_and_summarise(const Scene& scene, const std::vector<ClashTest>& tests, SceneClashResult& result) {
  // Order: test, body ids, clash id.
  std::map<std::string, std::size_t> test_index;  // (names are unique: clash_scene checks)
  for (std::size_t k = 0; k < tests.size(); ++k) test_index.emplace(tests[k].name, k);
  std::sort(result.clashes.begin(), result.clashes.end(), [&](const SceneClash& x, const SceneClash& y) {
    return std::tie(test_index.at(x.test), scene.bodies[x.a].id, scene.bodies[x.b].id, x.id) <
           std::tie(test_index.at(y.test), scene.bodies[y.a].id, scene.bodies[y.b].id, y.id);
  });
  for (std::size_t i = 0; i < result.clashes.size(); ++i) {
    const SceneClash& s = result.clashes[i];
    result.clash_count += s.verdict == Verdict::clash;
    result.contact_count += s.verdict == Verdict::contact;
    result.clearance_count += s.verdict == Verdict::clearance;
    result.undecided_count += s.verdict == Verdict::undecided;
    result.verdict = worst(result.verdict, s.verdict);
    if (result.pairs.empty() || result.pairs.back().test != s.test || result.pairs.back().a != s.a ||
        result.pairs.back().b != s.b) {
      result.pairs.push_back({.test = s.test, .a = s.a, .b = s.b});
      result.pairs.back().min_distance = -1;
    }
    PairSummary& p = result.pairs.back();
    p.clashes.push_back(static_cast<std::uint32_t>(i));
    p.verdict = worst(p.verdict, s.verdict);
    p.depth = std::max(p.depth, s.depth), p.depth_bound = std::max(p.depth_bound, s.depth_bound);
    if (s.verdict == Verdict::clearance) p.min_distance = p.min_distance < 0 ? s.distance : std::min(p.min_distance, s.distance);
  }
}

}  // namespace detail

void finish_result(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashOptions& options,
                   SceneClashResult& result) {
  detail::sort_and_summarise(scene, tests, result);
  detail::summarise_frames(scene, tests, result);
  detail::group_clashes(result, options);
}

namespace {

// SceneClashOptions::zero_clearance_fits on a static scene (issue #29, item 4): the candidates of
// every test over the broad boxes grown by the bodies' reach, each asked once; a fit is a contact
// where the test found no clash, contact or undecided pair (its clearance record dropped).
void add_zero_clearance_fits(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashOptions& options,
                             BroadPhase& broad, const std::vector<AabbF>& boxes, const std::vector<Transform>& pose,
                             const std::vector<double>& grid,
                             const std::function<bool(const CandidatePair&)>& decided, SceneClashResult& result) {
  const SceneClashOptions::ZeroClearanceFits& z = options.zero_clearance_fits;
  std::vector<AabbF> grown = boxes;
  bool any = false;
  for (std::uint32_t i = 0; i < grown.size(); ++i) {
    const double r = z.reach(i);
    if (!(r > 0) || !(grown[i].lo[0] <= grown[i].hi[0])) continue;
    for (int k = 0; k < 3; ++k)
      grown[i].lo[k] = round_down(double(grown[i].lo[k]) - r), grown[i].hi[k] = round_up(double(grown[i].hi[k]) + r);
    any = true;
  }
  if (!any) return;
  std::size_t found = 0, suppressed = 0;
  const std::vector<CandidatePair> cands = broad.candidates(grown, found, suppressed);
  // What each (test, a, b) has already: 2 a clash, contact or undecided record, 1 clearance only.
  std::map<std::tuple<std::string, std::uint32_t, std::uint32_t>, int> has;
  for (const SceneClash& c : result.clashes) {
    int& h = has[{c.test, c.a, c.b}];
    h = std::max(h, c.verdict == Verdict::clearance ? 1 : 2);
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::optional<double>> asked;  // (each pair once)
  std::vector<SceneClash> added;
  std::set<std::tuple<std::string, std::uint32_t, std::uint32_t>> replaced;
  for (const CandidatePair& c : cands) {
    const ClashTest& t = tests[c.test];
    if (!t.nominal_fits_are_contacts || t.mode == ClashMode::duplicates || !decided(c)) continue;
    const auto it = has.find({t.name, c.a, c.b});
    if (it != has.end() && it->second == 2) continue;
    auto [at, fresh] = asked.try_emplace({std::min(c.a, c.b), std::max(c.a, c.b)});
    if (fresh) {
      double gap = 0;
      if (z.check(c.a, c.b, &gap)) at->second = gap;
    }
    if (!at->second) continue;
    SceneClash s;
    s.test = t.name, s.a = c.a, s.b = c.b;
    s.verdict = Verdict::contact;
    s.kind = "zero_clearance_fit";
    s.distance = *at->second;
    const auto box_of = [](const AabbF& g) {
      Aabb b;
      b.expand(Vec3{g.lo[0], g.lo[1], g.lo[2]}), b.expand(Vec3{g.hi[0], g.hi[1], g.hi[2]});
      return b;
    };
    const Aabb ba = box_of(grown[c.a]), bb = box_of(grown[c.b]);
    s.box.lo = max(ba.lo, bb.lo), s.box.hi = min(ba.hi, bb.hi);  // (where the grown boxes meet)
    if (s.box.empty()) s.box = box_of(grown[c.a]), s.box.expand(box_of(grown[c.b]));
    s.point = s.box.center();
    s.reasons.push_back("a zero-clearance fit: coincident B-Rep faces, whose tessellations come " +
                        short_number(s.distance) + " apart there");
    s.id = detail::clash_id(t.name + "\n" + verdict_name(s.verdict), scene.bodies[c.a].id, scene.bodies[c.b].id,
                            {inverse(pose[c.a]).apply(s.point), inverse(pose[c.b]).apply(s.point)}, grid[c.test]);
    replaced.insert({t.name, c.a, c.b});
    added.push_back(std::move(s));
  }
  std::erase_if(result.clashes, [&](const SceneClash& c) {
    return c.verdict == Verdict::clearance && replaced.count({c.test, c.a, c.b});
  });
  for (SceneClash& s : added) result.clashes.push_back(std::move(s));
}

}  // namespace

SceneClashResult clash_scene(const Scene& scene, const std::vector<ClashTest>& tests, const SceneClashOptions& options) {
  const auto t_prepare = Clock::now();
  scene.validate();
  {
    std::set<std::string> names;
    for (const ClashTest& t : tests) {
      t.validate();
      if (!names.insert(t.name).second) throw std::invalid_argument("clash test '" + t.name + "': duplicate test name");
    }
  }
  SceneClashResult result;
  const std::size_t n = scene.bodies.size();
  result.bodies = n;
  for (const Body& b : scene.bodies) result.triangles += b.mesh->num_triangles();
  const double mm = millimetres_per_unit(scene.units).value_or(1.0);

  State st;
  st.pose.resize(n), st.shape.resize(n), st.local_box.resize(n), st.broad_box.resize(n);
  st.stale.assign(n, 1), st.built.assign(n, 0), st.sign.assign(n, 1);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    st.pose[i] = scene.bodies[i].pose;
    st.local_box[i] = bounds_of(scene.bodies[i].mesh->positions);
  });
  std::vector<detail::WorldBody> world(n);
  // Local models (decision frames) per mesh, kept over frames; the bodies that used them.
  std::map<const TriMesh*, std::unique_ptr<detail::WorldBody>> locals;
  std::vector<char> in_frame_unit(n, 0);

  // Selections per test (the broad phase: engine_broad.cpp), and each test's id grid.
  BroadPhase broad(scene.bodies, tests);
  result.warnings = broad.warnings();
  std::vector<double> grid(tests.size());
  for (std::size_t k = 0; k < tests.size(); ++k) {
    const ClashTest& t = tests[k];
    grid[k] = t.id_grid > 0 ? t.id_grid : t.tolerance > 0 ? t.tolerance : 1.0 / mm;
  }
  // Decide only these pairs (SceneClashOptions::decide_pairs), as (smaller index, larger index).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> decide;
  for (const auto& [x, y] : options.decide_pairs) decide.emplace_back(std::min(x, y), std::max(x, y));
  std::sort(decide.begin(), decide.end());
  const auto decided = [&](const Candidate& c) {
    return std::binary_search(decide.begin(), decide.end(), std::pair{std::min(c.a, c.b), std::max(c.a, c.b)});
  };
  result.prepare_seconds = since(t_prepare);

  const bool moving = !scene.frames.empty();
  const std::size_t frame_count = moving ? scene.frames.size() : 1;
  std::unordered_map<std::string, std::size_t> by_id;  // clash id -> index in result.clashes
  struct Track {
    std::string id, kind;
    Vec3 where;  // id location in a's frame
  };
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>, std::vector<Track>> last, next;
  // Deformed bodies: the reference configuration first (pass 0), then the frames (issue #26, item 4).
  bool deforms = false;
  for (const Frame& fr : scene.frames) deforms = deforms || !fr.shapes.empty();
  const std::size_t ref_pass = moving && deforms && options.reference ? 1 : 0;
  result.reference_checked = ref_pass == 1;
  bool tolerant = false;  // a test whose penetration tolerance the depth bound decides
  for (const ClashTest& t : tests) tolerant = tolerant || (t.mode == ClashMode::hard && t.tolerance > 0);
  const std::size_t bound_splits =
      moving && !tolerant ? std::min(options.depth_bound_splits, options.frame_depth_bound_splits) : options.depth_bound_splits;
  for (std::size_t pass = 0; pass < frame_count + ref_pass; ++pass) {
    const bool reference = pass < ref_pass;
    const std::size_t f = pass - ref_pass;  // (unused in the reference pass)
    auto t_broad = Clock::now();
    std::vector<char> box_dirty(n, pass == 0 ? 1 : 0);
    if (moving && !reference) {
      const Frame& fr = scene.frames[f];
      for (const Frame::Pose& p : fr.poses) st.pose[p.body] = p.pose, st.stale[p.body] = 1, box_dirty[p.body] = 1;
      for (const Frame::Shape& s : fr.shapes) {
        st.shape[s.body] = s.positions, st.stale[s.body] = 1, box_dirty[s.body] = 1;
        st.local_box[s.body] = bounds_of(*s.positions);
      }
    }
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      if (box_dirty[i]) st.broad_box[i] = broad_box(st.local_box[i], st.pose[i]);
    });
    // Candidates of every test (the reference pass's are checked, not counted).
    std::size_t counted = 0, suppressed = 0;
    std::vector<Candidate> cands = broad.candidates(st.broad_box, counted, suppressed);
    if (!reference) result.candidate_pairs += counted, result.suppressed += suppressed;
    if (!decide.empty()) std::erase_if(cands, [&](const Candidate& c) { return !decided(c); });
    if (moving && !reference && options.decide_in_frame)
      std::erase_if(cands, [&](const Candidate& c) { return !options.decide_in_frame(f, c.a, c.b); });
    // Units: one core run per body pair. The candidates of every test on the same pair share it, at
    // the largest clearance among them, each test deriving its clashes from it (largest clearance
    // first). Not shared: duplicates mode (no core), a caller that sees each test's core result
    // (on_pair), and clearances with a non-exact triangle test (the core then switches to exact).
    std::vector<std::size_t> order(cands.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    const bool share = !options.on_pair;
    const auto key = [&](std::size_t k) {
      const Candidate& c = cands[k];
      const bool dup = tests[c.test].mode == ClashMode::duplicates;
      const double split = !share || dup ? static_cast<double>(k)
                           : options.request.test == TriTest::exact ? 0.0 : c.clearance;
      return std::tuple{c.a, c.b, dup, split};
    };
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      const auto kx = key(x), ky = key(y);
      if (kx != ky) return kx < ky;
      return std::tie(cands[y].clearance, cands[x].test) < std::tie(cands[x].clearance, cands[y].test);
    });
    std::vector<std::size_t> unit_start;  // runs of `order` with one key
    for (std::size_t i = 0; i < order.size(); ++i)
      if (i == 0 || key(order[i]) != key(order[i - 1])) unit_start.push_back(i);
    unit_start.push_back(order.size());
    const std::size_t units = unit_start.size() - 1;
    // Decision frames (engine_internal.h, PairFrame): a unit is decided in its first body's local
    // frame when that body's pose is a rotation and neither body is deformed in this frame, and
    // units with the same two meshes, relative pose (bit for bit) and tests are one class, decided
    // once (its first unit: any member gives the same answer bit for bit). In the world frame:
    // duplicates, mirrored or scaled poses, deformed bodies.
    std::vector<std::size_t> unit_class(units, kNone);
    std::vector<FrameClass> classes;
    {
      std::map<ClassKey, std::size_t> class_of;
      std::vector<signed char> rigid(n, -1);
      for (std::size_t u = 0; u < units; ++u) {
        const Candidate& c = cands[order[unit_start[u]]];
        if (tests[c.test].mode == ClashMode::duplicates || st.shape[c.a] || st.shape[c.b]) continue;
        if (rigid[c.a] < 0) rigid[c.a] = st.pose[c.a].is_rigid() ? 1 : 0;
        if (!rigid[c.a]) continue;
        ClassKey k;
        k.a = reinterpret_cast<std::uintptr_t>(scene.bodies[c.a].mesh.get());
        k.b = reinterpret_cast<std::uintptr_t>(scene.bodies[c.b].mesh.get());
        const Transform t = st.pose[c.a] == st.pose[c.b] ? Transform{} : compose(inverse(st.pose[c.a]), st.pose[c.b]);
        k.t = t.to_row_major();  // (= relative_pose_key(pose a, pose b))
        for (std::size_t i = unit_start[u]; i < unit_start[u + 1]; ++i)
          k.tests.emplace_back(cands[order[i]].test, cands[order[i]].clearance);
        const auto [it, added] = class_of.emplace(std::move(k), classes.size());
        if (added) classes.push_back({.unit = u, .t = t});
        unit_class[u] = it->second;
      }
    }
    // Models: the local ones of the frame units' meshes (built once, kept over frames), the world
    // ones of the world units' bodies.
    // A body's own world model (Body::world_model) at the identity pose is its mesh's local model.
    std::vector<const TriMesh*> new_locals;
    std::map<const TriMesh*, const Model*> given;
    std::vector<char> need(n, 0);
    for (std::size_t u = 0; u < units; ++u) {
      const Candidate& c = cands[order[unit_start[u]]];
      if (unit_class[u] == kNone) {
        need[c.a] = need[c.b] = 1;
        continue;
      }
      in_frame_unit[c.a] = in_frame_unit[c.b] = 1;
      for (const std::uint32_t i : {c.a, c.b}) {
        const TriMesh* m = scene.bodies[i].mesh.get();
        if (locals.emplace(m, nullptr).second) new_locals.push_back(m);
        if (scene.bodies[i].world_model && scene.bodies[i].pose.is_identity()) given.emplace(m, scene.bodies[i].world_model.get());
      }
    }
    tbb::parallel_for(std::size_t{0}, new_locals.size(), [&](std::size_t k) {
      auto w = std::make_unique<detail::WorldBody>();
      if (const auto it = given.find(new_locals[k]); it != given.end()) w->prebuilt = it->second;
      else w->own = make_model(*new_locals[k], {}, false);
      w->box = w->model().mesh.bounds();
      locals.find(new_locals[k])->second = std::move(w);  // (the node exists: a lookup, no insertion)
    });
    std::vector<std::uint32_t> todo;
    for (std::uint32_t i = 0; i < n; ++i)
      if (need[i] && st.stale[i]) todo.push_back(i);
    tbb::parallel_for(std::size_t{0}, todo.size(), [&](std::size_t k) { refresh(scene, st, world, todo[k]); });
    result.broad_seconds += since(t_broad);

    // The exact core: once per class and per world unit, in parallel.
    const auto t_narrow = Clock::now();
    std::vector<std::vector<SceneClash>> found(cands.size());
    std::vector<std::vector<std::array<Vec3, 2>>> where(cands.size());  // the id locations
    std::vector<std::size_t> jobs;  // classes' first units, then the world units
    for (const FrameClass& fc : classes) jobs.push_back(fc.unit);
    for (std::size_t u = 0; u < units; ++u)
      if (unit_class[u] == kNone) jobs.push_back(u);
    if (!reference)
      for (const std::size_t u : jobs) result.core_runs += tests[cands[order[unit_start[u]]].test].mode != ClashMode::duplicates;
    const bool many_pairs = jobs.size() >= 4 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
    std::vector<PairDepthMap> unit_maps(units);
    std::vector<char> unit_has_map(units, 0);
    std::vector<std::size_t> cand_unit(cands.size());
    for (std::size_t u = 0; u < units; ++u)
      for (std::size_t i = unit_start[u]; i < unit_start[u + 1]; ++i) cand_unit[order[i]] = u;
    const auto local_of = [&](std::uint32_t j) -> const std::vector<Vec3>& { return local_positions(scene, st, j); };
    const std::uint32_t frame_no = static_cast<std::uint32_t>(moving ? f : 0);
    std::atomic<std::size_t> jobs_done{0};  // (pair_progress)
    tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t job) {
      const std::size_t u = jobs[job];
      const std::uint32_t a = cands[order[unit_start[u]]].a, b = cands[order[unit_start[u]]].b;
      FrameClass* fc = unit_class[u] == kNone ? nullptr : &classes[unit_class[u]];
      detail::PairFrame frame;
      Model moved;
      bool into_b = false;  // decided in b's local frame (a moved): clashes mapped back to a's
      if (fc) {
        detail::WorldBody& la = *locals.at(scene.bodies[a].mesh.get());
        detail::WorldBody& lb = *locals.at(scene.bodies[b].mesh.get());
        const bool same = fc->t.is_identity();
        // The body with fewer vertices is the one moved (issue #28): a 10^6-triangle workpiece
        // against a robot link is decided in the workpiece's frame, the link's few thousand
        // vertices re-posed, instead of the workpiece's million per pair and frame. The clashes
        // are mapped back to a's frame below, so everything after this is unchanged. Not with
        // on_pair (its ClashResult is in the decision frame) nor for a non-rigid relative pose.
        into_b = !same && !options.on_pair &&
                 lb.model().mesh.positions.size() > la.model().mesh.positions.size() && fc->t.is_rigid();
        if (into_b) {
          const Transform to_b = inverse(fc->t);  // a's local frame -> b's
          moved = detail::moved_model(la.model(), to_b);
          frame = {.a = &moved, .b = &lb.model(),
                   .stats = [&la, &lb](int side) -> const MeshStats& { return side == 0 ? la.stats() : lb.stats(); },
                   .box_a = moved.mesh.bounds(), .box_b = lb.box,
                   .to_frame = {to_b, Transform{}}, .to_local = {fc->t, Transform{}}, .world = false};
        } else {
          if (!same) moved = detail::moved_model(lb.model(), fc->t);
          frame = {.a = &la.model(), .b = same ? &lb.model() : &moved,
                   .stats = [&la, &lb](int side) -> const MeshStats& { return side == 0 ? la.stats() : lb.stats(); },
                   .box_a = la.box, .box_b = same ? lb.box : moved.mesh.bounds(),
                   .to_frame = {Transform{}, fc->t}, .to_local = {Transform{}, same ? Transform{} : inverse(fc->t)},
                   .world = false};
        }
      } else {
        detail::WorldBody& wa = world[a];
        detail::WorldBody& wb = world[b];
        frame = {.a = &wa.model(), .b = &wb.model(),
                 .stats = [&wa, &wb](int side) -> const MeshStats& { return side == 0 ? wa.stats() : wb.stats(); },
                 .box_a = wa.box, .box_b = wb.box, .to_frame = {st.pose[a], st.pose[b]},
                 .to_local = {inverse(st.pose[a]), inverse(st.pose[b])}, .world = true};
      }
      detail::PairCore core;
      for (std::size_t i = unit_start[u]; i < unit_start[u + 1]; ++i) {
        const std::size_t k = order[i];
        const Candidate& c = cands[k];
        const detail::PairContext ctx{scene, tests[c.test], c.test, options, local_of, many_pairs, bound_splits};
        const bool dup = tests[c.test].mode == ClashMode::duplicates;
        if (!dup && i == unit_start[u]) {
          core = detail::core_pair(ctx, frame, c.a, c.b, c.clearance);
          if (fc && options.on_pair) fc->core = core.r;  // (given to every member below)
          if (core.maps_known && !reference &&
              (core.maps.a.inside + core.maps.a.undecided + core.maps.b.inside + core.maps.b.undecided) > 0) {
            if (fc) fc->maps = std::move(core.maps), fc->has_maps = true;
            else {
              unit_maps[u] = detail::pair_depth_map(
                  scene, [&](std::uint32_t body, std::uint32_t v) { return world[body].model().mesh.positions[v]; },
                  frame_no, c.a, c.b, core.maps);
              unit_has_map[u] = 1;
            }
          }
          core.maps = {};
        }
        if (fc) {
          fc->found.push_back(detail::derive_pair(ctx, frame, c.a, c.b, c.clearance, &core, fc->where.emplace_back()));
          if (into_b) detail::place_clashes(fc->found.back(), fc->t, true);  // b's frame -> a's
        }
        else found[k] = detail::derive_pair(ctx, frame, c.a, c.b, c.clearance, dup ? nullptr : &core, where[k]);
      }
      if (!moving && !reference && options.pair_progress) options.pair_progress(++jobs_done, jobs.size());
    });
    // Every unit of a class: the class's clashes for its bodies, mapped to the world by its pose.
    tbb::parallel_for(std::size_t{0}, units, [&](std::size_t u) {
      if (unit_class[u] == kNone) return;
      const FrameClass& fc = classes[unit_class[u]];
      const Candidate& rep = cands[order[unit_start[fc.unit]]];
      for (std::size_t i = unit_start[u]; i < unit_start[u + 1]; ++i) {
        const std::size_t k = order[i];
        const Candidate& c = cands[k];
        found[k] = fc.found[i - unit_start[u]];
        where[k] = fc.where[i - unit_start[u]];
        detail::rehome(found[k], scene, rep.a, rep.b, c.a, c.b);
        detail::place_clashes(found[k], st.pose[c.a], options.curves);
      }
      if (options.on_pair) {  // (one candidate per unit with on_pair: no sharing between tests)
        const Candidate& c = cands[order[unit_start[u]]];
        options.on_pair(c.test, c.a, c.b, fc.core);
      }
      if (fc.has_maps) {
        const Candidate& c = cands[order[unit_start[u]]];
        unit_maps[u] = detail::pair_depth_map(
            scene, [&](std::uint32_t body, std::uint32_t v) { return st.pose[body].apply(local_of(body)[v]); },
            frame_no, c.a, c.b, fc.maps);
        unit_has_map[u] = 1;
      }
    });
    if (reference) {  // only each pair's verdict
      for (std::size_t k = 0; k < cands.size(); ++k) {
        if (found[k].empty()) continue;
        ReferencePair r{cands[k].test, cands[k].a, cands[k].b, Verdict::clear};
        for (const SceneClash& s : found[k]) r.verdict = worst(r.verdict, s.verdict);
        result.reference_pairs.push_back(r);
      }
      result.narrow_seconds += since(t_narrow);
      continue;
    }
    // Ids, then merge into the result.
    FrameRow row;
    row.frame = static_cast<std::uint32_t>(f);
    if (moving) row.label = scene.frames[f].label, row.time = scene.frames[f].time;
    for (std::size_t k = 0; k < cands.size(); ++k) {
      std::vector<SceneClash>& list = found[k];
      const Candidate& c = cands[k];
      std::vector<std::pair<std::string, Vec3>> keys;
      for (std::size_t i = 0; i < list.size(); ++i) {
        SceneClash& s = list[i];
        const std::array<Vec3, 2>& local = where[k][i];
        s.id = detail::clash_id(tests[c.test].name + "\n" + verdict_name(s.verdict), scene.bodies[c.a].id,
                                scene.bodies[c.b].id, local, grid[c.test]);
        keys.push_back({s.id, local[0]});
      }
      // Clashes of one pair in one grid cell: suffixes by location.
      std::vector<std::size_t> order(list.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
        const auto& [ix, px] = keys[x];
        const auto& [iy, py] = keys[y];
        if (ix != iy) return ix < iy;
        return std::tie(px.x, px.y, px.z, x) < std::tie(py.x, py.y, py.z, y);
      });
      for (std::size_t i = 1, run = 1; i < order.size(); ++i) {
        run = keys[order[i]].first == keys[order[i - 1]].first ? run + 1 : 1;
        if (run > 1) list[order[i]].id += "-" + std::to_string(run);
      }
      if (moving) {
        // Continuity over frames: a clash of this pair and kind in the previous frame is the same
        // clash, moved (a ball passing through a face keeps one id while it crosses), matched by
        // id first, then by the nearest location in a's frame; it keeps the earlier id.
        std::vector<Track>& prev = last[{c.test, c.a, c.b}];
        std::vector<char> used(prev.size(), 0), kept(list.size(), 0);
        for (std::size_t i = 0; i < list.size(); ++i)
          for (std::size_t j = 0; j < prev.size(); ++j)
            if (!used[j] && prev[j].id == list[i].id && prev[j].kind == list[i].kind) used[j] = kept[i] = 1;
        for (std::size_t i = 0; i < list.size(); ++i) {
          if (kept[i]) continue;
          std::size_t best = prev.size();
          for (std::size_t j = 0; j < prev.size(); ++j)
            if (!used[j] && prev[j].kind == list[i].kind &&
                (best == prev.size() || squared_norm(prev[j].where - where[k][i][0]) < squared_norm(prev[best].where - where[k][i][0])))
              best = j;
          if (best == prev.size()) continue;
          bool taken = false;  // (the earlier id is not another clash's of this frame)
          for (const SceneClash& o : list) taken = taken || o.id == prev[best].id;
          if (taken) continue;
          used[best] = 1;
          list[i].id = prev[best].id;
        }
        std::vector<Track>& now = next[{c.test, c.a, c.b}];
        for (std::size_t i = 0; i < list.size(); ++i) now.push_back({list[i].id, list[i].kind, where[k][i][0]});
      }
      const PairDepthMap* map = unit_has_map[cand_unit[k]] ? &unit_maps[cand_unit[k]] : nullptr;
      if (moving && !list.empty()) {
        result.frame_pairs.push_back(frame_pair_row(static_cast<std::uint32_t>(f), c, list));
        if (map && map->has_deepest) result.frame_pairs.back().has_deepest = true, result.frame_pairs.back().deepest = map->deepest;
      }
      for (SceneClash& s : list) {
        if (map && map->has_deepest && s.verdict == Verdict::clash) detail::keep_deeper(s.has_deepest, s.deepest, map->deepest);
        switch (s.verdict) {
          case Verdict::clash: ++row.clashes, row.max_depth = std::max(row.max_depth, s.depth_bound); break;
          case Verdict::contact: ++row.contacts; break;
          case Verdict::clearance:
            ++row.clearances;
            row.min_distance = row.min_distance < 0 ? s.distance : std::min(row.min_distance, s.distance);
            break;
          case Verdict::undecided: ++row.undecided; break;
          case Verdict::clear: break;
        }
        row.verdict = worst(row.verdict, s.verdict);
        const auto it = by_id.find(s.id);
        if (it != by_id.end()) {
          SceneClash& prev = result.clashes[it->second];
          if (moving) prev.frames.push_back(static_cast<std::uint32_t>(f));
          if (worst(prev.verdict, s.verdict) != prev.verdict) prev.verdict = s.verdict;
          if (s.has_deepest) detail::keep_deeper(prev.has_deepest, prev.deepest, s.deepest);
          prev.depth = std::max(prev.depth, s.depth), prev.depth_bound = std::max(prev.depth_bound, s.depth_bound);
          continue;
        }
        if (moving) s.frames.push_back(static_cast<std::uint32_t>(f));
        by_id.emplace(s.id, result.clashes.size());
        result.clashes.push_back(std::move(s));
      }
    }
    if (moving) result.frames.push_back(row);
    for (std::size_t u = 0; u < unit_maps.size(); ++u)
      if (unit_has_map[u]) result.depth_maps.push_back(std::move(unit_maps[u]));
    last = std::move(next);
    next.clear();
    result.narrow_seconds += since(t_narrow);
    if (options.progress) options.progress(f + 1, frame_count);
  }

  if (!moving && options.zero_clearance_fits.reach && options.zero_clearance_fits.check)
    add_zero_clearance_fits(scene, tests, options, broad, st.broad_box, st.pose, grid,
                            [&](const CandidatePair& c) { return decide.empty() || decided(c); }, result);
  finish_result(scene, tests, options, result);
  // Open bodies that took part (their verdicts say undecided where it mattered).
  for (std::size_t i = 0; i < n; ++i) {
    const MeshStats* stats = &world[i].lazy_stats;  // (of its local model: a mesh's statistics, once)
    if (stats->triangles == 0 && in_frame_unit[i]) stats = &locals.at(scene.bodies[i].mesh.get())->lazy_stats;
    if (const MeshStats& s = *stats; s.triangles > 0 && !s.closed())
      result.warnings.push_back("body '" + scene.bodies[i].id + "' is not closed (" + std::to_string(s.open_edges) +
                                " open, " + std::to_string(s.nonmanifold_edges) + " non-manifold, " +
                                std::to_string(s.inconsistent_edges) +
                                " inconsistently oriented edges): inside/outside is undecided where it matters");
  }
  return result;
}

}  // namespace interfere::scene
