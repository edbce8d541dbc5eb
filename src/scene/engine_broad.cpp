// The scene engine's broad phase (include/interfere/scene/engine.h, BroadPhase; issue #24, item 3:
// "a BVH of the bodies' world boxes, refitted per frame"), public so that interfere-mpi plans a
// distributed run with the engine's own candidate rule (issue #31): conservative world boxes
// (broad_box), per test a box tree per selection, the traversal's float overlap test with the
// test's margin, suppression rules.
#include <algorithm>
#include <cmath>

#include "engine_internal.h"
#include "interfere/bvh/traverse.h"

namespace interfere::scene {

// The world box of a local box under an affine pose (its 8 corners), padded by a relative 2^-40 so
// that rounding in the vertices' own transforms cannot leave it (the exact core decides anyway).
AabbF broad_box(const Aabb& local, const Transform& t) {
  Aabb w;
  for (int c = 0; c < 8; ++c)
    w.expand(t.apply({c & 1 ? local.hi.x : local.lo.x, c & 2 ? local.hi.y : local.lo.y, c & 4 ? local.hi.z : local.lo.z}));
  const Vec3 e = w.extent();
  const double pad = (std::max({std::fabs(w.lo.x), std::fabs(w.lo.y), std::fabs(w.lo.z), std::fabs(w.hi.x),
                                std::fabs(w.hi.y), std::fabs(w.hi.z)}) +
                      std::max({e.x, e.y, e.z})) *
                     0x1p-40;
  w.lo = w.lo - Vec3{pad, pad, pad}, w.hi = w.hi + Vec3{pad, pad, pad};
  return to_float_outward(w);
}

std::array<double, 12> relative_pose_key(const Transform& pose_a, const Transform& pose_b) {
  const Transform t = pose_a == pose_b ? Transform{} : compose(inverse(pose_a), pose_b);
  return t.to_row_major();
}

namespace detail {

bool pair_matches(const Selection& x, const Selection& y, const Body& p, const Body& q) {
  return (selects(x, p) && selects(y, q)) || (selects(x, q) && selects(y, p));
}

double pair_clearance(const ClashTest& t, const Body& p, const Body& q) {
  if (t.mode != ClashMode::clearance) return 0;
  for (const ClearanceOverride& o : t.clearance_overrides)
    if (pair_matches(o.a, o.b, p, q)) return o.clearance;
  return t.clearance;
}

}  // namespace detail

BroadPhase::BroadPhase(const std::vector<Body>& bodies, const std::vector<ClashTest>& tests)
    : bodies_(bodies), tests_(tests), a_(tests.size()), b_(tests.size()), margin_(tests.size(), 0),
      tree_a_(tests.size()), tree_b_(tests.size()) {
  const auto n = static_cast<std::uint32_t>(bodies.size());
  for (std::size_t k = 0; k < tests.size(); ++k) {
    const ClashTest& t = tests[k];
    for (std::uint32_t i = 0; i < n; ++i) {
      if (selects(t.a, bodies[i])) a_[k].push_back(i);
      if (!t.b.empty() && selects(t.b, bodies[i])) b_[k].push_back(i);
    }
    if (a_[k].empty()) warnings_.push_back("clash test '" + t.name + "': selection A selects no body");
    if (!t.b.empty() && b_[k].empty()) warnings_.push_back("clash test '" + t.name + "': selection B selects no body");
    margin_[k] = t.mode == ClashMode::duplicates ? t.tolerance : 0;
    if (t.mode == ClashMode::clearance) {
      margin_[k] = t.clearance;
      for (const ClearanceOverride& o : t.clearance_overrides) margin_[k] = std::max(margin_[k], o.clearance);
    }
  }
}

std::vector<CandidatePair> BroadPhase::candidates(const std::vector<AabbF>& boxes, std::size_t& candidate_count,
                                                  std::size_t& suppressed_count) {
  std::vector<CandidatePair> out;
  for (std::size_t k = 0; k < tests_.size(); ++k) {
    const ClashTest& t = tests_[k];
    const auto boxes_of = [&](const std::vector<std::uint32_t>& sel) {
      std::vector<AabbF> b(sel.size());
      for (std::size_t i = 0; i < sel.size(); ++i) b[i] = boxes[sel[i]];
      return b;
    };
    if (!built_) {
      tree_a_[k] = detail::build_box_tree(boxes_of(a_[k]));
      if (!b_[k].empty()) tree_b_[k] = detail::build_box_tree(boxes_of(b_[k]));
    } else {
      detail::refit_box_tree(tree_a_[k], boxes_of(a_[k]));
      if (!b_[k].empty()) detail::refit_box_tree(tree_b_[k], boxes_of(b_[k]));
    }
    const bool within = t.b.empty();
    const Bvh& other = within ? tree_a_[k] : tree_b_[k];
    const std::vector<std::uint32_t>& other_sel = within ? a_[k] : b_[k];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for_each_overlap(tree_a_[k], other, round_up(margin_[k]), [&](std::uint32_t x, std::uint32_t y) {
      std::uint32_t u = a_[k][x], v = other_sel[y];
      if (u == v) return;
      if (bodies_[v].id < bodies_[u].id) std::swap(u, v);
      pairs.emplace_back(u, v);
    });
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    candidate_count += pairs.size();
    for (const auto& [u, v] : pairs) {
      const Body& bu = bodies_[u];
      const Body& bv = bodies_[v];
      bool suppressed = false;
      for (const Suppression& s : t.suppressions) suppressed = suppressed || detail::pair_matches(s.a, s.b, bu, bv);
      if (suppressed) {
        ++suppressed_count;
        continue;
      }
      out.push_back({static_cast<std::uint32_t>(k), u, v, detail::pair_clearance(t, bu, bv)});
    }
  }
  built_ = true;
  return out;
}

}  // namespace interfere::scene
