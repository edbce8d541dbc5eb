// The clash of two deforming parts over load steps as a viewer document (issue #25, item 1: "FE
// series"; the series itself is fem/deform.h's clash_series, the CLI's `interfere clash` of two FE
// parts with displacements). Library interfere_view: it takes core types only (surface triangles,
// each step's vertex positions and clash regions); the caller gathers them from the FE model.
//
// Document: two bodies (ids "A" and "B"), one frame per checked step (label "step N (time t)",
// its time and verdict). Each body draws its surface at the step's positions: one ViewMesh per
// step where the body deforms (ViewBody::frame_meshes; the triangles are the surface's at every
// step), shared between consecutive steps whose positions and clash flags are equal; a body that
// never moves or changes its flags draws one mesh (no frame_meshes). Per triangle: source_ids (FE
// element ids, where given) and clash_flags (1 on the step's region triangles).
//
// Rows: one per checked step whose verdict is not clear, with frames = {that step's frame}: id
// "step N", verdict, status "new" on the first step of a run of consecutive checked steps with that
// verdict and "active" on the following ones, kind ("crossing", "touch", "inside"), the step's
// clash or contact regions at full resolution as one world mesh (the region triangles of both
// bodies at the step's positions), all its intersection curves, the box of its regions and the
// camera point at the box's centre; a containment without regions points at the inner body; a
// clearance step carries its closest pair as the witness and the distance. Row depths are not
// known (-1). A row per step, not per run, because the region moves and changes with the step.
// Steps with depth maps (FemSeriesStep::depth, issue #26 item 3) give their body meshes per-vertex
// point_depth; a step without them, where another step has them, gets zeros (no depth measured:
// not a clash); depths of the wrong length: none on that mesh (NaN in the .pvd) and a note.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/vec.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/query/clash.h"
#include "interfere/query/verdict.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// One of the two parts.
struct FemSeriesBody {
  std::string id, name, path, role;
  const TriMesh* surface = nullptr;       ///< its triangles (the positions are the steps'); null: no geometry
  std::vector<std::int64_t> source_ids;   ///< per triangle (FE element ids); empty: none
};

/// What the document keeps of one checked step.
struct FemSeriesStep {
  std::size_t step = 0;  ///< 0-based step of the series
  double time = 0;
  Verdict verdict = Verdict::clear;
  /// Each body's surface vertex positions at the step (world coordinates), surface->num_vertices() long.
  std::array<std::vector<Vec3>, 2> positions;
  std::vector<ClashRegion> regions;  ///< triangle indices into the surfaces (A's, B's)
  Containment containment = Containment::not_checked;
  std::vector<std::string> reasons;  ///< ClashResult::verdict_reasons
  bool has_clearance = false;
  ClearancePair closest;  ///< the closest clearance pair, when has_clearance
  /// Per body, per surface vertex: its penetration depth in the other body at this step (issue
  /// #26, item 3: fem/deform.h's depth maps; 0 outside); empty where the step's depth was not
  /// measured. Drawn as ViewMesh::point_depth (the .pvd's point array penetration_depth).
  std::array<std::vector<double>, 2> depth;
};

/// The step record of a clash result (regions, containment, reasons, closest clearance pair);
/// positions are left empty for the caller.
FemSeriesStep fem_series_step(std::size_t step, double time, const ClashResult& result);

struct FemSeriesInput {
  std::array<FemSeriesBody, 2> bodies;
  std::vector<FemSeriesStep> steps;  ///< the checked steps, in step order
  std::size_t num_steps = 0;         ///< steps in the series (a note says when fewer were checked)
  Verdict verdict = Verdict::clear;  ///< the series' verdict
  std::string units = "mm";
};

struct FemSeriesDocumentOptions {
  std::string title;    ///< empty: "interfere clash: FE series, N steps"
  bool regions = true;  ///< region meshes of the rows
};

/// The document (full resolution; view/budget.h decimates the HTML page's copy). Steps' positions
/// are moved into the document. Positions of the wrong length: an empty mesh and a note for that
/// body and step (never an out-of-range read).
Document fem_series_document(FemSeriesInput input, const FemSeriesDocumentOptions& options = {});

}  // namespace interfere::view
