// Mesh file input/output: STL (ASCII, binary), OBJ, PLY (ASCII, binary little/big endian), OFF.
// Every error names the file, the line (text formats) or byte offset (binary formats) and the
// reason.
//
// Supported flavours:
//  - STL binary: 80-byte header, uint32 count, 50 bytes per facet; a file whose size is exactly
//    84 + 50·n is binary even when its header starts with "solid". The size must match exactly.
//  - STL ASCII: solid/facet normal/outer loop/vertex/endloop/endfacet/endsolid, keywords in any
//  case,
//    several solids per file; a loop with more than 3 vertices is fan-triangulated. Facet normals
//    are read but ignored (NaN normals, as some exporters write for slivers, are accepted).
//  - OBJ: `v x y z [w | r g b]` and `f` with `i`, `i/t`, `i//n`, `i/t/n` corners, negative
//  (relative)
//    indices, polygons; every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is
//    ignored.
//  - PLY 1.0: ascii, binary_little_endian, binary_big_endian; element `vertex` with scalar x, y, z
//  of
//    any numeric type among other properties in any order; element `face` with the list property
//    `vertex_indices` or `vertex_index` (integer count and index types); other elements and
//    properties are skipped; polygons fan-triangulated.
//  - OFF (also COFF, NOFF, STOFF, ... with extra per-vertex/per-face values ignored): `#` comments,
//    counts on the keyword line or the next one, polygons fan-triangulated. 4OFF, nOFF and binary
//    OFF are rejected with an error.
//  - glTF 2.0, binary (.glb) or JSON (.gltf); read only: the triangles of the default scene, each
//    mesh instance placed by its nodes' matrix or translation/rotation/scale (in double), in the
//    file's units (glTF: metres; `interfere simplify` writes a root node scaling model units to
//    metres). Buffers: a GLB's BIN chunk, base64 `data:` URIs, or files named by relative URIs
//    (resolved against the glTF file's folder; nothing is fetched from a network); TRIANGLES,
//    TRIANGLE_STRIP and TRIANGLE_FAN primitives are read, points and lines skipped; positions FLOAT
//    or quantized (KHR_mesh_quantization); sparse accessors, Draco and meshopt compression are
//    errors. Write glTF with write_glb
//    (interfere/simplify/gltf_io.h).
#pragma once
#include <filesystem>
#include <string>

#include "interfere/core/error.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {

enum class MeshFormat {
  automatic,
  stl_ascii,
  stl_binary,
  obj,
  ply_ascii,
  ply_binary_le,
  ply_binary_be,
  off,
  glb,  ///< binary glTF 2.0: read only (the triangles of its default scene, placed)
  gltf  ///< JSON glTF 2.0 (.gltf): read only, as glb
};

/// The file family of a format (STL, OBJ, PLY, OFF), without the ASCII/binary flavour.
enum class MeshFamily { unknown, stl, obj, ply, off, glb, gltf };
MeshFamily mesh_family(MeshFormat f);

/// "stl" (= binary), "stl-ascii"/"stla", "stl-binary"/"stlb", "obj", "ply" (= binary LE),
/// "ply-ascii", "ply-le", "ply-be", "off", "glb", "gltf", "auto" -> MeshFormat ('_' may replace '-', case
/// is ignored); automatic if unknown.
MeshFormat mesh_format_from_name(const std::string& name);
/// "stl-ascii", "stl-binary", "obj", "ply-ascii", "ply-le", "ply-be", "off", "glb", "gltf" or "auto".
const char* mesh_format_name(MeshFormat f);

struct ReadOptions {
  /// automatic: by extension (.stl .obj .ply .off, any case), by content for other extensions.
  /// For reading, the format picks the family only: the STL flavour (ASCII/binary) is always
  /// decided from the content (see above) and the PLY flavour from its header.
  MeshFormat format = MeshFormat::automatic;
  /// Merge vertices with bit-identical positions (weld_exact: triangle order is kept, vertices are
  /// numbered in order of first use, unreferenced vertices are dropped). Without it, indexed
  /// formats keep the file's vertices and STL gives 3 vertices per facet.
  bool weld = true;
};

/// Reads a triangle mesh. Polygons (OBJ/PLY/OFF faces with > 3 corners) are fan-triangulated and
/// counted in MeshReadInfo. NaN/Inf coordinates, out-of-range or negative indices, truncated or
/// malformed content and empty meshes are errors. Triangle i of the result is the i-th triangle of
/// the file (a polygon with k corners contributes k-2 consecutive triangles (v0,v1,v2), (v0,v2,v3),
/// ...).
struct MeshReadInfo {
  MeshFormat format = MeshFormat::automatic;  ///< the format actually read
  std::size_t polygons_split = 0;             ///< faces with more than 3 corners, fan-triangulated
  std::size_t vertices_before_weld = 0;
};
Expected<TriMesh> read_mesh(const std::filesystem::path& path, const ReadOptions& options = {},
                            MeshReadInfo* info = nullptr);

struct WriteOptions {
  /// automatic: by extension (.stl -> binary STL, .ply -> binary little endian).
  MeshFormat format = MeshFormat::automatic;
  /// PLY only: store coordinates as float instead of double (double is exact and the default).
  bool ply_float = false;
};

/// Writes atomically: to a temporary file beside `path`, renamed over it only on success, so an
/// existing file is never left half-written; on failure the temporary file is removed.
/// The mesh is checked first and rejected, without touching any file, when it has no triangles, an
/// index out of range, a non-finite position, or (STL, float PLY) a coordinate that overflows
/// float. Precision: binary STL stores float (facet normals computed in double); ASCII STL, OBJ,
/// OFF and PLY ASCII write the shortest decimal that reads back to the same double; binary PLY
/// stores double unless `ply_float`. The data is fsync'ed before the rename.
Status write_mesh(const std::filesystem::path& path, const TriMesh& mesh,
                  const WriteOptions& options = {});

}  // namespace interfere
