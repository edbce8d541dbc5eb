// Welding and validation of triangle meshes (issue #2, item 2).
#pragma once
#include <cstddef>

#include "interfere/mesh/tri_mesh.h"

namespace interfere {

/// Merges vertices whose positions are bit-identical (+0.0 and -0.0 are the same). Triangles keep
/// their order; vertices are renumbered in order of first use. Returns the number of vertices removed.
std::size_t weld_exact(TriMesh& mesh);

struct MeshStats {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t degenerate_triangles = 0;  ///< repeated corner index or three collinear corners (exact test)
  std::size_t duplicate_triangles = 0;   ///< same vertex set as an earlier triangle (any orientation)
  std::size_t open_edges = 0;            ///< edges used by exactly one triangle
  std::size_t nonmanifold_edges = 0;     ///< edges used by more than two triangles
  std::size_t inconsistent_edges = 0;    ///< manifold edges whose two triangles do not orient it oppositely
  std::size_t components = 0;            ///< connected by shared vertices
  /// closed: no open and no non-manifold edges, and orientation consistent (required for containment).
  bool closed() const { return triangles > 0 && open_edges == 0 && nonmanifold_edges == 0 && inconsistent_edges == 0; }
};

MeshStats mesh_stats(const TriMesh& mesh);

}  // namespace interfere
