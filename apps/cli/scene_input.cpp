// Scene inputs of `interfere clash` (apps/cli/scene_input.h).
#include "scene_input.h"

#include <filesystem>

#include "fem_parts.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/fem/bodies.h"
#include "interfere/scene/clash_test.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/assembly_scene.h"
#endif
#include "interfere/core/units.h"
#include "interfere/mesh/validate.h"

namespace interfere::cli {
namespace {

std::string stem(const std::string& file) { return std::filesystem::path(file).stem().string(); }

// Checks the world coordinates a body's pose gives (the exact predicates' range, issue #23 item 7).
void check_posed(const scene::Body& b, const std::string& file) {
  std::vector<Vec3> w(b.mesh->positions.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = b.pose.apply(b.mesh->positions[i]);
  if (const std::size_t i = first_out_of_range(w); i < w.size())
    throw InputError(file + ": body '" + b.id + "': vertex " + std::to_string(i) + " once converted and posed: " +
                     coordinate_range_reason(w[i]));
}

// One mesh file (or a STEP file read as one part): one body.
scene::Body mesh_body(const scene::BodySpec& spec, const SceneInputOptions& o, std::vector<std::string>& warnings) {
  PartSpec ps{.file = spec.file, .units = spec.units, .units_flag = spec.where + " units"};
  const PartUnit unit = part_unit(ps);
  const double scale = unit_in_mm(unit.unit, unit.source) / unit_in_mm(o.units, "--units");
  PartMesh m = [&] {
    Progress progress("reading " + spec.file);
    return read_part_mesh(spec.file, o.tessellation);
  }();
  if (m.format != "step") weld_exact(m.mesh);
  for (const std::string& w : m.warnings) warnings.push_back(spec.file + ": " + w);
  if (scale != 1)
    for (Vec3& v : m.mesh.positions) v = v * scale;
  scene::Body b;
  b.id = spec.id.empty() ? scene::make_body_id(stem(spec.file)) : spec.id;
  b.name = spec.name.empty() ? stem(spec.file) : spec.name;
  b.path = spec.path.empty() ? "/" + b.name : spec.path;
  b.source = {scene::SourceKind::mesh_file, spec.file, ""};
  b.unit = unit.unit;
  b.tessellation_error = m.format == "step" ? std::max(m.linear_deflection, m.tessellation_deviation) * scale : 0;
  b.mesh = std::make_shared<const TriMesh>(std::move(m.mesh));
  b.pose = spec.pose;
  b.tags = spec.tags;
  return b;
}

}  // namespace

namespace {

bool is_gltf(const std::string& f) {
  const std::string e = lower_extension(f);
  return e == ".glb" || e == ".gltf";
}

// The bodies of a file that expands to several: ids "<prefix>/<sub-id>", the spec's pose applied
// after the file's own placements, tags added, `select` (a glob over the bodies' paths and names).
void adopt(const scene::BodySpec& spec, std::vector<scene::Body>& bodies, bool filter) {
  const std::string prefix = spec.id.empty() ? scene::make_body_id(stem(spec.file)) : spec.id;
  std::vector<scene::Body> kept;
  for (scene::Body& b : bodies) {
    if (filter && !spec.select.empty() && !scene::glob_match(spec.select, b.path) && !scene::glob_match(spec.select, b.name))
      continue;
    b.id = prefix + (b.id.starts_with('/') ? "" : "/") + b.id;
    if (spec.pose_given) b.pose = scene::compose(spec.pose, b.pose);
    b.tags.insert(b.tags.end(), spec.tags.begin(), spec.tags.end());
    kept.push_back(std::move(b));
  }
  if (kept.empty()) throw InputError(spec.where + ": " + spec.file + ": \"select\" " + spec.select + " selects no body");
  bodies = std::move(kept);
}

}  // namespace

SceneInput load_scene(const std::vector<scene::BodySpec>& specs, const SceneInputOptions& o) {
  SceneInput in;
  in.scene.units = o.units;
  const double working_mm = unit_in_mm(o.units, "--units");
#ifdef INTERFERE_HAS_CAD
  // The STEP assemblies read, with their sub-scenes, for the nominal-fit check by global index.
  struct Step {
    cad::CadModel model;
    scene::Scene sub;
    std::size_t first = 0;
    std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&, const ClashResult&, double)> check;
  };
  auto steps = std::make_shared<std::vector<std::unique_ptr<Step>>>();
#endif
  for (const scene::BodySpec& spec : specs) {
    in.files.push_back(spec.file);
    std::vector<scene::Body> bodies;
    if (is_step_file(spec.file)) {
#ifdef INTERFERE_HAS_CAD
      if (!spec.units.empty())
        throw InputError(spec.where + ": " + spec.file + " is a STEP file, which carries its own length unit: give no unit for it");
      auto model = [&] {
        Progress progress("reading " + spec.file);
        return cad::import_step(spec.file, {.linear_deflection = o.tessellation.linear_deflection,
                                            .angular_deflection = o.tessellation.angular_deflection});
      }();
      if (!model) throw InputError(model.error());
      auto step = std::make_unique<Step>();
      step->model = std::move(*model);
      step->sub = cad::assembly_scene(step->model);
      for (const std::string& w : step->sub.warnings) in.warnings.push_back(spec.file + ": " + w);
      const double scale = 1.0 / working_mm;  // STEP geometry is in mm
      for (scene::Body& b : step->sub.bodies) {
        if (scale != 1) {
          TriMesh m = *b.mesh;
          for (Vec3& v : m.positions) v = v * scale;
          b.mesh = std::make_shared<const TriMesh>(std::move(m));
          b.pose.t = b.pose.t * scale;
          b.tessellation_error *= scale;
        }
      }
      bodies = step->sub.bodies;
      for (scene::Body& b : bodies) b.source.file = spec.file;
      adopt(spec, bodies, true);
      // The sub-scene sees the bodies as the merged scene has them (poses), at their global indices.
      std::vector<scene::Body> sub_bodies;
      step->first = in.scene.bodies.size();
      for (const scene::Body& b : bodies) sub_bodies.push_back(b);
      // (the check maps global indices back to the model's instances through the body's detail)
      step->sub.bodies = sub_bodies;
      step->check = cad::nominal_fit_check(step->model, step->sub);
      steps->push_back(std::move(step));
#else
      throw InputError(spec.file + ": STEP input needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
#endif
    } else if (is_fem_file(spec.file)) {
      PartSpec ps{.file = spec.file, .units = spec.units, .units_flag = spec.where + " units"};
      const PartUnit unit = part_unit(ps);
      FemSceneOptions fo;
      fo.split = o.fem_split, fo.linear_faces = o.fem_linear_faces, fo.unit = unit.unit, fo.working_unit = o.units;
      fo.unit_scale = unit_in_mm(unit.unit, unit.source) / working_mm;
      fo.select = spec.select, fo.displacement_scale = o.fem_scale, fo.field = o.fem_field;
      fo.displacement_csv = o.fem_disp;
      auto fs = [&] {
        Progress progress("reading " + spec.file);
        return read_fem_scene(spec.file, fo);
      }();
      if (!fs) throw InputError(fs.error());
      for (const std::string& w : fs->warnings) in.warnings.push_back(w);
      if (!fs->frames.empty()) {
        if (!in.scene.frames.empty()) throw InputError(spec.file + ": a second input with displacement steps (one per run)");
        const auto offset = static_cast<std::uint32_t>(in.scene.bodies.size());
        in.scene.frames = fs->frames;
        for (scene::Frame& f : in.scene.frames) {
          for (auto& p : f.poses) p.body += offset;
          for (auto& sh : f.shapes) sh.body += offset;
        }
      }
      bodies = std::move(fs->bodies);
      adopt(spec, bodies, false);
    } else if (is_gltf(spec.file)) {
      const double scale = (spec.units.empty() ? 1000.0 : unit_in_mm(spec.units, spec.where + " units")) / working_mm;
      auto gb = [&] {
        Progress progress("reading " + spec.file);
        return scene::read_gltf_bodies(spec.file, scale);
      }();
      if (!gb) throw InputError(gb.error());
      bodies = std::move(*gb);
      if (!spec.units.empty())
        for (scene::Body& b : bodies) b.unit = spec.units;
      adopt(spec, bodies, true);
    } else {
      bodies.push_back(mesh_body(spec, o, in.warnings));
    }
    for (scene::Body& b : bodies) {
      if (b.mesh->num_triangles() == 0) throw InputError(spec.file + ": body '" + b.id + "' has no triangles");
      check_posed(b, spec.file);
      in.scene.bodies.push_back(std::move(b));
    }
  }
#ifdef INTERFERE_HAS_CAD
  if (!steps->empty()) {
    in.keep_alive = steps;
    in.nominal_fit = [steps](std::uint32_t a, std::uint32_t b, const Model& wa, const Model& wb, const ClashResult& r,
                             double depth) {
      for (const auto& s : *steps) {
        const std::size_t n = s->sub.bodies.size();
        if (a >= s->first && a < s->first + n && b >= s->first && b < s->first + n)
          return s->check(static_cast<std::uint32_t>(a - s->first), static_cast<std::uint32_t>(b - s->first), wa, wb, r, depth);
      }
      return false;  // bodies of different files share no B-Rep faces
    };
  }
#endif
  const std::vector<scene::Body> before = in.scene.bodies;
  scene::make_ids_unique(in.scene);
  for (std::size_t i = 0; i < before.size(); ++i)
    if (before[i].id != in.scene.bodies[i].id)
      in.warnings.push_back("two bodies have the id '" + before[i].id + "': the later one is '" + in.scene.bodies[i].id +
                            "' (ids then depend on the order of the inputs: give ids in a scene file)");
  for (const std::string& w : in.warnings) warning(w);
  return in;
}

}  // namespace interfere::cli
