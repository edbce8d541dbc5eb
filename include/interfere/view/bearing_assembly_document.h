// A bearing assembly's run (bearing/assembly.h; issue #27) as a viewer document (view/document.h):
// every part as a body moving with the motion (rings, cage webs, rollers, scarred ones coloured),
// the frames with their worst verdicts, and one clash row per pair and run of consecutive frames
// with the same verdict other than clear (its deepest frame's witness points).
#pragma once
#include "interfere/bearing/assembly.h"
#include "interfere/core/error.h"
#include "interfere/view/document.h"

namespace interfere::view {

Expected<Document> bearing_assembly_document(const bearing::Assembly& as, const bearing::AssemblyMotion& motion,
                                             const bearing::AssemblyResult& result);

}  // namespace interfere::view
