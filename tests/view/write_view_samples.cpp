// Sample viewer documents for the independent readers of the file exports (issue #25, items 2 and
// 3): writes OUTDIR/{static,frames}.glb and .pvd (view/gltf.h, view/pvd.h) and OUTDIR/expect.json,
// the facts of each document computed here from the document itself (never from the files):
// per step and body the triangle count, the world box, the clash flags, source ids and depths;
// per step the clashes present. tests/view/check_gltf.py and check_pvd.py read the files back with
// three.js's GLTFLoader and ParaView and compare.
//
// Usage: interfere_view_samples OUTDIR
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/view/document.h"
#include "interfere/view/gltf.h"
#include "interfere/view/pvd.h"

namespace iv = interfere::view;
using interfere::Transform;
using interfere::Vec3;
using json = nlohmann::json;

namespace {

Transform rotation_z(double degrees, const Vec3& t) {
  const double a = degrees * M_PI / 180, c = std::cos(a), s = std::sin(a);
  Transform x;
  x.r = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  x.t = t;
  return x;
}

// A small triangle fan around `centre` (a clash region in world coordinates).
interfere::TriMesh patch(const Vec3& centre, int triangles) {
  interfere::TriMesh m;
  m.positions.push_back(centre);
  for (int i = 0; i <= triangles; ++i) {
    const double a = 2 * M_PI * i / (triangles + 1);
    m.positions.push_back(centre + Vec3{0.3 * std::cos(a), 0.3 * std::sin(a), 0.05 * i});
  }
  for (int i = 0; i < triangles; ++i)
    m.triangles.push_back({0, static_cast<std::uint32_t>(i + 1), static_cast<std::uint32_t>(i + 2)});
  return m;
}

iv::ViewMesh view_mesh(interfere::TriMesh m) {
  iv::ViewMesh v;
  v.source_triangles = m.num_triangles();
  v.mesh = std::move(m);
  return v;
}

/// Three bodies (two drawing one shared mesh), a clash with a region and two curves, a contact
/// region, a clearance witness; face colours, clash flags, source ids and point depths.
iv::Document static_document() {
  iv::Document d;
  d.title = "sample clash";
  d.command = "interfere clash plate.stl pin.stl --html sample.html";
  d.tool_version = "test";
  d.units = "mm";
  d.verdict = "clash";
  d.legend = {{"hole", {0.2f, 0.4f, 0.9f}}, {"plane", {0.7f, 0.7f, 0.7f}}};
  d.notes = {"sample document"};
  iv::ViewMesh plate = view_mesh(interfere::make_box({-2, -1, 0}, {3, 2, 1}, 2));  // 48 triangles, not symmetric (a transposed rotation moves its box)
  for (std::size_t t = 0; t < plate.mesh.num_triangles(); ++t) plate.source_ids.push_back(1000 + static_cast<std::int64_t>(t));
  plate.clash_flags.assign(plate.mesh.num_triangles(), 0);
  for (std::size_t t : {0u, 1u, 5u}) plate.clash_flags[t] = 1;
  iv::ViewMesh pin = view_mesh(interfere::make_sphere({.target_triangles = 80, .radius = 0.5}));
  for (std::size_t t = 0; t < pin.mesh.num_triangles(); ++t) pin.face_colors.push_back(t % 2);
  for (const Vec3& p : pin.mesh.positions) pin.point_depth.push_back(std::max(0.0, p.z));
  d.meshes = {plate, pin, view_mesh(patch({10, 0, 1}, 6)), view_mesh(patch({20, 5, 0}, 3))};
  iv::ViewBody a;
  a.id = "p1", a.name = "plate", a.path = "/asm/plate", a.mesh = 0, a.role = "workpiece", a.tags = {"steel", "fixed"};
  a.pose.t = {10, 0, 0};
  a.color = {0.5f, 0.6f, 0.7f};
  iv::ViewBody b;
  b.id = "p2", b.name = "pin", b.path = "/asm/pin", b.mesh = 1, b.role = "tool";
  b.pose = rotation_z(90, {10, 0, 1});
  b.color = {0.9f, 0.8f, 0.2f};
  iv::ViewBody c;
  c.id = "p3", c.name = "plate copy", c.path = "/asm/plate[2]", c.mesh = 0, c.visible = false;
  c.pose = rotation_z(30, {20, 5, -1});
  d.bodies = {a, b, c};
  iv::ViewClash k1;
  k1.id = "C1", k1.verdict = "clash", k1.status = "new", k1.kind = "crossing", k1.body_a = 0, k1.body_b = 1;
  k1.depth = 0.5, k1.depth_bound = 0.6, k1.point = {10, 0, 1}, k1.box_min = {9.5, -0.5, 0.5}, k1.box_max = {10.5, 0.5, 1.5};
  k1.curves = {{{9.7, 0, 1}, {10, 0.3, 1}, {10.3, 0, 1}, {10, -0.3, 1}, {9.7, 0, 1}}, {{10, 0, 1.2}, {10.1, 0, 1.3}, {10.2, 0.1, 1.3}}};
  k1.region_mesh = 2;
  k1.note = "pin through plate";
  iv::ViewClash k2;
  k2.id = "C2", k2.verdict = "contact", k2.status = "active", k2.kind = "touching", k2.body_a = 0, k2.body_b = 2;
  k2.point = {20, 5, 0}, k2.region_mesh = 3;
  iv::ViewClash k3;
  k3.id = "C3", k3.verdict = "clearance", k3.kind = "clearance", k3.body_a = 1, k3.body_b = 2, k3.distance = 0.2;
  k3.point = {15, 2, 0}, k3.has_witness = true, k3.witness_a = {15, 2, 0}, k3.witness_b = {15.2, 2, 0};
  d.clashes = {k1, k2, k3};
  return d;
}

/// Three frames: a rigidly moving body, a deforming body (its mesh changes at frame 1), a clash in
/// frames 1 and 2 only.
iv::Document frames_document() {
  iv::Document d;
  d.title = "sample frames";
  d.command = "interfere bearing sample.parameters --html frames.html";
  d.units = "cm";
  d.verdict = "clash";
  d.frames.labels = {"step 0", "step 1", "step 2"};
  d.frames.times = {0, 0.5, 1.5};
  d.frames.verdicts = {"clear", "clash", "clash"};
  iv::ViewMesh box = view_mesh(interfere::make_box({0, 0, 0}, {1, 2, 3}, 1));  // 12 triangles
  iv::ViewMesh ring0 = view_mesh(interfere::make_box({-1, -1, -1}, {1, 1, 1}, 1));
  for (std::size_t t = 0; t < 12; ++t) ring0.source_ids.push_back(static_cast<std::int64_t>(t) + 1);
  iv::ViewMesh ring1 = view_mesh(interfere::make_box({-1, -1, -1}, {1.5, 1, 1}, 2));  // 48 triangles
  for (std::size_t t = 0; t < 48; ++t) ring1.source_ids.push_back(static_cast<std::int64_t>(t) + 101);
  ring1.clash_flags.assign(48, 0);
  for (std::size_t t = 0; t < 7; ++t) ring1.clash_flags[t] = 1;
  for (const Vec3& p : ring1.mesh.positions) ring1.point_depth.push_back(p.x > 1 ? p.x - 1 : 0);
  d.meshes = {box, ring0, ring1, view_mesh(patch({1.2, 0, 0}, 4))};
  iv::ViewBody roller;
  roller.id = "r1", roller.name = "roller", roller.mesh = 0;
  roller.pose.t = {5, 0, 0};
  for (int k = 0; k < 3; ++k) roller.frame_poses.push_back(rotation_z(30.0 * k, {5.0 + k, 0, 0}));
  iv::ViewBody ring;
  ring.id = "g1", ring.name = "ring", ring.mesh = 1, ring.frame_meshes = {1, 2, 2};
  d.bodies = {roller, ring};
  iv::ViewClash k;
  k.id = "F1", k.verdict = "clash", k.status = "new", k.body_a = 0, k.body_b = 1, k.depth = 0.5;
  k.point = {1.2, 0, 0}, k.region_mesh = 3, k.frames = {1, 2};
  k.curves = {{{1.1, 0, 0}, {1.3, 0.1, 0}}};
  d.clashes = {k};
  return d;
}

json box_json(const std::vector<Vec3>& points) {
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec3 hi = lo * -1.0;
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return json::array({{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}});
}

/// What each step of `d` holds, from the document alone.
json expectations(const iv::Document& d) {
  json e;
  e["title"] = d.title, e["units"] = d.units, e["command"] = d.command, e["verdict"] = d.verdict;
  e["metres_per_unit"] = d.units == "mm" ? 0.001 : d.units == "cm" ? 0.01 : 1.0;
  const std::size_t frames = d.frames.labels.size();
  e["frame_count"] = frames;
  e["times"] = d.frames.times;
  e["bodies"] = json::array();
  for (const iv::ViewBody& b : d.bodies)
    e["bodies"].push_back({{"id", b.id}, {"name", b.name}, {"path", b.path}, {"role", b.role}, {"tags", b.tags}, {"visible", b.visible},
                           {"color", b.color}});
  e["clashes"] = json::array();
  for (const iv::ViewClash& c : d.clashes) {
    json curves = json::array();
    for (const auto& l : c.curves) curves.push_back(l.size());
    e["clashes"].push_back({{"id", c.id}, {"verdict", c.verdict}, {"status", c.status}, {"kind", c.kind},
                            {"depth", c.depth < 0 ? json(nullptr) : json(c.depth)},
                            {"distance", c.distance < 0 ? json(nullptr) : json(c.distance)},
                            {"bodies", json::array({d.bodies[c.body_a].id, d.bodies[c.body_b].id})},
                            {"region_triangles", c.region_mesh < 0 ? 0 : d.meshes[c.region_mesh].mesh.num_triangles()},
                            {"curve_points", curves}, {"witness", c.has_witness}, {"frames", c.frames}});
  }
  e["steps"] = json::array();
  for (std::size_t k = 0; k < std::max<std::size_t>(frames, 1); ++k) {
    json step{{"time", frames > 0 && !d.frames.times.empty() ? d.frames.times[k] : 0.0}, {"bodies", json::array()}, {"clashes", json::array()}};
    for (const iv::ViewBody& b : d.bodies) {
      const iv::ViewMesh& m = d.meshes[frames > 0 && !b.frame_meshes.empty() ? b.frame_meshes[k] : b.mesh];
      const Transform& pose = frames > 0 && !b.frame_poses.empty() ? b.frame_poses[k] : b.pose;
      std::vector<Vec3> world;
      for (const Vec3& p : m.mesh.positions) world.push_back(pose.apply(p));
      long flagged = 0;
      for (auto f : m.clash_flags) flagged += f != 0;
      json depth = nullptr;
      if (!m.point_depth.empty())
        depth = {*std::min_element(m.point_depth.begin(), m.point_depth.end()), *std::max_element(m.point_depth.begin(), m.point_depth.end())};
      step["bodies"].push_back({{"triangles", m.mesh.num_triangles()}, {"vertices", m.mesh.num_vertices()}, {"world_box", box_json(world)},
                                {"clash_flagged", flagged}, {"source_ids", m.source_ids}, {"depth_range", depth}});
    }
    for (std::size_t c = 0; c < d.clashes.size(); ++c) {
      const auto& f = d.clashes[c].frames;
      if (frames == 0 || f.empty() || std::find(f.begin(), f.end(), k) != f.end()) step["clashes"].push_back(d.clashes[c].id);
    }
    e["steps"].push_back(step);
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: interfere_view_samples OUTDIR\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  json expect;
  for (const auto& [name, doc] : {std::pair{std::string("static"), static_document()}, std::pair{std::string("frames"), frames_document()}}) {
    for (const interfere::Status& s : {iv::write_glb(out / (name + ".glb"), doc), iv::write_pvd(out / (name + ".pvd"), doc)})
      if (!s.ok()) {
        std::fprintf(stderr, "interfere_view_samples: %s\n", s.error().message().c_str());
        return 1;
      }
    expect[name] = expectations(doc);
  }
  std::ofstream(out / "expect.json") << expect.dump(1) << "\n";
  return 0;
}
