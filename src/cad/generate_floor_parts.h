// Generated parts with floor features and fillets (issue #29, item 1), internal to src/cad: see
// generate_floor_parts.cpp.
#pragma once
#include <TopoDS_Shape.hxx>

#include "interfere/cad/model.h"

namespace interfere::cad::detail {

/// The solid of slot_features_block, filleted_pocket_block or filleted_step_block (Standard_Failure
/// for other parts or when OCCT's fillet fails).
TopoDS_Shape floor_feature_part(TestPart p);

}  // namespace interfere::cad::detail
