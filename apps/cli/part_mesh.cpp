// Part geometry for the commands that take meshes (clash, distance, check, sweep): a mesh file
// (read_mesh: STL, OBJ, PLY, OFF, GLB) or, built with OpenCASCADE, a STEP part or assembly
// tessellated by cad::import_step (default deflections: 0.1 % of each part's diagonal, 0.5 rad),
// every instance placed, lengths in millimetres, welded where faces meet (BRepMesh discretises a
// shared edge once, so a closed solid stays closed for the containment test).
#include "common.h"
#include "interfere/mesh/validate.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/model.h"
#endif

namespace interfere::cli {

bool is_step_file(const std::string& file) {
  const std::string e = lower_extension(file);
  return e == ".step" || e == ".stp";
}

PartMesh read_part_mesh(const std::string& file) {
  PartMesh p;
  if (is_step_file(file)) {
#ifdef INTERFERE_HAS_CAD
    auto model = cad::import_step(file);
    if (!model) throw InputError(model.error());
    p.mesh = cad::world_mesh(*model);
    p.info.vertices_before_weld = p.mesh.num_vertices();
    weld_exact(p.mesh);
    p.format = "step";
    p.warnings = std::move(model->warnings);
    for (const std::string& w : p.warnings) warning(file + ": " + w);
    return p;
#else
    throw InputError(file + ": STEP input needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
#endif
  }
  auto m = read_mesh(file, {}, &p.info);
  if (!m) throw InputError(m.error());
  p.mesh = std::move(*m);
  p.format = mesh_format_name(p.info.format);
  return p;
}

}  // namespace interfere::cli
