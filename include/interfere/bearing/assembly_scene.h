// A bearing assembly's parts as scene bodies (scene/scene.h; issue #27, "bearing assemblies as
// scene bodies"): one body per part, id = the part id ("ID/inner", "ID/rollerK", ...), its closed
// outward mesh in its body frame, posed by `poses` (default: the rest poses), source kind
// `primitive` with the part kind as detail, tags = the bearing id and the part kind. The scene
// engine (scene/engine.h) and the mesh queries can check them; motion files name them.
#pragma once
#include <vector>

#include "interfere/bearing/assembly.h"
#include "interfere/scene/scene.h"

namespace interfere::bearing {

scene::Scene assembly_scene(const Assembly& as, const std::vector<Transform>* poses = nullptr);

}  // namespace interfere::bearing
