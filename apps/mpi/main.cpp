// interfere-mpi: `mpirun -n K interfere-mpi clash --scene product.json --json out.json` (issue #31,
// items 1, 2 and 4; docs/mpi.md). Each rank reads a share of the scene file's entries and sends
// their bodies' metadata, triangle counts and boxes to every rank (allgather); every rank runs the
// same broad phase and partition (plan.h); each rank reads the entries its pairs need and runs the
// scene engine (scene::clash_scene, oneTBB inside) on its blocks; rank 0 merges the findings
// (merge.h) and writes the same report as `interfere clash --scene` (docs/report.md), plus an
// "mpi" section (ranks, per-rank load).
#include <mpi.h>
#include <sys/resource.h>
#include <unistd.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "args.h"
#include "clash_outputs.h"
#include "driver.h"
#include "bearing.h"
#include "cell.h"
#include "sweep.h"
#include "comm.h"
#include "merge.h"
#include "plan.h"
#include "series.h"
#include "simulate.h"
#include "usage.h"
#include "wire.h"
#include "interfere/scene/load.h"
#include "interfere/scene/report.h"

namespace interfere::mpi {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string read_bytes(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(std::string(what) + ": " + path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first reader of every entry (step 1): the entries in file order cut into K runs of about
// equal file size, so that a rank reads neighbours in the file (a product's files are usually
// listed part by part, and a generated one in space order) and the partition can leave most
// bodies' pairs with the rank that read them already (plan.h: the read cost is saved there).
// The file sizes: each rank asked the file system for every K-th entry's (checked_share: `mine`,
// one 8-byte size + 1 each), then they are exchanged.
std::vector<std::uint32_t> first_readers(const scene::SceneSpec& spec, const World& w, const std::string& mine) {
  const std::size_t m = spec.bodies.size(), k = static_cast<std::size_t>(w.size);
  const std::vector<std::string> all = allgather(mine);
  std::vector<std::uintmax_t> size(m);
  std::uintmax_t total = 0;
  for (std::size_t i = 0; i < m; ++i) {
    std::uint64_t v = 0;
    std::memcpy(&v, all[i % k].data() + sizeof v * (i / k), sizeof v);
    total += size[i] = v;
  }
  std::vector<std::uint32_t> reader(spec.bodies.size(), 0);
  std::uintmax_t before = 0;
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    // The run holding this entry's middle byte.
    const long double middle = static_cast<long double>(before) + static_cast<long double>(size[i]) / 2;
    reader[i] = static_cast<std::uint32_t>(std::min<long double>(w.size - 1, middle * w.size / static_cast<long double>(total)));
    before += size[i];
  }
  return reader;
}

// Every K-th entry's file, from this rank's (rank, rank + K, ...): checked as read_scene_file
// checks it (the scene file is parsed with check_body_files off, so that no rank stats every file
// of the product); their sizes (+ 1, 8 bytes each) for first_readers. A problem: the entry's index
// and read_scene_file's message (the ranks' first one in file order is reported, as one process).
struct Share {
  std::string sizes;
  std::size_t bad = SIZE_MAX;
  std::string why;
};
Share checked_share(const scene::SceneSpec& spec, const World& w) {
  Share out;
  for (std::size_t i = static_cast<std::size_t>(w.rank); i < spec.bodies.size(); i += static_cast<std::size_t>(w.size)) {
    const Expected<std::uintmax_t> size = scene::check_body_file(spec.bodies[i]);
    if (!size) {
      out.bad = i, out.why = size.error().message();
      break;
    }
    const std::uint64_t v = static_cast<std::uint64_t>(*size) + 1;
    out.sizes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  return out;
}

// --memory-limit MB: the rank's address space may grow by MB beyond what it has mapped now (after
// MPI_Init: the MPI run-time's mappings are not counted), so that a rank short of memory fails an
// allocation (std::bad_alloc: the job ends with its message, exit status 2) instead of being
// killed by the kernel's out-of-memory killer, which no rank can report.
void limit_memory(double mb) {
  std::ifstream statm("/proc/self/statm");
  unsigned long long pages = 0;
  statm >> pages;
  const rlim_t now = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE));
  rlimit limit{};
  getrlimit(RLIMIT_AS, &limit);
  limit.rlim_cur = std::min(limit.rlim_max, now + static_cast<rlim_t>(mb * 1048576.0));
  if (!statm || setrlimit(RLIMIT_AS, &limit) != 0) throw UsageError("--memory-limit: cannot limit the address space of a rank");
}

// The mesh key of body k of entry s (wire.h BodyInfo::mesh_key): equal keys where load_scene on
// the whole scene file gives bodies one mesh (scene_load/load.cpp: a mesh file read once per
// canonical path and unit; an entry's bodies sharing their part's mesh).
std::uint64_t mesh_key(const scene::BodySpec& entry, std::size_t s, const scene::Scene& loaded, std::uint32_t k) {
  const scene::Body& body = loaded.bodies[k];
  if (body.source.kind == scene::SourceKind::mesh_file && loaded.bodies.size() == 1) {
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(entry.file, ec);
    return fnv1a(0xcbf29ce484222325ULL, "F" + (ec ? entry.file : canonical.string()) + "\n" + body.unit);
  }
  std::uint32_t first = 0;
  while (loaded.bodies[first].mesh != body.mesh) ++first;
  return fnv1a(0xcbf29ce484222325ULL, "E" + std::to_string(s) + ":" + std::to_string(first));
}

int run(const World& w, int argc, char** argv) {
  const auto t_total = Clock::now();
  const Options o = parse_clash(argc, argv);
  std::optional<tbb::global_control> threads;
  if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(o.threads));
  const bool talk = w.rank == 0 && !o.quiet;
  if (o.memory_limit_mb > 0) limit_memory(o.memory_limit_mb);
  // Wall and CPU seconds of each step (wire.h kPhases), for the report's mpi section.
  std::vector<std::array<double, 2>> phases(kPhaseCount, {0.0, 0.0});
  auto phase_wall = t_total;
  double phase_cpu = cpu_seconds();
  const auto phase_done = [&](std::size_t k) {
    const double c = cpu_seconds();
    phases[k] = {since(phase_wall), c - phase_cpu};
    phase_wall = Clock::now(), phase_cpu = c;
  };

  // Every rank's view of the inputs: a checksum of the scene file, the motion and baseline files
  // and the command line, compared at the start (a rank that cannot read them says so; no rank
  // goes on alone).
  std::optional<scene::SceneSpec> spec;
  std::string motion, baseline_text, token;
  Share share;
  try {
    const std::string scene_text = read_bytes(o.scene, "--scene");
    std::uint64_t sum = fnv1a(0xcbf29ce484222325ULL, scene_text);
    for (int i = 1; i < argc; ++i) sum = fnv1a(sum, std::string(argv[i]) + '\0');
    auto s = scene::read_scene_file(o.scene, {.check_body_files = false});  // (each rank checks its share below)
    if (!s) throw UsageError(s.error().message());
    spec = std::move(*s);
    motion = !o.motion.empty() ? o.motion : spec->motion;
    if (!motion.empty()) sum = fnv1a(sum, read_bytes(motion, "--motion"));
    if (!o.tests_file.empty()) sum = fnv1a(sum, read_bytes(o.tests_file, "--tests"));
    if (!o.fem_disp.empty()) sum = fnv1a(sum, read_bytes(o.fem_disp, "--disp"));
    if (!o.baseline.empty()) {
      baseline_text = read_bytes(o.baseline, "--baseline"), sum = fnv1a(sum, baseline_text);
      scene::SceneClashResult probe;  // (checked by every rank now, so that rank 0 cannot fail alone later)
      if (const Status st = scene::apply_baseline(probe, baseline_text, o.baseline); !st) throw UsageError(st.error().message());
    }
    // Outputs: their folders must exist (checked by every rank before any work; rank 0 writes them).
    for (const auto& [flag, out] : {std::pair<const char*, const std::string*>{"--json", &o.json}, {"--csv", &o.csv},
                                    {"--frames-csv", &o.frames_csv}, {"--frame-pairs-csv", &o.frame_pairs_csv}}) {
      if (out->empty() || *out == "-") continue;
      const std::filesystem::path dir = std::filesystem::absolute(*out).parent_path();
      if (!std::filesystem::is_directory(dir)) throw UsageError(std::string(flag) + " " + *out + ": no folder " + dir.string());
      if (std::filesystem::absolute(*out) == std::filesystem::absolute(o.scene))
        throw UsageError(std::string(flag) + " " + *out + ": is the scene file");
    }
    token = "S" + std::to_string(sum);
    share = checked_share(*spec, w);
    if (share.bad != SIZE_MAX) token = "F" + std::to_string(share.bad) + "\n" + share.why;
  } catch (const UsageError& e) {
    token = std::string("E") + e.what();
  }
  {
    const std::vector<std::string> tokens = allgather(token);
    bool failed = false;
    // An entry's file missing (its rank's check): the first in file order, as one process says it.
    std::size_t first_bad = SIZE_MAX;
    std::string first_why;
    for (const std::string& t : tokens)
      if (t[0] == 'F')
        if (const std::size_t i = std::stoull(t.substr(1)); i < first_bad) first_bad = i, first_why = t.substr(t.find('\n') + 1);
    if (first_bad != SIZE_MAX && std::none_of(tokens.begin(), tokens.end(), [](const std::string& t) { return t[0] == 'E'; })) {
      if (w.rank == 0) std::fprintf(stderr, "interfere: error: %s\n", first_why.c_str());
      return 2;
    }
    for (int r = 0; r < w.size; ++r) {
      const std::string& t = tokens[static_cast<std::size_t>(r)];
      if (t[0] == 'E') {
        failed = true;
        if (w.rank == r && (r == 0 || t != tokens[0]))
          std::fprintf(stderr, "interfere: error: %s%s\n", r == 0 ? "" : ("rank " + std::to_string(r) + ": ").c_str(),
                       t.substr(1).c_str());
      }
    }
    if (failed) return 2;
    for (int r = 0; r < w.size; ++r)
      if (tokens[static_cast<std::size_t>(r)] != tokens[0])
        throw UsageError("rank " + std::to_string(r) + " sees other inputs than rank 0 (the checksum of the scene file, motion, "
                         "baseline and command line differs): every rank must read the same files");
  }
  if (spec->bodies.empty()) throw UsageError(o.scene + ": no \"bodies\"");
  const std::string units = !o.units.empty() ? o.units : !spec->units.empty() ? spec->units : "mm";
  // Tests as `interfere clash --scene` (scene::select_clash_tests).
  auto selected = scene::select_clash_tests({.texts = o.test_texts, .tests_file = o.tests_file, .scene_tests = spec->tests,
                                             .clearance = o.clearance, .tolerance = o.tolerance,
                                             .default_options_given = o.clearance_given || o.tolerance_given});
  if (!selected) throw UsageError(selected.error().message());
  const std::vector<scene::ClashTest> tests = std::move(*selected);
  const scene::LoadOptions lo{.units = units, .fem_split = o.fem_split, .fem_linear_faces = o.fem_linear_faces,
                              .fem_field = o.fem_field, .fem_disp = o.fem_disp, .fem_scale = o.fem_scale};
  // --distribute frames: each rank a block of the frames for the whole scene (series.h); nothing
  // returned: the scene has no frames, so it goes by body pairs (docs/mpi.md, "Time series").
  if (o.distribute == Distribute::frames)
    if (const std::optional<int> done = run_frames(w, o, {*spec, tests, lo, motion, baseline_text, t_total})) return *done;

  phase_done(0);

  // 1. This rank's share of the entries: metadata, triangle counts, local boxes.
  const auto t_load = Clock::now();
  const double cpu_load1 = cpu_seconds();
  const std::vector<std::uint32_t> entry_reader = first_readers(*spec, w, share.sizes);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < entry_reader.size(); ++i)
    if (entry_reader[i] == static_cast<std::uint32_t>(w.rank)) mine.push_back(i);
  std::map<std::size_t, scene::LoadedScene> loaded;
  const auto load_specs = [&](const std::vector<std::size_t>& which) {
    std::vector<std::optional<scene::LoadedScene>> got(which.size());
    std::vector<std::string> errors(which.size());
    tbb::parallel_for(std::size_t{0}, which.size(), [&](std::size_t k) {
      auto s = scene::load_scene({spec->bodies[which[k]]}, lo);
      if (!s) errors[k] = s.error().message();
      else got[k] = std::move(*s);
    });
    for (std::size_t k = 0; k < which.size(); ++k) {
      if (!errors[k].empty()) abort_job(w, errors[k]);
      loaded.emplace(which[k], std::move(*got[k]));
    }
  };
  load_specs(mine);
  std::vector<BodyInfo> my_info;
  nlohmann::json input_warnings = nlohmann::json::array();  // [entry, warning]
  nlohmann::json steps = nlohmann::json::array();  // an FE entry's steps: [entry, labels, times, per step [[ordinal, box]]]
  for (const std::size_t s : mine) {
    const scene::LoadedScene& l = loaded.at(s);
    for (const std::string& x : l.scene.warnings) input_warnings.push_back({s, x});
    if (!l.scene.frames.empty()) {
      nlohmann::json labels = nlohmann::json::array(), times = nlohmann::json::array(), shapes = nlohmann::json::array();
      for (const scene::Frame& f : l.scene.frames) {
        if (!f.poses.empty()) abort_job(w, spec->bodies[s].where + ": steps with poses are not distributed (issue #31)");
        labels.push_back(f.label), times.push_back(f.time);
        nlohmann::json list = nlohmann::json::array();
        for (const scene::Frame::Shape& sh : f.shapes) {
          Aabb b;
          for (const Vec3& p : *sh.positions) b.expand(p);
          list.push_back({sh.body, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z});
        }
        shapes.push_back(list);
      }
      steps.push_back({s, labels, times, shapes});
    }
    for (std::uint32_t k = 0; k < l.scene.bodies.size(); ++k) {
      BodyInfo b;
      b.mesh_key = mesh_key(spec->bodies[s], s, l.scene, k);
      b.meta = l.scene.bodies[k];
      b.meta.mesh = nullptr, b.meta.source_ids = nullptr, b.meta.source_faces = nullptr, b.meta.vertex_ids = nullptr;
      b.meta.world_model = nullptr;
      b.triangles = l.scene.bodies[k].mesh->num_triangles();
      for (const Vec3& p : l.scene.bodies[k].mesh->positions) b.local_box.expand(p);
      b.spec = static_cast<std::uint32_t>(s), b.ordinal = k;
      if (l.zero_clearance_fits.reach && l.zero_clearance_fits.check) b.fit_reach = l.zero_clearance_fits.reach(k);
      my_info.push_back(std::move(b));
    }
  }
  phase_done(1);
  std::string warn_bytes;
  {
    const std::vector<std::uint8_t> v = nlohmann::json::to_cbor(nlohmann::json{input_warnings, steps});
    warn_bytes.assign(v.begin(), v.end());
  }
  std::vector<BodyInfo> info;
  {
    const Gathered all = allgather_buffer(encode(my_info, spec->bodies));
    my_info = {};
    std::size_t count = 0;
    for (std::size_t r = 0; r < all.size(); ++r) count += count_bodies(all.part(r));
    info.reserve(count);
    for (std::size_t r = 0; r < all.size(); ++r) decode_bodies(all.part(r), spec->bodies, info);
  }
  std::vector<std::string> all_input_warnings;  // (in the order of the entries, as one process reads them)
  nlohmann::json all_steps = nlohmann::json::array();
  {
    std::vector<std::pair<std::size_t, std::string>> keyed;
    for (const std::string& bytes : allgather(warn_bytes)) {
      const nlohmann::json j = nlohmann::json::from_cbor(bytes);
      for (const nlohmann::json& x : j[0]) keyed.emplace_back(x[0].get<std::size_t>(), x[1].get<std::string>());
      for (const nlohmann::json& x : j[1]) all_steps.push_back(x);
    }
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto& [e, x] : keyed) all_input_warnings.push_back(std::move(x));
  }
  std::sort(info.begin(), info.end(), [](const BodyInfo& x, const BodyInfo& y) {
    return std::tie(x.spec, x.ordinal) < std::tie(y.spec, y.ordinal);
  });
  const auto n = static_cast<std::uint32_t>(info.size());
  {
    std::unordered_map<std::string_view, std::uint32_t> seen;
    seen.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i)
      if (const auto [it, added] = seen.emplace(info[i].meta.id, i); !added)
        throw UsageError(spec->bodies[info[i].spec].where + ": body id '" + info[i].meta.id + "' also belongs to " +
                         spec->bodies[info[it->second].spec].where +
                         ": interfere-mpi needs ids unique across the scene file's entries (give \"id\"s)");
  }
  if (static_cast<std::uint32_t>(w.size) > n && w.rank == 0)
    std::fprintf(stderr, "[interfere-mpi] warning: %d ranks for %u bodies: %u ranks stay idle\n", w.size, n,
                 static_cast<unsigned>(w.size) - n);
  const double load1_seconds = since(t_load);
  phase_done(2);
  const double load1_cpu = cpu_seconds() - cpu_load1;

  // The scene as metadata (every rank): the motion's frames by body id.
  scene::Scene skeleton;
  skeleton.units = units;
  skeleton.bodies.reserve(info.size());
  for (BodyInfo& b : info) skeleton.bodies.push_back(std::move(b.meta));  // (one copy of the metadata: memory a rank)
  if (!motion.empty())
    if (const Status s = scene::read_motion(motion, skeleton); !s) throw UsageError(s.error().message());
  // An FE entry's displacement steps (fem/bodies.h): frames that deform its bodies; every rank
  // knows their labels, times and the deformed bodies' local boxes per step.
  std::vector<std::vector<std::pair<std::uint32_t, Aabb>>> step_boxes;  // per frame: (global body, local box)
  std::size_t fe_entry = SIZE_MAX;
  if (all_steps.size() > 1) throw UsageError("two entries with displacement steps: a scene's motion comes from one source");
  if (!all_steps.empty()) {
    if (!motion.empty()) throw UsageError("--motion: the inputs already carry steps (an FE model's); give one motion");
    const nlohmann::json& st = all_steps[0];
    fe_entry = st[0].get<std::size_t>();
    std::uint32_t first = 0;
    while (first < n && info[first].spec != fe_entry) ++first;
    for (std::size_t f = 0; f < st[1].size(); ++f) {
      scene::Frame fr;
      fr.label = st[1][f].get<std::string>(), fr.time = st[2][f].get<double>();
      skeleton.frames.push_back(std::move(fr));
      step_boxes.emplace_back();
      for (const nlohmann::json& x : st[3][f]) {
        Aabb b;
        b.lo = {x[1].get<double>(), x[2].get<double>(), x[3].get<double>()}, b.hi = {x[4].get<double>(), x[5].get<double>(), x[6].get<double>()};
        step_boxes.back().emplace_back(first + x[0].get<std::uint32_t>(), b);
      }
    }
  }
  const bool moving = !skeleton.frames.empty();
  bool deforms = false;
  for (const auto& sb : step_boxes) deforms = deforms || !sb.empty();
  const bool reference = moving && deforms && o.reference;  // (SceneClashOptions::reference; --no-reference)

  // 2. The broad phase and the partition (the same on every rank).
  // (with deformation, the reference configuration first: its pairs are checked, not counted)
  const std::size_t uncounted = reference ? 1 : 0;
  std::vector<std::vector<AabbF>> boxes(uncounted + (moving ? skeleton.frames.size() : 1), std::vector<AabbF>(n));
  std::vector<std::vector<Transform>> poses(boxes.size());
  {
    std::vector<Transform> pose(n);
    std::vector<Aabb> local(n);
    for (std::uint32_t i = 0; i < n; ++i) pose[i] = skeleton.bodies[i].pose, local[i] = info[i].local_box;
    for (std::size_t pass = 0; pass < boxes.size(); ++pass) {
      const std::size_t f = pass - uncounted;
      if (moving && pass >= uncounted) {
        for (const scene::Frame::Pose& p : skeleton.frames[f].poses) pose[p.body] = p.pose;
        if (f < step_boxes.size())
          for (const auto& [i, b] : step_boxes[f]) local[i] = b;
      }
      tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t i) { boxes[pass][i] = broad_box(local[i], pose[i]); });
      poses[pass] = pose;
    }
  }
  // Zero-clearance fits of STEP assemblies (static scenes, as the engine's hook): the pairs whose
  // broad boxes grown by the bodies' reach overlap are units too (an uncounted box set, as the
  // engine asks them apart from its candidates), so that each is decided on one rank, whose engine
  // call classifies it as one process does (SceneClashOptions::zero_clearance_fits, decide_pairs).
  bool any_reach = false;
  for (std::uint32_t i = 0; i < n; ++i) any_reach = any_reach || info[i].fit_reach > 0;
  const bool fits = any_reach && !moving;
  BroadResult broad = [&] {
    if (!fits) return broad_phase(skeleton.bodies, tests, boxes, uncounted);
    std::vector<std::vector<AabbF>> sets{boxes[0], boxes[0]};
    for (std::uint32_t i = 0; i < n; ++i) {
      AabbF& g = sets[0][i];
      const double r = info[i].fit_reach;
      if (!(r > 0) || !(g.lo[0] <= g.hi[0])) continue;
      for (int k = 0; k < 3; ++k) g.lo[k] = round_down(double(g.lo[k]) - r), g.hi[k] = round_up(double(g.hi[k]) + r);
    }
    return broad_phase(skeleton.bodies, tests, sets, 1);
  }();
  if (fits) poses.insert(poses.begin(), poses[0]);  // (join_classes: one pose set per box set)
  for (Unit& u : broad.units) u.cost = o.cost.pair(info[u.a].triangles, info[u.b].triangles) * u.frames;
  std::vector<std::uint64_t> triangles(n), mesh_keys(n);
  for (std::uint32_t i = 0; i < n; ++i) triangles[i] = info[i].triangles, mesh_keys[i] = info[i].mesh_key;
  join_classes(broad, mesh_keys, poses);  // (pairs the engine decides once stay on one rank)
  std::vector<std::uint32_t> reader(n);
  for (std::uint32_t i = 0; i < n; ++i) reader[i] = entry_reader[info[i].spec];
  const Partition part = partition(broad, boxes[0], triangles, o.cost, static_cast<std::size_t>(w.size), reader,
                                   o.cost.merge(broad.units.size()));  // (rank 0 merges after its engine call)
  if (talk)
    std::fprintf(stderr, "[interfere-mpi] %u bodies, %zu candidate pairs (%zu units) on %d ranks: estimated cost per rank %s\n",
                 n, broad.candidate_pairs, broad.units.size(), w.size, [&] {
                   std::string s;
                   for (const double c : part.rank_cost) s += (s.empty() ? "" : ", ") + std::to_string(c).substr(0, 8);
                   return s;
                 }().c_str());

  phase_done(3);

  // 3. The entries this rank's bodies come from (the rest of the first read is dropped), then one
  // engine call on those bodies deciding exactly this rank's pairs (decide_pairs).
  const std::vector<std::uint32_t>& my_units = part.rank_units[static_cast<std::size_t>(w.rank)];
  const std::vector<std::uint32_t>& my_bodies = part.rank_bodies[static_cast<std::size_t>(w.rank)];
  std::set<std::size_t> need;
  for (const std::uint32_t i : my_bodies) need.insert(info[i].spec);
  for (auto it = loaded.begin(); it != loaded.end();) it = need.count(it->first) ? std::next(it) : loaded.erase(it);
  std::vector<std::size_t> more;
  for (const std::size_t s : need)
    if (!loaded.count(s)) more.push_back(s);
  const auto t_load2 = Clock::now();
  const double cpu_load2 = cpu_seconds();
  load_specs(more);
  phase_done(4);
  RankResult mine_result;
  mine_result.load_seconds = load1_seconds + since(t_load2);
  mine_result.load_cpu_seconds = load1_cpu + cpu_seconds() - cpu_load2;
  for (const auto& [s, l] : loaded) {
    mine_result.bodies_loaded += l.scene.bodies.size();
    for (const scene::Body& b : l.scene.bodies) mine_result.triangles_loaded += b.mesh->num_triangles();
  }

  scene::SceneClashOptions eo;
  eo.group_by = scene::GroupBy::none;
  eo.depth_maps = true;  // (as `interfere clash`: the deepest node per clash and step)
  eo.reference = o.reference;
  const auto t_engine = Clock::now();
  const double cpu_engine = cpu_seconds();
  std::vector<scene::FrameRow> rows(moving ? skeleton.frames.size() : 0);
  for (std::size_t f = 0; f < rows.size(); ++f) rows[f].frame = static_cast<std::uint32_t>(f);
  std::set<std::string> open_warnings;
  if (!my_units.empty()) {
    scene::Scene sub;
    sub.units = units;
    std::vector<std::uint32_t> local(n, UINT32_MAX);
    // Bodies with one mesh key share one mesh, as in one process (entries read separately here).
    std::map<std::uint64_t, std::shared_ptr<const TriMesh>> shared;
    for (const std::uint32_t i : my_bodies) {
      local[i] = static_cast<std::uint32_t>(sub.bodies.size());
      sub.bodies.push_back(loaded.at(info[i].spec).scene.bodies[info[i].ordinal]);
      const auto [it, added] = shared.emplace(info[i].mesh_key, sub.bodies.back().mesh);
      if (!added && it->second->triangles == sub.bodies.back().mesh->triangles &&
          it->second->positions == sub.bodies.back().mesh->positions)
        sub.bodies.back().mesh = it->second;
    }
    const scene::LoadedScene* fe = fe_entry != SIZE_MAX && loaded.count(fe_entry) ? &loaded.at(fe_entry) : nullptr;
    std::uint32_t fe_first = 0;
    while (fe && fe_first < n && info[fe_first].spec != fe_entry) ++fe_first;
    for (std::size_t fi = 0; fi < skeleton.frames.size(); ++fi) {
      const scene::Frame& f = skeleton.frames[fi];
      scene::Frame g;
      g.label = f.label, g.time = f.time;
      for (const scene::Frame::Pose& p : f.poses)
        if (local[p.body] != UINT32_MAX) g.poses.push_back({local[p.body], p.pose});
      if (fe)
        for (const scene::Frame::Shape& sh : fe->scene.frames[fi].shapes)
          if (local[fe_first + sh.body] != UINT32_MAX) g.shapes.push_back({local[fe_first + sh.body], sh.positions});
      sub.frames.push_back(std::move(g));
    }
    bool any_fit = false;
    for (const std::uint32_t i : my_bodies) any_fit = any_fit || bool(loaded.at(info[i].spec).nominal_fit);
    if (any_fit)
      eo.nominal_fit = [&](std::uint32_t a, std::uint32_t b, const Model& wa, const Model& wb, const ClashResult& r, double depth) {
        const BodyInfo& ia = info[my_bodies[a]];
        const BodyInfo& ib = info[my_bodies[b]];
        if (ia.spec != ib.spec) return false;  // (bodies of different files share no B-Rep faces)
        const scene::LoadedScene& l = loaded.at(ia.spec);
        return l.nominal_fit && l.nominal_fit(ia.ordinal, ib.ordinal, wa, wb, r, depth);
      };
    if (fits) {
      bool any = false;
      for (const std::uint32_t i : my_bodies) any = any || info[i].fit_reach > 0;
      if (any) {
        eo.zero_clearance_fits.reach = [&](std::uint32_t a) { return info[my_bodies[a]].fit_reach; };
        eo.zero_clearance_fits.check = [&](std::uint32_t a, std::uint32_t b, double* gap) {
          const BodyInfo& ia = info[my_bodies[a]];
          const BodyInfo& ib = info[my_bodies[b]];
          if (ia.spec != ib.spec) return false;  // (bodies of different files share no B-Rep faces)
          const scene::LoadedScene& l = loaded.at(ia.spec);
          return l.zero_clearance_fits.check && l.zero_clearance_fits.check(ia.ordinal, ib.ordinal, gap);
        };
      }
    }
    for (const std::uint32_t k : my_units) eo.decide_pairs.emplace_back(local[broad.units[k].a], local[broad.units[k].b]);
    scene::SceneClashResult r = scene::clash_scene(sub, tests, eo);
    ++mine_result.calls;
    mine_result.pairs += my_units.size();
    mine_result.bodies_used = my_bodies.size();
    for (const std::uint32_t i : my_bodies) mine_result.body_triangles += info[i].triangles;
    for (const std::uint32_t k : my_units) mine_result.pair_triangles += info[broad.units[k].a].triangles + info[broad.units[k].b].triangles;
    mine_result.core_runs += r.core_runs;
    mine_result.prepare_seconds += r.prepare_seconds, mine_result.broad_seconds += r.broad_seconds;
    mine_result.narrow_seconds += r.narrow_seconds;
    mine_result.reference_checked = mine_result.reference_checked || r.reference_checked;
    std::set<std::pair<std::uint32_t, std::uint32_t>> own;
    for (const std::uint32_t k : my_units) own.emplace(broad.units[k].a, broad.units[k].b);
    for (scene::SceneClash& c : r.clashes) {
      c.a = my_bodies[c.a], c.b = my_bodies[c.b];
      if (c.has_deepest) c.deepest.body = my_bodies[c.deepest.body];
      if (!own.count({c.a, c.b}))
        throw std::logic_error("the engine found a clash of bodies '" + skeleton.bodies[c.a].id + "' and '" + skeleton.bodies[c.b].id +
                               "', which the plan did not give this rank");
      mine_result.clashes.push_back(std::move(c));
    }
    for (scene::FramePairRow& p : r.frame_pairs) {
      p.a = my_bodies[p.a], p.b = my_bodies[p.b];
      if (p.has_deepest) p.deepest.body = my_bodies[p.deepest.body];
      mine_result.frame_pairs.push_back(p);
    }
    for (scene::ReferencePair& p : r.reference_pairs) {
      p.a = my_bodies[p.a], p.b = my_bodies[p.b];
      mine_result.reference_pairs.push_back(p);
    }
    if (reference && !r.reference_checked) {
      // None of this rank's bodies deforms: its reference configuration is every frame's (FE steps
      // move no body), so its pairs' reference verdicts are those of frame 0.
      std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>, Verdict> v0;
      for (const scene::FramePairRow& p : r.frame_pairs)
        if (p.frame == 0) v0[{p.test, p.a, p.b}] = p.verdict;  // (rows already in global indices)
      for (const auto& [k, v] : v0) mine_result.reference_pairs.push_back({std::get<0>(k), std::get<1>(k), std::get<2>(k), v});
    }
    for (std::size_t f = 0; f < r.frames.size() && f < rows.size(); ++f) add_row(rows[f], r.frames[f]);
    for (const std::string& x : r.warnings)
      if (x.starts_with("body '")) open_warnings.insert(x);  // (selections: the broad phase's, over the whole scene)
  }
  mine_result.frames = std::move(rows);
  mine_result.warnings.assign(open_warnings.begin(), open_warnings.end());
  mine_result.engine_seconds = since(t_engine);
  mine_result.engine_cpu_seconds = cpu_seconds() - cpu_engine;
  phase_done(5);
  mine_result.phases = phases;
  mine_result.peak_rss_mb = peak_rss_mb();
  mine_result.cpu_seconds = cpu_seconds();

  // 4. Rank 0 merges and writes the report.
  const auto t_merge = Clock::now();
  const double cpu_merge = cpu_seconds();
  // (rank 0 keeps its own findings as they are: only the other ranks' are encoded and sent)
  const Gathered results = gather_buffer(w.rank == 0 ? std::string() : encode(mine_result));
  int status = 0;
  if (w.rank == 0) {
    std::vector<RankResult> per_rank;
    per_rank.push_back(std::move(mine_result));
    for (std::size_t r = 1; r < results.size(); ++r) per_rank.push_back(decode_result(results.part(r)));
    scene::SceneClashOptions go;
    go.group_by = o.group_by == "pair" ? scene::GroupBy::pair : o.group_by == "location" ? scene::GroupBy::location : scene::GroupBy::none;
    go.group_distance = o.group_distance;
    scene::SceneClashResult result = merge(skeleton, tests, go, broad, triangles, per_rank, reference);
    if (!o.baseline.empty())
      if (const Status s = scene::apply_baseline(result, baseline_text, o.baseline); !s) throw UsageError(s.error().message());
    status = verdict_exit_status(result.verdict, o.fail_on.empty() ? FailOn{} : *parse_fail_on(o.fail_on));
    // (the gather, waiting for the last rank included, and the merge: CostModel::merge_pair_s)
    const std::array<double, 2> merge_s{since(t_merge), cpu_seconds() - cpu_merge};
    const double seconds = since(t_total);
    std::vector<std::string> inputs;
    std::set<std::string> listed;
    for (const scene::BodySpec& b : spec->bodies)  // (each file once, as load_scene lists them)
      if (listed.insert(b.file).second) inputs.push_back(b.file);
    if (!motion.empty()) inputs.push_back(motion);
    scene::ReportContext ctx{.command = "clash", .tool_version = INTERFERE_VERSION, .inputs = inputs,
                             .threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)),
                             .total_seconds = since(t_total), .exit_status = status, .warnings = all_input_warnings};
    if (!o.json.empty()) write_file(o.json, report_with_mpi(scene::report_json(skeleton, tests, result, ctx), triangles, per_rank, part, seconds, merge_s));
    write_clash_tables(o, skeleton, tests, result);
    if (!o.quiet) {
      for (const std::string& x : result.warnings) std::fprintf(stderr, "[interfere-mpi] warning: %s\n", x.c_str());
      for (std::size_t r = 0; r < per_rank.size(); ++r)
        std::fprintf(stderr, "[interfere-mpi] rank %zu: %zu pairs in %zu engine calls, %zu bodies read, load %.3f s, engine %.3f s, peak %.0f MB\n",
                     r, per_rank[r].pairs, per_rank[r].calls, per_rank[r].bodies_loaded, per_rank[r].load_seconds,
                     per_rank[r].engine_seconds, per_rank[r].peak_rss_mb);
    }
    std::FILE* out = summary_stream(o);
    const std::string verdict = summary_verdict(result.verdict);
    std::fprintf(out, "%s: %zu bodies, %zu candidate pairs: %zu clashes, %zu contacts, %zu clearance, %zu undecided (%d ranks)\n",
                 verdict.c_str(), result.bodies, result.candidate_pairs, result.clash_count, result.contact_count,
                 result.clearance_count, result.undecided_count, w.size);
  }
  return broadcast(status);
}

}  // namespace
}  // namespace interfere::mpi

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  interfere::mpi::World w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  int status = 0;
  try {
    if (argc >= 2 && std::string(argv[1]) == "simulate") {  // (docs/scaling.md: the partitioner alone, rank 0)
      if (w.rank == 0) status = interfere::mpi::simulate(argc - 2, argv + 2);
      MPI_Finalize();
      return status;
    }
    if (argc >= 2 && std::string(argv[1]) == "bearing")  // (issue #31 item 3: assembly frames in blocks per rank)
      status = interfere::mpi::run_bearing(w, argc - 1, argv + 1);
    else if (argc >= 2 && std::string(argv[1]) == "cell")  // (issue #31 item 3: path points in blocks per rank)
      status = interfere::mpi::run_cell(w, argc - 1, argv + 1);
    else if (argc >= 2 && std::string(argv[1]) == "sweep")  // (issue #31 item 3: probe path points in blocks per rank)
      status = interfere::mpi::run_sweep(w, argc - 1, argv + 1);
    else
      status = interfere::mpi::run(w, argc, argv);
  } catch (const interfere::mpi::InfoRequest& info) {
    if (w.rank == 0) std::fputs(info.text.c_str(), stdout);
    status = 0;
  } catch (const interfere::mpi::UsageError& e) {
    // (found alike by every rank: rank 0 says it; a rank that alone finds one ends the job)
    if (w.rank == 0) std::fprintf(stderr, "interfere: error: %s\n", e.what());
    status = 2;
  } catch (const std::bad_alloc&) {
    // (this rank ran out of memory: its message, the whole job ends with exit status 2)
    interfere::mpi::abort_job(w, "out of memory (std::bad_alloc): give the job more ranks or a rank more memory");
  } catch (const std::exception& e) {
    interfere::mpi::abort_job(w, e.what());
  }
  MPI_Finalize();
  return status;
}
