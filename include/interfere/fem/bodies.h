// FE models as scenes (issue #24, item 1; docs/fem.md, "FE models as scenes"): every body of an FE
// model becomes a scene::Body (its boundary surface, fem/surface.h, with the solver's element ids
// and local faces per triangle), and every step of its nodal displacements a scene::Frame holding
// each body's deformed surface. The scene clash engine (scene/engine.h) then checks all bodies at
// every step with one tree per body, refitted per frame.
#pragma once
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/surface.h"
#include "interfere/scene/scene.h"

namespace interfere {

struct FemSceneOptions {
  /// How the elements split into bodies, as the CLI's --split (part_split_from_name): "auto" (by
  /// group when some element has one — an Abaqus element set or instance, a Nastran property, a
  /// Gmsh physical group, a VTK cell-data id —, else by connectivity), "group", "connectivity",
  /// "single".
  std::string split = "auto";
  bool linear_faces =
      false;  ///< quadratic faces by their corners only (SurfaceOptions::subdivide_quadratic)
  /// File unit -> working unit, applied to nodes and displacements (issue #23, item 6). A value
  /// other than 1 needs `working_unit`.
  double unit_scale = 1;
  std::string unit = "mm";   ///< the file's unit (Body::unit)
  std::string working_unit;  ///< the scene's unit (Scene::units); empty: `unit`
  /// Glob (scene::glob_match) over the body names; empty: every body. Matching nothing is an error.
  std::string select;
  /// Deformed position = node + displacement_scale × u (both in the working unit).
  double displacement_scale = 1;

  // Displacement steps -> Scene::frames.
  bool steps = true;  ///< false: a static scene (no frames), whatever the file holds
  /// Nodal displacements from CSV (read_displacements_csv: node_id,ux,uy,uz or
  /// step,node_id,ux,uy,uz); non-empty: these, not the mesh's fields.
  std::string displacement_csv;
  /// A nodal vector field of the mesh (FemMesh::fields: VTU point data, Gmsh $NodeData) by name.
  /// Empty: automatic — the one field whose name contains "disp" (any case: DISP, DISPL,
  /// displacement) or is "u"/"U"; none: no frames (a warning lists the fields left out); several:
  /// an error asking for one. Naming a field the mesh lacks is an error listing its fields.
  std::string field;
  bool parallel = true;  ///< oneTBB; the result is identical for any thread count
};

/// The bodies of `mesh` (read from `file`, which names them; FemMesh::file when empty) as a scene:
///  - one Body per surface part of extract_surface, in its order (group order, "ungrouped" last;
///    connectivity: by smallest element), parts without triangles left out (warned);
///  - id make_body_id(name), made unique (make_ids_unique); name the group name ("PSOLID 3",
///    "Part-1-1"), "ungrouped", "body N" (connectivity) or "all"; path "/<file stem>/<name>";
///    source {fe_body, file, name}; unit `unit`; identity pose;
///  - mesh: the boundary surface at the reference positions in the working unit, closed surfaces
///    oriented outward (cavities inward), vertices the FE nodes the body uses;
///  - source_id_kind fe_element_face: source_ids the solver's element id of each triangle,
///    source_faces its local face (1-based, the Abaqus numbering of fem/surface.h; 1 for shells);
///  - frames: one per displacement step (see FemSceneOptions), label "step N (time T)" (N
///    0-based), time the series' time, and one Frame::Shape per body: its surface vertices at
///    node + displacement_scale × u (a body whose nodes did not move since the previous step
///    shares the previous shape's positions);
///  - warnings: the reader's (FemMesh::warnings), the surface's (surface_warnings) and each body's
///    (surface_part_warnings), prefixed "<file>: " / "<file>, body '<name>': ".
/// Errors (values, naming the file): unknown split, unit_scale != 1 without working_unit, a
/// non-finite or non-positive scale, a mesh without surface, `select` matching no body (the error
/// lists the bodies), an unknown field or several displacement-like ones, a CSV and a field
/// together, the CSV reader's errors, a position outside the coordinate range
/// (core/coordinate_range.h; names the node id and step).
Expected<scene::Scene> fem_scene(const FemMesh& mesh, const std::string& file,
                                 const FemSceneOptions& options = {});

/// read_fem (format by extension, then content) followed by fem_scene.
Expected<scene::Scene> read_fem_scene(const std::string& file, const FemSceneOptions& options = {});

/// The surface's warnings for the user (no prefix): zero-area faces, non-manifold faces left out,
/// inverted elements. Shared by the CLI (apps/cli/fem_parts.cpp) and fem_scene.
std::vector<std::string> surface_warnings(const SurfaceResult& surface);
/// One body's: open, degenerate or non-orientable surface components (inside/outside is
/// undecidable there, issue #23, item 1). No prefix.
std::vector<std::string> surface_part_warnings(const SurfacePart& part);

}  // namespace interfere
