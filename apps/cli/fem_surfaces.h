// FE files as triangle meshes for `distance` and `check` (issue #26, item 5): they take every FE
// format `clash` takes (is_fem_file: .msh .bdf .nas .dat .vtk .vtu .inp .frd .e .exo). The one path
// from an FE file to meshes is clash's own, load_fem_part (fem_parts.h: read_fem, the displacements
// of --disp/--field, extract_surface, the body of --part); here the chosen bodies' boundary
// surfaces are taken at one configuration: node + scale × u of one step (fem/deform.h), the last
// step by default (as `surface`), the reference positions without displacements.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem_parts.h"

namespace CLI {
class App;
}

namespace interfere::cli {

/// The FE flags of a command (clash's names and meaning, docs/fem.md "CLI"): a flag without -a/-b
/// applies to both parts; a part's own displacement flag (--disp-a or --field-a) replaces both
/// shared ones.
struct FemFlags {
  std::string part, part_a, part_b;
  std::string disp, disp_a, disp_b;
  std::string field, field_a, field_b;
  std::string split = "auto";
  bool linear_faces = false;
  long long step = -1;  ///< -1: the last step (distance, check); clash: every step
  double scale = 1.0;   ///< position = node + scale × u
};

/// Registers --part, --split, --linear-faces, --disp, --field, --step, --scale; `two_parts`: also
/// --part-a/-b, --disp-a/-b, --field-a/-b.
void add_fem_flags(CLI::App& command, FemFlags& flags, bool two_parts);
/// The FE flag given on the command line first ("--part-a"), or "" when none was: a command whose
/// inputs hold no FE file rejects them (they would silently do nothing).
std::string given_fem_flag(const CLI::App& command);
/// One part's options from the flags: side 'a', 'b' (own flags over shared ones), or 0 (one input).
/// No pose and no unit (the caller's).
FemPartOptions fem_part_options(const FemFlags& flags, char side);

/// An FE input at one configuration.
struct FemSurfaces {
  FemPart part;                 ///< as load_fem_part gives it (mesh, surfaces, displacements, warnings)
  std::size_t step = 0;         ///< the displacement step taken (0 without displacements)
  double scale = 1;             ///< the displacement scale
  std::vector<TriMesh> bodies;  ///< per chosen body (part.chosen), its surface at that step
};

/// Reads `file` through load_fem_part (label "A", "B" or "input"; `all_bodies`: every body unless
/// --part names one, else exactly one) and places its chosen bodies at the step (--step, default
/// the last; checked against the displacements, the message naming the file; without displacements
/// the reference positions) and scale. Throws
/// InputError naming the file: also for a deformed node outside the exact tests' coordinate range
/// (its id and the step).
FemSurfaces read_fem_surfaces(const std::string& file, const FemPartOptions& options, long long step, double scale,
                              const std::string& label, bool all_bodies);

/// Throws InputError for a --step beyond 0 when no part has displacements; `what`: "model.msh has
/// no displacements" (the message's subject).
void check_no_steps(long long step, const std::string& what);

/// "field 'disp' of model.msh" / "CSV disp.csv for model.inp": where a part's displacements come
/// from (messages).
std::string displacement_source_text(const FemPart& p);
/// Throws InputError when both parts have displacements with different step counts, naming each
/// part's file and displacement source and both counts (clash, distance).
void check_step_counts(const FemPart& a, const FemPart& b);

/// The FE block of a report: fem_part_json of the part (file, bodies, the chosen body, counts,
/// displacement) with the step and scale taken; without the pose and unit keys when `with_pose`
/// is false (the caller reports those).
nlohmann::json fem_surfaces_json(const FemSurfaces& s, bool with_pose);

}  // namespace interfere::cli
