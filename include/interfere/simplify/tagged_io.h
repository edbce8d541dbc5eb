// Meshes with a per-triangle face id / feature tag (issue #6, item 7), where the format allows:
// PLY (face element property `uint face_id` and `uchar feature`), OBJ (`g face_<id>` groups, feature
// faces as `g feature_face_<id>`), binary STL (the 16-bit attribute word of each facet holds the
// face id when every id is below 65535). Other formats, or no ids: interfere::write_mesh.
// Written atomically (core/atomic_file.h). error_bound >= 0 is stored with the mesh: a PLY
// `comment error_bound <value>` line, an OBJ `# error_bound <value>` line (the conservative margin
// for clash checks on the simplified mesh, see qem.h).
#pragma once
#include <filesystem>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {

Status write_tagged_mesh(const std::filesystem::path& path, const TriMesh& mesh,
                         const std::vector<std::uint32_t>& face_ids,
                         const std::vector<std::uint32_t>& feature_faces, MeshFormat format = MeshFormat::automatic,
                         double error_bound = -1);

/// The error bound a simplified mesh file carries (see write_tagged_mesh; a .glb: write_glb's scene
/// extras, in metres when the file's root node scales to them, as read_mesh reads it): -1 when it
/// has none (no such line, or a format that cannot hold one). Errors: an unreadable file, a
/// malformed or negative value (naming the line or byte).
Expected<double> read_error_bound(const std::filesystem::path& path);

/// Reads a per-triangle region file: whitespace-separated unsigned integers, one per triangle, `#`
/// comments. Errors name the line.
Expected<std::vector<std::uint32_t>> read_region_file(const std::filesystem::path& path, std::size_t triangles);

}  // namespace interfere
