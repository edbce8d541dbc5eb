// glTF 2.0 output (binary GLB or JSON .gltf) of simplified parts for digital-twin renderers (issue #6: real-time
// rendering of assembly lines): one glTF mesh per part, one node per instance with its placement,
// so a part used N times is stored once. Per vertex, besides POSITION: NORMAL (smooth within a
// face, sharp across face borders; without faces, across crease edges), `_FACE_ID` (the B-Rep face
// or region, float: exact below 2^24) and `_FEATURE` (1 on the step's assembly-feature faces);
// vertices are split along face boundaries first, so every vertex has one face. The scene's
// `extras` hold `units` and the largest `error_bound`, each mesh's `extras` its own bound and face
// count. Written atomically (core/atomic_file.h).
// Twin-ready (issue #29, item 6): each mesh has up to two primitives sharing its vertices, the part's
// triangles with material "part" and the assembly-feature triangles with material "assembly
// feature" (orange, so a plain viewer shows what was kept); instances with a product path
// ("/as1/l-bracket-assembly_1/nut-bolt-assembly_2/bolt_1") are placed under group nodes, one per
// path level (named by it, no transform: the instance's placement stays on its leaf), so the
// product hierarchy is the node tree, and each leaf's `extras.path` is its full path.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {

struct GltfPart {
  std::string name;
  TriMesh mesh;                             ///< part coordinates
  std::vector<std::uint32_t> face_ids;      ///< per triangle (empty: no ids written)
  std::vector<std::uint32_t> feature_faces;  ///< face ids tagged _FEATURE = 1
  double error_bound = -1;                  ///< < 0: not stored
  /// Without face ids: NORMAL is smooth within the regions between edges sharper than this
  /// (degrees; sharp_edge_regions); with them, within each face.
  double crease_deg = 40;
  /// Per triangle: 1 for an assembly-feature triangle (SimplifyResult::feature_flags: faces and
  /// clamped annuli); empty: the triangles of `feature_faces`.
  std::vector<std::uint8_t> feature_flags;
  /// Coarser levels of detail of the same part (issue #29, item 6), finest first: each is written as
  /// its own mesh ("<name> LOD<k>") and every instance node gets the MSFT_lod extension pointing to
  /// nodes of those meshes (same name + " LOD<k>", same placement, outside the scene tree), with
  /// `extras.MSFT_screencoverage` (1/2^k thresholds). Their own `lods` are ignored.
  std::vector<GltfPart> lods;
  /// The part's own colour (a STEP file's, linear RGB): its triangles get a material of that colour
  /// named after the part instead of the grey "part"; the features stay orange.
  bool has_color = false;
  float color[3] = {0, 0, 0};
};

struct GltfInstance {
  std::string name;
  std::uint32_t part = 0;  ///< index into the parts
  Transform placement;     ///< part coordinates -> world
  /// Product path, "/"-separated (empty: the node is a child of the root, named `name`).
  std::string path;
};

/// The container write_glb writes: binary GLB, or JSON .gltf with its buffer embedded as a base64
/// data: URI (one self-contained file either way); by_extension: .gltf is JSON, anything else GLB.
enum class GltfContainer { by_extension, glb, gltf };

/// Writes `path` as `container` says; `units` (mm, cm, m, um, in, ft) scale the scene to metres, anything else
/// (a mesh file's unknown unit: "") leaves the coordinates as they are. Errors: no parts, an empty part, an instance of a part that does not
/// exist, a coordinate or placement that is not finite or overflows float, an id at or above 2^24.
Status write_glb(const std::filesystem::path& path, const std::vector<GltfPart>& parts,
                 const std::vector<GltfInstance>& instances, const std::string& units = "mm",
                 GltfContainer container = GltfContainer::by_extension);

}  // namespace interfere
