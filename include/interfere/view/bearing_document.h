// The bearing simulation as a viewer document (issue #25, item 1: "bearing frames"): per pair the
// roller (its scarred mesh when scarred) and its partner, the rollers' poses per frame, and one
// clash row per pair and run of consecutive interfering frames (Jia & Zheng 2019: the maximum
// interference per frame). Needs the result of bearing::simulate with keep_rows.
#pragma once
#include "interfere/bearing/simulation.h"
#include "interfere/core/error.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// Errors: a result simulated without keep_rows (no poses to draw).
Expected<Document> bearing_document(const bearing::SceneParams& params, const bearing::SimulationResult& result);

}  // namespace interfere::view
