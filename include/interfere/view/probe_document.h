// A probe sweep as a viewer document (issue #25, item 1: "the probe moving along its path with
// colliding poses marked"; Li, Zhou & Zheng 2008): the workpiece, the probe (and its holder) posed
// at every path point as one frame each, the path itself as a curve, and one clash row per run of
// consecutive colliding path points (the workpiece triangles hit drawn red) and per segment that
// collides between its two points.
#pragma once
#include "interfere/core/error.h"
#include "interfere/probe/path.h"
#include "interfere/probe/sweep.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// `path` with its poses resolved (path.poses, one per point), `result` from probe::sweep on it.
Expected<Document> probe_document(const TriMesh& workpiece, const probe::ProbeShape& shape, const probe::ProbePath& path,
                                  const probe::SweepResult& result);

}  // namespace interfere::view
