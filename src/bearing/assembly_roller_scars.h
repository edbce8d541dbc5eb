// Imported roller scars in bearing assemblies (issue #27, deliverable 2: scars on any part,
// generated or imported): the top-level `scar` with map / png / points (assembly.h,
// RollerScarImport) read by the importers of scar_import.h (the same code as `interfere bearing
// --scar-map / --scar-points` and the raceway scars' imports) and resampled onto a bearing's roller
// grid.
#pragma once
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/scar_import.h"

namespace interfere::bearing::detail {

/// The imported roller scar of `spec` (spec.scar_import.any()) on the roller grid `rp` of bearing
/// `b`: a CSV map or a PNG (placed on the scar window: angle_center_deg +- angle_width_deg / 2,
/// z_min .. z_max, defaults 25 % / 75 % of the roller length) resampled bilinearly, or a point
/// cloud (text or mesh vertices) by inverse-distance weighting. Errors name the file and line (or
/// pixel, point), and the bearing whose roller grid the map did not fit.
Expected<VertexHeights> roller_scar_heights(const AssemblySpec& spec, const BearingSpec& b, const RollerParams& rp);

}  // namespace interfere::bearing::detail
