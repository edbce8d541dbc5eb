// Internal (src/cad only): OCCT-side helpers shared by the importer and the AAG builder.
#pragma once
#include <IMeshTools_MeshAlgoFactory.hxx>
#include <Poly_Triangulation.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Trsf.hxx>

#include <vector>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

/// AAG of `shape` whose faces are numbered by `faces` (1-based OCCT map -> 0-based ids).
Aag build_aag(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces, double canonical_tolerance);

/// The largest distance from points of the face's triangles (centroids, edge midpoints; the
/// triangulation's nodes placed by `to_world`) to its surface, each an upper estimate: the surface
/// point of the same (u, v), or where that is beyond `threshold` the nearest point a projection
/// finds (tessellation_deviation.cpp); -1 when the triangulation has no UV nodes.
double tessellation_deviation(const TopoDS_Face& face, const Poly_Triangulation& tri, const gp_Trsf& to_world,
                              double threshold);

/// The shape to mesh where faces are split into angular sectors (sector_split.cpp, issue #29): `shape`
/// (the part itself where no face qualifies or a check failed), and for each face of `faces`
/// (0-based) its faces in `shape`, in order, oriented as there.
struct SectorSplit {
  TopoDS_Shape shape;
  std::vector<std::vector<TopoDS_Face>> faces;
  int split_faces = 0;  ///< faces divided into sectors
};
SectorSplit split_for_meshing(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces);
/// BRepMesh's algorithms for `split.shape`: OCCT's Delabella for the sectors, the default for the other faces.
Handle(IMeshTools_MeshAlgoFactory) sector_algo_factory(const SectorSplit& split);

}  // namespace interfere::cad::detail
