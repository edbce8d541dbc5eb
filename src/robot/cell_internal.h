// Shared pieces of the cell's checks along the path (robot/cell.h; issue #28): the bodies' links,
// bounding spheres and models, the per-body motion bounds, the pairs the tests check, and the
// conservative advancement between points (cell_between.cpp), used by the whole-path check with
// certified distances across path points (cell_path.cpp).
#pragma once
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "interfere/query/model.h"
#include "interfere/robot/cell.h"

namespace interfere::robot::detail {

using PairKey = std::pair<std::uint32_t, std::uint32_t>;

/// Per body: the link it moves with (-1: static) and its mesh radius about that link's origin.
struct BodyLink {
  std::int64_t link = -1;
  double radius = 0;
};
std::vector<BodyLink> body_links(const Cell& cell, const CellScene& cs);

/// motion_bounds (robot/cell.h) from precomputed body links.
std::vector<double> reach_bounds(const Cell& cell, const std::vector<BodyLink>& bl,
                                 const std::vector<double>& dq);

/// Per body: the link it moves with (-1: static), its bounding sphere in its own frame (centre
/// of its box, radius to the farthest vertex), its local model (moving bodies; posed per middle
/// by refit) or world model (static bodies), and whether it is closed (containment needs it).
struct BodyGeom {
  std::int64_t link = -1;
  Vec3 centre;
  double radius = 0;
  std::shared_ptr<const Model> model;  ///< local (moving) or world (static)
  bool closed = false;
  std::vector<std::uint32_t> component_vertices;  ///< one vertex of each connected component
};
std::vector<BodyGeom> body_geometry(const Cell& cell, const CellScene& cs, bool models);

/// motion_bounds_at (robot/cell.h) at link frames f, capped by reach_bound.
std::vector<double> bounds_at(const Cell& cell, const std::vector<BodyGeom>& geom,
                              const std::vector<Transform>& f, const std::vector<double>& dq,
                              const std::vector<double>& reach_bound);

/// Gap between two boxes (0 when they overlap).
double box_gap(const Aabb& x, const Aabb& y);
Aabb to_double(const AabbF& b);

/// The body pairs the cell's tests check (each once, smaller index first), suppressions left out.
std::vector<PairKey> test_pairs(const CellScene& cs);

/// The conservative advancement between points (BetweenMethod::advancement). `initial`: per
/// segment, the pairs still to prove (the others are proven clear on the whole segment already;
/// a segment with none is clear without a middle); null: every pair on every segment. `geom`:
/// body_geometry(cell, cs, true) when the caller has it.
std::vector<SegmentResult> check_advancement(const Cell& cell, const CellScene& cs, const JointPath& path,
                                             const BetweenOptions& options,
                                             const std::vector<std::vector<PairKey>>* initial = nullptr,
                                             const std::vector<BodyGeom>* geom = nullptr);

/// clash_scene on the frames of `sc`, in chunks of consecutive frames run in parallel (one run when
/// `parallel` is false): for callers that read only the per-frame verdicts (frame_pairs; frames
/// renumbered to sc's). A frame's verdicts do not depend on the other frames, so they are the same
/// as one run's.
scene::SceneClashResult engine_in_chunks(const scene::Scene& sc, const std::vector<scene::ClashTest>& tests,
                                         const scene::SceneClashOptions& eo, bool parallel);

}  // namespace interfere::robot::detail
