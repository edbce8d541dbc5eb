// Internal (src/cad only): OCCT-side helpers shared by the importer and the AAG builder.
#pragma once
#include <Poly_Triangulation.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Trsf.hxx>

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

}  // namespace interfere::cad::detail
