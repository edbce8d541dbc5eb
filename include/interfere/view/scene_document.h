// A scene clash run as a viewer document (issue #25, item 1: `clash` with any number of bodies;
// the report of issue #24, scene/report.h): every body posed in its assembly, one row per clash
// with its verdict, status against the baseline, depth or distance, intersection curves, clearance
// witness and its clash or contact region at full resolution, and the frames of a motion.
//
// Meshes: one ViewMesh per distinct local mesh (Body::mesh is shared between the instances of a
// part: they share one ViewMesh), one per deformed shape of a frame (Frame::Shape), one world
// mesh per clash region (the triangles_a of body a and triangles_b of body b, moved into the world
// by the bodies' poses and shapes at the clash's first frame). Per-triangle clash flags are set on
// the meshes only one body draws (an instanced part's mesh has none, unless
// SceneDocumentOptions::flag_instances gives each clashing instance its own copy).
#pragma once
#include <string>
#include <vector>

#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/scene.h"
#include "interfere/view/document.h"

namespace interfere::view {

struct SceneDocumentOptions {
  std::string title;  ///< empty: "interfere clash: N bodies, M clashes"
  std::string command, tool_version;
  /// Clash and contact regions as world meshes (ViewClash::region_mesh).
  bool regions = true;
  /// Baseline clashes resolved now (SceneClashResult::resolved) as rows with status "resolved",
  /// where both their bodies (by id) are still in the scene; the others are counted in a note.
  bool resolved = true;
  /// Clashing bodies whose mesh other bodies share get a copy of it with their own clash flags
  /// (the ParaView series' per-cell flags); off: instanced meshes carry no flags.
  bool flag_instances = false;
};

/// The document (not decimated: view/budget.h's decimate_for_display makes the HTML page's). A body
/// without geometry gets an empty mesh and a note naming it.
Document scene_document(const scene::Scene& scene, const std::vector<scene::ClashTest>& tests,
                        const scene::SceneClashResult& result, const SceneDocumentOptions& options = {});

/// The colour of body `index` in every scene document: a fixed palette of muted colours, none of
/// them the red, orange, blue, yellow or magenta of clash regions, contacts, witnesses, curves and
/// undecided clashes.
Rgb body_color(std::size_t index);

}  // namespace interfere::view
