// `interfere surface IN OUT`: the boundary surface of a FEM model (fem/surface.h), optionally
// deformed (node + scale × displacement of one step), written as a triangle mesh (STL/PLY/OBJ/OFF)
// or as a FEM file (VTU/VTK/MSH) with the source element id and face of every triangle.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>

#include "commands.h"
#include "common.h"
#include "fem_parts.h"
#include "interfere/core/atomic_file.h"
#include "interfere/fem/io.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/validate.h"
#include "report_envelope.h"

namespace interfere::cli {
namespace {

struct SurfaceOptions {
  std::string in, out, json, part, disp, field, split = "auto", transform;
  double scale = 1.0;
  long long step = -1;
  bool linear_faces = false;
  int threads = 0;
};

int run_surface(const SurfaceOptions& o) {
  if (o.in.empty() || o.out.empty()) throw InputError("surface: IN and OUT are needed");
  const std::vector<std::string> mesh_ext{".stl", ".ply", ".obj", ".off"};
  const std::vector<std::string> fem_ext{".vtu", ".vtk", ".msh"};
  std::vector<std::string> all_ext = mesh_ext;
  all_ext.insert(all_ext.end(), fem_ext.begin(), fem_ext.end());
  check_output(o.out, all_ext, "OUT");
  check_output(o.json, {}, "--json");
  check_distinct_files({{"IN", o.in}}, {{"OUT", o.out}, {"--json", o.json}});
  if (!std::isfinite(o.scale)) throw InputError("--scale must be a finite number");
  if (o.step < -1) throw InputError("--step must be >= 0");
  set_threads(o.threads);
  Progress total("surface");

  const FemPart p = load_fem_part(o.in, {.part = o.part, .disp = o.disp, .field = o.field,
                                         .linear_faces = o.linear_faces, .split = o.split, .transform = o.transform},
                                  "input", true);
  for (const std::string& w : p.warnings) {
    warning(w);
  }
  // Default step: the last one (the final deformed state).
  std::size_t step = 0;
  if (p.displacement) step = o.step >= 0 ? check_step(o.step, p.num_steps()) : p.num_steps() - 1;
  else if (o.step > 0) check_step(o.step, 0);

  // All chosen parts in one mesh (vertices per part: parts sharing nodes keep their own copies).
  TriMesh merged;
  FemMesh fem;
  FemArray elem{.name = "fem_element_id"}, face{.name = "fem_face"}, part{.name = "part"}, node{.name = "fem_node_id"};
  nlohmann::json parts_json = nlohmann::json::array();
  std::size_t index = 0;
  for (std::size_t k : p.chosen) {
    const SurfacePart& sp = p.surface().parts[k];
    std::vector<Vec3> pos;
    deformed_positions(sp, *p.mesh, p.displacement, step, o.scale, pos);
    const auto base = static_cast<std::uint32_t>(merged.positions.size());
    fem.groups.push_back({.name = sp.name, .id = static_cast<std::int64_t>(index + 1), .dim = 2});
    for (std::size_t i = 0; i < pos.size(); ++i) {
      merged.positions.push_back(pos[i]);
      fem.nodes.push_back(pos[i]);
      fem.node_ids.push_back(static_cast<std::int64_t>(fem.nodes.size()));
      node.ints.push_back(p.mesh->node_ids[sp.vertex_node[i]]);
    }
    for (std::size_t t = 0; t < sp.mesh.num_triangles(); ++t) {
      const Tri& tri = sp.mesh.triangles[t];
      const Tri g{tri[0] + base, tri[1] + base, tri[2] + base};
      merged.triangles.push_back(g);
      fem.add_element(ElemType::tri3, static_cast<std::int64_t>(fem.num_elements() + 1),
                      static_cast<std::int32_t>(index), g.data(), 3);
      elem.ints.push_back(p.mesh->elem_ids[sp.tri_element[t]]);
      face.ints.push_back(sp.tri_face[t]);
      part.ints.push_back(static_cast<std::int64_t>(index));
    }
    TriMesh deformed = sp.mesh;
    deformed.positions = pos;
    const MeshStats s = mesh_stats(deformed);
    nlohmann::json pj = {{"name", sp.name},
                         {"volume_elements", sp.volume_elements},
                         {"shell_elements", sp.shell_elements}};
    pj.update(stats_json(s));
    parts_json.push_back(pj);
    ++index;
  }

  const std::string ext = lower_extension(o.out);
  if (std::find(fem_ext.begin(), fem_ext.end(), ext) != fem_ext.end()) {
    FemWriteOptions wo;
    wo.cell_data = {elem, face, part};
    wo.point_data = {node};
    write_or_throw(write_fem(fem, o.out, wo));
  } else {
    if (merged.triangles.empty()) throw InputError(o.in + ": the surface has no triangle; " + o.out + " not written");
    write_or_throw(write_mesh(o.out, merged));
  }
  if (!o.json.empty()) {
    nlohmann::json j = {{"interfere_version", INTERFERE_VERSION},
                        {"command", "surface"},
                        {"input", fem_part_json(p)},
                        {"output", o.out},
                        {"step", p.displacement ? nlohmann::json(step) : nlohmann::json(nullptr)},
                        {"scale", o.scale},
                        {"linear_faces", o.linear_faces},
                        {"parts", parts_json},
                        {"triangles", merged.triangles.size()},
                        {"vertices", merged.positions.size()},
                        {"input_warnings", p.warnings},
                        {"timings_s", {{"read", p.read_seconds}, {"extract", p.extract_seconds}, {"total", total.seconds()}}}};
    write_or_throw(write_output(o.json, report_text(j)));
  }
  std::printf("surface: %zu part%s, %zu triangles, %zu vertices", p.chosen.size(), p.chosen.size() == 1 ? "" : "s",
              merged.triangles.size(), merged.positions.size());
  if (p.displacement) std::printf(", step %zu of %zu, scale %g", step, p.num_steps(), o.scale);
  std::printf(" -> %s\n", o.out.c_str());
  return kClear;
}

}  // namespace

void add_surface_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SurfaceOptions>();
  CLI::App* c = app.add_subcommand("surface", "Boundary surface of a FEM model (optionally deformed) as "
                                              "STL/PLY/OBJ/OFF or VTU/VTK/MSH with element ids");
  c->add_option("IN", o->in, "FEM file (.msh .bdf .nas .dat .vtk .vtu .inp .frd .e .exo)");
  c->add_option("OUT", o->out, "output: .stl .ply .obj .off (triangles) or .vtu .vtk .msh (with cell data)");
  c->add_option("--part", o->part, "only this body (default: every body)");
  c->add_option("--split", o->split, "bodies by auto (default), group, connectivity, single");
  c->add_flag("--linear-faces", o->linear_faces, "quadratic faces by their corners only");
  c->add_option("--disp", o->disp, "nodal displacement CSV");
  c->add_option("--field", o->field, "nodal vector field of IN used as displacement");
  c->add_option("--scale", o->scale, "position = node + scale * u (default 1)");
  c->add_option("--step", o->step, "step of the displacement (0-based; default the last)");
  c->add_option("--transform", o->transform, "pose: \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\"")
      ->check([](const std::string& text) {  // empty, non-finite, singular: an error (issue #23, item 8)
        const auto t = Transform::parse(text);
        return t ? std::string() : t.error().reason;
      });
  c->add_option("--json", o->json, "write a JSON report here");
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  c->callback([o, &exit_code] { exit_code = run_surface(*o); });
}

}  // namespace interfere::cli
