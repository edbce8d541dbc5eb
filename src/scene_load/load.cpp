// The scene loader (include/interfere/scene/load.h): one reader per kind of file, one scene.
#include "interfere/scene/load.h"

#include <tbb/parallel_for.h>

#include <filesystem>
#include <map>
#include <unordered_set>
#include <memory>
#include <optional>
#include <stdexcept>

#include "interfere/core/coordinate_range.h"
#include "interfere/core/units.h"
#include "interfere/fem/bodies.h"
#include "interfere/fem/io.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/validate.h"
#include "interfere/scene/clash_test.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/assembly_scene.h"
#endif

namespace interfere::scene {
namespace {

// Errors inside the loader; load_scene turns them into its Error value.
struct LoadError {
  Error error;
};
[[noreturn]] void fail(const std::string& file, const std::string& reason) { throw LoadError{Error{.file = file, .reason = reason}}; }
[[noreturn]] void fail(const Error& e) { throw LoadError{e}; }

std::string stem(const std::string& f) { return std::filesystem::path(f).stem().string(); }
std::string lower_ext(const std::string& f) {
  std::string e = std::filesystem::path(f).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
bool is_step(const std::string& f) { return lower_ext(f) == ".step" || lower_ext(f) == ".stp"; }
bool is_gltf(const std::string& f) { return lower_ext(f) == ".glb" || lower_ext(f) == ".gltf"; }
bool is_fem(const std::string& f) {
  const std::string e = lower_ext(f);
  for (const char* x : {".msh", ".bdf", ".nas", ".dat", ".vtk", ".vtu", ".inp", ".frd", ".e", ".exo"})
    if (e == x) return true;
  return false;
}

double mm_per(const std::string& unit, const std::string& file, const std::string& what) {
  const auto m = millimetres_per_unit(unit);
  if (!m) fail(file, what + ": unknown unit '" + unit + "' (" + std::string(known_units()) + ")");
  return *m;
}

// Every posed vertex within the supported coordinate range (issue #23, item 7).
void check_posed(const Body& b, const std::string& file) {
  std::vector<Vec3> w(b.mesh->positions.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = b.pose.apply(b.mesh->positions[i]);
  if (const std::size_t i = first_out_of_range(w); i < w.size())
    fail(file, "body '" + b.id + "': vertex " + std::to_string(i) + " once converted and posed: " + coordinate_range_reason(w[i]));
}

// The bodies of a file that expands to several: ids "<prefix>/<path>", the spec's pose after the
// file's own placements, its tags; `select` (a glob over paths and names) when `filter`.
void adopt(const BodySpec& spec, std::vector<Body>& bodies, bool filter) {
  const std::string prefix = spec.id.empty() ? make_body_id(stem(spec.file)) : spec.id;
  std::vector<Body> kept;
  for (Body& b : bodies) {
    if (filter && !spec.select.empty() && !glob_match(spec.select, b.path) && !glob_match(spec.select, b.name)) continue;
    b.id = prefix + (b.id.starts_with('/') ? "" : "/") + b.id;
    if (spec.pose_given) b.pose = compose(spec.pose, b.pose);
    b.tags.insert(b.tags.end(), spec.tags.begin(), spec.tags.end());
    kept.push_back(std::move(b));
  }
  if (kept.empty())
    fail(spec.file, spec.where + ": " + (spec.select.empty() ? std::string("the file has no body")
                                                              : "\"select\" " + spec.select + " selects no body"));
  bodies = std::move(kept);
}

// The unit a mesh file's body is read in.
std::string mesh_unit(const BodySpec& spec) { return !spec.units.empty() ? spec.units : is_gltf(spec.file) ? "m" : "mm"; }

// One mesh file read, welded and converted to the working unit.
std::shared_ptr<const TriMesh> read_mesh_file(const BodySpec& spec, double working_mm) {
  const std::string unit = mesh_unit(spec);
  const double scale = mm_per(unit, spec.file, spec.where + " units") / working_mm;
  auto m = read_mesh(spec.file);
  if (!m) fail(m.error());
  weld_exact(*m);
  if (scale != 1)
    for (Vec3& v : m->positions) v = v * scale;
  return std::make_shared<const TriMesh>(std::move(*m));
}

// One mesh file: one body.
Body mesh_body(const BodySpec& spec, std::shared_ptr<const TriMesh> mesh) {
  Body b;
  b.id = spec.id.empty() ? make_body_id(stem(spec.file)) : spec.id;
  b.name = spec.name.empty() ? stem(spec.file) : spec.name;
  b.path = spec.path.empty() ? "/" + b.name : spec.path;
  b.source = {SourceKind::mesh_file, spec.file, ""};
  b.unit = mesh_unit(spec);
  b.mesh = std::move(mesh);
  b.pose = spec.pose;
  b.tags = spec.tags;
  return b;
}

#ifdef INTERFERE_HAS_CAD
// A STEP assembly read: its model and its bodies as the scene has them (from index `first`), for
// the nominal-fit check (cad/assembly_scene.h).
struct StepSource {
  cad::CadModel model;
  Scene sub;
  std::size_t first = 0;
  std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&, const ClashResult&, double)> check;
  SceneClashOptions::ZeroClearanceFits fits;
};
#endif

}  // namespace

bool load_supports_step() {
#ifdef INTERFERE_HAS_CAD
  return true;
#else
  return false;
#endif
}

Expected<LoadedScene> load_scene(const std::vector<BodySpec>& specs, const LoadOptions& o) {
  LoadedScene out;
  Scene& scene = out.scene;
  scene.units = o.units;
  try {
    const double working_mm = mm_per(o.units, "", "units");
#ifdef INTERFERE_HAS_CAD
    auto steps = std::make_shared<std::vector<std::unique_ptr<StepSource>>>();
#endif
    // Mesh files (one body each) are read, welded and converted in parallel first (item 8: many
    // files), each file once per unit: bodies that name the same file share its mesh, and the
    // engine decides their pairs in the same relative pose once (engine_frame.cpp). Errors are
    // reported in input order below, so the first bad file is always named.
    std::vector<std::size_t> mesh_of(specs.size(), 0);
    std::vector<std::size_t> first_spec;  // per distinct (file, unit): its first spec
    {
      std::map<std::pair<std::string, std::string>, std::size_t> index;
      for (std::size_t i = 0; i < specs.size(); ++i) {
        const BodySpec& spec = specs[i];
        if (is_step(spec.file) || is_fem(spec.file) || is_gltf(spec.file)) continue;
        std::error_code ec;
        const std::filesystem::path canonical = std::filesystem::weakly_canonical(spec.file, ec);
        const auto [it, added] = index.emplace(std::pair{ec ? spec.file : canonical.string(), mesh_unit(spec)}, first_spec.size());
        if (added) first_spec.push_back(i);
        mesh_of[i] = it->second;
      }
    }
    std::vector<std::shared_ptr<const TriMesh>> meshes(first_spec.size());
    std::vector<std::optional<Error>> mesh_error(first_spec.size());
    tbb::parallel_for(std::size_t{0}, first_spec.size(), [&](std::size_t k) {
      try {
        meshes[k] = read_mesh_file(specs[first_spec[k]], working_mm);
      } catch (const LoadError& e) {
        mesh_error[k] = e.error;
      }
    });
    std::unordered_set<std::string> listed;
    for (std::size_t si = 0; si < specs.size(); ++si) {
      const BodySpec& spec = specs[si];
      if (listed.insert(spec.file).second) {  // (each file once)
        out.files.push_back(spec.file);
        if (o.reading) o.reading(spec.file);
      }
      std::vector<Body> bodies;
      if (is_step(spec.file)) {
#ifdef INTERFERE_HAS_CAD
        if (!spec.units.empty()) fail(spec.file, spec.where + ": a STEP file carries its own length unit: give no unit for it");
        auto model = cad::import_step(spec.file, {.linear_deflection = o.linear_deflection, .angular_deflection = o.angular_deflection});
        if (!model) fail(model.error());
        auto step = std::make_unique<StepSource>();
        step->model = std::move(*model);
        Scene sub = cad::assembly_scene(step->model);
        for (const std::string& w : sub.warnings) scene.warnings.push_back(spec.file + ": " + w);
        const double scale = 1.0 / working_mm;  // STEP geometry is in mm
        for (Body& b : sub.bodies) {
          b.source.file = spec.file;
          if (scale == 1) continue;
          TriMesh m = *b.mesh;
          for (Vec3& v : m.positions) v = v * scale;
          b.mesh = std::make_shared<const TriMesh>(std::move(m));
          b.pose.t = b.pose.t * scale;
          b.tessellation_error *= scale;
        }
        bodies = std::move(sub.bodies);
        adopt(spec, bodies, true);
        // The check sees the bodies as the scene has them, at their indices from `first`.
        step->first = scene.bodies.size();
        step->sub.units = o.units;
        step->sub.bodies = bodies;
        step->check = cad::nominal_fit_check(step->model, step->sub);
        step->fits = cad::zero_clearance_fit_check(step->model, step->sub);
        steps->push_back(std::move(step));
#else
        fail(spec.file, spec.where + ": STEP input needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)");
#endif
      } else if (is_fem(spec.file)) {
        FemSceneOptions fo;
        fo.split = o.fem_split, fo.linear_faces = o.fem_linear_faces;
        fo.unit = spec.units.empty() ? "mm" : spec.units;
        fo.unit_scale = mm_per(fo.unit, spec.file, spec.where + " units") / working_mm;
        fo.working_unit = o.units;
        fo.select = spec.select, fo.displacement_scale = o.fem_scale, fo.field = o.fem_field;
        fo.displacement_csv = o.fem_disp;
        auto fs = read_fem_scene(spec.file, fo);
        if (!fs) fail(fs.error());
        for (const std::string& w : fs->warnings) scene.warnings.push_back(w);
        if (!fs->frames.empty()) {
          if (!scene.frames.empty()) fail(spec.file, "a second input with displacement steps: a scene's motion comes from one source");
          const auto offset = static_cast<std::uint32_t>(scene.bodies.size());
          scene.frames = std::move(fs->frames);
          for (Frame& f : scene.frames) {
            for (auto& p : f.poses) p.body += offset;
            for (auto& sh : f.shapes) sh.body += offset;
          }
        }
        bodies = std::move(fs->bodies);
        adopt(spec, bodies, false);  // (fem_scene applied `select`: its frames index every body)
      } else if (is_gltf(spec.file)) {
        const double scale = mm_per(spec.units.empty() ? "m" : spec.units, spec.file, spec.where + " units") / working_mm;
        auto gb = read_gltf_bodies(spec.file, scale);
        if (!gb) fail(gb.error());
        bodies = std::move(*gb);
        if (!spec.units.empty())
          for (Body& b : bodies) b.unit = spec.units;
        adopt(spec, bodies, true);
      } else {
        if (mesh_error[mesh_of[si]]) fail(*mesh_error[mesh_of[si]]);
        bodies.push_back(mesh_body(spec, meshes[mesh_of[si]]));
      }
      for (Body& b : bodies) {
        if (!b.mesh || b.mesh->num_triangles() == 0) fail(spec.file, "body '" + b.id + "' has no triangles");
        check_posed(b, spec.file);
        scene.bodies.push_back(std::move(b));
      }
    }
    std::vector<std::string> before;
    for (const Body& b : scene.bodies) before.push_back(b.id);
    make_ids_unique(scene);
    for (std::size_t i = 0; i < before.size(); ++i)
      if (before[i] != scene.bodies[i].id)
        scene.warnings.push_back("two bodies have the id '" + before[i] + "': the later one is '" + scene.bodies[i].id +
                                 "' (ids then depend on the order of the inputs: give ids in a scene file)");
#ifdef INTERFERE_HAS_CAD
    if (!steps->empty()) {
      out.keep_alive = steps;
      out.nominal_fit = [steps](std::uint32_t a, std::uint32_t b, const Model& wa, const Model& wb, const ClashResult& r,
                                double depth) {
        for (const auto& s : *steps) {
          const std::size_t n = s->sub.bodies.size();
          if (a >= s->first && a < s->first + n && b >= s->first && b < s->first + n)
            return s->check(static_cast<std::uint32_t>(a - s->first), static_cast<std::uint32_t>(b - s->first), wa, wb, r, depth);
        }
        return false;  // bodies of different files share no B-Rep faces
      };
      // The same body ranges for the zero-clearance fits (issue #29: as assembly-clash classifies them).
      out.zero_clearance_fits.reach = [steps](std::uint32_t a) {
        for (const auto& s : *steps)
          if (a >= s->first && a < s->first + s->sub.bodies.size()) return s->fits.reach(static_cast<std::uint32_t>(a - s->first));
        return 0.0;
      };
      out.zero_clearance_fits.check = [steps](std::uint32_t a, std::uint32_t b, double* gap) {
        for (const auto& s : *steps) {
          const std::size_t n = s->sub.bodies.size();
          if (a >= s->first && a < s->first + n && b >= s->first && b < s->first + n)
            return s->fits.check(static_cast<std::uint32_t>(a - s->first), static_cast<std::uint32_t>(b - s->first), gap);
        }
        return false;
      };
    }
#endif
  } catch (const LoadError& e) {
    return e.error;
  }
  return out;
}

}  // namespace interfere::scene
