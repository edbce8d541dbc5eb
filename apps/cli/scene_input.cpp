// Scene inputs of `interfere clash` (apps/cli/scene_input.h).
#include "scene_input.h"

#include <cstdio>

namespace interfere::cli {

scene::LoadedScene load_scene(const std::vector<scene::BodySpec>& specs, scene::LoadOptions options,
                              std::vector<std::string>& warnings) {
  options.reading = [](const std::string& file) {
    if (!Progress::quiet()) std::fprintf(stderr, "[interfere] reading %s\n", file.c_str());
  };
  auto loaded = scene::load_scene(specs, options);
  if (!loaded) throw InputError(loaded.error());
  warnings = std::move(loaded->scene.warnings);
  loaded->scene.warnings.clear();
  for (const std::string& w : warnings) warning(w);
  return std::move(*loaded);
}

}  // namespace interfere::cli
