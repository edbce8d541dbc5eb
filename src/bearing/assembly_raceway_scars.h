// Raceway scars in bearing assemblies (issue #27, deliverable 2; raceway_scar.h,
// raceway_scar_solver.h): building a bearing's raceway scars from its description, and the
// roller-raceway rows in range of one.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "interfere/bearing/assembly.h"
#include "interfere/bearing/raceway_scar.h"

namespace interfere::bearing::detail {

/// A file named in the description: as given when absolute (or when the description has no file),
/// else relative to the assembly file's folder.
std::string resolve(const AssemblySpec& spec, const std::string& path);

/// The raceway `part` of bearing b in the bearing frame (the ring's body frame).
RacewayGeometry raceway_geometry(const BearingSpec& b, const BearingGeometry& g, RacewaySurface part);

/// The scar of one description (generated, or imported from a file resolved against the assembly
/// file's folder). Errors name the JSON path (`bearings[0].scars[1].z_max ...`) or the file and line.
Expected<std::shared_ptr<const RacewayScar>> build_raceway_scar(const AssemblySpec& spec, const BearingSpec& b,
                                                                const BearingGeometry& g, const RacewayScarSpec& s);

/// A roller-inner/outer/cone/cup row whose ring carries a raceway scar in range of the roller
/// (raceway_scar_in_range): raceway_scar_pair's value, solver `scarred`; nullopt otherwise (the
/// intact ring's solvers decide the row).
std::optional<AssemblyPairResult> solve_raceway_scar_row(const Assembly& as, const AssemblyPair& pair,
                                                         const std::vector<Transform>& poses, double clearance);

}  // namespace interfere::bearing::detail
