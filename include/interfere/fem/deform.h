// Deformed configurations of FEM parts and the clash per load step (issue #3, item 3), and the
// clash results named by the solver's element and node ids (item 5).
//
// A part's deformed vertex positions are node + scale × displacement[step] of the FEM nodes it uses.
// For a time series the two parts' trees are built once (reference positions) and refitted per
// step (same topology; refit_bvh keeps the tree and recomputes its boxes), then the clash runs.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/surface.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"

namespace interfere {

/// Vertex positions of `part` at `step` of `displacement` (nullptr: the reference positions):
/// p = node + scale × u. `out` is resized to the part's vertex count. Preconditions: the part was
/// extracted from `mesh`; step < displacement->num_steps().
void deformed_positions(const SurfacePart& part, const FemMesh& mesh, const NodalSeries* displacement,
                        std::size_t step, double scale, std::vector<Vec3>& out);

/// One side of a series clash: the mesh, the extracted part, and its displacements (may be null:
/// the part stays at its reference position).
struct SeriesPart {
  const FemMesh* mesh = nullptr;
  const SurfacePart* part = nullptr;
  const NodalSeries* displacement = nullptr;
};

struct StepSummary;

struct SeriesRequest {
  ClashRequest clash;
  BvhBuildOptions bvh;
  double scale = 1.0;
  std::vector<std::size_t> steps;  ///< 0-based steps to check, increasing; empty = every step
  bool keep_first_clash = true;    ///< keep the full ClashResult of the first clashing step
  bool keep_all = false;           ///< keep the full ClashResult of every checked step
  bool keep_last = false;          ///< keep the full ClashResult of the last checked step
  /// Called after each checked step with its summary and full result, before the result is kept
  /// or dropped: a caller keeps what it needs of every step (the viewer document of issue #25 keeps
  /// the regions and the closest clearance pair) without keep_all's copies of every result.
  std::function<void(const StepSummary&, const ClashResult&)> on_step;
  /// Penetration depth of every checked step whose verdict is clash (issue #26, item 3; Deng et
  /// al. 2018 judge a clash by how deep the deformed parts reach into each other): with both parts
  /// closed, query/depth.h's penetration_depth and the per-vertex depth maps of both parts, the
  /// deepest node on StepSummary; a part not closed: not measured, StepSummary::depth_note says so.
  bool depth = false;
  /// Splits per direction for the depth's upper bound (penetration_depth's max_splits); 0: none.
  std::size_t depth_bound_splits = 5000;
  /// With `depth`: called with each measured step's summary and both per-vertex maps (maps.a: the
  /// surface vertices of part a in b's solid; maps.b: b's in a's; indices of SurfacePart::mesh),
  /// right before on_step for that step; the maps are not kept.
  std::function<void(const StepSummary&, const DepthMaps&)> on_depth_maps;
};

/// The deepest surface node of a step's depth maps (issue #26, item 3).
struct DeepestNode {
  int part = 0;                      ///< 0: a node of part a inside b's solid; 1: of b inside a's
  std::uint32_t vertex = kNoVertex;  ///< the part's surface vertex (SurfacePart::mesh)
  std::int64_t node = -1;            ///< its FE node id (FemMesh::node_ids of SurfacePart::vertex_node)
  /// Id of the element of the part's first surface triangle at the vertex (FemMesh::elem_ids of
  /// SurfacePart::tri_element): an element that has the node.
  std::int64_t element = -1;
  double depth = 0;  ///< its distance to the other part's surface
  Vec3 point;        ///< its deformed position
};

struct StepSummary {
  std::size_t step = 0;  ///< 0-based
  double time = 0;       ///< the series' time of the step (step number when it has none)
  std::size_t pairs = 0, cross_pairs = 0, touch_pairs = 0, regions = 0;
  double max_curve_length = 0;    ///< longest region curve length
  double total_curve_length = 0;  ///< sum over regions
  Containment containment = Containment::not_checked;
  bool interference = false;  ///< the surfaces meet or one part contains the other (contact included)
  Verdict verdict = Verdict::clear;  ///< the step's verdict (ClashResult::verdict, query/verdict.h)
  double refit_seconds = 0, clash_seconds = 0;
  /// SeriesRequest::depth, a clashing step of closed parts: `depth` is the sampled penetration
  /// depth (a lower bound: PenetrationDepth::depth; for one part inside the other, which has no
  /// crossing, the largest node depth of the maps), `depth_bound` its proven upper bound where
  /// `depth_bounded` (crossing or touching-overlap steps with depth_bound_splits > 0).
  bool depth_measured = false;
  double depth = 0, depth_bound = 0;
  bool depth_bounded = false;
  bool has_deepest = false;  ///< a surface node lies inside the other part (depth maps)
  DeepestNode deepest;
  /// A clashing step whose depth is not measured says why (a part not closed); a measured one,
  /// what limits it (undecided nodes, a containment without bound). Empty otherwise.
  std::string depth_note;
  double depth_seconds = 0;
};

struct SeriesResult {
  std::size_t num_steps = 0;          ///< steps in the series (1 when neither part has a field)
  std::vector<StepSummary> steps;     ///< one per checked step, in step order
  /// The series' verdict: the worst of its steps' (clash > undecided > contact > clearance > clear).
  Verdict verdict = Verdict::clear;
  std::int64_t first_clash_step = -1;    ///< 0-based, first step whose verdict is clash; -1 if none
  std::int64_t first_contact_step = -1;  ///< first step whose surfaces meet (contact or clash); -1 if none
  std::int64_t worst_step = -1;          ///< first step with the series' verdict; -1 if no step checked
  /// SeriesRequest::depth: the first step of the largest measured depth; -1 if none measured.
  std::int64_t deepest_step = -1;
  ClashResult first_clash;            ///< the first clashing step's result (keep_first_clash)
  ClashResult worst;                  ///< the result of worst_step (keep_first_clash)
  std::vector<ClashResult> results;   ///< per checked step (keep_all)
  ClashResult last;                   ///< the last checked step's result (keep_last)
  double build_seconds = 0;           ///< both trees, once
};

/// Checks every requested step. Errors (as values): a part or mesh missing, displacement fields
/// of the two parts with different step counts, a field with the wrong node count, a step out
/// of range, a non-finite scale, a non-finite deformed position (names the node id and step).
Expected<SeriesResult> clash_series(const SeriesPart& a, const SeriesPart& b, const SeriesRequest& request = {});

/// A clash region named by the solver: the element ids of its triangles, and the node ids of the
/// element faces they come from (all nodes of each face, mid-side nodes included); sorted, unique.
struct RegionIds {
  std::vector<std::int64_t> elements_a, elements_b;
  std::vector<std::int64_t> nodes_a, nodes_b;
  std::vector<std::pair<std::int64_t, int>> faces_a, faces_b;  ///< (element id, local face)
};
RegionIds region_ids(const ClashRegion& region, const SurfacePart& a, const FemMesh& mesh_a, const SurfacePart& b,
                     const FemMesh& mesh_b);

/// Node indices of local face `face` (1-based, surface.h numbering; 1 for shells) of element `e`:
/// corners, then mid-side nodes, then the centre node.
std::vector<std::uint32_t> element_face_nodes(const FemMesh& mesh, std::size_t e, int face);

}  // namespace interfere
