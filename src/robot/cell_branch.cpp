// The first path point's inverse-kinematics branch chosen with collisions in mind (issue #28):
// robot/cell.h, collision_free_start. The numerical solver (robot/ik.h) keeps a path on the branch
// of its first point, and the first point takes the first seed that converges, whichever arm
// configuration that is (on the example cell, "home" puts the elbow through the plate). Here every
// seed is solved on its own, the distinct solutions within the limits are kept in seed order, and
// the first whose pose the scene engine finds clear of everything is chosen.
#include <algorithm>
#include <cmath>

#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"

namespace interfere::robot {

Expected<StartChoice> collision_free_start(const Cell& cell, const probe::ProbePose& first,
                                           const IkOptions& options, int seeds) {
  const Chain& chain = cell.robot;
  const std::size_t n = chain.dof();
  const IkTool tool = cell_ik_tool(cell);
  // Seeds: the given start, home (zeros clamped into the limits), then deterministic
  // pseudo-random configurations within the limits (angles within +-180 degrees).
  std::vector<std::pair<std::string, std::vector<double>>> list;
  if (options.start.size() == n) list.emplace_back("start", options.start);
  std::vector<double> home(n, 0.0);
  for (std::size_t m = 0; m < n; ++m) {
    const ChainJoint& j = chain.joints[chain.movable[m]];
    home[m] = std::clamp(0.0, j.lower, j.upper);
  }
  list.emplace_back("home", home);
  std::uint64_t state = options.random_state ^ 0x9E3779B97F4A7C15ULL;
  auto uniform = [&] {  // xorshift64*, top 53 bits
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return static_cast<double>((state * 0x2545F4914F6CDD1DULL) >> 11) * 0x1.0p-53;
  };
  for (int k = 0; k < seeds; ++k) {
    std::vector<double> q(n);
    for (std::size_t m = 0; m < n; ++m) {
      const ChainJoint& j = chain.joints[chain.movable[m]];
      const double span = j.kind == JointKind::prismatic ? 1e3 : 180.0;
      double lo = std::max(j.lower, -span), hi = std::min(j.upper, span);
      if (lo > hi) lo = j.lower, hi = j.upper;
      q[m] = lo + (hi - lo) * uniform();
    }
    list.emplace_back("seed " + std::to_string(k + 1), std::move(q));
  }
  IkOptions single = options;
  single.start.clear();
  single.random_seeds = 0;
  StartChoice out;
  std::vector<std::vector<double>> distinct;
  for (const auto& [name, seed] : list) {
    const IkSolution s = solve_ik(chain, cell.base, tool, first, &seed, single);
    if (!s.ok || s.seed != "previous") continue;  // (converged from another seed: not this one's)
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const std::vector<double>& d) {
      for (std::size_t m = 0; m < n; ++m)
        if (std::fabs(d[m] - s.q[m]) > 1e-6) return false;
      return true;
    });
    if (seen) continue;
    distinct.push_back(s.q);
    ++out.candidates;
    // The pose at this solution, checked by the scene engine (every test of the cell, hard).
    const JointPath one{{s.q}, {0}};
    const CellScene cs = cell_scene(cell, one);
    std::vector<scene::ClashTest> tests = cs.tests;
    for (scene::ClashTest& t : tests) t.mode = scene::ClashMode::hard, t.clearance = 0;
    scene::SceneClashOptions eo;
    eo.depth = false, eo.curves = false, eo.reference = false;
    const scene::SceneClashResult r = scene::clash_scene(cs.scene, tests, eo);
    if (r.verdict != Verdict::clear) {
      ++out.colliding;
      if (out.q.empty()) out.q = s.q, out.seed = name;  // (the solver's own choice, none clear)
      continue;
    }
    out.q = s.q, out.seed = name, out.collision_free = true;
    return out;
  }
  if (out.q.empty()) {
    return Error{.file = cell.file,
                 .reason = "the first point: no inverse kinematics solution within the limits from " +
                           std::to_string(list.size()) + " seeds"};
  }
  return out;
}

}  // namespace interfere::robot
