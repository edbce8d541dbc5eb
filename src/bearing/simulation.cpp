// Dynamic simulation of N bearing pairs (Jia & Zheng 2019, §4): seeded spin and tilt random walk,
// broad phase over all parts, per pair the standard solver (§3.1) or, with a scar in the window of
// Eq. (1), the temporally coherent scarred solver (§3.2); every pair of parts of different bearing
// pairs that the broad phase reports is decided as well (part_pair.h), each with its verdict.
#include "interfere/bearing/simulation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/raised_bound.h"
#include "interfere/bearing/scarred.h"
#include "interfere/bearing/window.h"
#include "interfere/query/model.h"

namespace interfere::bearing {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int kScarVariants = 8;  // distinct scarred meshes shared round-robin by the scarred pairs

Error param_error(const char* name, const std::string& what, double got) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", got);
  return Error{.reason = std::string(name) + " must be " + what + ", got " + buf};
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  SplitMix64 g{a ^ (b * 0x9E3779B97F4A7C15ull) ^ (c * 0xC2B2AE3D27D4EB4Full)};
  g.next();
  return g.next();
}

struct PairState {
  double tx = 0, ty = 0;  // tilt in units of alpha (inside the unit disk)
  double spin0 = 0;
  bool scarred = false;
  int variant = -1;
  ScarredSolver solver;
};

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Status validate(const SceneParams& p) {
  if (p.pairs < 1 || p.pairs > 1 << 22) return param_error("pairs", "in [1, 4194304]", p.pairs);
  if (p.frames < 1 || p.frames > 1 << 24) return param_error("frames", "in [1, 16777216]", p.frames);
  if (Status s = validate(p.roller, "roller"); !s) return s;
  if (!(p.partner_radius > 0 && p.partner_radius <= 1e9))
    return param_error("partner.radius", "> 0 (and <= 1e9)", p.partner_radius);
  if (!(p.partner_height > 0 && p.partner_height <= 1e9))
    return param_error("partner.height", "> 0 (and <= 1e9)", p.partner_height);
  const double rmax = std::max(p.roller.radius, p.roller.top());
  if (!(p.gap > -(rmax + p.partner_radius) && p.gap <= 1e9))
    return param_error("gap", "> -(roller radius + partner radius) (and <= 1e9)", p.gap);
  if (!(p.max_tilt_deg >= 0)) return param_error("max_tilt_deg", ">= 0", p.max_tilt_deg);
  const WindowParams w{.roller_radius = p.roller.radius, .partner_radius = p.partner_radius,
                       .height = p.roller.height, .max_tilt = p.max_tilt_deg * kDeg};
  if (Status s = validate(w); !s) return Error{.reason = "max_tilt_deg: " + s.error().reason};
  if (!(p.tilt_step >= 0 && p.tilt_step <= 1)) return param_error("tilt_step", "in [0, 1]", p.tilt_step);
  if (!std::isfinite(p.spin_deg_per_frame)) return param_error("spin_deg_per_frame", "finite", p.spin_deg_per_frame);
  if (!(p.scar_fraction >= 0 && p.scar_fraction <= 1))
    return param_error("scar_fraction", "in [0, 1]", p.scar_fraction);
  if (!p.imported_scar.height.empty()) {
    const VertexHeights& h = p.imported_scar;
    const std::size_t nv = static_cast<std::size_t>(p.roller.radial_segments) * (p.roller.height_segments + 1);
    if (h.n != p.roller.radial_segments || h.m != p.roller.height_segments || h.height.size() != nv ||
        h.covered.size() != nv)
      return Error{.file = h.source,
                   .reason = "the imported scar is on a " + std::to_string(h.n) + " x " + std::to_string(h.m + 1) +
                             " vertex grid, the roller's is " + std::to_string(p.roller.radial_segments) + " x " +
                             std::to_string(p.roller.height_segments + 1)};
  } else if (p.scar_fraction > 0) {
    if (Status s = validate(p.scar, p.roller, "scar"); !s) return s;
  }
  if (!(p.spacing >= 0 && p.spacing <= 1e9)) return param_error("spacing", ">= 0 and <= 1e9 (0 = automatic)", p.spacing);
  if (!(p.clearance >= 0 && p.clearance <= 1e9)) return param_error("clearance", ">= 0 and <= 1e9", p.clearance);
  return {};
}

Transform partner_pose(const SceneParams& p, double spacing, int k) {
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p.pairs))));
  Transform tb;
  tb.t = {(k % cols) * spacing, (k / cols) * spacing, 0.5 * p.roller.height - 0.5 * p.partner_height};
  return tb;
}

Expected<SimulationResult> simulate(const SceneParams& p, bool keep_rows,
                                    const std::function<void(std::size_t, std::size_t)>& progress) {
  if (Status s = validate(p); !s) return s.error();
  const double t_start = now();
  SimulationResult res;
  const double r = p.roller.radius, rmax = std::max(r, p.roller.top()), hb = p.roller.height;
  const double R = p.partner_radius, D = R + r + p.gap;
  const double alpha = p.max_tilt_deg * kDeg;
  res.theta = ideal_interference_range({.roller_radius = r, .partner_radius = R, .height = hb, .max_tilt = alpha});
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p.pairs))));

  // scarred roller variants (meshes and quadtrees) shared by the scarred pairs
  std::vector<Roller> variants;
  std::vector<RollerQuadtree> trees;
  std::vector<PairState> st(static_cast<std::size_t>(p.pairs));
  int scarred = 0;
  for (int k = 0; k < p.pairs; ++k) {
    PairState& s = st[static_cast<std::size_t>(k)];
    s.scarred = std::floor((k + 1) * p.scar_fraction) > std::floor(k * p.scar_fraction);
    if (s.scarred) s.variant = scarred++ % kScarVariants;
    SplitMix64 g{mix(p.seed, static_cast<std::uint64_t>(k), 0xA11CEull)};
    do {
      s.tx = g.symmetric(), s.ty = g.symmetric();
    } while (s.tx * s.tx + s.ty * s.ty > 1);
    s.spin0 = 2 * std::numbers::pi * g.uniform();
  }
  res.scarred_rollers = scarred;
  // an imported scar (issue #27) is one mesh shared by every scarred roller
  const bool imported = !p.imported_scar.height.empty();
  const int nvariants = std::min(scarred, imported ? 1 : kScarVariants);
  if (imported)
    for (PairState& s : st)
      if (s.scarred) s.variant = 0;
  variants.reserve(static_cast<std::size_t>(nvariants));
  for (int v = 0; v < nvariants; ++v) {
    Expected<Roller> roller = make_roller(p.roller);
    if (!roller) return roller.error();
    if (imported) {
      if (Expected<int> e = apply_vertex_heights(*roller, p.imported_scar, 0); !e) return e.error();
    } else {
      ScarParams sp = p.scar;
      sp.seed = p.scar.seed + static_cast<std::uint64_t>(v);
      if (Expected<int> e = apply_scar(*roller, sp); !e) return e.error();
    }
    variants.push_back(std::move(*roller));
  }
  // the scar window of the range test: the generated scar's, or the imported scar's covered window
  const ScarParams scar_window = imported ? covered_window(p.imported_scar, p.roller) : p.scar;
  for (const Roller& v : variants) trees.push_back(build_quadtree(v));
  // raised scars (issue #27) reach outside the intact cylinder: by at most `raise`, and the spheres
  // of raised_bound.h bound where
  std::vector<RaisedBound> raised_bounds;
  double max_raise = 0;
  for (const Roller& v : variants) {
    raised_bounds.push_back(build_raised_bound(v));
    max_raise = std::max(max_raise, v.raise);
  }
  const double reach = D + rmax + max_raise + hb;
  const double auto_spacing =
      1.05 * std::max(R + reach, 2 * std::max(R, rmax + max_raise + hb)) + 1e-3 * reach;
  const double S = p.spacing > 0 ? p.spacing : auto_spacing;
  res.spacing = S;
  // the closed scarred meshes as solids, for the containment test (part_pair.h mesh_containment)
  std::vector<Model> solids;
  for (const Roller& v : variants) solids.push_back(make_model(v.mesh, {}, false));
  for (PairState& s : st)
    if (s.scarred) {
      const auto vi = static_cast<std::size_t>(s.variant);
      s.solver = ScarredSolver(&variants[vi], &trees[vi]);
    }
  const double col = 2 * std::numbers::pi / p.roller.radial_segments;
  const double cell_z = hb / p.roller.height_segments;

  std::unique_ptr<BroadPhase> broad = make_broad_phase(p.broad_phase);
  const auto n = static_cast<std::size_t>(p.pairs);
  std::vector<Box3> boxes(2 * n);
  std::vector<Transform> poses(n);
  std::vector<Cylinder> cyl_a(n), cyl_b(n);
  std::vector<PairFrame> frame_rows(n);
  std::vector<std::uint8_t> overlapping(n);
  std::vector<IndexPair> cross;
  std::vector<PartPairResult> cross_out;
  // part 2k: the roller of pair k (its scarred mesh if any), 2k + 1: its partner
  const auto part = [&](std::uint32_t q) {
    const std::size_t k = q / 2;
    ScenePart sp;
    if (q % 2 == 1) {
      sp.cylinder = cyl_b[k], sp.partner = true;
      return sp;
    }
    sp.cylinder = cyl_a[k], sp.pose = poses[k];
    if (st[k].scarred) {
      const auto vi = static_cast<std::size_t>(st[k].variant);
      sp.mesh = &variants[vi], sp.tree = &trees[vi], sp.solid = &solids[vi];
    }
    return sp;
  };
  const auto note_undecided = [&](const std::string& reason) {
    if (std::find(res.undecided_reasons.begin(), res.undecided_reasons.end(), reason) == res.undecided_reasons.end())
      res.undecided_reasons.push_back(reason);
  };
  if (keep_rows) res.rows.reserve(n * static_cast<std::size_t>(p.frames));
  if (keep_rows) {  // what a viewer needs to draw the frames (view/bearing_document.h)
    res.roller_poses.reserve(n * static_cast<std::size_t>(p.frames));
    for (const Roller& v : variants) res.scar_meshes.push_back(v.mesh);
    for (const PairState& s : st) res.pair_variant.push_back(s.scarred ? s.variant : -1);
  }
  // boxes grown by half the clearance and the touch band (part_pair.h), so that every pair of parts
  // within the clearance or touching (up to rounding of the boxes) reaches the narrow phase (a raised
  // scar's roller also by its raise: its solid lies in its cylinder grown radially by it, and a box
  // grown by it in every direction contains that cylinder's box)
  const auto grown = [&](const Cylinder& c, double raise) {
    Box3 box = cylinder_box(c);
    const double m = 0.5 * p.clearance + touch_tolerance(c, c) + raise;
    box.lo = box.lo - Vec3{m, m, m}, box.hi = box.hi + Vec3{m, m, m};
    return box;
  };
  // the partners stand still: their cylinders and boxes once (issue #27, Table 3: the frame loop
  // recomputed them for every pair in every frame, to the same values)
  for (std::size_t k = 0; k < n; ++k) {
    cyl_b[k] = posed_cylinder(R, -1, p.partner_height, partner_pose(p, S, static_cast<int>(k)));
    boxes[2 * k + 1] = grown(cyl_b[k], 0.0);
  }
  // The frame loop's two parallel passes over the pairs (poses, then rows) hand the same blocks of
  // pairs to the same threads in every frame (issue #27, Table 3 with the scars in range: a scarred
  // row's solve descends ~70 nodes of its roller's bound tree near last frame's contact, which then
  // stay in that core's cache; with work stealing a block moved between the cores from frame to
  // frame). Blocks of 16 pairs: a scarred row costs ~15 intact ones, so smaller blocks than the
  // default balance the cores better. Each pair is solved into its own slot: the results do not
  // depend on which thread solves it.
  tbb::affinity_partitioner pose_affinity, row_affinity;
  constexpr std::size_t kGrain = 16;
  res.min_distance = std::numeric_limits<double>::infinity();
  res.setup_seconds = now() - t_start;
  res.threads = tbb::this_task_arena::max_concurrency();
  const std::clock_t cpu_start = std::clock();

  for (int f = 0; f < p.frames; ++f) {
    const double t0 = now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& br) {
      for (std::size_t k = br.begin(); k != br.end(); ++k) {
        PairState& s = st[k];
        if (f > 0 && p.tilt_step > 0) {
          SplitMix64 g{mix(p.seed, k, static_cast<std::uint64_t>(f))};
          s.tx += p.tilt_step * g.symmetric(), s.ty += p.tilt_step * g.symmetric();
          const double l = std::hypot(s.tx, s.ty);
          if (l > 1) s.tx /= l, s.ty /= l;
        }
        const double ox = (static_cast<int>(k) % cols) * S, oy = (static_cast<int>(k) / cols) * S;
        const double tilt = alpha * std::min(1.0, std::hypot(s.tx, s.ty));
        const double az = std::atan2(s.ty, s.tx);
        const double spin = s.spin0 + f * p.spin_deg_per_frame * kDeg;
        poses[k] = roller_pose({ox + D, oy, 0}, tilt, az, spin);
        cyl_a[k] = posed_cylinder(r, p.roller.top_radius, hb, poses[k]);
        boxes[2 * k] = grown(cyl_a[k], s.scarred ? variants[static_cast<std::size_t>(s.variant)].raise : 0.0);
        PairFrame& row = frame_rows[k];
        row.frame = f, row.pair = static_cast<std::int32_t>(k);
        row.tilt_deg = tilt / kDeg, row.azimuth_deg = az / kDeg;
        row.spin_deg = std::fmod(spin / kDeg, 360.0);
        row.scarred_roller = s.scarred;
      }
    }, pose_affinity);
    const std::vector<IndexPair> pairs = broad->update(boxes);
    std::fill(overlapping.begin(), overlapping.end(), 0);
    cross.clear();
    for (const auto& [i, j] : pairs) {
      if (i / 2 == j / 2) overlapping[i / 2] = 1;
      else cross.push_back({i, j});
    }
    res.cross_pairs += cross.size();
    res.broad_pairs_total += pairs.size();
    const double t1 = now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& br) {
      for (std::size_t k = br.begin(); k != br.end(); ++k) {
        PairState& s = st[k];
        PairFrame& row = frame_rows[k];
        row.box_overlap = overlapping[k] != 0;
        // An intact (unscarred) roller: the pair's two-sided value S = min(s(A, B), s(B, A)) (part_pair.h;
        // issue #27): untapered by intact_row_distance, tapered by two_sided_frustum_distance (the value
        // decide_part_pair gives the same two parts). A scarred roller: s(A, B) of the standard solver as
        // the scarred solver's start and out-of-range value (its reverse depth has no exact solver;
        // decide_part_pair brackets it).
        const PairDistance pd = s.scarred                ? cylinder_pair_distance(cyl_a[k], cyl_b[k])
                                : cyl_a[k].tapered()     ? two_sided_frustum_distance(cyl_a[k], cyl_b[k])
                                                         : intact_row_distance(cyl_a[k], cyl_b[k]);
        row.distance = pd.distance, row.point_a = pd.point_a, row.point_b = pd.point_b;
        row.path = static_cast<std::uint8_t>(pd.path);
        row.solver = 0, row.evaluated = 0, row.scar_in_range = false;
        if (s.scarred) {
          const ScarParams& sp = scar_window;
          const double phi = contact_direction_angle(poses[k], cyl_b[k], hb);
          // §3.1: the scar is in the range of Eq. (1) (half-width theta/2 about the contact direction)
          bool in_range = scar_angle_contains(sp, phi, 0.5 * res.theta + 2 * col);
          if (!in_range) {  // exactness guard: the standard witness itself on the scar window
            const Transform& T = poses[k];
            const Vec3 w = pd.point_a - T.t;
            const double bx = T.r[0][0] * w.x + T.r[1][0] * w.y + T.r[2][0] * w.z;
            const double by = T.r[0][1] * w.x + T.r[1][1] * w.y + T.r[2][1] * w.z;
            const double bz = T.r[0][2] * w.x + T.r[1][2] * w.y + T.r[2][2] * w.z;
            in_range = scar_angle_contains(sp, std::atan2(by, bx), 2 * col) && bz >= sp.z_min - cell_z &&
                       bz <= sp.z_max + cell_z;
          }
          row.scar_in_range = in_range;
          // a raised scar (issue #27) may reach deeper than the intact cylinder from anywhere: the
          // standard value stands only when no outward-displaced triangle can come below it
          const RaisedBound& rb = raised_bounds[static_cast<std::size_t>(s.variant)];
          const bool raised_reach = !rb.empty() && raised_lower_bound(rb, poses[k], cyl_b[k]) < pd.distance;
          if (in_range || raised_reach) {
            const MeshPairResult mr = s.solver.solve(poses[k], cyl_b[k], pd.point_a);
            row.distance = mr.distance, row.point_a = mr.point_a, row.point_b = mr.point_b;
            row.solver = 1, row.evaluated = mr.evaluated;
          }
        }
        row.verdict = distance_verdict(row.distance, touch_tolerance(cyl_a[k], cyl_b[k]), p.clearance);
        // a raised scar's roller also on the standard value: apart from the intact cylinder by s0 and
        // (raised bound) from every outward triangle by at least s0, the partner can still lie wholly
        // inside the raised part of the solid (an inward scar's solid lies in the intact cylinder)
        const bool raised_roller = s.scarred && !raised_bounds[static_cast<std::size_t>(s.variant)].empty();
        if ((row.solver == 1 || raised_roller) && row.verdict != Verdict::clash && row.verdict != Verdict::contact) {
          // the surface minimum is apart: the partner may still lie wholly inside the roller
          const int inside = mesh_containment(part(static_cast<std::uint32_t>(2 * k)), cyl_b[k]);
          if (inside != 0) row.verdict = inside == 1 ? Verdict::clash : Verdict::undecided;
        }
      }
    }, row_affinity);
    // every other box overlap: parts of different pairs (part_pair.h)
    cross_out.resize(cross.size());
    if (!cross.empty())
      tbb::parallel_for(std::size_t{0}, cross.size(), [&](std::size_t c) {
        cross_out[c] = decide_part_pair(part(cross[c].first), part(cross[c].second), p.clearance);
      });
    const double t2 = now();
    res.broad_seconds += t1 - t0;
    res.narrow_seconds += t2 - t1;
    for (const PairFrame& row : frame_rows) {
      if (row.distance < res.min_distance) res.min_distance = row.distance, res.worst = row;
      res.interfering_rows += row.distance < 0;
      res.scarred_solves += row.solver == 1;
      res.general_solves += row.solver == 0 && row.path == static_cast<std::uint8_t>(AnalyticPath::general);
      ++res.row_verdicts[static_cast<std::size_t>(row.verdict)];
      res.verdict = worst(res.verdict, row.verdict);
      if (row.verdict == Verdict::undecided)
        note_undecided("whether a partner lies inside its scarred roller: every ray direction was degenerate");
      if (keep_rows) res.rows.push_back(row);
    }
    if (keep_rows) res.roller_poses.insert(res.roller_poses.end(), poses.begin(), poses.end());
    for (std::size_t c = 0; c < cross.size(); ++c) {
      const PartPairResult& d = cross_out[c];
      ++res.cross_verdicts[static_cast<std::size_t>(d.verdict)];
      res.verdict = worst(res.verdict, d.verdict);
      if (d.verdict == Verdict::undecided) note_undecided(d.reason);
      if (d.verdict == Verdict::clear) continue;
      CrossPair cp;
      cp.frame = f;
      cp.part_a = d.swapped ? cross[c].second : cross[c].first;
      cp.part_b = d.swapped ? cross[c].first : cross[c].second;
      cp.distance = d.distance, cp.point_a = d.point_a, cp.point_b = d.point_b;
      cp.solver = d.solver, cp.verdict = d.verdict;
      res.cross_results.push_back(cp);
    }
    if (progress) progress(static_cast<std::size_t>(f) + 1, static_cast<std::size_t>(p.frames));
  }
  res.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const double busy = res.broad_seconds + res.narrow_seconds;
  res.frames_per_second = busy > 0 ? p.frames / busy : 0;
  res.total_seconds = now() - t_start;
  return res;
}

}  // namespace interfere::bearing
