// `interfere distance A B`: minimum distance between two parts with the two witness points.
#include <CLI/CLI.hpp>

#include "commands.h"
#include "common.h"
#include "interfere/core/atomic_file.h"
#include "interfere/query/distance.h"
#include "report_json.h"

namespace interfere::cli {
namespace {

struct DistanceOptions {
  PartSpec a, b;
  std::string scene, units, json, builder = "lbvh";
  int threads = 0;
};

int run_distance(const DistanceOptions& o) {
  PartSpec a = o.a, b = o.b;
  std::string units = o.units;
  if (!o.scene.empty()) apply_scene(o.scene, a, b, units);
  if (a.file.empty() || b.file.empty()) throw InputError("distance: two parts are needed (A B, or --scene)");
  if (units.empty()) units = "mm";
  check_units(units);
  const BvhBuildOptions bvh{.builder = parse_builder(o.builder)};
  set_threads(o.threads);
  Progress total("distance");
  const LoadedPart pa = load_part(a, "A", bvh);
  const LoadedPart pb = load_part(b, "B", bvh);
  DistanceResult r;
  double query_seconds = 0;
  {
    Progress progress("distance query");
    r = distance(pa.model, pb.model);
    query_seconds = progress.seconds();
  }
  if (!o.json.empty()) {
    nlohmann::json j = {{"interfere_version", INTERFERE_VERSION},
                        {"command", "distance"},
                        {"units", units},
                        {"inputs", {{"a", part_json(pa)}, {"b", part_json(pb)}}},
                        {"result", distance_result_json(r)},
                        {"timings_s",
                         {{"read", pa.read_seconds + pb.read_seconds},
                          {"build", pa.build_seconds + pb.build_seconds},
                          {"query", query_seconds},
                          {"total", total.seconds()}}},
                        {"exit_status", r.intersecting ? kInterference : kClear}};
    const Status s = write_file_atomic(o.json, j.dump(2) + "\n");
    if (!s) throw InputError(s.error());
  }
  if (r.intersecting) {
    std::printf("INTERFERENCE: surfaces intersect (triangles %u of A and %u of B), distance 0\n", r.triangle_a,
                r.triangle_b);
    return kInterference;
  }
  std::printf("distance %.17g %s between A (%.17g %.17g %.17g) and B (%.17g %.17g %.17g), triangles %u and %u\n",
              r.distance, units.c_str(), r.point_a.x, r.point_a.y, r.point_a.z, r.point_b.x, r.point_b.y,
              r.point_b.z, r.triangle_a, r.triangle_b);
  return kClear;
}

}  // namespace

void add_distance_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DistanceOptions>();
  CLI::App* c = app.add_subcommand("distance", "Minimum distance between parts A and B, with witness points");
  c->add_option("A", o->a.file, "mesh file of part A");
  c->add_option("B", o->b.file, "mesh file of part B");
  c->add_option("--scene", o->scene, "JSON scene giving both parts and their transforms");
  c->add_option("--transform-a", o->a.transform, "pose of A: \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\"");
  c->add_option("--transform-b", o->b.transform, "pose of B, same form");
  c->add_option("--json", o->json, "write the JSON report here");
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  c->add_option("--builder", o->builder, "tree builder: lbvh (default), sah, median, insertion");
  c->add_option("--units", o->units, "length unit of the inputs, reported (mm, cm, m, um, in, ft)");
  c->callback([o, &exit_code] { exit_code = run_distance(*o); });
}

}  // namespace interfere::cli
