// A bearing assembly's parts as scene bodies (bearing/assembly_scene.h).
#include "interfere/bearing/assembly_scene.h"

namespace interfere::bearing {

scene::Scene assembly_scene(const Assembly& as, const std::vector<Transform>* poses) {
  scene::Scene sc;
  for (std::size_t i = 0; i < as.parts.size(); ++i) {
    const AssemblyPart& p = as.parts[i];
    scene::Body body;
    body.id = p.id;
    body.name = p.id;
    body.path = "/" + as.spec.bearings[p.bearing].id + "/" + p.id.substr(p.id.find('/') + 1);
    body.mesh = p.mesh;
    body.pose = poses != nullptr ? (*poses)[i] : p.rest;
    body.source.kind = scene::SourceKind::primitive;
    body.source.file = as.spec.file;
    body.source.detail = std::string(part_kind_name(p.kind)) + (p.scarred ? " (scarred)" : "");
    body.tags = {as.spec.bearings[p.bearing].id, part_kind_name(p.kind)};
    sc.bodies.push_back(std::move(body));
  }
  return sc;
}

}  // namespace interfere::bearing
