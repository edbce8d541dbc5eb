// Feature-preserving QEM simplification, the public entry point (issue #6, item 5): validation,
// the budget, exact-position welding, one run of the Simplifier (qem_run.cpp; Garland & Heckbert,
// SIGGRAPH 1997, with the assembly-feature rule of He & Xu, SJTU 2023, §3.3), the result's
// self-intersection check with the guarded rerun, the output split per face and the Hausdorff error.
#include "interfere/simplify/qem.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <tuple>

#include <tbb/parallel_invoke.h>

#include "interfere/simplify/hausdorff.h"
#include "contact_zone.h"
#include "local_frame.h"
#include "qem_internal.h"

namespace interfere {
namespace {

std::size_t budget_of(const TriMesh& mesh, const SimplifyOptions& o, Error& err) {
  const std::size_t n = mesh.num_triangles();
  if (o.target_triangles > 0) {
    if (o.target_triangles > n) {
      err.reason = "triangle budget " + std::to_string(o.target_triangles) + " is larger than the mesh (" +
                   std::to_string(n) + " triangles)";
      return 0;
    }
    return o.target_triangles;
  }
  if (!(o.ratio > 0 && o.ratio <= 1)) {
    err.reason = o.ratio == 0 ? "no triangle budget: give target_triangles > 0 or a ratio in (0, 1]"
                              : "ratio must lie in (0, 1], got " + short_number(o.ratio);
    return 0;
  }
  const auto t = static_cast<std::size_t>(std::llround(o.ratio * static_cast<double>(n)));
  if (t == 0) {
    err.reason = "ratio " + short_number(o.ratio) + " leaves no triangle of " + std::to_string(n);
    return 0;
  }
  return t;
}

// `box`: the mesh's bounds when known (0: computed). `budget_warnings`: false leaves out the
// warnings about this run's own budget (not reached, one below): simplify_within's runs, whose
// budgets are its search's, not the caller's.
Expected<SimplifyResult> simplify_in_frame(const TriMesh& mesh, const SimplifyOptions& options, std::size_t target,
                                           const Aabb* box = nullptr, bool budget_warnings = true);

double phase_total(const SimplifyResult& r) {
  double s = 0;
  for (const auto& [name, sec] : r.phases) s += sec;
  return s;
}

// The result of a run in `frame` back in the input's coordinates: positions (kept vertices map
// back exactly, moved ones are rounded), lengths (exact), the error bound grown by that rounding.
// With a translated frame the rounding could in principle make two triangles meet: the result is
// checked again and false returned (the caller runs in the input's frame) if it has an
// intersecting pair other than the input's own.
bool to_world(SimplifyResult& r, const TriMesh& input, const qem::LocalFrame& frame, const SimplifyOptions& o) {
  for (Vec3& p : r.mesh.positions) p = frame.to_world(p);
  const auto length = [&](double& d) {
    if (d > 0) d = frame.length_to_world(d);
  };
  length(r.hausdorff);
  length(r.hausdorff_features);
  length(r.bbox_diagonal);
  r.max_unmodified_cost = std::ldexp(r.max_unmodified_cost, -4 * frame.exponent);  // area x distance^2
  if (r.error_bound >= 0) {
    length(r.error_bound);
    if (frame.translated) {  // each coordinate of a moved vertex rounded by at most half an ulp
      const Aabb b = r.mesh.bounds();
      const double m = std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x),
                                 std::abs(b.hi.y), std::abs(b.hi.z)});
      if (m > 0) r.error_bound += std::ldexp(1.0, std::ilogb(m) - 52);  // >= sqrt(3)/2 ulp
    }
  }
  if (!frame.translated || !o.prevent_self_intersections) return true;
  const auto pairs = self_intersecting_pairs(r.mesh);
  r.inherited_pairs = 0;
  if (pairs.empty()) return true;
  // The input's own pairs: both triangles as in the input (same corners).
  using Key = std::array<double, 9>;  // the corners, sorted
  const auto key = [](std::array<Vec3, 3> c) {
    std::sort(c.begin(), c.end(), [](const Vec3& a, const Vec3& b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    return Key{c[0].x, c[0].y, c[0].z, c[1].x, c[1].y, c[1].z, c[2].x, c[2].y, c[2].z};
  };
  std::vector<Key> in(input.num_triangles());
  for (std::size_t t = 0; t < in.size(); ++t) in[t] = key(input.corners(t));
  std::sort(in.begin(), in.end());
  const auto kept = [&](std::uint32_t t) { return std::binary_search(in.begin(), in.end(), key(r.mesh.corners(t))); };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> moved;
  for (const auto& xy : pairs)
    if (!kept(xy.first) || !kept(xy.second)) moved.push_back(xy);
  if (moved.empty()) return true;
  if (!o.inherit_input_contacts) return false;
  const std::vector<Aabb> near = qem::ContactZone::reach(r.mesh, moved);
  const qem::ContactZone zone(input, &near);
  for (const auto& [x, y] : moved)
    if (!zone.holds(r.mesh.corners(x), r.mesh.corners(y))) return false;
  r.inherited_pairs = moved.size();
  return true;
}

}  // namespace

namespace {

// One run to `target` triangles (in a local frame where the coordinates call for one).
Expected<SimplifyResult> simplify_to(const TriMesh& mesh, const SimplifyOptions& options, std::size_t target,
                                     bool budget_warnings = true) {
  const Aabb box = mesh.bounds();
  if (const auto frame = qem::local_frame(mesh, box)) {
    const auto t0 = std::chrono::steady_clock::now();
    auto r = simplify_in_frame(qem::to_local(mesh, *frame), options, target, nullptr, budget_warnings);
    if (!r) return r;
    if (to_world(*r, mesh, *frame, options)) {
      r->phases.insert(r->phases.begin(),
                       {"local frame", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() -
                                           phase_total(*r)});
      return r;
    }
  }
  return simplify_in_frame(mesh, options, target, &box);
}

// SimplifyOptions::max_error: from the budget asked for (its error bound too large), a budget that
// should hold the error if it falls as 1/N (QEM on a smooth surface: the error goes with the squared
// edge length), raised until one does (the input's own count does: error 0); then the bracket
// between the last budget that did not and the first that did is narrowed to 2 % of the triangles
// (or 2), alternately by interpolating log error against log budget and by halving (the halving
// bounds the runs where the model is off); each step a full run. The result with the fewest
// triangles within the error is returned, its phases led by the time of the other runs.
Expected<SimplifyResult> simplify_within(const TriMesh& mesh, const SimplifyOptions& options, std::size_t target) {
  const double limit = options.max_error;
  SimplifyOptions o = options;
  o.measure_error = true;
  const auto t0 = std::chrono::steady_clock::now();
  auto r = simplify_to(mesh, o, target);  // (the budget asked for: its warnings stand if it holds)
  if (!r) return r;
  r->max_error_runs = 1;
  if (r->error_bound <= limit) return r;
  std::size_t lo = target, hi = mesh.num_triangles(), runs = 1;
  double e_lo = r->error_bound, e_hi = 0;
  std::optional<SimplifyResult> best;
  // The search's runs report themselves as a stage each (their collapses' progress would restart).
  o.progress = nullptr;
  o.stage = nullptr;
  const auto step = [&](std::size_t budget) -> Status {
    if (options.stage) {
      const std::string what = "error limit: run " + std::to_string(runs + 1) + " (budget " + std::to_string(budget) + ")";
      options.stage(what.c_str());
    }
    auto m = simplify_to(mesh, o, budget, false);
    ++runs;
    if (!m) return m.error();
    if (m->error_bound <= limit) {
      hi = std::min(budget, m->mesh.num_triangles());
      e_hi = m->error_bound;
      best = std::move(*m);
    } else {
      lo = budget, e_lo = m->error_bound;
    }
    return {};
  };
  const auto tolerance = [&] { return std::max<std::size_t>(2, hi / 50); };
  while (!best && hi > lo + tolerance()) {  // 1/N model, 10 % beyond; at least a tolerance up
    const double guess = double(lo) * (e_lo / limit) * 1.1;
    const std::size_t b = std::clamp<std::size_t>(static_cast<std::size_t>(std::min(guess, double(hi))),
                                                  lo + tolerance(), hi);
    if (b >= hi) break;
    if (Status s = step(b); !s) return s.error();
  }
  for (bool halve = false; hi > lo + tolerance(); halve = !halve) {
    std::size_t b = lo + (hi - lo) / 2;
    if (!halve && e_hi > 0 && e_lo > limit) {  // log-log interpolation, kept a half-tolerance inside
      const double x = std::log(double(lo)) + (std::log(limit) - std::log(e_lo)) *
                                                  (std::log(double(hi)) - std::log(double(lo))) /
                                                  (std::log(e_hi) - std::log(e_lo));
      const std::size_t margin = tolerance() / 2;
      if (std::isfinite(x))
        b = std::clamp<std::size_t>(static_cast<std::size_t>(std::exp(x)), lo + margin, hi - margin);
    }
    if (Status s = step(b); !s) return s.error();
  }
  if (!best) {  // nothing between held the error: the input's own count
    auto m = simplify_to(mesh, o, hi, false);
    ++runs;
    if (!m) return m;
    best = std::move(*m);
  }
  const double before = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - phase_total(*best);
  best->phases.insert(best->phases.begin(), {"max-error search (other runs)", before});
  best->max_error_runs = runs;
  best->error_limited_budget = best->target_triangles;
  // (its own budget's warnings were left out: the one below says what happened)
  best->one_below = false;
  best->target_triangles = target;
  best->reached = false;
  const std::string held = best->error_bound <= limit
                               ? " triangles keep it within (error bound "
                               : " triangles, the input's own, do not either (its rounding margin alone: error bound ";
  best->warnings.insert(best->warnings.begin(),
                        "budget " + std::to_string(target) + ": its error bound " + short_number(r->error_bound) +
                            " exceeds max_error " + short_number(limit) + "; " +
                            std::to_string(best->mesh.num_triangles()) + held + short_number(best->error_bound) +
                            ", " + std::to_string(runs) + " runs)");
  return std::move(*best);
}

}  // namespace

std::optional<FeatureMode> feature_mode_from_name(std::string_view name) {
  for (const FeatureMode m : {FeatureMode::weight, FeatureMode::last, FeatureMode::lock})
    if (name == feature_mode_name(m)) return m;
  return std::nullopt;
}

const char* feature_mode_name(FeatureMode mode) {
  switch (mode) {
    case FeatureMode::weight: return "weight";
    case FeatureMode::last: return "last";
    case FeatureMode::lock: return "lock";
  }
  return "?";
}

std::optional<SeamMode> seam_mode_from_name(std::string_view name) {
  if (name == "all") return SeamMode::all;
  if (name == "auto") return SeamMode::as_needed;
  if (name == "features") return SeamMode::features;
  if (name == "none") return SeamMode::none;
  return std::nullopt;
}

std::string one_below_warning(std::size_t budget) {
  return "budget " + std::to_string(budget) + " not reached exactly: " + std::to_string(budget - 1) +
         " triangles, one below (every collapse left removes two triangles, as on a closed mesh)";
}

Expected<SimplifyResult> simplify(const TriMesh& mesh, const SimplifyOptions& options) {
  const std::size_t nt = mesh.num_triangles();
  if (nt == 0) return Error{.reason = "the mesh has no triangles"};
  for (const Vec3& p : mesh.positions)
    if (!is_finite(p)) return Error{.reason = "the mesh has a non-finite vertex position"};
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t v : mesh.triangles[t])
      if (v >= mesh.num_vertices())
        return Error{.reason = "triangle " + std::to_string(t) + " has a vertex index out of range"};
  if (!options.face_ids.empty() && options.face_ids.size() != nt)
    return Error{.reason = "face_ids has " + std::to_string(options.face_ids.size()) + " entries for " +
                           std::to_string(nt) + " triangles"};
  for (std::uint32_t t : options.feature_triangles)
    if (t >= nt)
      return Error{.reason = "feature triangle " + std::to_string(t) + " is out of range: the mesh has " +
                             std::to_string(nt) + " triangles"};
  if (!(options.sharp_angle_deg >= 0 && options.sharp_angle_deg < 180))
    return Error{.reason = "sharp angle " + short_number(options.sharp_angle_deg) +
                           " degrees: give a dihedral angle in (0, 180), or 0 for no sharp-edge regions"};
  if (!(options.max_error >= 0 && std::isfinite(options.max_error)))
    return Error{.reason = "max_error " + (std::isnan(options.max_error) ? std::string("is not a number") : short_number(options.max_error)) +
                           ": give a length > 0 (the largest error bound allowed), or 0 for none"};
  Error err;
  const std::size_t target = budget_of(mesh, options, err);
  if (target == 0) return err;
  if (options.max_error > 0) return simplify_within(mesh, options, target);
  // Far from the origin, or very large or small: simplified in a local frame (local_frame.h).
  return simplify_to(mesh, options, target);
}

namespace {

Expected<SimplifyResult> simplify_in_frame(const TriMesh& mesh, const SimplifyOptions& options, std::size_t target,
                                           const Aabb* known_box, bool budget_warnings) {
  const std::size_t nt = mesh.num_triangles();
  SimplifyResult r;
  qem::PhaseClock clock(r);
  r.input_triangles = nt;
  r.target_triangles = target;
  const Aabb box = known_box ? *known_box : mesh.bounds();
  r.bbox_diagonal = norm(box.extent());

  std::vector<std::uint32_t> face = options.face_ids;
  const bool have_faces = !face.empty();
  if (!have_faces) {
    face = options.sharp_angle_deg > 0 ? sharp_edge_regions(mesh, options.sharp_angle_deg)
                                       : std::vector<std::uint32_t>(nt, 0);
  }
  std::vector<std::uint32_t> features = options.feature_faces;
  std::sort(features.begin(), features.end());
  features.erase(std::unique(features.begin(), features.end()), features.end());
  std::vector<std::uint8_t> feature_tri(nt, 0);
  if (!features.empty()) {
    // Face ids are dense (B-Rep faces, regions): a flag per id; else (ids beyond 4 per triangle)
    // a binary search per triangle.
    const std::uint32_t max_id = *std::max_element(face.begin(), face.end());
    if (max_id < 4 * nt + 1024) {
      std::vector<std::uint8_t> is_feature(std::size_t{max_id} + 1, 0);
      for (std::uint32_t f : features)
        if (f <= max_id) is_feature[f] = 1;
      for (std::size_t t = 0; t < nt; ++t) feature_tri[t] = is_feature[face[t]];
    } else {
      for (std::size_t t = 0; t < nt; ++t)
        feature_tri[t] = std::binary_search(features.begin(), features.end(), face[t]) ? 1 : 0;
    }
  }
  // Parts of larger faces (the clamped annuli of He & Xu's TopFace/BottomFace, issue #29).
  for (std::uint32_t t : options.feature_triangles) feature_tri[t] = 1;
  const bool any_feature = !features.empty() || !options.feature_triangles.empty();
  if (any_feature)
    for (std::size_t t = 0; t < nt; ++t) r.feature_triangles_in += feature_tri[t];
  if (!features.empty()) {  // ids no triangle carries keep nothing: named (the first ten)
    std::vector<std::uint8_t> carried(features.size(), 0);
    for (std::size_t t = 0; t < nt; ++t)
      if (feature_tri[t]) carried[std::lower_bound(features.begin(), features.end(), face[t]) - features.begin()] = 1;
    std::string missing;
    std::size_t n_missing = 0;
    for (std::size_t i = 0; i < features.size(); ++i)
      if (!carried[i] && n_missing++ < 10) missing += (missing.empty() ? "" : ", ") + std::to_string(features[i]);
    if (n_missing > 0)
      r.warnings.push_back((n_missing == features.size() ? std::string("no triangle carries any of the feature face ids: ")
                                                         : std::string("no triangle carries feature face id(s) ")) +
                           missing + (n_missing > 10 ? " and " + std::to_string(n_missing - 10) + " more" : ""));
  }

  // The face ids the simplifier constrains (SimplifyOptions::seams): all; the feature faces', the
  // others as one; none. `face` stays the output's tag.
  std::vector<std::uint32_t> seam_face;
  if (options.seams == SeamMode::all || options.seams == SeamMode::as_needed) {
    seam_face = face;
  } else {
    std::uint32_t other = std::numeric_limits<std::uint32_t>::max();  // an id no feature face has
    while (std::binary_search(features.begin(), features.end(), other)) --other;
    seam_face.resize(nt);
    for (std::size_t t = 0; t < nt; ++t)
      seam_face[t] = options.seams == SeamMode::features && feature_tri[t] ? face[t] : other;
  }
  TriMesh welded = weld_positions(mesh);
  r.input_vertices_welded = welded.num_vertices();
  clock.lap("weld");
  // No self-intersections: plain QEM first, its result checked with the engine's exact self-clash;
  // only when it created an intersection is the run repeated with the per-collapse guard (which
  // costs about 10x). Either way the result has no self-intersection the input did not have.
  SimplifyOptions plain = options;
  plain.prevent_self_intersections = options.prevent_self_intersections && options.guard_every_collapse;
  const SimplifyResult before = r;
  // The input's own contact zone (contact_zone.h): a result pair inside it is inherited. Made
  // where new pairs were found (grown when one lies outside), or everywhere when every collapse
  // is guarded from the start.
  const bool inherit = options.prevent_self_intersections && options.inherit_input_contacts;
  std::optional<qem::ContactZone> zone;
  std::vector<Aabb> zone_near;  // where it was made
  const auto make_zone = [&](const TriMesh& m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& p) {
    if (zone && options.guard_every_collapse) return;  // made everywhere
    const qem::BoxGrid made(zone_near);
    std::size_t added = 0;
    for (const Aabb& b : qem::ContactZone::reach(m, p))
      if (made.empty() || !made.contains(b)) zone_near.push_back(b), ++added;
    if (added > 0 || !zone) zone.emplace(mesh, &zone_near);
  };
  const auto zone_ptr = [&]() -> const qem::ContactZone* { return inherit && zone ? &*zone : nullptr; };
  if (inherit && options.guard_every_collapse) zone.emplace(mesh);
  // The welded input is not copied for a possible rerun (rare): it is welded again then.
  auto sp = std::make_unique<qem::Simplifier>(std::move(welded), seam_face, feature_tri, plain);
  sp->set_contact_zone(zone_ptr());
  if (options.prevent_self_intersections && !options.guard_every_collapse) sp->keep_handoff();
  sp->run(target, r);
  if (r.degenerate_triangles == nt)
    return Error{.reason = "every triangle of the mesh is degenerate (two corners at one position): nothing to "
                           "simplify"};
  clock.restart();
  // Surviving triangles in input order, unused vertices dropped (new ids in order of first use).
  // out_origin: the input triangle of each output triangle.
  auto compact = [&](const qem::Simplifier& s, std::vector<std::uint32_t>& out_face,
                     std::vector<std::uint32_t>& out_origin) {
    TriMesh m = s.live_mesh(out_origin);  // after the run: input triangle numbers, in order
    out_face.resize(out_origin.size());
    for (std::size_t i = 0; i < out_origin.size(); ++i) out_face[i] = face[out_origin[i]];
    return m;
  };
  std::vector<std::uint32_t> out_face, out_origin;
  TriMesh out = compact(*sp, out_face, out_origin);
  clock.lap("output");
  // SeamMode::as_needed: with every seam kept the budget is out of reach; again with the borders of
  // the feature faces only (the error is measured once, on the result returned). Decided on the
  // plain run (its checks and reruns are not needed then), and again after them.
  const auto with_feature_seams = [&](std::size_t held) {
    SimplifyOptions o = options;
    o.seams = SeamMode::features;
    auto again = simplify_in_frame(mesh, o, target, &box, budget_warnings);
    if (!again) return again;
    again->seams_relaxed_at = held;
    again->warnings.insert(again->warnings.begin(),
                           "with every face seam kept the budget " + std::to_string(target) + " was out of reach (" +
                               std::to_string(held) +
                               " triangles at most): only the borders of assembly-feature faces were kept "
                               "(--seams auto)");
    clock.lap("check");
    again->phases.insert(again->phases.begin(), {"every seam kept (first attempt)", phase_total(r)});
    return again;
  };
  if (options.seams == SeamMode::as_needed && out.num_triangles() > target) return with_feature_seams(out.num_triangles());
  // Split along faces when face ids were given or regions were made; done beside the check (a
  // rerun, rare, splits its own result again).
  const bool splitting = have_faces || options.sharp_angle_deg > 0;
  TriMesh split;
  // The intersecting pairs of a result (m, each triangle's input triangle `origin`) the input did
  // not have: not both as in the input, and not inherited (counted in `held`).
  const auto pairs_of = [&](const TriMesh& m, const std::vector<std::uint32_t>& origin, std::size_t* held = nullptr) {
    std::vector<std::uint8_t> unmodified(m.num_triangles());  // pairs of two are not tested
    for (std::uint32_t i = 0; i < unmodified.size(); ++i)
      unmodified[i] = m.corners(i) == mesh.corners(origin[i]) ? 1 : 0;
    auto p = self_intersecting_pairs(m, &unmodified);
    if (p.empty() || !inherit) return p;
    make_zone(m, p);
    if (const qem::ContactZone* z = zone_ptr()) {
      std::size_t k = 0;
      for (const auto& xy : p)
        if (!z->holds(m.corners(xy.first), m.corners(xy.second))) p[k++] = xy;
      if (held) *held = p.size() - k;
      p.resize(k);
    }
    return p;
  };
  std::size_t inherited = 0;
  if (inherit && options.guard_every_collapse) pairs_of(out, out_origin, &inherited);
  if (options.prevent_self_intersections && !options.guard_every_collapse) {
    // The input's own intersections (touching parts of an assembly, say) cannot be removed: a pair
    // of output triangles both identical to their input triangles (same corner positions) was in
    // the input; every other intersecting pair is new and calls for a rerun.
    // The first reruns repeat the plain run's batched passes, which make the same collapses, check
    // the mesh they leave at the handoff, and if it has no new pair guard the heap phase, where the
    // coarsest, last collapses make most intersections: first near the new pairs only, then every
    // heap collapse (casing, P1 with strict features: 102 -> 48 ms). Otherwise, or if pairs
    // remain, the next reruns guard the neighbourhoods of the new pairs found so far in the
    // batched passes too; should a rerun still add an intersection elsewhere, its neighbourhood
    // joins the region, and the last resort guards every collapse (a moved triangle then meets no
    // other: none can be added).
    const auto new_pairs = [&] {
      inherited = 0;
      return pairs_of(out, out_origin, &inherited);
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    tbb::parallel_invoke([&] { pairs = new_pairs(); },
                         [&] {
                           if (splitting) split = split_by_face(out, out_face);
                         });
    std::size_t reruns = 0;
    // The reruns' own phases (setup .. heap) are added to their names; "check" keeps only the
    // checks and the output between them.
    const auto restart = [&] {
      clock.lap("check");
      auto phases = std::move(r.phases);
      r = before;
      r.phases = std::move(phases);
      r.guard_rerun = true;
      r.guard_reruns = ++reruns;
    };
    // The guard region: each new pair's box grown by its diagonal, from every run so far.
    std::vector<Aabb> region;
    bool pending = true;  // the current pairs are not in the region yet
    const auto grow_region = [&] {
      if (!pending) return;
      pending = false;
      const std::vector<Aabb> grown = qem::pair_neighbourhoods(out, pairs, 1);
      region.insert(region.end(), grown.begin(), grown.end());
    };
    if (!pairs.empty()) {
      const TriMesh input = weld_positions(mesh);
      // Heap-only reruns: the first guards the heap's collapses near the new pairs only (a fold
      // left by the heap is usually local: 10^6 -> 10 % of the bumpy sphere, 6 pairs around one
      // vertex), the second every heap collapse.
      // Large meshes start these from the plain run's state at the handoff (kept by it) instead
      // of repeating the passes. The handoff mesh is the same each time: checked once.
      const auto kept = sp->handoff();
      int handoff_clean = -1;
      const auto clean = [&](const qem::Simplifier& h) {
        if (handoff_clean < 0) {
          std::vector<std::uint32_t> handoff_origin;
          const TriMesh m = h.live_mesh(handoff_origin);
          handoff_clean = pairs_of(m, handoff_origin).empty() ? 1 : 0;
        }
        return handoff_clean == 1;
      };
      for (int heap_attempt = 0; heap_attempt < 2 && !pairs.empty(); ++heap_attempt) {
        grow_region();
        restart();
        std::unique_ptr<qem::Simplifier> hp;
        if (kept) {
          hp = qem::Simplifier::resume(*kept, heap_attempt == 0 ? region : std::vector<Aabb>{}, zone_ptr(), clean,
                                       target, r);
          r.guard_rerun = true;
          r.guard_reruns = reruns;
        } else {
          hp = std::make_unique<qem::Simplifier>(TriMesh(input), seam_face, feature_tri, plain);
          if (heap_attempt == 0) hp->set_guard_region(region);
          hp->set_contact_zone(zone_ptr());
          const qem::Simplifier* h = hp.get();
          hp->set_handoff_check([&, h] { return clean(*h); });
          hp->run(target, r);
        }
        clock.restart();
        if (hp->handoff_failed()) break;
        sp = std::move(hp);
        out = compact(*sp, out_face, out_origin);
        pairs = new_pairs();
        pending = true;
        split = TriMesh{};
      }
      constexpr int kRegionalReruns = 3;
      for (int attempt = 0; !pairs.empty() && attempt <= kRegionalReruns; ++attempt) {
        grow_region();
        restart();
        sp = std::make_unique<qem::Simplifier>(TriMesh(input), seam_face, feature_tri, options);
        if (attempt < kRegionalReruns) sp->set_guard_region(region);
        sp->set_contact_zone(zone_ptr());
        sp->run(target, r);
        clock.restart();
        out = compact(*sp, out_face, out_origin);
        pairs = new_pairs();
        pending = true;
        split = TriMesh{};
      }
    }
  }
  clock.lap("check");
  sp.reset();  // (its memory, about 150 bytes per input triangle, is not needed for the error)
  for (std::uint32_t t : out_origin) r.feature_triangles_out += feature_tri[t];
  if (any_feature) {
    r.feature_flags.resize(out_origin.size());
    for (std::size_t i = 0; i < out_origin.size(); ++i) r.feature_flags[i] = feature_tri[out_origin[i]];
  }
  if (splitting) {
    r.mesh = split.num_triangles() == out.num_triangles() ? std::move(split) : split_by_face(out, out_face);
  } else {
    r.mesh = std::move(out);
  }
  if (splitting) r.face_ids = std::move(out_face);  // (the face ids given, or the sharp-edge regions)
  clock.lap("split");
  if (r.degenerate_triangles > 0)
    r.warnings.push_back(std::to_string(r.degenerate_triangles) +
                         " degenerate triangles (two corners at one position) dropped");
  r.reached = r.mesh.num_triangles() == target;
  r.one_below = !r.reached && r.mesh.num_triangles() + 1 == target && nt - r.degenerate_triangles > target;
  if (options.seams == SeamMode::as_needed && r.mesh.num_triangles() > target)
    return with_feature_seams(r.mesh.num_triangles());  // (the guard held it back)
  if (r.one_below && budget_warnings) r.warnings.push_back(one_below_warning(target));
  // Collapses refused by the guard are usually next to the input's own contacts: CAD exports with
  // cracks (T-junctions, the two sides of a face border tessellated apart, meeting or overlapping by
  // rounding), penetrating or touching bodies (the Newell teapot's spout and body), where any collapse
  // beside them makes a new intersecting pair. Say so, and how to lift the guard.
  r.inherited_pairs = inherited;
  const std::size_t own = r.rejected_intersection > 0 ? count_self_intersections(mesh) : 0;
  r.input_contact_pairs = r.rejected_intersection > 0 ? own : zone ? zone->input_pairs() : 0;
  const std::string own_pairs = own > 0 ? "; the input's own " + std::to_string(own) +
                                              " intersecting or touching triangle pairs (cracks, T-junctions, "
                                              "penetrating or touching bodies) hold the collapses next to them"
                                        : std::string();
  const std::string lift =
      std::string(inherit || !options.prevent_self_intersections
                      ? ""
                      : "inheriting the input's contacts (without --strict-intersection-guard, "
                        "inherit_input_contacts = true: they may move within their zone) or ") +
      "without the guard (--no-intersection-guard, prevent_self_intersections = false)";
  // What else holds the rest: the vertex classes of the input and the other refused collapses.
  std::string why = std::to_string(r.corner_vertices) +
                    " corner vertices (where face seams, open boundaries or sharp-edge borders meet: never "
                    "removed), " +
                    std::to_string(r.seam_vertices) + " seam vertices (removed along their seam only)";
  if (r.locked_vertices > 0) why += ", " + std::to_string(r.locked_vertices) + " locked vertices";
  why += "; " + std::to_string(r.rejected_link) + " collapses refused as non-manifold, " +
         std::to_string(r.rejected_flip) + " as flipping a triangle";
  if (r.rejected_face > 0) why += ", " + std::to_string(r.rejected_face) + " as removing a face's last triangle";
  if (options.seams == SeamMode::all && splitting && r.corner_vertices + r.seam_vertices > 0)
    why += "; --seams auto or features (SimplifyOptions::seams) lets the seams between faces that are not "
           "assembly features go";
  const std::string missed =
      "budget " + std::to_string(target) + " not reached: " + std::to_string(r.mesh.num_triangles()) + " triangles remain";
  const bool guard_held = !r.reached && r.rejected_intersection > 0 && r.mesh.num_triangles() > target;
  if (guard_held && budget_warnings) {
    r.warnings.push_back(missed + "; the self-intersection guard refused " + std::to_string(r.rejected_intersection) +
                         " collapses" + own_pairs + "; " + lift +
                         " it simplifies further but may add self-intersections; besides (" + why + ")");
  } else if (!r.reached && !r.one_below) {
    if (budget_warnings) r.warnings.push_back(missed + " (" + why + ")");
  } else if (!guard_held && own > 0 && r.rejected_intersection > 0) {
    r.warnings.push_back("the self-intersection guard refused " + std::to_string(r.rejected_intersection) +
                         " collapses" + own_pairs + ", so more were made elsewhere: the error can be larger than " +
                         lift);
  }
  if (options.measure_error) {
    if (options.stage) options.stage("measuring the error");
    const HausdorffResult h = hausdorff(mesh, r.mesh);
    r.hausdorff = h.symmetric();
    // An upper bound of the input's distance to the result (the direction a conservative clash
    // check needs: a point of two touching inputs has a point of each result within it), never
    // below the measured Hausdorff distance.
    r.error_bound = std::max(r.hausdorff, h.a_to_b_bound);
    if (r.feature_triangles_in > 0) {
      std::vector<std::uint32_t> fin, fout;
      for (std::uint32_t t = 0; t < nt; ++t)
        if (feature_tri[t]) fin.push_back(t);
      // An output triangle is on a feature face when its input triangle is (face ids or sharp-edge
      // regions alike; the output keeps the order of out_origin).
      for (std::uint32_t i = 0; i < out_origin.size(); ++i)
        if (feature_tri[out_origin[i]]) fout.push_back(i);
      if (fout.empty()) {
        r.hausdorff_features = std::numeric_limits<double>::infinity();
      } else {
        r.hausdorff_features = hausdorff(submesh(mesh, fin), submesh(r.mesh, fout), false).symmetric();
      }
    }
    clock.lap("error");
  }
  return r;
}

}  // namespace
}  // namespace interfere
