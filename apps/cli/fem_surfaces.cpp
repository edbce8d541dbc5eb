// FE files as triangle meshes for `distance` and `check` (issue #26, item 5); see fem_surfaces.h.
#include "fem_surfaces.h"

#include <CLI/CLI.hpp>

#include <cmath>

#include "interfere/core/coordinate_range.h"
#include "interfere/fem/deform.h"

namespace interfere::cli {

void add_fem_flags(CLI::App& c, FemFlags& f, bool two_parts) {
  c.add_option("--part", f.part, two_parts ? "FE: body of both parts (group name, or 'body N' by connectivity)"
                                           : "FE: only this body (default: every body)");
  if (two_parts) {
    c.add_option("--part-a", f.part_a, "FE: body of part A (overrides --part)");
    c.add_option("--part-b", f.part_b, "FE: body of part B (overrides --part)");
  }
  c.add_option("--split", f.split, "FE: bodies by auto (default), group, connectivity, single");
  c.add_flag("--linear-faces", f.linear_faces, "FE: quadratic faces by their corners only");
  c.add_option("--disp", f.disp,
               two_parts ? "FE: nodal displacement CSV for both parts" : "FE: nodal displacement CSV");
  if (two_parts) {
    c.add_option("--disp-a", f.disp_a, "FE: displacement CSV of part A (overrides --disp/--field)");
    c.add_option("--disp-b", f.disp_b, "FE: displacement CSV of part B (overrides --disp/--field)");
  }
  c.add_option("--field", f.field, "FE: nodal vector field of the file(s) used as displacement");
  if (two_parts) {
    c.add_option("--field-a", f.field_a, "FE: field of part A (overrides --disp/--field)");
    c.add_option("--field-b", f.field_b, "FE: field of part B (overrides --disp/--field)");
  }
  c.add_option("--step", f.step, "FE: step of the displacements (0-based; default the last)");
  c.add_option("--scale", f.scale, "FE: displacement scale, position = node + scale * u (default 1)");
}

std::string given_fem_flag(const CLI::App& c) {
  for (const char* flag : {"--part", "--part-a", "--part-b", "--split", "--linear-faces", "--disp", "--disp-a",
                           "--disp-b", "--field", "--field-a", "--field-b", "--step", "--scale"}) {
    try {
      if (c.count(flag) > 0) return flag;
    } catch (const CLI::OptionNotFound&) {  // (a flag this command does not have)
    }
  }
  return {};
}

FemPartOptions fem_part_options(const FemFlags& f, char side) {
  const std::string& part_own = side == 'a' ? f.part_a : side == 'b' ? f.part_b : f.part;
  const std::string& disp_own = side == 'a' ? f.disp_a : side == 'b' ? f.disp_b : f.disp;
  const std::string& field_own = side == 'a' ? f.field_a : side == 'b' ? f.field_b : f.field;
  const bool own = !disp_own.empty() || !field_own.empty();
  FemPartOptions o;
  o.part = part_own.empty() ? f.part : part_own;
  o.disp = own ? disp_own : f.disp;
  o.field = own ? field_own : f.field;
  o.linear_faces = f.linear_faces;
  o.split = f.split;
  return o;
}

std::string displacement_source_text(const FemPart& p) {
  if (!p.displacement) return "none";
  if (p.displacement_source == "field") return "field '" + p.displacement->name + "' of " + p.file;
  return "CSV " + p.displacement_file + " for " + p.file;
}

void check_step_counts(const FemPart& a, const FemPart& b) {
  const std::size_t na = a.num_steps(), nb = b.num_steps();
  if (na == 0 || nb == 0 || na == nb) return;
  throw InputError("mismatched step counts: the displacements of A (" + displacement_source_text(a) + ") have " +
                   std::to_string(na) + " step" + (na == 1 ? "" : "s") + ", those of B (" + displacement_source_text(b) +
                   ") " + std::to_string(nb) + ": both parts need the same steps");
}

FemSurfaces read_fem_surfaces(const std::string& file, const FemPartOptions& options, long long step, double scale,
                              const std::string& label, bool all_bodies) {
  if (!std::isfinite(scale)) throw InputError("--scale must be a finite number");
  if (step < -1) throw InputError("--step must be >= 0");
  FemSurfaces s{.part = load_fem_part(file, options, label, all_bodies)};
  const FemPart& p = s.part;
  const std::string whose = "the displacements of " + (label == "input" ? std::string() : label + " ") + "(" +
                            displacement_source_text(p) + ")";
  // (Without displacements the part stays at its reference positions whatever the step: the
  // other part may have them; check_no_steps rejects a step when no part has any.)
  if (p.displacement) s.step = step >= 0 ? check_step(step, p.num_steps(), whose) : p.num_steps() - 1;
  s.scale = scale;
  for (std::size_t k : p.chosen) {
    const SurfacePart& sp = p.surface().parts[k];
    TriMesh m = sp.mesh;
    deformed_positions(sp, *p.mesh, p.displacement, s.step, scale, m.positions);
    if (p.displacement) {
      // The coordinate range of the exact tests (issue #23, item 7), for the positions queried.
      if (const std::size_t i = first_out_of_range(m.positions); i < m.positions.size())
        throw InputError(file + ": node " + std::to_string(p.mesh->node_ids[sp.vertex_node[i]]) + " at step " +
                         std::to_string(s.step) + " (" + displacement_source_text(p) + ", scale " +
                         short_number(scale) + "): " + coordinate_range_reason(m.positions[i]));
    }
    s.bodies.push_back(std::move(m));
  }
  return s;
}

void check_no_steps(long long step, const std::string& what) {
  if (step > 0)
    throw InputError("--step " + std::to_string(step) + ": " + what +
                     " (give --disp or --field): only step 0, the reference positions");
}

nlohmann::json fem_surfaces_json(const FemSurfaces& s, bool with_pose) {
  nlohmann::json j = fem_part_json(s.part);
  if (!with_pose) {
    for (const char* k : {"file", "format", "units", "units_source", "scale_to_working_unit", "transform"}) j.erase(k);
  }
  j["step"] = s.part.displacement ? nlohmann::json(s.step) : nlohmann::json(nullptr);
  j["displacement_scale"] = s.scale;
  return j;
}

}  // namespace interfere::cli
