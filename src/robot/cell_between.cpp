// The conservative check of the whole cell between path points (issue #28, deliverable 3;
// robot/cell.h, check_between_points): per segment, interval halving with a per-body motion bound.
// Two ways to prove a pair clear on a sub-interval (BetweenMethod): conservative advancement with
// certified distances (the BVH distance query at the middle against per-body motion bounds
// measured at the middle pose; default), or the earlier subdivision (each level's middles in one
// scene-engine run with clearance tests at the largest bound of the level, the bound from the
// chain's reach), kept as the tests' reference.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "interfere/query/model.h"
#include "interfere/robot/cell.h"
#include "cell_internal.h"

namespace interfere::robot {
using namespace detail;  // (cell_internal.h)
namespace {

struct Interval {
  std::size_t segment = 0;
  double ta = 0, tb = 1;
  bool all_pairs = true;      ///< every pair still open (the first level)
  std::set<PairKey> pending;  ///< otherwise: the pairs not yet proven clear on it
};

}  // namespace

std::vector<BodyLink> detail::body_links(const Cell& cell, const CellScene& cs) {
  std::vector<BodyLink> out(cs.scene.bodies.size());
  auto radius = [](const TriMesh& m) {
    double r = 0;
    for (const Vec3& p : m.positions) r = std::max(r, norm(p));
    return r * (1 + 1e-12);
  };
  for (std::size_t k = 0; k < cs.link_body.size(); ++k) {
    if (cs.link_body[k] >= 0)
      out[cs.link_body[k]] = {static_cast<std::int64_t>(k),
                              radius(*cs.scene.bodies[cs.link_body[k]].mesh)};
  }
  for (std::int64_t b : {cs.probe_body, cs.holder_body}) {
    if (b >= 0)
      out[b] = {static_cast<std::int64_t>(cell.tool_link), radius(*cs.scene.bodies[b].mesh)};
  }
  return out;
}

const char* segment_state_name(SegmentState s) {
  switch (s) {
    case SegmentState::clear:
      return "clear";
    case SegmentState::collides:
      return "collides";
    case SegmentState::unresolved:
      return "unresolved";
  }
  return "?";
}

std::vector<double> motion_bounds(const Cell& cell, const CellScene& cs,
                                  const std::vector<double>& dq) {
  return detail::reach_bounds(cell, detail::body_links(cell, cs), dq);
}

std::vector<double> detail::reach_bounds(const Cell& cell, const std::vector<BodyLink>& bl,
                                         const std::vector<double>& dq) {
  const Chain& chain = cell.robot;
  std::vector<double> out(bl.size(), 0.0);
  for (std::size_t b = 0; b < bl.size(); ++b) {
    if (bl[b].link < 0) continue;
    const auto k = static_cast<std::size_t>(bl[b].link);
    double delta = 0;
    for (std::size_t m = 0; m < chain.movable.size(); ++m) {
      const std::size_t ji = chain.movable[m];  // joint ji moves links ji+1 ... end
      if (ji + 1 > k) continue;
      const ChainJoint& j = chain.joints[ji];
      if (j.kind == JointKind::prismatic) {
        delta += std::fabs(dq[m]);
        continue;
      }
      // Distance from joint ji's origin (link ji+1's origin) to any point of the body.
      double reach = bl[b].radius;
      for (std::size_t i = ji + 1; i < k; ++i) {
        const ChainJoint& o = chain.joints[i];
        reach += norm(o.origin.t);
        if (o.kind == JointKind::prismatic)
          reach += std::max(std::fabs(o.lower), std::fabs(o.upper));
      }
      delta += std::fabs(dq[m]) * std::numbers::pi / 180.0 * reach;
    }
    out[b] = delta * (1 + 1e-9);
  }
  return out;
}

namespace {

/// The test a pair belongs to (the first that selects it), and the reported pairs of a segment.
void finish(const CellScene& cs, std::vector<SegmentResult>& out,
            const std::vector<std::map<PairKey, double>>& meeting,
            const std::vector<std::set<PairKey>>& unresolved);

std::vector<SegmentResult> check_subdivision(const Cell& cell, const CellScene& cs,
                                             const JointPath& path, const BetweenOptions& options) {
  const std::size_t segments = path.size() > 1 ? path.size() - 1 : 0;
  std::vector<SegmentResult> out(segments);
  std::vector<Interval> level;
  for (std::size_t s = 0; s < segments; ++s) {
    out[s].from = s;
    level.push_back({s, 0.0, 1.0, true, {}});
  }
  std::vector<std::set<PairKey>> unresolved(segments);
  std::vector<std::map<PairKey, double>> meeting(segments);  // pair -> first t found
  const std::size_t dof = cell.robot.dof();
  for (int depth = 0; !level.empty(); ++depth) {
    // The middles of this level, and each one's motion bounds over half its interval.
    scene::Scene sc;
    sc.units = cs.scene.units;
    sc.bodies = cs.scene.bodies;
    std::vector<std::vector<double>> bounds(level.size());
    double need = 0;
    for (std::size_t i = 0; i < level.size(); ++i) {
      const Interval& iv = level[i];
      const double tm = 0.5 * (iv.ta + iv.tb), half = 0.5 * (iv.tb - iv.ta);
      const std::vector<double>& q0 = path.q[iv.segment];
      const std::vector<double>& q1 = path.q[iv.segment + 1];
      std::vector<double> q(dof), dq(dof);
      for (std::size_t j = 0; j < dof; ++j)
        q[j] = q0[j] + tm * (q1[j] - q0[j]), dq[j] = half * (q1[j] - q0[j]);
      bounds[i] = motion_bounds(cell, cs, dq);
      std::vector<double> sorted = bounds[i];
      std::sort(sorted.rbegin(), sorted.rend());
      need = std::max(need, sorted[0] + (sorted.size() > 1 ? sorted[1] : 0.0));
      const std::vector<Transform> f = link_frames(cell.robot, q, cell.base);
      scene::Frame fr;
      fr.label = "segment " + std::to_string(iv.segment) + " t " + short_number(tm);
      fr.time = static_cast<double>(iv.segment) + tm;
      for (std::size_t k = 0; k < cs.link_body.size(); ++k) {
        if (cs.link_body[k] >= 0)
          fr.poses.push_back({static_cast<std::uint32_t>(cs.link_body[k]), f[k]});
      }
      for (std::int64_t b : {cs.probe_body, cs.holder_body}) {
        if (b >= 0) fr.poses.push_back({static_cast<std::uint32_t>(b), f[cell.tool_link]});
      }
      sc.frames.push_back(std::move(fr));
      ++out[iv.segment].frames;
    }
    std::vector<scene::ClashTest> tests = cs.tests;
    for (scene::ClashTest& t : tests) {
      t.mode = scene::ClashMode::clearance;
      t.clearance = std::max(need, cell.clearance) * (1 + 1e-9) + 1e-9;
    }
    scene::SceneClashOptions eo = options.engine;
    eo.depth = false, eo.curves = false, eo.triangles = false, eo.reference = false;
    eo.group_by = scene::GroupBy::none;
    const scene::SceneClashResult r = scene::clash_scene(sc, tests, eo);
    std::vector<std::map<PairKey, const scene::FramePairRow*>> rows(level.size());
    for (const scene::FramePairRow& row : r.frame_pairs) rows[row.frame][{row.a, row.b}] = &row;
    std::vector<Interval> next;
    for (std::size_t i = 0; i < level.size(); ++i) {
      Interval& iv = level[i];
      if (out[iv.segment].state == SegmentState::collides) continue;
      const double tm = 0.5 * (iv.ta + iv.tb);
      std::set<PairKey> open;
      auto decide = [&](const PairKey& key, const scene::FramePairRow* row) {
        if (!row) return;  // no finding within the clearance: farther than any bound here
        if (row->verdict == Verdict::clash || row->verdict == Verdict::contact) {
          auto [it, fresh] = meeting[iv.segment].emplace(key, tm);
          if (!fresh) it->second = std::min(it->second, tm);
          return;
        }
        const double d = row->verdict == Verdict::clearance ? row->min_distance : -1;
        if (row->verdict == Verdict::clear || d > bounds[i][key.first] + bounds[i][key.second])
          return;
        open.insert(key);  // too close to prove, or undecided
      };
      if (iv.all_pairs) {
        for (const auto& [key, row] : rows[i]) decide(key, row);
      } else {
        for (const PairKey& key : iv.pending) {
          auto it = rows[i].find(key);
          decide(key, it == rows[i].end() ? nullptr : it->second);
        }
      }
      if (!meeting[iv.segment].empty()) {
        out[iv.segment].state = SegmentState::collides;
        continue;
      }
      if (open.empty()) continue;
      if (depth + 1 > options.max_depth) {
        unresolved[iv.segment].insert(open.begin(), open.end());
        continue;
      }
      next.push_back({iv.segment, iv.ta, tm, false, open});
      next.push_back({iv.segment, tm, iv.tb, false, std::move(open)});
    }
    level.clear();
    for (Interval& iv : next) {
      if (out[iv.segment].state != SegmentState::collides) level.push_back(std::move(iv));
    }
  }
  finish(cs, out, meeting, unresolved);
  return out;
}

void finish(const CellScene& cs, std::vector<SegmentResult>& out,
            const std::vector<std::map<PairKey, double>>& meeting,
            const std::vector<std::set<PairKey>>& unresolved) {
  auto pair_name = [&](const PairKey& k) {
    return cs.scene.bodies[k.first].id + " / " + cs.scene.bodies[k.second].id;
  };
  for (std::size_t s = 0; s < out.size(); ++s) {
    SegmentResult& sr = out[s];
    if (sr.state == SegmentState::collides) {
      for (const auto& [key, t] : meeting[s]) {
        std::string test;
        for (const scene::ClashTest& ct : cs.tests) {
          const bool a_in_a = scene::selects(ct.a, cs.scene.bodies[key.first]);
          const bool b_in_a = scene::selects(ct.a, cs.scene.bodies[key.second]);
          const bool a_in_b = !ct.b.empty() && scene::selects(ct.b, cs.scene.bodies[key.first]);
          const bool b_in_b = !ct.b.empty() && scene::selects(ct.b, cs.scene.bodies[key.second]);
          if (ct.b.empty() ? (a_in_a && b_in_a) : ((a_in_a && b_in_b) || (b_in_a && a_in_b))) {
            test = ct.name;
            break;
          }
        }
        sr.pairs.push_back(
            {test, cs.scene.bodies[key.first].id, cs.scene.bodies[key.second].id, t});
        sr.t = sr.t < 0 ? t : std::min(sr.t, t);
      }
    } else if (!unresolved[s].empty()) {
      sr.state = SegmentState::unresolved;
      for (const PairKey& k : unresolved[s]) sr.unresolved_pairs.push_back(pair_name(k));
    }
  }
}

}  // namespace

std::vector<BodyGeom> detail::body_geometry(const Cell& cell, const CellScene& cs, bool models) {
  const std::vector<BodyLink> bl = body_links(cell, cs);
  std::vector<BodyGeom> out(bl.size());
  for (std::size_t b = 0; b < bl.size(); ++b) {
    const scene::Body& body = cs.scene.bodies[b];
    BodyGeom& g = out[b];
    g.link = bl[b].link;
    const TriMesh& m = *body.mesh;
    Aabb box;
    for (const Vec3& p : m.positions) box.expand(p);
    g.centre = m.positions.empty() ? Vec3{} : box.center();
    for (const Vec3& p : m.positions) g.radius = std::max(g.radius, norm(p - g.centre));
    g.radius *= 1 + 1e-12;
    if (!models) continue;
    if (g.link >= 0) {
      g.model = std::make_shared<const Model>(make_model(m));
      g.closed = g.model->stats.closed();
    } else {
      g.model = body.world_model
                    ? body.world_model
                    : std::make_shared<const Model>(make_model(
                          body.pose.is_identity() ? m : transformed(m, body.pose), {}, false));
      // The statistics do not depend on the pose: those of the body's own mesh.
      g.closed = (g.model->stats.triangles > 0 ? g.model->stats : mesh_stats(m)).closed();
    }
    const std::vector<std::uint32_t> set = connected_sets(m, std::vector<char>(m.num_triangles(), 1));
    for (std::uint32_t t = 0; t < set.size(); ++t)
      if (set[t] == t) g.component_vertices.push_back(m.triangles[t][0]);
  }
  return out;
}

std::vector<double> detail::bounds_at(const Cell& cell, const std::vector<BodyGeom>& geom,
                                      const std::vector<Transform>& f, const std::vector<double>& dq,
                                      const std::vector<double>& reach_bound) {
  const Chain& chain = cell.robot;
  std::vector<double> out(geom.size(), 0.0);
  for (std::size_t b = 0; b < geom.size(); ++b) {
    if (geom[b].link < 0) continue;
    const auto k = static_cast<std::size_t>(geom[b].link);
    const Vec3 c = f[k].apply(geom[b].centre);
    double delta = 0;
    for (std::size_t m = 0; m < chain.movable.size(); ++m) {
      const std::size_t ji = chain.movable[m];  // moves links ji+1 ... end
      if (ji + 1 > k) continue;
      const ChainJoint& j = chain.joints[ji];
      if (j.kind == JointKind::prismatic) {
        delta += std::fabs(dq[m]);
        continue;
      }
      // Joint ji turns about the line through link ji+1's origin along its axis (fixed by the
      // joint's own rotation): the body's distance from it at q.
      Vec3 w = f[ji + 1].rotate(j.axis);
      w = w / norm(w);
      const double rho = norm(cross(c - f[ji + 1].t, w)) + geom[b].radius;
      delta += std::fabs(dq[m]) * std::numbers::pi / 180.0 * rho;
    }
    out[b] = std::min(delta * (1 + 1e-9), reach_bound[b]);
  }
  return out;
}

double detail::box_gap(const Aabb& x, const Aabb& y) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max({0.0, x.lo[k] - y.hi[k], y.lo[k] - x.hi[k]});
    d2 += g * g;
  }
  return std::sqrt(d2);
}

Aabb detail::to_double(const AabbF& b) {
  Aabb r;
  for (int k = 0; k < 3; ++k) r.lo[k] = b.lo[k], r.hi[k] = b.hi[k];
  return r;
}

std::vector<PairKey> detail::test_pairs(const CellScene& cs) {
  std::set<PairKey> out;
  const auto& bodies = cs.scene.bodies;
  for (const scene::ClashTest& ct : cs.tests) {
    for (std::uint32_t u = 0; u < bodies.size(); ++u) {
      for (std::uint32_t v = u + 1; v < bodies.size(); ++v) {
        const bool ua = scene::selects(ct.a, bodies[u]), va = scene::selects(ct.a, bodies[v]);
        const bool ub = !ct.b.empty() && scene::selects(ct.b, bodies[u]);
        const bool vb = !ct.b.empty() && scene::selects(ct.b, bodies[v]);
        if (!(ct.b.empty() ? (ua && va) : ((ua && vb) || (va && ub)))) continue;
        bool suppressed = false;
        for (const scene::Suppression& sp : ct.suppressions) {
          const bool fwd = scene::selects(sp.a, bodies[u]) && scene::selects(sp.b, bodies[v]);
          const bool back = scene::selects(sp.a, bodies[v]) && scene::selects(sp.b, bodies[u]);
          suppressed = suppressed || fwd || back;
        }
        if (!suppressed) out.insert({u, v});
      }
    }
  }
  return {out.begin(), out.end()};
}

namespace {

/// What the advancement found for one pair at one middle.
struct PairAtMiddle {
  PairKey key;
  bool cleared = false;       ///< distance > bound sum: no surface contact on the sub-interval
  bool needs_engine = false;  ///< containment possible, an open body, or a non-exact engine test
  /// The surfaces meet (two triangles intersect or touch, exact test; both bodies closed): the
  /// engine's verdict there is clash or contact, so the pair meets without asking it.
  bool meets = false;
};

}  // namespace

std::vector<SegmentResult> detail::check_advancement(const Cell& cell, const CellScene& cs,
                                                     const JointPath& path, const BetweenOptions& options,
                                                     const std::vector<std::vector<PairKey>>* initial,
                                                     const std::vector<BodyGeom>* given_geom) {
  const std::size_t segments = path.size() > 1 ? path.size() - 1 : 0;
  std::vector<SegmentResult> out(segments);
  const std::vector<BodyGeom> own_geom = given_geom ? std::vector<BodyGeom>{} : body_geometry(cell, cs, true);
  const std::vector<BodyGeom>& geom = given_geom ? *given_geom : own_geom;
  const std::vector<BodyLink> links = body_links(cell, cs);
  const std::vector<PairKey> all_pairs = test_pairs(cs);
  // Meeting surfaces found by the exact triangle test are the engine's meeting too (its exact
  // triangle test; a float filter could call some touches apart: then the engine decides).
  const bool exact_meets = options.engine.request.test == TriTest::exact;
  // Coordinates' scale (rounding of the posed vertices and of the distances): absolute slack.
  double scale = 1;
  for (const BodyGeom& g : geom) {
    if (g.link < 0 && g.model && !g.model->bvh.empty()) {
      const Aabb b = to_double(g.model->bvh.nodes[0].box);
      scale = std::max({scale, norm(b.lo), norm(b.hi)});
    }
  }
  for (const Transform& t : link_frames(cell.robot, path.size() ? path.q[0]
                                                                : std::vector<double>(cell.robot.dof(), 0.0),
                                        cell.base))
    scale = std::max(scale, norm(t.t));
  for (const BodyGeom& g : geom) scale += g.link >= 0 ? g.radius : 0.0;
  const double slack = 1e-9 * scale;

  struct Interval {
    std::size_t segment = 0;
    double ta = 0, tb = 1;
    std::vector<PairKey> pending;
  };
  struct Middle {
    std::vector<double> q;
    std::vector<PairAtMiddle> pairs;
    bool engine = false;
  };
  // Per thread: the moving bodies' models, posed by refit at the current middle.
  tbb::enumerable_thread_specific<std::vector<Model>> posed_tls([&] {
    std::vector<Model> v(geom.size());
    for (std::size_t b = 0; b < geom.size(); ++b)
      if (geom[b].link >= 0) v[b] = *geom[b].model;
    return v;
  });

  std::vector<Interval> level;
  for (std::size_t s = 0; s < segments; ++s) {
    out[s].from = s;
    // (given pending pairs: the others are proven clear on the whole segment already)
    if (!initial) level.push_back({s, 0.0, 1.0, all_pairs});
    else if (!(*initial)[s].empty()) level.push_back({s, 0.0, 1.0, (*initial)[s]});
  }
  std::vector<std::set<PairKey>> unresolved(segments);
  std::vector<std::map<PairKey, double>> meeting(segments);
  const std::size_t dof = cell.robot.dof();
  const std::vector<double> zero(dof, 0.0);
  for (int depth = 0; !level.empty(); ++depth) {
    std::vector<Middle> mid(level.size());
    auto examine = [&](std::size_t i) {
      const Interval& iv = level[i];
      Middle& md = mid[i];
      const double tm = 0.5 * (iv.ta + iv.tb), half = 0.5 * (iv.tb - iv.ta);
      const std::vector<double>& q0 = path.q[iv.segment];
      const std::vector<double>& q1 = path.q[iv.segment + 1];
      md.q.resize(dof);
      std::vector<double> dq(dof);
      for (std::size_t j = 0; j < dof; ++j)
        md.q[j] = q0[j] + tm * (q1[j] - q0[j]), dq[j] = half * (q1[j] - q0[j]);
      const std::vector<Transform> f = link_frames(cell.robot, md.q, cell.base);
      const std::vector<double> delta = bounds_at(cell, geom, f, dq, reach_bounds(cell, links, dq));
      // Each body's world box at the middle: its bounding cube (moving) or its model's root box.
      std::vector<Aabb> cube(geom.size());
      for (std::size_t b = 0; b < geom.size(); ++b) {
        if (geom[b].link >= 0) {
          const Vec3 c = f[geom[b].link].apply(geom[b].centre);
          const Vec3 r{geom[b].radius, geom[b].radius, geom[b].radius};
          cube[b].lo = c - r, cube[b].hi = c + r;
        } else if (!geom[b].model->bvh.empty()) {
          cube[b] = to_double(geom[b].model->bvh.nodes[0].box);
        }
      }
      std::vector<Model>& posed = posed_tls.local();
      std::vector<char> is_posed(geom.size(), 0);
      auto model = [&](std::uint32_t b) -> const Model& {
        if (geom[b].link < 0) return *geom[b].model;
        if (!is_posed[b]) {
          const Transform& fb = f[geom[b].link];
          std::vector<Vec3> p(geom[b].model->mesh.positions.size());
          for (std::size_t v = 0; v < p.size(); ++v) p[v] = fb.apply(geom[b].model->mesh.positions[v]);
          refit(posed[b], std::move(p));
          is_posed[b] = 1;
        }
        return posed[b];
      };
      // World position of vertex v of body b at the middle.
      auto at = [&](std::uint32_t b, std::uint32_t v) {
        return geom[b].link >= 0 ? f[geom[b].link].apply(geom[b].model->mesh.positions[v])
                                 : geom[b].model->mesh.positions[v];
      };
      // With the surfaces apart, every connected component of x lies wholly inside or wholly
      // outside y's solid, and one vertex of it decides. Whether the engine could find x inside
      // y, or leave it undecided: y closed, a vertex outside y's box is outside y; else exact ray
      // parity (query/clash.h point_in_solid, the engine's own test), inside or undecided. y open
      // (the engine says undecided where a component of x lies in y's box in the frame it
      // decides in): any vertex within sqrt(3) radii of y's centre (that box lies in this ball).
      auto could_contain = [&](std::uint32_t x, std::uint32_t y, const Model* my) {
        const Vec3 cy = geom[y].link >= 0 ? f[geom[y].link].apply(geom[y].centre)
                                          : geom[y].model->bvh.empty()
                                                ? Vec3{}
                                                : to_double(geom[y].model->bvh.nodes[0].box).center();
        for (const std::uint32_t v : geom[x].component_vertices) {
          const Vec3 p = at(x, v);
          if (!geom[y].closed) {
            const double reach = std::sqrt(3.0) * (geom[y].link >= 0 ? geom[y].radius
                                                                     : 0.5 * norm(cube[y].hi - cube[y].lo));
            if (norm(p - cy) <= reach * (1 + 1e-9) + slack) return true;
            continue;
          }
          if (p.x < cube[y].lo.x || p.x > cube[y].hi.x || p.y < cube[y].lo.y || p.y > cube[y].hi.y ||
              p.z < cube[y].lo.z || p.z > cube[y].hi.z)
            continue;  // outside a box holding y, so outside y's solid
          if (!my) return true;  // (not posed: let the engine decide)
          if (point_in_solid(*my, p) != 0) return true;
        }
        return false;
      };
      for (const PairKey& key : iv.pending) {
        PairAtMiddle pm{key};
        const double bound = (delta[key.first] + delta[key.second]) * (1 + 1e-9) + slack;
        if (box_gap(cube[key.first], cube[key.second]) > bound) {
          // Apart by more than the bound: no contact on the sub-interval, and neither body lies
          // inside the other (their boxes are apart).
          pm.cleared = true;
          pm.needs_engine = (!geom[key.second].closed && could_contain(key.first, key.second, nullptr)) ||
                            (!geom[key.first].closed && could_contain(key.second, key.first, nullptr));
          md.pairs.push_back(pm);
          continue;
        }
        const Model& ma = model(key.first);
        const Model& mb = model(key.second);
        const DistanceResult d = distance(ma, mb, {.upper_bound = bound});
        pm.cleared = !d.intersecting && d.distance > bound;
        if (d.intersecting && exact_meets && geom[key.first].closed && geom[key.second].closed) {
          pm.meets = true;
          md.pairs.push_back(pm);
          continue;
        }
        pm.needs_engine = d.intersecting || could_contain(key.first, key.second, &mb) ||
                          could_contain(key.second, key.first, &ma);
        md.pairs.push_back(pm);
      }
      for (const PairAtMiddle& pm : md.pairs) md.engine = md.engine || pm.needs_engine;
    };
    if (options.parallel) {
      tbb::parallel_for(std::size_t(0), level.size(), examine);
    } else {
      for (std::size_t i = 0; i < level.size(); ++i) examine(i);
    }
    // The scene engine decides the middles that need it (exact mesh core: surfaces, containment).
    scene::Scene sc;
    sc.units = cs.scene.units;
    sc.bodies = cs.scene.bodies;
    std::vector<std::size_t> frame_of(level.size(), SIZE_MAX);
    for (std::size_t i = 0; i < level.size(); ++i) {
      ++out[level[i].segment].frames;
      if (!mid[i].engine) continue;
      ++out[level[i].segment].engine_frames;
      const double tm = 0.5 * (level[i].ta + level[i].tb);
      const std::vector<Transform> f = link_frames(cell.robot, mid[i].q, cell.base);
      scene::Frame fr;
      fr.label = "segment " + std::to_string(level[i].segment) + " t " + short_number(tm);
      fr.time = static_cast<double>(level[i].segment) + tm;
      for (std::size_t k = 0; k < cs.link_body.size(); ++k) {
        if (cs.link_body[k] >= 0)
          fr.poses.push_back({static_cast<std::uint32_t>(cs.link_body[k]), f[k]});
      }
      for (std::int64_t b : {cs.probe_body, cs.holder_body}) {
        if (b >= 0) fr.poses.push_back({static_cast<std::uint32_t>(b), f[cell.tool_link]});
      }
      frame_of[i] = sc.frames.size();
      sc.frames.push_back(std::move(fr));
    }
    std::vector<std::map<PairKey, const scene::FramePairRow*>> rows(sc.frames.size());
    scene::SceneClashResult r;
    if (!sc.frames.empty()) {
      std::vector<scene::ClashTest> tests = cs.tests;
      for (scene::ClashTest& t : tests) t.mode = scene::ClashMode::hard, t.clearance = 0;
      scene::SceneClashOptions eo = options.engine;
      eo.depth = false, eo.curves = false, eo.triangles = false, eo.reference = false;
      eo.group_by = scene::GroupBy::none;
      // Only the middle's pending pairs are read: the engine decides only those.
      std::vector<std::size_t> level_of(sc.frames.size());
      for (std::size_t i = 0; i < level.size(); ++i)
        if (frame_of[i] != SIZE_MAX) level_of[frame_of[i]] = i;
      eo.decide_in_frame = [&](std::size_t fr, std::uint32_t a, std::uint32_t b) {
        const PairKey key{std::min(a, b), std::max(a, b)};
        for (const PairAtMiddle& pm : mid[level_of[fr]].pairs)
          if (pm.key == key) return true;
        return false;
      };
      r = engine_in_chunks(sc, tests, eo, options.parallel);
      for (const scene::FramePairRow& row : r.frame_pairs)
        rows[row.frame][{std::min(row.a, row.b), std::max(row.a, row.b)}] = &row;
    }
    std::vector<Interval> next;
    for (std::size_t i = 0; i < level.size(); ++i) {
      Interval& iv = level[i];
      if (out[iv.segment].state == SegmentState::collides) continue;
      const double tm = 0.5 * (iv.ta + iv.tb);
      std::vector<PairKey> open;
      for (const PairAtMiddle& pm : mid[i].pairs) {
        const scene::FramePairRow* row = nullptr;
        if (frame_of[i] != SIZE_MAX) {
          auto it = rows[frame_of[i]].find(pm.key);
          if (it != rows[frame_of[i]].end()) row = it->second;
        }
        if (pm.meets || (row && (row->verdict == Verdict::clash || row->verdict == Verdict::contact))) {
          // (keyed as the engine orders the pair, by body id, as the subdivision reports it)
          const auto& [x, y] = pm.key;
          const PairKey engine_key = cs.scene.bodies[x].id < cs.scene.bodies[y].id ? PairKey{x, y} : PairKey{y, x};
          auto [it, fresh] = meeting[iv.segment].emplace(engine_key, tm);
          if (!fresh) it->second = std::min(it->second, tm);
          continue;
        }
        const bool undecided = row && row->verdict == Verdict::undecided;
        if (pm.cleared && !undecided) continue;
        open.push_back(pm.key);  // too close to prove, or undecided
      }
      if (!meeting[iv.segment].empty()) {
        out[iv.segment].state = SegmentState::collides;
        continue;
      }
      if (open.empty()) continue;
      if (depth + 1 > options.max_depth) {
        unresolved[iv.segment].insert(open.begin(), open.end());
        continue;
      }
      next.push_back({iv.segment, iv.ta, tm, open});
      next.push_back({iv.segment, tm, iv.tb, std::move(open)});
    }
    level.clear();
    for (Interval& iv : next) {
      if (out[iv.segment].state != SegmentState::collides) level.push_back(std::move(iv));
    }
  }
  finish(cs, out, meeting, unresolved);
  return out;
}

scene::SceneClashResult detail::engine_in_chunks(const scene::Scene& sc, const std::vector<scene::ClashTest>& tests,
                                                 const scene::SceneClashOptions& eo, bool parallel) {
  const std::size_t n = sc.frames.size();
  const std::size_t chunks =
      parallel ? std::min<std::size_t>(n, 4 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency())) : 1;
  if (chunks <= 1) return scene::clash_scene(sc, tests, eo);
  std::vector<scene::SceneClashResult> part(chunks);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t lo = n * c / chunks, hi = n * (c + 1) / chunks;
    scene::Scene piece;
    piece.units = sc.units;
    piece.bodies = sc.bodies;
    piece.frames.assign(sc.frames.begin() + static_cast<std::ptrdiff_t>(lo),
                        sc.frames.begin() + static_cast<std::ptrdiff_t>(hi));
    scene::SceneClashOptions o = eo;
    if (eo.decide_in_frame)
      o.decide_in_frame = [&eo, lo](std::size_t f, std::uint32_t a, std::uint32_t b) { return eo.decide_in_frame(lo + f, a, b); };
    part[c] = scene::clash_scene(piece, tests, o);
    for (scene::FramePairRow& row : part[c].frame_pairs) row.frame += static_cast<std::uint32_t>(lo);
  });
  scene::SceneClashResult r;
  for (scene::SceneClashResult& p : part)
    r.frame_pairs.insert(r.frame_pairs.end(), p.frame_pairs.begin(), p.frame_pairs.end());
  return r;
}

std::vector<double> motion_bounds_at(const Cell& cell, const CellScene& cs,
                                     const std::vector<double>& q, const std::vector<double>& dq) {
  return bounds_at(cell, body_geometry(cell, cs, false), link_frames(cell.robot, q, cell.base), dq,
                   motion_bounds(cell, cs, dq));
}

std::vector<SegmentResult> check_between_points(const Cell& cell, const CellScene& cs,
                                                const JointPath& path,
                                                const BetweenOptions& options) {
  return options.method == BetweenMethod::subdivision ? check_subdivision(cell, cs, path, options)
                                                      : detail::check_advancement(cell, cs, path, options);
}

}  // namespace interfere::robot
