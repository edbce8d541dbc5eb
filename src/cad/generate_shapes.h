// OCCT primitives and Booleans the generated test parts are built from (generate.cpp,
// generate_floor_parts.cpp), internal to src/cad. Sizes in mm.
#pragma once
#include <TopoDS_Shape.hxx>

namespace interfere::cad::detail {

/// The axis-aligned box [x0, x1] x [y0, y1] x [z0, z1].
TopoDS_Shape box(double x0, double y0, double z0, double x1, double y1, double z1);
/// The cylinder of radius r about the vertical through (x, y), from z0 up by h.
TopoDS_Shape cyl(double x, double y, double z0, double r, double h);
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b);
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b);
/// Faces and edges on one surface / curve merged (ShapeUpgrade_UnifySameDomain).
TopoDS_Shape unify(const TopoDS_Shape& s);

}  // namespace interfere::cad::detail
