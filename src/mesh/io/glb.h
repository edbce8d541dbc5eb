// Internal: the GLB container (binary glTF 2.0, Khronos glTF 2.0 specification §4.4 "GLB File
// Format"), shared by the mesh reader (glb.cpp) and read_error_bound (simplify/tagged_io.cpp), and
// the walk of a glTF scene's nodes shared by the mesh reader and scene::read_gltf_bodies.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "interfere/core/error.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::io_detail {

struct GlbChunks {
  std::string_view json, bin;            ///< the JSON chunk's text; the BIN chunk (empty if none)
  std::int64_t json_at = 0, bin_at = 0;  ///< their byte offsets in the file
};

/// Checks the 12-byte header ("glTF", version 2, the file's length) and the chunks (a JSON chunk
/// first, then an optional BIN chunk; unknown chunk types after them are skipped, as the
/// specification asks). Errors name the byte offset.
Expected<GlbChunks> split_glb(const std::string& path, std::string_view data);

/// The length of the JSON chunk, which starts at byte 20, from the file's first 20 bytes (`head`)
/// and its size: the header and the JSON chunk's header checked as split_glb does, so that the
/// JSON can be read without the rest of the file.
Expected<std::uint32_t> glb_json_length(const std::string& path, std::string_view head,
                                        std::uint64_t file_size);

/// True when the bytes start with the GLB magic "glTF".
inline bool is_glb(std::string_view data) {
  return data.substr(0, 4) == "glTF";
}

using Mat4 = std::array<double, 16>;  ///< column-major, as glTF stores it

/// A node of a glTF scene that has a mesh, as walk_gltf visits it.
struct GltfMeshNode {
  std::size_t node = 0, mesh = 0;  ///< indices into the document's nodes and meshes
  std::string name;                ///< the node's name ("" when it has none)
  std::string path;                ///< "/parent/.../node", an unnamed node "node<index>"
  Mat4 world{};                    ///< node coordinates -> scene (the ancestors' matrices or TRS)
  /// The mesh's triangle primitives (TRIANGLES, strips, fans), in node coordinates; one object per
  /// glTF mesh, shared by the nodes that use it.
  std::shared_ptr<const TriMesh> local;
};
using GltfVisitor = std::function<Status(const GltfMeshNode&)>;

/// The one walk of a glTF 2.0 document (GLB when `data` starts with the GLB magic, else JSON)
/// behind read_glb/read_gltf (which flatten it) and scene::read_gltf_bodies (one body per node):
/// the default scene's nodes with a mesh, depth first in the scene's order; an error of `visitor`
/// stops it. Errors name the JSON path (glb.cpp's header says what is read).
Status walk_gltf(const std::string& path, std::string_view data, const std::filesystem::path& dir,
                 const GltfVisitor& visitor);

}  // namespace interfere::io_detail
