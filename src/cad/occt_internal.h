// Internal (src/cad only): OCCT-side helpers shared by the importer and the AAG builder.
#pragma once
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

/// AAG of `shape` whose faces are numbered by `faces` (1-based OCCT map -> 0-based ids).
Aag build_aag(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces, double canonical_tolerance);

}  // namespace interfere::cad::detail
