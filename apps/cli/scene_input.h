// The scene of `interfere clash` with one input, three or more, a scene file with "bodies", or
// scene options (issue #24, item 7): the library's loader (scene/load.h) with the CLI's progress
// lines, warnings on stderr and errors as InputError.
#pragma once
#include <string>
#include <vector>

#include "common.h"
#include "interfere/scene/load.h"

namespace interfere::cli {

/// scene::load_scene, printing "reading FILE" progress lines and the loader's warnings; the
/// warnings move from the scene into `warnings` (the report's). Throws InputError on error.
scene::LoadedScene load_scene(const std::vector<scene::BodySpec>& specs, scene::LoadOptions options,
                              std::vector<std::string>& warnings);

}  // namespace interfere::cli
