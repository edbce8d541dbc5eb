// The whole path at once (robot/cell.h, check_cell_path; issue #28, speed): conservative
// advancement with certified distances carried across path points. A body pair's certified
// distance at one path point (a lower bound of the distance between the two bodies there, with
// neither inside the other) stays a proof of separation along the path for as long as the sum of
// the two bodies' motion bounds since that point stays below it: the pair needs no decision at
// those points nor between them (the argument of conservative advancement, Mirtich 1996 and
// Redon et al. 2002, here with the per-segment bounds of motion_bounds_at). Only pairs without a
// valid certificate go to the scene engine (SceneClashOptions::decide_in_frame) at the points, and
// only segments some pair is not proven clear on go to the advancement between points
// (cell_between.cpp, its pending pairs only).
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

#include "cell_internal.h"
#include "interfere/query/clash.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"
#include "interfere/query/distance.h"
#include "interfere/robot/cell.h"

namespace interfere::robot {
namespace {

using namespace detail;  // (cell_internal.h)

/// Segments a certificate looks ahead: its BVH query's upper bound is the motion of the pair
/// over this many segments (a larger bound costs more per query, a smaller one more queries).
constexpr std::size_t kLookahead = 64;
/// Path points per block of a pair's walk (blocks run in parallel).
constexpr std::size_t kBlock = 2048;

/// Relative shortfall allowed in a certified distance (distance_lower_bound): the query stops once
/// what is left cannot be nearer than this fraction below the best found.
constexpr double kShortfall = 0.05;

double box_distance(const AabbF& x, const AabbF& y) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, static_cast<double>(x.lo[k]) - y.hi[k], static_cast<double>(y.lo[k]) - x.hi[k]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

/// A lower bound of the distance between the surfaces of a and b: query/distance.h's best-first
/// search over node pairs ordered by box distance, stopped early. Every node or triangle pair left
/// unexplored is at least its (float, outward-rounded) box distance apart and every triangle pair
/// explored at least its computed distance, so the smallest of those is a lower bound. It stops
/// once the nearest box distance left reaches `enough`, or (1 - kShortfall) times the best
/// triangle distance found (a flat probe face over a finely divided plate has hundreds of
/// triangles at one distance: the exact query visits them all). -1: two triangles meet (exact
/// test, as distance() decides it).
double distance_lower_bound(const Model& a, const Model& b, double enough) {
  if (a.bvh.empty() || b.bvh.empty()) return std::numeric_limits<double>::infinity();
  struct NodePair {
    double d;
    std::uint32_t na, nb;
    bool operator>(const NodePair& o) const { return d != o.d ? d > o.d : (na != o.na ? na > o.na : nb > o.nb); }
  };
  std::priority_queue<NodePair, std::vector<NodePair>, std::greater<>> queue;
  queue.push({box_distance(a.bvh.nodes[0].box, b.bvh.nodes[0].box), 0, 0});
  double best = std::numeric_limits<double>::infinity();  // explored triangle pairs
  double skipped = std::numeric_limits<double>::infinity();  // triangle pairs left by their boxes
  const auto stop = [&] { return std::min(enough, (1 - kShortfall) * best); };
  while (!queue.empty()) {
    const NodePair np = queue.top();
    if (np.d >= stop()) break;
    queue.pop();
    const BvhNode& x = a.bvh.nodes[np.na];
    const BvhNode& y = b.bvh.nodes[np.nb];
    if (x.is_leaf() && y.is_leaf()) {
      for (std::uint32_t i = x.first; i < x.first + x.count; ++i) {
        for (std::uint32_t j = y.first; j < y.first + y.count; ++j) {
          const double db = box_distance(a.bvh.prim_boxes[i], b.bvh.prim_boxes[j]);
          if (db >= stop()) {
            skipped = std::min(skipped, db);
            continue;
          }
          const auto ca = a.mesh.corners(a.bvh.prims[i]), cb = b.mesh.corners(b.bvh.prims[j]);
          if (db == 0 && tri_tri_exact_intersects(ca, cb)) return -1;
          best = std::min(best, triangle_triangle_closest(ca, cb).distance);
        }
      }
      continue;
    }
    const bool split_a = !x.is_leaf() && (y.is_leaf() || x.box.surface_area() >= y.box.surface_area());
    for (int c = 0; c < 2; ++c) {
      const std::uint32_t na = split_a ? x.first + c : np.na;
      const std::uint32_t nb = split_a ? np.nb : y.first + c;
      queue.push({box_distance(a.bvh.nodes[na].box, b.bvh.nodes[nb].box), na, nb});
    }
  }
  const double left = queue.empty() ? std::numeric_limits<double>::infinity() : queue.top().d;
  return std::min({best, skipped, left});
}

/// The scene engine on the frames of `cs` that need it, in chunks of consecutive frames run in
/// parallel. A chunk starts only after a frame without a pair to decide (no findings there, so the
/// engine's clash continuity, which links a pair's clashes in consecutive frames, starts afresh
/// there in one run too); the chunks' results are merged as one run makes them: frames renumbered,
/// clashes with the same id over chunks merged (frames, worst verdict, largest depths; the first
/// occurrence's data), then finish_result.
scene::SceneClashResult engine_on_frames(const CellScene& cs, const scene::SceneClashOptions& eo,
                                         const std::vector<char>& frame_needs) {
  const std::size_t n = cs.scene.frames.size();
  const std::size_t threads = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  std::size_t work = 0;
  for (char c : frame_needs) work += c != 0;
  std::vector<std::size_t> starts{0};
  if (threads > 1 && !eo.depth_maps && work > 1) {
    const std::size_t per = std::max<std::size_t>(1, work / (8 * threads));
    std::size_t acc = 0;
    for (std::size_t f = 1; f < n; ++f) {
      acc += frame_needs[f - 1] != 0;
      if (acc >= per && !frame_needs[f - 1]) starts.push_back(f), acc = 0;
    }
  }
  if (starts.size() == 1) return scene::clash_scene(cs.scene, cs.tests, eo);
  starts.push_back(n);
  const std::size_t chunks = starts.size() - 1;
  std::vector<scene::SceneClashResult> part(chunks);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t lo = starts[c], hi = starts[c + 1];
    scene::Scene piece;
    piece.units = cs.scene.units;
    piece.bodies = cs.scene.bodies;
    piece.frames.assign(cs.scene.frames.begin() + static_cast<std::ptrdiff_t>(lo),
                        cs.scene.frames.begin() + static_cast<std::ptrdiff_t>(hi));
    scene::SceneClashOptions o = eo;
    o.progress = nullptr;
    o.decide_in_frame = [&eo, lo](std::size_t f, std::uint32_t a, std::uint32_t b) {
      return eo.decide_in_frame(lo + f, a, b);
    };
    part[c] = scene::clash_scene(piece, cs.tests, o);
  });
  if (eo.progress) eo.progress(n, n);  // (the chunks run concurrently: no progress before the end)
  scene::SceneClashResult r;
  std::unordered_map<std::string, std::size_t> by_id;
  std::vector<std::string> other_warnings;
  for (std::size_t c = 0; c < chunks; ++c) {
    scene::SceneClashResult& p = part[c];
    const auto lo = static_cast<std::uint32_t>(starts[c]);
    for (scene::FrameRow& row : p.frames) row.frame += lo, r.frames.push_back(std::move(row));
    for (scene::FramePairRow& row : p.frame_pairs) row.frame += lo, r.frame_pairs.push_back(row);
    // (chunks in frame order: a clash's first occurrence is the entry one run keeps; its ids are
    // distinct within a chunk)
    for (scene::SceneClash& s : p.clashes) {
      for (std::uint32_t& f : s.frames) f += lo;
      const auto it = by_id.find(s.id);
      if (it == by_id.end()) {
        by_id.emplace(s.id, r.clashes.size());
        r.clashes.push_back(std::move(s));
        continue;
      }
      scene::SceneClash& prev = r.clashes[it->second];
      prev.frames.insert(prev.frames.end(), s.frames.begin(), s.frames.end());
      prev.verdict = worst(prev.verdict, s.verdict);
      prev.depth = std::max(prev.depth, s.depth), prev.depth_bound = std::max(prev.depth_bound, s.depth_bound);
    }
    r.candidate_pairs += p.candidate_pairs, r.suppressed += p.suppressed, r.core_runs += p.core_runs;
    r.prepare_seconds += p.prepare_seconds, r.broad_seconds += p.broad_seconds;
    r.narrow_seconds += p.narrow_seconds;
    r.bodies = p.bodies, r.triangles = p.triangles;
    for (const std::string& w : p.warnings)
      if (std::find(other_warnings.begin(), other_warnings.end(), w) == other_warnings.end())
        other_warnings.push_back(w);
  }
  scene::finish_result(cs.scene, cs.tests, eo, r);
  // Warnings as one run gives them: the selections' (every chunk's), then the open bodies' in body
  // order (any chunk's).
  const scene::BroadPhase broad(cs.scene.bodies, cs.tests);
  r.warnings = broad.warnings();
  for (const scene::Body& b : cs.scene.bodies) {
    const std::string head = "body '" + b.id + "' is not closed";
    for (const std::string& w : other_warnings)
      if (w.rfind(head, 0) == 0) {
        r.warnings.push_back(w);
        break;
      }
  }
  return r;
}

}  // namespace

PathCheckResult check_cell_path(const Cell& cell, const CellScene& cs, const JointPath& path,
                                const PathCheckOptions& options) {
  PathCheckResult out;
  bool plain = !options.accelerate;
  double threshold = 0;  // pairs closer than this are findings (clearance tests)
  for (const scene::ClashTest& t : cs.tests) {
    if (t.mode == scene::ClashMode::duplicates) plain = true;
    if (t.mode != scene::ClashMode::clearance) continue;
    threshold = std::max(threshold, t.clearance);
    for (const scene::ClearanceOverride& o : t.clearance_overrides) threshold = std::max(threshold, o.clearance);
  }
  const std::size_t n_frames = cs.scene.frames.size();
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  if (plain || n_frames == 0 || path.size() == 0) {
    auto t = Clock::now();
    out.frames = scene::clash_scene(cs.scene, cs.tests, options.engine);
    out.engine_seconds = since(t);
    t = Clock::now();
    if (options.between) out.segments = check_between_points(cell, cs, path, options.between_options);
    out.between_seconds = since(t);
    return out;
  }
  auto t_phase = Clock::now();
  const std::vector<BodyGeom> geom = body_geometry(cell, cs, true);
  const std::vector<BodyLink> links = body_links(cell, cs);
  const std::vector<PairKey> pairs = test_pairs(cs);
  const std::size_t nb = geom.size(), np = pairs.size(), n = path.size(), segments = n - 1;
  std::vector<std::int32_t> pair_of(nb * nb, -1);
  for (std::size_t p = 0; p < np; ++p)
    pair_of[pairs[p].first * nb + pairs[p].second] = pair_of[pairs[p].second * nb + pairs[p].first] =
        static_cast<std::int32_t>(p);
  // The absolute slack of check_advancement (rounding of the posed vertices and of distances).
  double scale = 1;
  for (const BodyGeom& g : geom) {
    if (g.link < 0 && g.model && !g.model->bvh.empty()) {
      const Aabb b = to_double(g.model->bvh.nodes[0].box);
      scale = std::max({scale, norm(b.lo), norm(b.hi)});
    }
  }
  for (const Transform& t : link_frames(cell.robot, path.q[0], cell.base)) scale = std::max(scale, norm(t.t));
  for (const BodyGeom& g : geom) scale += g.link >= 0 ? g.radius : 0.0;
  const double slack = 1e-9 * scale;

  // Where each moving body's pose sits in a frame's pose list.
  std::vector<std::size_t> slot(nb, SIZE_MAX);
  for (std::size_t k = 0; k < cs.scene.frames[0].poses.size(); ++k) slot[cs.scene.frames[0].poses[k].body] = k;
  const auto pose = [&](std::uint32_t b, std::size_t f) -> const Transform& {
    const auto& ps = cs.scene.frames[f].poses;
    if (slot[b] < ps.size() && ps[slot[b]].body == b) return ps[slot[b]].pose;
    for (const scene::Frame::Pose& p : ps)
      if (p.body == b) return p.pose;
    throw std::invalid_argument("check_cell_path: frame " + std::to_string(f) + " has no pose for body '" +
                                cs.scene.bodies[b].id + "'");
  };
  std::vector<std::size_t> point_frame(n, SIZE_MAX);
  for (std::size_t f = 0; f < n_frames; ++f)
    if (cs.frame_t[f] == 0) point_frame[cs.frame_point[f]] = f;
  for (std::size_t i = 0; i < n; ++i)
    if (point_frame[i] == SIZE_MAX)
      throw std::invalid_argument("check_cell_path: path point " + std::to_string(i) + " has no frame");

  // Per segment and moving body: how far any of its points gets from where it is at either end
  // while the joints move along the segment (motion_bounds_at at both ends, the larger).
  std::vector<double> seg_bound(segments * nb, 0.0);
  tbb::parallel_for(std::size_t(0), segments, [&](std::size_t k) {
    std::vector<double> dq(path.q[k].size());
    for (std::size_t j = 0; j < dq.size(); ++j) dq[j] = path.q[k + 1][j] - path.q[k][j];
    const std::vector<double> reach = reach_bounds(cell, links, dq);
    const std::vector<double> b0 = bounds_at(cell, geom, link_frames(cell.robot, path.q[k], cell.base), dq, reach);
    const std::vector<double> b1 = bounds_at(cell, geom, link_frames(cell.robot, path.q[k + 1], cell.base), dq, reach);
    for (std::size_t b = 0; b < nb; ++b) seg_bound[k * nb + b] = std::max(b0[b], b1[b]);
  });

  // Per thread: the moving bodies' models, posed by refit when a certificate needs them.
  tbb::enumerable_thread_specific<std::vector<Model>> posed_tls([&] {
    std::vector<Model> v(nb);
    for (std::size_t b = 0; b < nb; ++b)
      if (geom[b].link >= 0) v[b] = *geom[b].model;
    return v;
  });
  std::atomic<std::size_t> certificates{0}, queries{0};
  // A certified distance of pair p at frame f, less the threshold and the slack: > 0 proves the
  // pair apart by more than the threshold with neither body inside the other; <= 0: no proof.
  // `wanted` (the motion it should cover): the BVH query looks no farther than that, and a
  // bounding-sphere bound is taken when it covers at least half of it.
  const auto certify = [&](std::size_t p, std::size_t f, double wanted) -> double {
    ++certificates;
    const std::uint32_t a = pairs[p].first, b = pairs[p].second;
    const BodyGeom& ga = geom[a];
    const BodyGeom& gb = geom[b];
    if (!ga.closed || !gb.closed) return -1;  // (an open body: the engine decides every frame)
    const double need = threshold + wanted;
    // Bounding spheres: a moving body lies within its sphere.
    const auto world_centre = [&](std::uint32_t x) { return pose(x, f).apply(geom[x].centre); };
    if (ga.link >= 0 && gb.link >= 0) {
      const double lb = norm(world_centre(a) - world_centre(b)) - ga.radius - gb.radius;
      if (lb - slack >= 0.5 * need && lb > threshold + slack) return lb - threshold - slack;
    } else if (ga.link >= 0 || gb.link >= 0) {
      const std::uint32_t x = ga.link >= 0 ? a : b, y = ga.link >= 0 ? b : a;
      const Model& my = *geom[y].model;
      const Vec3 c = world_centre(x);
      const double lb = std::sqrt(nearest_triangle_d2(my.mesh, my.bvh, c)) - geom[x].radius;
      if (lb - slack >= 0.5 * need && lb > threshold + slack) {
        // The sphere does not reach y's surface: it lies wholly inside or outside y's solid (its
        // centre decides), and y can lie inside x only if a component of y lies in the sphere.
        bool maybe = point_in_solid(my, c) != 0;
        for (const std::uint32_t v : geom[y].component_vertices)
          maybe = maybe || norm(my.mesh.positions[v] - c) <= geom[x].radius + slack;
        if (!maybe) return lb - threshold - slack;
      }
    }
    // The BVH distance query between the posed models.
    ++queries;
    std::vector<Model>& posed = posed_tls.local();
    const auto posed_by = [&](std::uint32_t x, const Transform& t) -> const Model& {
      const std::vector<Vec3>& local = geom[x].model->mesh.positions;
      std::vector<Vec3> w(local.size());
      for (std::size_t v = 0; v < w.size(); ++v) w[v] = t.apply(local[v]);
      refit(posed[x], std::move(w));
      return posed[x];
    };
    // Two moving bodies: in a's own frame (b posed relative to a: one refit instead of two; the
    // distances and the sides of points are those of the world up to rounding, within the slack).
    // A moving and a static body: the moving one posed in the world.
    const bool both_moving = ga.link >= 0 && gb.link >= 0;
    const Model& ma = ga.link < 0 ? *ga.model : both_moving ? *ga.model : posed_by(a, pose(a, f));
    const Model& mb = gb.link < 0 ? *gb.model
                      : both_moving ? posed_by(b, scene::compose(scene::inverse(pose(a, f)), pose(b, f)))
                                    : posed_by(b, pose(b, f));
    const double dist = std::min(distance_lower_bound(ma, mb, need + 2 * slack), need + 2 * slack);
    if (!(dist > threshold + slack)) return -1;
    // Apart: each component of one body lies wholly inside or outside the other's solid; one
    // vertex of it decides (exact ray parity; a vertex outside the other's box is outside).
    const auto could_contain = [&](const Model& mx, std::uint32_t x, const Model& my) {
      const Aabb box = to_double(my.bvh.nodes[0].box);
      for (const std::uint32_t v : geom[x].component_vertices) {
        const Vec3& q = mx.mesh.positions[v];
        if (q.x < box.lo.x || q.x > box.hi.x || q.y < box.lo.y || q.y > box.hi.y || q.z < box.lo.z || q.z > box.hi.z)
          continue;
        if (point_in_solid(my, q) != 0) return true;
      }
      return false;
    };
    if (could_contain(ma, a, mb) || could_contain(mb, b, ma)) return -1;
    return dist - threshold - slack;
  };

  // Per pair, along the path: need[p * F + f] (the engine decides p at frame f), covered[p * S + k]
  // (p proven clear on the whole segment k).
  std::vector<char> need(np * n_frames, 0), covered(np * segments, 0);
  const auto pair_bound = [&](std::size_t p, std::size_t k) {
    return seg_bound[k * nb + pairs[p].first] + seg_bound[k * nb + pairs[p].second];
  };
  constexpr double kRel = 1 + 1e-9;  // (relative rounding of the sums of bounds)
  // Each pair's walk in blocks of points walked independently (a block starts with a certificate
  // at its first point), so that one busy pair (the probe over the workpiece) does not hold up the
  // rest; the blocks are fixed, so the results do not depend on the thread count. A segment is
  // covered forwards (from a certificate at or before its first point, in the block of that
  // point) or backwards (from a certificate at its last point): two flags, each written by one
  // block only.
  std::vector<char> covered_back(np * segments, 0);
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  tbb::parallel_for(std::size_t(0), np * blocks, [&](std::size_t job) {
    const std::size_t p = job / blocks, lo = (job % blocks) * kBlock, hi = std::min(n, lo + kBlock);
    char* nd = need.data() + p * n_frames;
    char* cov = covered.data() + p * segments;
    char* back = covered_back.data() + p * segments;
    double cert = -1, moved = 0;  // the current certificate and the motion since its point
    for (std::size_t i = lo; i < hi; ++i) {
      if (!(cert > 0 && moved * kRel < cert)) {
        double wanted = 0;
        for (std::size_t k = i; k < std::min(segments, i + kLookahead); ++k) wanted += pair_bound(p, k);
        if (i > 0) wanted = std::max(wanted, pair_bound(p, i - 1));
        cert = certify(p, point_frame[i], wanted * kRel);
        moved = 0;
        if (cert > 0) {
          if (i > 0 && pair_bound(p, i - 1) * kRel < cert) back[i - 1] = 1;  // backwards
        } else {
          nd[point_frame[i]] = 1;
        }
      }
      if (i + 1 < n && cert > 0) {
        moved += pair_bound(p, i);
        if (moved * kRel < cert) cov[i] = 1;
      }
    }
  });
  for (std::size_t k = 0; k < covered.size(); ++k) covered[k] = covered[k] || covered_back[k];
  // Frames inside segments (cell_scene's `between` samples): covered with their segment, else each
  // on its own.
  tbb::parallel_for(std::size_t(0), np, [&](std::size_t p) {
    for (std::size_t f = 0; f < n_frames; ++f) {
      if (cs.frame_t[f] == 0 || covered[p * segments + cs.frame_point[f]]) continue;
      if (!(certify(p, f, 0) > 0)) need[p * n_frames + f] = 1;
    }
  });
  out.certificates = certificates, out.bvh_queries = queries;
  out.certify_seconds = since(t_phase);
  t_phase = Clock::now();

  // The engine at the frames, on the pairs without a certificate there.
  std::vector<char> frame_needs(n_frames, 0);
  for (std::size_t p = 0; p < np; ++p)
    for (std::size_t f = 0; f < n_frames; ++f)
      if (need[p * n_frames + f]) frame_needs[f] = 1, ++out.engine_pair_frames;
  scene::SceneClashOptions eo = options.engine;
  eo.decide_in_frame = [&](std::size_t f, std::uint32_t a, std::uint32_t b) {
    const std::int32_t p = pair_of[a * nb + b];
    return p < 0 || need[static_cast<std::size_t>(p) * n_frames + f] != 0;
  };
  out.frames = engine_on_frames(cs, eo, frame_needs);
  out.engine_seconds = since(t_phase);
  t_phase = Clock::now();

  if (options.between) {
    std::vector<std::vector<PairKey>> pending(segments);
    for (std::size_t k = 0; k < segments; ++k) {
      for (std::size_t p = 0; p < np; ++p)
        if (!covered[p * segments + k]) pending[k].push_back(pairs[p]);
      out.segments_certified += pending[k].empty();
    }
    BetweenOptions bo = options.between_options;
    if (bo.method == BetweenMethod::subdivision) {
      out.segments = check_between_points(cell, cs, path, bo);
    } else {
      out.segments = check_advancement(cell, cs, path, bo, &pending, &geom);
    }
    out.between_seconds = since(t_phase);
  }
  return out;
}

}  // namespace interfere::robot
