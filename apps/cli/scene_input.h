// The scene of `interfere clash` with one input, three or more, a scene file with "bodies", or
// scene options (issue #24, item 7): every input expands to its bodies (a STEP assembly to its
// instances, an FE model to its bodies and steps, a glTF scene to its nodes, a mesh file to one
// body), converted to the working unit, posed, range-checked.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/io.h"

namespace interfere::cli {

struct SceneInput {
  scene::Scene scene;
  std::vector<std::string> files;  ///< every file read (for the report and output checks)
  std::vector<std::string> warnings;
  /// The nominal-fit check of STEP assemblies (SceneClashOptions::nominal_fit), when any.
  std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&, const ClashResult&, double)> nominal_fit;
  std::shared_ptr<void> keep_alive;  ///< what nominal_fit refers to (CAD models)
};

struct SceneInputOptions {
  std::string units = "mm";  ///< working unit
  StepTessellation tessellation;
  std::string fem_split = "auto";
  bool fem_linear_faces = false;
  std::string fem_field;          ///< displacement field of FE inputs (steps become frames)
  std::string fem_disp;           ///< displacement CSV of the FE input (instead of a field)
  double fem_scale = 1;
};

/// Reads the bodies of every spec, in order. Ids: a spec's id, else the file's stem; the bodies of
/// a multi-body file get "<id>/<sub-id>". Duplicate ids from different specs are made unique
/// ("#2") with a warning (give ids in a scene file to make them independent of the order).
SceneInput load_scene(const std::vector<scene::BodySpec>& specs, const SceneInputOptions& options);

}  // namespace interfere::cli
