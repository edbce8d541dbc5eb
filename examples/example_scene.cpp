// Scenes: three bodies, one clash test, the clashes with their stable ids, and the JSON report
// (docs/scene.md, "Library").
#include <cstdio>
#include <memory>

#include "interfere/mesh/generate.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/report.h"

int main() {
  using namespace interfere;
  using namespace interfere::scene;
  const auto box = std::make_shared<const TriMesh>(make_box({0, 0, 0}, {10, 10, 10}));
  Scene s;  // working unit mm
  s.bodies.push_back({.id = "base", .name = "base", .mesh = box});
  s.bodies.push_back({.id = "block", .name = "block", .mesh = box, .pose = {.t = {5, 2, 2}}, .tags = {"moving"}});
  s.bodies.push_back({.id = "lid", .name = "lid", .mesh = box, .pose = {.t = {0, 0, 10}}});  // on base's top face
  ClashTest test;  // every pair, hard
  const SceneClashResult r = clash_scene(s, {test});
  for (const SceneClash& c : r.clashes)
    std::printf("%s %s-%s %s (%s), depth <= %g\n", c.id.c_str(), s.bodies[c.a].id.c_str(), s.bodies[c.b].id.c_str(),
                verdict_name(c.verdict), c.kind.c_str(), c.depth_bound);
  const std::string json = report_json(s, {test}, r, {.command = "example_scene"});
  // base-block and block-lid cross (clashes, 5 mm deep into base); base-lid touch (a contact).
  return r.clash_count == 2 && r.contact_count == 1 && json.find("interfere.scene-clash") != std::string::npos ? 0 : 1;
}
