// Display decimation (issue #25, item 1: "bodies decimated for display by the project's own
// simplifier above a triangle budget, clash regions at full resolution"; "a viewer asked for a scene
// above its triangle budget: decimate, say so in the page").
//
// The bodies' meshes (every mesh a body draws: its mesh and its frame meshes, each stored mesh
// counted once however many bodies draw it) share the budget by simplify/budget.h's
// triangle_budgets, each mesh reserving min(its triangles, min_mesh_triangles) as the formula's
// feature triangles (a floor: small parts are not reduced to a handful of triangles). Meshes above
// their share are simplified by simplify/qem.h (Garland & Heckbert QEM) in its fast settings (no
// self-intersection guard: the result is only drawn); clash region meshes are never touched.
// Per-triangle face colours and clash flags are carried (each distinct pair of them is a face of
// the simplification, whose borders are kept where the budget allows: SeamMode::as_needed);
// source ids and per-vertex depths do not survive a simplification and are dropped from the
// meshes decimated. Decimate the document for the HTML page only: the glTF and ParaView writers
// take the full-resolution document.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/view/document.h"

namespace interfere::view {

/// The error a decimated mesh is labelled with, from the full mesh's surface to the decimated one
/// (hausdorff.h's one_sided(full, decimated)). Measured on this machine (2 cores, under load) for
/// 2,000,000 -> 300,000 triangles: the simplification about 2.3-2.6 s, `sampled` 0.9-1.8 s more,
/// `bound` 3-4 s more (1,000,000 -> 300,000: 1.2-1.3 s, 0.5 s, 1.8 s).
enum class DisplayError : std::uint8_t {
  none,     ///< not measured: decimation_error 0, the note says "error not measured"
  /// The largest distance from the full mesh's vertices, edge midpoints and centroids to the
  /// decimated mesh: the deviation as drawn (a lower bound of the true largest distance, tight where
  /// QEM's error is largest, at vertices); the note says "largest deviation ... (sampled)".
  sampled,
  /// An upper bound of the distance from any point of the full mesh's surface to the decimated one
  /// (OneSidedDistance::bound, the simplifier's error_bound without its reverse sampling); the note
  /// says "error bound ...".
  bound,
};

struct DisplayOptions {
  /// The most triangles the bodies' meshes may have together; 0: no limit (nothing decimated).
  std::size_t triangle_budget = 300000;
  /// A mesh keeps at least this many triangles (or all it has) when it is decimated.
  std::size_t min_mesh_triangles = 100;
  /// How each decimated mesh's error (ViewMesh::decimation_error) is measured (see DisplayError).
  DisplayError error = DisplayError::sampled;
};

/// What decimate_for_display did.
struct DisplayDecimation {
  std::size_t meshes_decimated = 0;
  /// The bodies' meshes, each stored mesh once: triangles before and after.
  std::size_t triangles_before = 0, triangles_after = 0;
  double largest_error = 0;  ///< the largest decimation_error of the meshes decimated (0 with DisplayError::none)
  /// The simplifier could not reach some shares (open boundaries, face borders, refused flips):
  /// the meshes hold more triangles than the budget.
  bool over_budget = false;
  std::vector<std::string> warnings;  ///< meshes kept at full resolution (and why), the simplifier's warnings
  double seconds = 0;                 ///< wall time
};

/// Decimates the bodies' meshes of `doc` in place when they hold more than the budget, and then adds a
/// note to doc.notes ("bodies decimated for display: 2,000,000 -> 300,000 triangles, largest
/// deviation 0.0036 mm (sampled)"). A mesh the simplifier fails on stays at full resolution (a warning in the result and
/// in the note). Deterministic.
DisplayDecimation decimate_for_display(Document& doc, const DisplayOptions& options = {});

/// 1234567 -> "1,234,567" (the notes' counts).
std::string grouped_count(std::size_t n);

}  // namespace interfere::view
