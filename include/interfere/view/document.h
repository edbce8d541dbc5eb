// What the viewer shows (issue #25): one document model that every command fills and three writers
// read — the self-contained HTML viewer (view/html.h), the glTF 2.0 scene (view/gltf.h) and the
// ParaView time series (view/pvd.h). The HTML page embeds it as JSON, schema "interfere.viewer"
// (docs/viewer.md); geometry is in world coordinates of the report's unit.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/transform.h"
#include "interfere/core/vec.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::view {

inline constexpr const char* kViewerSchema = "interfere.viewer";
inline constexpr int kViewerSchemaVersion = 1;

using Rgb = std::array<float, 3>;  ///< 0..1

/// A mesh stored once and drawn by any number of bodies, clashes or frames.
struct ViewMesh {
  TriMesh mesh;                        ///< the geometry as drawn (possibly decimated; see below)
  std::vector<std::uint32_t> face_colors;  ///< optional, per triangle: index into Document::legend
  /// Per-cell flags for the ParaView series and colouring: 1 where the triangle takes part in a
  /// clash (optional, per triangle).
  std::vector<std::uint8_t> clash_flags;
  std::vector<std::int64_t> source_ids;  ///< optional, per triangle (FE element ids, B-Rep faces)
  std::vector<double> point_depth;        ///< optional, per vertex: penetration depth (>= 0) where known
  /// Optional, per triangle: the clash region holding it (scene documents: the index into
  /// Document::clashes; FE series: the step's region number), -1 none (issue #26, item 3: the
  /// ParaView series' `clash_region`).
  std::vector<std::int32_t> clash_region;
  std::size_t source_triangles = 0;       ///< triangles before decimation (== mesh size when not decimated)
  double decimation_error = 0;            ///< the simplifier's error bound when decimated (0 otherwise)
};

/// One body: a mesh placed by a pose, per frame when it moves or deforms.
struct ViewBody {
  std::string id, name, path;
  std::uint32_t mesh = 0;  ///< index into Document::meshes (local coordinates)
  Transform pose;          ///< local -> world, for the static view and frames without their own
  Rgb color{0.62f, 0.66f, 0.72f};
  std::vector<std::string> tags;
  /// Motion: per frame (empty = static): the pose, and the mesh when the body deforms (FE steps;
  /// empty = `mesh` at every frame).
  std::vector<Transform> frame_poses;
  std::vector<std::uint32_t> frame_meshes;
  std::string role;  ///< free text shown in the list ("workpiece", "roller 3", "original", "simplified")
  bool visible = true;  ///< initially shown (e.g. the original mesh beside a simplification starts hidden)
};

/// One row of the clash list and its geometry (world coordinates).
struct ViewClash {
  std::string id;
  std::string verdict;  ///< "clash", "contact", "clearance", "undecided"
  std::string status;   ///< "new", "active", "resolved", "approved", ... (empty: no baseline)
  std::string kind;     ///< the engine's kind (crossing, containment, touching, ...)
  std::uint32_t body_a = 0, body_b = 0;  ///< indices into Document::bodies
  double depth = -1, depth_bound = -1;   ///< < 0: not known
  double distance = -1;                  ///< clearance: the gap (< 0: not known)
  Vec3 point;                            ///< where the camera flies to
  Vec3 box_min, box_max;                 ///< the clash's tight box
  std::vector<std::vector<Vec3>> curves;  ///< intersection curves (each a polyline; closed ones repeat the first point)
  /// Clash or contact region at full resolution (world), as one mesh (index into Document::meshes;
  /// -1: none), drawn red (clash) or in the contact colour.
  std::int64_t region_mesh = -1;
  bool has_witness = false;
  Vec3 witness_a, witness_b;  ///< clearance: the closest points
  std::vector<std::uint32_t> frames;  ///< frames it is present in (empty: static or every frame)
  std::string note;                   ///< a line of text (e.g. "scar 2 on roller 5")
};

/// Frames or load steps (motion); their count is frame_labels.size().
struct ViewFrames {
  std::vector<std::string> labels;  ///< "step 3", "pose 120", "t = 0.25 s"
  std::vector<double> times;        ///< optional, same length
  std::vector<std::string> verdicts;  ///< per frame: "clash", "clear", ... (marks on the slider)
};

struct LegendEntry {
  std::string label;
  Rgb color{};
};

struct Document {
  std::string title;
  std::string command;  ///< the command line that produced it
  std::string tool_version;
  std::string units = "mm";
  std::string verdict;  ///< the run's overall verdict ("" for commands without one)
  std::vector<ViewMesh> meshes;
  std::vector<ViewBody> bodies;
  std::vector<ViewClash> clashes;
  ViewFrames frames;
  std::vector<LegendEntry> legend;  ///< face colours (features) and anything else the page should explain
  std::vector<std::string> notes;   ///< shown in the page ("bodies decimated for display: 2,000,000 -> 300,000 triangles")
  std::string error;                ///< a report that could not be shown: the page shows this text
};

}  // namespace interfere::view
