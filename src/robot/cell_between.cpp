// The conservative check of the whole cell between path points (issue #28, deliverable 3;
// robot/cell.h, check_between_points): per segment, interval halving with a per-body motion bound,
// each level's middles decided in one scene-engine run with clearance tests.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "interfere/robot/cell.h"

namespace interfere::robot {
namespace {

using PairKey = std::pair<std::uint32_t, std::uint32_t>;

struct Interval {
  std::size_t segment = 0;
  double ta = 0, tb = 1;
  bool all_pairs = true;      ///< every pair still open (the first level)
  std::set<PairKey> pending;  ///< otherwise: the pairs not yet proven clear on it
};

/// Per body: the link it moves with (-1: static) and its mesh radius about that link's origin.
struct BodyLink {
  std::int64_t link = -1;
  double radius = 0;
};

std::vector<BodyLink> body_links(const Cell& cell, const CellScene& cs) {
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

}  // namespace

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
  const Chain& chain = cell.robot;
  const std::vector<BodyLink> bl = body_links(cell, cs);
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

std::vector<SegmentResult> check_between_points(const Cell& cell, const CellScene& cs,
                                                const JointPath& path,
                                                const BetweenOptions& options) {
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
  auto pair_name = [&](const PairKey& k) {
    return cs.scene.bodies[k.first].id + " / " + cs.scene.bodies[k.second].id;
  };
  for (std::size_t s = 0; s < segments; ++s) {
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
  return out;
}

}  // namespace interfere::robot
