// Welding and validation of triangle meshes (issue #2, item 2).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interfere/mesh/tri_mesh.h"

namespace interfere {

/// Merges vertices whose positions are bit-identical (+0.0 and -0.0 are the same; NaNs are equal
/// only with the same bits). Triangles keep their order and their corner order; vertices are
/// renumbered in order of first use by the triangles, so unreferenced vertices are dropped too.
/// Each kept vertex keeps the position of its lowest-numbered duplicate. Returns the number of
/// vertices removed (duplicates plus unreferenced). A mesh with an index out of range is left
/// unchanged (returns 0). Cost: O(n) expected, parallel (hash-partitioned), deterministic for any
/// thread count. With `map`, map[v] is the new index of old vertex v (of its class: none when no
/// vertex of the class is referenced); left empty when the mesh is left unchanged.
std::size_t weld_exact(TriMesh& mesh, std::vector<std::uint32_t>* map = nullptr);

struct MeshStats {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  /// Repeated corner index, or three collinear corners (exact test, interfere::collinear).
  std::size_t degenerate_triangles = 0;
  /// Same vertex set as an earlier triangle (any orientation).
  std::size_t duplicate_triangles = 0;
  /// Edges used by exactly one triangle.
  std::size_t open_edges = 0;
  /// Edges used by more than two triangles.
  std::size_t nonmanifold_edges = 0;
  /// Edges used by exactly two triangles that run along it in the same direction (a flipped face).
  std::size_t inconsistent_edges = 0;
  /// Connected sets of triangles (sharing a vertex).
  std::size_t components = 0;
  /// Triangles with a vertex index >= vertices; they are left out of every other count.
  std::size_t invalid_triangles = 0;
  /// closed: no open and no non-manifold edges, and orientation consistent (required for
  /// containment).
  bool closed() const {
    return triangles > 0 && open_edges == 0 && nonmanifold_edges == 0 && inconsistent_edges == 0;
  }
};

/// Topology and degeneracy counts. Edges are undirected vertex-index pairs; a triangle with a
/// repeated index is degenerate and contributes no edges (a collinear triangle with three distinct
/// indices does). Components count connected sets of triangles (unreferenced vertices are not
/// components). Duplicates are counted by vertex-index set, so an unwelded mesh may need weld_exact
/// first. O(n log n) worst case, O(n) typical (edges bucketed by their smaller vertex); about 1 s
/// for 10^7 triangles on two cores.
MeshStats mesh_stats(const TriMesh& mesh);

/// The connected sets of the triangles t with keep[t] set, joined across shared vertices (vertex
/// indices): per triangle, the smallest index of its set (a triangle not kept: its own index).
/// keep.size() must equal the triangle count. O(n) (union-find).
std::vector<std::uint32_t> connected_sets(const TriMesh& mesh, const std::vector<char>& keep);

}  // namespace interfere
