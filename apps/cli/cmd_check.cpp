// `interfere check FILE`: read and validate a mesh; print (and optionally write) its statistics.
// An FE model (issue #26, item 5): the statistics of each body's boundary surface.
#include <CLI/CLI.hpp>

#include "commands.h"
#include "common.h"
#include "fem_surfaces.h"
#include "interfere/core/atomic_file.h"
#include "interfere/fem/bodies.h"
#include "interfere/mesh/validate.h"
#include "report_envelope.h"

namespace interfere::cli {
namespace {

struct CheckOptions {
  std::string file, json;
  StepTessellation tessellation;
  FemFlags fem;  ///< FE models (issue #26, item 5)
};

// Signed volume enclosed by the triangles as oriented (positive when they face outward), summed
// relative to the box centre (smaller terms than about the origin).
double signed_volume(const TriMesh& m) {
  const Vec3 c = m.bounds().center();
  double v = 0;
  for (const Tri& t : m.triangles) {
    const Vec3 a = m.positions[t[0]] - c, b = m.positions[t[1]] - c, d = m.positions[t[2]] - c;
    v += dot(a, cross(b, d));
  }
  return v / 6;
}

// An FE model (issue #26, item 5): per chosen body, its boundary surface (load_fem_part, as clash
// and surface read it) at the step: closed, outward (closed with a positive enclosed volume: the
// extraction orients outward, shells keep their own order), volume, the counts of mesh_stats and
// the body's surface warnings; the model's warnings (reader, extraction) beside them.
/// The report finished, written to --json (when given) and printed; `interfere check` exits 0.
int print_check_report(nlohmann::json& j, const std::string& json_path) {
  finish_report(j);
  if (!json_path.empty()) {
    const Status st = write_output(json_path, j.dump(2) + "\n");
    if (!st) throw InputError(st.error());
  }
  std::printf("%s\n", j.dump(2).c_str());
  return kClear;
}

int run_fem_check(const CheckOptions& o) {
  const FemSurfaces s = read_fem_surfaces(o.file, fem_part_options(o.fem, 0), o.fem.step, o.fem.scale, "input", true);
  const FemPart& p = s.part;
  if (!p.displacement) check_no_steps(o.fem.step, o.file + " has no displacements");
  for (const std::string& w : p.warnings) warning(w);
  nlohmann::json bodies = nlohmann::json::array();
  Aabb box;
  for (std::size_t i = 0; i < p.chosen.size(); ++i) {
    const SurfacePart& sp = p.surface().parts[p.chosen[i]];
    const TriMesh& m = s.bodies[i];
    const MeshStats st = mesh_stats(m);
    const double volume = signed_volume(m);
    box.expand(m.bounds());
    nlohmann::json b = {{"name", sp.name},
                        {"volume_elements", sp.volume_elements},
                        {"shell_elements", sp.shell_elements}};
    b.update(stats_json(st));
    b["outward"] = st.closed() && volume > 0;
    b["volume"] = st.closed() ? nlohmann::json(volume) : nlohmann::json(nullptr);
    b["signed_volume"] = volume;
    b["surface_components"] = sp.components;
    b["open_components"] = sp.open_components;
    b["degenerate_components"] = sp.degenerate_components;
    b["nonorientable_components"] = sp.nonorientable_components;
    b["warnings"] = surface_part_warnings(sp);
    const Aabb bb = m.bounds();
    b["bbox"] = {{"min", {bb.lo.x, bb.lo.y, bb.lo.z}}, {"max", {bb.hi.x, bb.hi.y, bb.hi.z}}};
    bodies.push_back(std::move(b));
  }
  std::vector<std::string> model_warnings = p.mesh->warnings;
  for (const std::string& w : surface_warnings(p.surface())) model_warnings.push_back(w);
  nlohmann::json j = {{"interfere_version", INTERFERE_VERSION},
                      {"command", "check"},
                      {"file", o.file},
                      {"format", p.format},
                      {"fem", fem_surfaces_json(s, false)},
                      {"bodies", bodies},
                      {"warnings", model_warnings}};
  if (!box.empty()) j["bbox"] = {{"min", {box.lo.x, box.lo.y, box.lo.z}}, {"max", {box.hi.x, box.hi.y, box.hi.z}}};
  return print_check_report(j, o.json);
}

int run_check(CheckOptions o, const CLI::App& command) {
  check_output(o.json, {}, "--json");
  check_distinct_files({{"FILE", o.file}}, {{"--json", o.json}});
  resolve_step_tessellation(command, o.tessellation, {o.file});
  if (is_fem_file(o.file)) return run_fem_check(o);
  if (const std::string flag = given_fem_flag(command); !flag.empty())
    throw InputError(flag + ": " + o.file + " is not an FE file");
  o.tessellation.measure_deviation = true;  // (a STEP input: how far its triangles really lie)
  PartMesh part = read_part_mesh(o.file, o.tessellation);
  const MeshReadInfo& info = part.info;
  const TriMesh* m = &part.mesh;
  const MeshStats s = mesh_stats(*m);
  const Aabb box = m->bounds();
  nlohmann::json j = {{"interfere_version", INTERFERE_VERSION},
                      {"command", "check"},
                      {"file", o.file},
                      {"format", part.format},
                      {"polygons_split", info.polygons_split},
                      {"vertices_before_weld", info.vertices_before_weld},
                      {"bbox", {{"min", {box.lo.x, box.lo.y, box.lo.z}}, {"max", {box.hi.x, box.hi.y, box.hi.z}}}}};
  if (part.format == "step") {
    j["linear_deflection"] = part.linear_deflection;
    j["tessellation_deviation"] = part.tessellation_deviation >= 0 ? nlohmann::json(part.tessellation_deviation)
                                                                   : nlohmann::json(nullptr);
    j["warnings"] = part.warnings;
  }
  j.update(stats_json(s));
  return print_check_report(j, o.json);
}

}  // namespace

void add_check_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* c = app.add_subcommand("check", "Read and validate a mesh: counts of degenerate/duplicate "
                                            "triangles, open and non-manifold edges (an FE model: per body of "
                                            "its boundary surface, closed, outward, volume)");
  c->add_option("FILE", o->file, "mesh file (STL, OBJ, PLY, OFF, glTF .glb/.gltf), STEP file (.step, .stp), or FE "
                                 "model (.msh .bdf .nas .dat .vtk .vtu .inp .frd .e .exo)")->required();
  c->add_option("--json", o->json, "write the statistics as JSON here");
  add_step_tessellation_options(*c, o->tessellation);
  add_fem_flags(*c, o->fem, false);
  c->callback([o, c, &exit_code] { exit_code = run_check(*o, *c); });
}

}  // namespace interfere::cli
