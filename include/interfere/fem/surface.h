// Boundary surface of a finite-element mesh (issue #3, item 2): the faces used by exactly one volume
// element of a part, triangulated and oriented outward, plus the shell elements as they are. Each
// part becomes a TriMesh whose vertices are the FEM nodes it uses (with the map back to the node
// index, so that displaced positions of any load step can be gathered, fem/deform.h), and whose
// triangles remember their element and local face.
//
// Faces are numbered as Abaqus/CalculiX number them (1-based, "S1".."S6"; the VTK node order of
// fem_mesh.h is Abaqus's for every supported volume type):
//   tet    S1 (0,1,2)  S2 (0,3,1)  S3 (1,3,2)  S4 (2,3,0)
//   hex    S1 (0,1,2,3)  S2 (4,7,6,5)  S3 (0,4,5,1)  S4 (1,5,6,2)  S5 (2,6,7,3)  S6 (3,7,4,0)
//   wedge  S1 (0,1,2)  S2 (3,5,4)  S3 (0,3,4,1)  S4 (1,4,5,2)  S5 (2,5,3,0)
//   pyr    S1 (0,1,2,3)  S2 (0,4,1)  S3 (1,4,2)  S4 (2,4,3)  S5 (3,4,0)
//   shells face 1 (the element itself, its own node order kept).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere {

/// How the elements are split into parts (bodies).
enum class PartSplit {
  automatic,     ///< by group when some element has a group, else by connectivity
  by_group,      ///< one part per group (elements without group: one part named "ungrouped")
  connectivity,  ///< one part per set of elements connected through shared corner nodes
  single,        ///< the whole mesh is one part
};

struct SurfaceOptions {
  /// Quadratic faces through their mid-side nodes (true, the default, keeps the curved/deformed
  /// shape): tri6 -> 4 triangles; quad8 -> 6 triangles (the four corner triangles and the inner
  /// quad of the mid-side nodes, split along its shorter diagonal; no new vertex); quad9 -> 8
  /// triangles fanned around the centre node. False: corners only (tri -> 1, quad -> 2).
  bool subdivide_quadratic = true;
  PartSplit split = PartSplit::automatic;
  /// Leave out shell elements that lie on a face of a volume element of the same part (matched by
  /// corner nodes): Gmsh files hold the 2D boundary elements of their volumes, which are not
  /// shells. Other shells are always taken.
  bool drop_boundary_shells = true;
  bool parallel = true;  ///< oneTBB; the result is identical for any thread count
};

/// One body's boundary surface.
struct SurfacePart {
  std::string name;        ///< group name, "ungrouped", "body <k>" (connectivity), or "all"
  std::int32_t group = -1;  ///< group index (by_group), else -1
  /// Vertices: the FEM nodes used by the triangles, in order of first use; positions are the
  /// reference (undeformed) node positions.
  TriMesh mesh;
  std::vector<std::uint32_t> vertex_node;  ///< mesh vertex -> FEM node index
  std::vector<std::uint32_t> tri_element;  ///< triangle -> FEM element index (elem_ids[] gives the id)
  std::vector<std::uint8_t> tri_face;      ///< triangle -> local face number (1-based, above)
  std::size_t volume_elements = 0;         ///< volume elements of this part
  std::size_t shell_elements = 0;          ///< shell elements of this part (taken as they are)
  /// Orientation (see extract_surface): connected components of the volume faces' triangles
  /// (across edges two of them share), how many are open (an edge used once: the part is not a
  /// closed solid there), degenerate (their outward side is undecidable: the volume sum that
  /// decides it is zero within rounding, e.g. flat elements), or non-orientable (the propagation
  /// met a contradiction).
  std::size_t components = 0;
  std::size_t open_components = 0;
  std::size_t degenerate_components = 0;
  std::size_t nonorientable_components = 0;
  /// Signed volume enclosed by the closed components as oriented (reference positions): outer
  /// boundaries count positive, cavities negative, so a closed body's is its volume.
  double enclosed_volume = 0;
};

struct SurfaceResult {
  std::vector<SurfacePart> parts;  ///< by group index / by smallest element index
  std::size_t boundary_faces = 0;     ///< element faces used once within their part
  std::size_t interior_faces = 0;     ///< faces shared by exactly two elements of a part (pairs)
  std::size_t nonmanifold_faces = 0;  ///< faces shared by more than two elements (left out)
  /// Boundary faces of elements given with inverted (negative-Jacobian) node order; they are
  /// oriented outward all the same (the orientation is decided by geometry).
  std::size_t inverted_faces = 0;
  /// Boundary faces whose opposite-corner vote tied (warped or flat elements): oriented by the
  /// propagation like every other face.
  std::size_t tied_faces = 0;
  /// Boundary faces with a triangle of zero area (collinear corners, exact test): they carry no
  /// orientation of their own (reported, and warned about by the CLI).
  std::size_t degenerate_faces = 0;
  /// Triangles whose orientation the propagation / volume sign turned against their face's vote.
  std::size_t reoriented_triangles = 0;
  /// Linear faces split at the mid-side nodes of quadratic neighbours (mixed bodies, conforming).
  std::size_t split_faces = 0;
  std::size_t skipped_elements = 0;   ///< points and lines (no surface)
  std::size_t dropped_shells = 0;     ///< shells on volume faces (drop_boundary_shells)
};

/// Extracts the boundary surface of every part. Method: every face of every volume element gets
/// a key (its sorted corner nodes); the faces are bucketed by their smallest corner node (a
/// parallel counting sort), each small bucket is sorted by (key, part, element, face), and a face
/// whose key occurs once among the volume faces of its part is on the boundary. Faces between two parts are boundary
/// faces of both. Triangles come out in element order, then face order (deterministic for any
/// thread count).
///
/// Mixed bodies (linear and quadratic elements, subdivided faces): a linear face whose edge is an
/// edge of a quadratic element of the part is split at that edge's mid-side node (no T-junction).
///
/// Orientation: each boundary face's normal is first turned away from the element's corners that
/// are not on the face (a vote of exact orient3d signs on the reference positions; it ties or errs
/// on warped elements); then the triangles of each part are made consistent by propagation across
/// the edges exactly two of them share, and every component is turned outward by the sign of its
/// summed cone volumes (each triangle to its element's centroid): outer boundaries face out of the
/// body, a cavity's boundary into the cavity. A component whose sum is zero within its rounding
/// bound is degenerate (counted). Shells keep their own node order. Quads are split along the
/// shorter diagonal of the reference positions, the one through the smaller node index on a tie.
///
/// Precondition: `mesh` passes validate_fem_mesh (the readers guarantee it); node indices are
/// checked again. Errors: a node index out of range, more than 2^29 elements.
Expected<SurfaceResult> extract_surface(const FemMesh& mesh, const SurfaceOptions& options = {});

/// Local face count of a volume element type (0 for shells, lines, points).
int element_face_count(ElemType t);

/// Parses "auto", "group", "connectivity", "single"; false if unknown.
bool part_split_from_name(const std::string& name, PartSplit& out);

}  // namespace interfere
