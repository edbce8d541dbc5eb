// Part geometry for the commands that take meshes (clash, distance, check, sweep): a mesh file
// (read_mesh: STL, OBJ, PLY, OFF, glTF) or, built with OpenCASCADE, a STEP part or assembly
// tessellated by cad::import_step (deflections from --linear-deflection/--angular-deflection;
// defaults 0.1 % of each part's diagonal, 0.5 rad; no AAG, only triangles are needed),
// every instance placed, lengths in millimetres, welded where faces meet (BRepMesh discretises a
// shared edge once, so a closed solid stays closed for the containment test).
#include "cad_exec.h"
#include "common.h"
#include "fem_parts.h"
#include "interfere/mesh/validate.h"

#include <algorithm>
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/model.h"
#endif

namespace interfere::cli {

bool is_step_file(const std::string& file) {
  const std::string e = lower_extension(file);
  return e == ".step" || e == ".stp";
}

PartMesh read_part_mesh(const std::string& file, [[maybe_unused]] const StepTessellation& tessellation) {
  PartMesh p;
  if (is_step_file(file)) {
    require_cad("STEP input " + file);  // (returns in interfere-cad only)
#ifdef INTERFERE_HAS_CAD
    auto model = cad::import_step(file, {.linear_deflection = tessellation.linear_deflection,
                                         .angular_deflection = tessellation.angular_deflection,
                                         .measure_deviation = tessellation.measure_deviation,
                                         .build_aag = false});  // triangles only
    if (!model) throw InputError(model.error());
    double deviation = tessellation.measure_deviation ? 0 : -1;
    for (const cad::Part& part : model->parts) {
      p.linear_deflection = std::max(p.linear_deflection, part.linear_deflection);
      if (deviation >= 0) deviation = part.tessellation_deviation < 0 ? -1 : std::max(deviation, part.tessellation_deviation);
      // BRepMesh refines to its tolerance where it checks; elsewhere it may stay above it.
      if (part.tessellation_deviation > part.linear_deflection)
        p.warnings.push_back("part '" + part.name + "': its triangles lie up to " + short_number(part.tessellation_deviation) +
                             " mm from their B-Rep surfaces, beyond the linear deflection " +
                             short_number(part.linear_deflection) + " mm (BRepMesh)");
    }
    p.tessellation_deviation = deviation;
    p.mesh = cad::world_mesh(*model);
    p.info.vertices_before_weld = p.mesh.num_vertices();
    weld_exact(p.mesh);
    p.format = "step";
    p.warnings.insert(p.warnings.begin(), model->warnings.begin(), model->warnings.end());
    for (const std::string& w : p.warnings) warning(file + ": " + w);
    return p;
#endif
  }
  if (is_fem_file(file)) {
    // (distance and check read FE models through fem_surfaces.h; the other callers take meshes)
    throw InputError(file + ": an FE model; this command takes mesh and STEP files (`interfere surface " + file +
                     " OUT.stl` writes its boundary surface as a mesh)");
  }
  auto m = read_mesh(file, {}, &p.info);
  if (!m) throw InputError(m.error());
  p.mesh = std::move(*m);
  p.format = mesh_format_name(p.info.format);
  return p;
}

}  // namespace interfere::cli
