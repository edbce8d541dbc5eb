// Vertex quadtree over the unrolled side surface (angle x height) of a roller (Jia & Zheng 2019,
// §2.4): every node is a rectangle of side vertices; scar labels are propagated to the ancestors;
// inner nodes carry a virtual vertex (the average of their vertices); the "calculation layer" is,
// as in the paper (§2.4, issue #27), the highest level whose nodes have all their leaves inside the
// range of Eq. (1) (window.h) — or, as an option (CalculationLayerRule::spanning_window), the
// project's former rule: the deepest level whose nodes still span the whole window. Both are
// measured in bench/bearing/bench_quadtree_layer.cpp (docs/bearing.md, "Calculation layer").
//
// The same tree carries, for the exact solver (scarred.h), a conservative bound of the node's
// triangles: an oriented box in the node's own (radial, tangential, axial) frame at its middle angle,
// containing every vertex of every triangle of the node's cells (so the triangles too). The two end
// caps get binary trees over their fan triangles with the same bounds.
//
// The exact solvers descend a second tree of the same boxes, `RollerQuadtree::bounds` (issue #27,
// the target "a scarred roller against a scarred raceway, <= 20 us"): a binary tree over the side
// cells that halves the columns first, down to single columns, and only then the rows. In a bearing
// the parts' axes are nearly parallel, so a contact is a strip along a generator, one or two
// columns wide and as long as the contact line; the quadtree halves both directions at once, so it
// reaches the strip's width only at its deepest levels and carries every node along the strip
// through them (about 2.5x the node bounds per solve, docs/bearing.md). The quadtree itself stays as
// it is: the paper's method (§2.4) needs its levels.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/bearing/roller.h"

namespace interfere::bearing {

struct QuadNode {
  // vertex rectangle [i0, i1) x [j0, j1) (columns wrap at n: i1 may equal n)
  std::int32_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  std::int32_t level = 0;
  std::int32_t first_child = -1;  ///< children are contiguous: first_child .. first_child+child_count-1
  std::int32_t child_count = 0;
  std::uint8_t scar = 0;          ///< some vertex below is labelled scar
  Vec3 virtual_vertex;            ///< average of the node's vertices (body frame)
  // exact bound of the node's triangles (cells [i0, i1) x [j0, min(j1, m)) for the side tree;
  // fan triangles [i0, i1) for a cap tree)
  std::uint32_t tri_first = 0, tri_count = 0;  ///< leaves only: triangle ids tri_first + k*stride
  Vec3 box_center;                ///< body frame
  double half_r = 0, half_t = 0, half_z = 0;
  double cos_mid = 1, sin_mid = 0;  ///< the frame's radial direction (cos, sin, 0)
};

/// A node of the exact solvers' bound tree (`RollerQuadtree::bounds`): the same oriented box as
/// QuadNode's exact bound, compact (80 bytes), children contiguous.
struct BoundNode {
  Vec3 box_center;  ///< body frame
  double half_r = 0, half_t = 0, half_z = 0;  ///< < 0 (half_r): no triangles (an empty root)
  double cos_mid = 1, sin_mid = 0;            ///< the frame's radial direction (cos, sin, 0)
  std::int32_t first_child = -1, child_count = 0;
  std::uint32_t tri_first = 0, tri_count = 0;  ///< leaves: triangle ids tri_first .. + tri_count - 1
};

/// Column-first binary tree over the side cells (a leaf: one cell, its 2 triangles) and binary trees
/// over the end-cap fans (leaves of at most 2 triangles), roots as RollerQuadtree's. A root may be
/// an empty node (half_r < 0: a raceway bore's caps, raceway_scar.h).
struct BoundTree {
  std::vector<BoundNode> nodes;
  std::int32_t side_root = -1, bottom_root = -1, top_root = -1;
  bool empty() const { return nodes.empty(); }
};

/// Coplanar facet strips (issue #27, the 1,024-roller target): the exact solver's tree over maximal
/// planar pieces of the surface. In a side column i, a run of cells (i, j0) .. (i, j1 - 1) whose
/// vertices keep the same (x, y) down each of the two vertex columns (an intact run: the body-frame
/// positions are computed identically for every height, roller.cpp) and the same z across the two
/// columns per row is exactly one planar rectangle, the union of its cells' triangles; it is stored
/// as two triangles (v(i, j0), v(i+1, j0), v(i+1, j1)) and (v(i, j0), v(i+1, j1), v(i, j1)), so the
/// minimum of sd_B over the run is the minimum over those two. Cells where the test fails (a scar
/// window's displaced vertices) keep their own two triangles; the caps their fan triangles.
/// The tree: column-first as BoundTree (the same oriented boxes over the same vertices), a single
/// column split over its pieces (runs and single cells) instead of its rows; a leaf is one piece.
/// Leaves index `pieces` (tri_first .. + tri_count - 1) of `corners`.
///
/// The solver reads a leaf's entries from its `StripLeaf` record (issue #27, the 1,024-roller
/// frame: a cold tree's cache misses were about half of a scarred row): copies of the body-frame
/// positions of the leaf's (at most 4) distinct corners, contiguous, in leaf order, so an entry
/// costs no fetch of `corners` and of 3 scattered mesh vertices, and a shared corner is mapped to
/// B's frame once. The same doubles, so the same arithmetic and bits. A strip-tree leaf's
/// `first_child` is the index of its record in `leaves` (its child_count is 0); an inner node's
/// tri_first .. + tri_count - 1 are the entries of its subtree (contiguous: the solver does not
/// bound a node that holds its best entry so far).
struct alignas(64) StripLeaf {
  Vec3 v[4];                      ///< body frame: copies of mesh positions
  std::uint32_t entry = 0;        ///< the first entry (== the node's tri_first)
  std::uint32_t mesh_triangle[2] = {};  ///< per entry: FacetStrips::mesh_triangle
  std::int32_t strip[3] = {};     ///< a strip leaf: its column and rows [j0, j1) (FacetStrips::strip_cells)
  std::uint8_t count = 0;         ///< entries (1 or 2; == the node's tri_count)
  std::uint8_t vertices = 0;      ///< distinct corners (v[0 .. vertices - 1])
  std::uint8_t corner[2][3] = {}; ///< per entry, its corners (the order of `corners`) as indices into v
};
static_assert(sizeof(StripLeaf) == 128, "a leaf record is two cache lines");

struct FacetStrips {
  BoundTree tree;
  std::vector<StripLeaf> leaves;  ///< per leaf node (its first_child), the entries' corners
  /// per mesh triangle: the record (index into `leaves`) of the leaf that holds it
  std::vector<std::int32_t> leaf_record_of_triangle;
  /// per record: the first_child of the leaf's ancestors from its root down (the first 16; 0xffff
  /// after the last, and where a node index does not fit): the solver fetches the node pairs on the
  /// way to its first leaf at once instead of one level at a time (issue #27; a hint, no effect on
  /// any value)
  std::vector<std::array<std::uint16_t, 16>> leaf_paths;
  std::vector<std::array<std::uint32_t, 3>> corners;  ///< per entry: vertex ids of the roller mesh
  /// per entry: the mesh triangle it is (a cell's or a cap's), or kStrip for a strip triangle
  std::vector<std::uint32_t> mesh_triangle;
  /// per entry of a strip: its column and rows [j0, j1) (else 0)
  std::vector<std::array<std::int32_t, 3>> strip_cells;
  /// per mesh triangle: the leaf node of `tree` that holds it (for the solvers' first bounds)
  std::vector<std::int32_t> leaf_of_triangle;
  static constexpr std::uint32_t kStrip = 0xffffffffu;
  /// The end caps' rims, for the solver's cap test (scarred.cpp, cap_cannot_improve; issue #27,
  /// speed): per cap (0 bottom, 1 top) the radius r of its rim vertex 0, the rim's height z and
  /// the largest distance `dev` of a rim vertex i from the regular polygon's (r cos a_i, r sin a_i,
  /// z), a_i = 2 pi i / n (0 for an intact rim; a scarred rim: its displacement). `rim_gap` is
  /// cos(0.6 * 2 pi / n) - cos(1.4 * 2 pi / n) (less a relative 1e-3): a linear function of the
  /// regular polygon's vertices is larger at every vertex 1.5 steps or more from its minimising
  /// angle than at the vertex nearest that angle, by at least r |its gradient across the axis| gap.
  struct Rim {
    double radius = 0, z = 0, dev = 0;
  };
  std::array<Rim, 2> rims{};
  double rim_gap = 0;
  bool empty() const { return tree.empty(); }
};

/// How the calculation layer (the level where the quadtree method starts, §2.4) is chosen for a
/// window of half-width w (the range of Eq. (1) is [phi - w, phi + w] about the contact direction phi).
enum class CalculationLayerRule {
  /// The paper's: the highest (shallowest) level every node of which has all its leaves (side
  /// vertices, at angles i * 2 pi / n) within an angular span of 2w, i.e. each node of the level fits
  /// inside the range. The default.
  paper,
  /// The project's former rule: the deepest level whose nodes still span 2w in angle (their cells'
  /// width, ceil(n / 2^level) columns). One level higher than the paper's in general: fewer, wider nodes.
  spanning_window,
};

struct QuadtreeOptions {
  CalculationLayerRule layer_rule = CalculationLayerRule::paper;
};

struct RollerQuadtree {
  std::vector<QuadNode> nodes;
  std::int32_t side_root = 0, bottom_root = -1, top_root = -1;
  std::int32_t depth = 0;  ///< deepest level of the side tree
  QuadtreeOptions options;
  /// The exact solvers' tree (above): built by build_quadtree; when empty (a tree assembled by
  /// hand) the solvers descend `nodes`.
  BoundTree bounds;
  /// The scarred solver's tree of coplanar facet strips (above; built by build_quadtree; empty: the
  /// solver descends `bounds`).
  FacetStrips strips;
  /// Per level of the side tree, the largest column count (i1 - i0) of its nodes.
  std::vector<std::int32_t> level_max_columns;
  /// The calculation layer for a window half-width `half_width` (radians, e.g. interference_window()
  /// of window.h) under options.layer_rule.
  std::int32_t calculation_layer(double half_width, int radial_segments) const;
  /// The same under an explicit rule.
  std::int32_t calculation_layer(double half_width, int radial_segments, CalculationLayerRule rule) const;
};

/// Builds the tree of a meshed (possibly scarred) roller. Side leaves are single vertices for the
/// vertex methods; the exact bound of a leaf (i, j) covers side cell (i, j) (its 2 triangles) when
/// j < m. O(n*m).
RollerQuadtree build_quadtree(const Roller& roller, const QuadtreeOptions& options = {});

}  // namespace interfere::bearing
