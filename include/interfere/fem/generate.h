// Structured finite-element meshes for tests and benchmarks (issue #3): a box of nx × ny × nz
// cells split into elements of one type, and a cylinder or a sphere made by mapping that box.
// Every element is positively oriented (positive Jacobian: for tets (1-0)x(2-0)·(3-0) > 0, the
// first face of wedges and the base of pyramids turned toward the opposite nodes, as in Abaqus and
// Gmsh), node order as in fem_mesh.h, the mesh is conforming, and it passes validate_fem_mesh.
//
//   hex8/hex20/hex27  one hexahedron per cell
//   tet4/tet10        6 tets per cell (Kuhn/Freudenthal split along the cell's main diagonal), or 5
//                     (a central tet on the cell's corners of even global parity, so that
//                     neighbouring cells' face diagonals agree)
//   wedge6/wedge15    2 wedges per cell (the xy square split along its (0,0)-(1,1) diagonal)
//   pyr5              6 pyramids per cell (apex at the cell centre, one per cell face)
// Quadratic nodes sit on the straight edges (midpoints) before the mapping; the mapping moves every
// node, so mapped quadratic elements are curved.
#pragma once
#include <cstdint>
#include <string>

#include "interfere/fem/fem_mesh.h"

namespace interfere {

struct FemBoxOptions {
  ElemType type = ElemType::tet4;
  int nx = 4, ny = 4, nz = 4;   ///< cells per axis (>= 1)
  Vec3 lo{0, 0, 0}, hi{1, 1, 1};  ///< the box (ignored by the cylinder and sphere)
  int tets_per_cell = 6;        ///< tet4/tet10: 6 or 5
  std::string group;            ///< non-empty: one FemGroup of this name holding every element
  std::int64_t first_node_id = 1, first_element_id = 1;  ///< ids are consecutive from these
};

/// A generated mesh and the exact volume and area of the shape it discretises.
struct GeneratedFem {
  FemMesh mesh;
  double volume = 0;  ///< analytic: the box's exactly; cylinder/sphere: of the smooth shape
  double area = 0;
};

/// Box [lo, hi].
GeneratedFem make_fem_box(const FemBoxOptions& options);

/// Cylinder of `radius` and `height`, axis z from `base`: the box [-1,1]² × [0,1] of nx × ny × nz
/// cells mapped by the elliptical square-to-disc map (x√(1-y²/2), y√(1-x²/2)).
GeneratedFem make_fem_cylinder(const FemBoxOptions& options, double radius, double height, const Vec3& base = {});

/// Ball of `radius` around `center`: the cube [-1,1]³ mapped by the cube-to-ball map
/// x' = x√(1 - y²/2 - z²/2 + y²z²/3) (and cyclically).
GeneratedFem make_fem_sphere(const FemBoxOptions& options, double radius, const Vec3& center = {});

/// Elements one generated cell becomes (for sizing benchmarks): 1, 5/6, 2 or 6.
int fem_elements_per_cell(const FemBoxOptions& options);

}  // namespace interfere
