// glTF 2.0 scene export of a viewer document (issue #25, item 2): any report as one binary .glb that
// Blender, the three.js editor or Windows 3D Viewer open (Khronos glTF 2.0 specification; the GLB
// container of core/glb.h, shared with simplify/gltf_io.h).
//
// Layout: a root node "interfere_root" scales the document's unit to metres (glTF's unit, §3.4;
// unknown units: no scale) and holds two groups. "bodies": one node per body, named by the body,
// placed by its pose (node `matrix`, column-major; TRS when it is animated), `extras` {id, path,
// role, tags, visible}; each ViewMesh a body uses is stored once (one set of accessors) and shared
// by every body drawing it. Body materials are PBR (metallic 0) in the body's colour with alpha
// GltfOptions::body_opacity (alphaMode BLEND below 1), double-sided; a mesh with face colours carries
// them as COLOR_0 (vertices split between colours) under a white material. "clashes": one node per
// clash, named by its id and placed at its point (geometry stored relative to it, so float32 keeps
// its precision far from the world origin), `extras` {clash_id, verdict, status, kind, depth,
// depth_bound, distance (null: not known), bodies (body ids), body_names, note, frames}; its children
// "<id> region" (the region mesh, red for a clash, orange for a contact, magenta undecided, blue
// clearance), "<id> curves" (intersection curves, mode 1 LINES, yellow) and "<id> witness" (the
// clearance witness segment, LINES, blue); line materials are KHR_materials_unlit. Colours are the
// page's sRGB colours (docs/viewer.md) converted to glTF's linear colour factors. Every POSITION
// accessor has exact min/max; every buffer view starts 4-byte aligned. The scene's `extras`:
// {schema "interfere.viewer", schema_version, title, command, tool_version, units, metres_per_unit,
// verdict, notes, frames {labels, times, verdicts}, legend}.
//
// Frames (GltfOptions::animation): one animation "frames", STEP interpolation, keyed at
// frames.times (or 0, 1, 2, ... seconds when absent or not increasing): the translation and
// rotation of every body with frame_poses (when all its poses are rigid; a scaled or sheared pose
// stays static, with extras.animated = false), for a deforming body (frame_meshes) the scale (1 or
// 0) of one child node per mesh it draws, and the scale of each clash node present only in some
// frames. Without animation (or frames) the file is the static view: poses `pose`, mesh `mesh`.
#pragma once
#include <filesystem>

#include "interfere/core/error.h"
#include "interfere/view/document.h"

namespace interfere::view {

struct GltfOptions {
  /// Alpha of the body materials: below 1, alphaMode BLEND (see the clashes inside); 1: OPAQUE.
  float body_opacity = 0.35f;
  /// Frames as a glTF animation (see above); false: the static view only.
  bool animation = true;
  /// Also bodies with visible = false (extras.visible = false; glTF has no hidden nodes).
  bool hidden_bodies = true;
};

/// Writes `doc` as a binary glTF 2.0 file, atomically (core/atomic_file.h). Errors naming the file
/// and the field: a document with `error` set, an index out of range, arrays of the wrong length,
/// a coordinate not finite or beyond float32, body_opacity outside [0, 1], above GLB's 4 GiB.
Status write_glb(const std::filesystem::path& path, const Document& doc, const GltfOptions& options = {});

}  // namespace interfere::view
