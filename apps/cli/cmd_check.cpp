// `interfere check FILE`: read and validate a mesh; print (and optionally write) its statistics.
#include <CLI/CLI.hpp>

#include "commands.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/mesh/validate.h"

namespace interfere::cli {
namespace {

struct CheckOptions {
  std::string file, json;
  StepTessellation tessellation;
};

int run_check(CheckOptions o, const CLI::App& command) {
  check_output(o.json, {}, "--json");
  check_distinct_files({{"FILE", o.file}}, {{"--json", o.json}});
  resolve_step_tessellation(command, o.tessellation, {o.file});
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
  if (!o.json.empty()) {
    const Status st = write_output(o.json, j.dump(2) + "\n");
    if (!st) throw InputError(st.error());
  }
  std::printf("%s\n", j.dump(2).c_str());
  return kClear;
}

}  // namespace

void add_check_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* c = app.add_subcommand("check", "Read and validate a mesh: counts of degenerate/duplicate "
                                            "triangles, open and non-manifold edges");
  c->add_option("FILE", o->file, "mesh file (STL, OBJ, PLY, OFF, glTF .glb/.gltf) or STEP file (.step, .stp)")->required();
  c->add_option("--json", o->json, "write the statistics as JSON here");
  add_step_tessellation_options(*c, o->tessellation);
  c->callback([o, c, &exit_code] { exit_code = run_check(*o, *c); });
}

}  // namespace interfere::cli
