// Scene inputs of `interfere clash` (apps/cli/scene_input.h): the library's loader
// (scene/load.h), with progress lines, warnings on stderr and errors as InputError.
#include "scene_input.h"

#include "interfere/scene/load.h"

namespace interfere::cli {

SceneInput load_scene(const std::vector<scene::BodySpec>& specs, const SceneInputOptions& o) {
  scene::LoadOptions lo{.units = o.units,
                        .linear_deflection = o.tessellation.linear_deflection,
                        .angular_deflection = o.tessellation.angular_deflection,
                        .fem_split = o.fem_split,
                        .fem_linear_faces = o.fem_linear_faces,
                        .fem_field = o.fem_field,
                        .fem_disp = o.fem_disp,
                        .fem_scale = o.fem_scale};
  lo.reading = [](const std::string& file) {
    if (!Progress::quiet()) std::fprintf(stderr, "[interfere] reading %s\n", file.c_str());
  };
  auto loaded = scene::load_scene(specs, lo);
  if (!loaded) throw InputError(loaded.error());
  SceneInput in;
  in.scene = std::move(loaded->scene);
  in.files = std::move(loaded->files);
  in.nominal_fit = std::move(loaded->nominal_fit);
  in.keep_alive = std::move(loaded->keep_alive);
  in.warnings = std::move(in.scene.warnings);
  in.scene.warnings.clear();
  for (const std::string& w : in.warnings) warning(w);
  return in;
}

}  // namespace interfere::cli
