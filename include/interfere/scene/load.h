// Scene sources combined (issue #24, item 1): the bodies of scene-file entries or command-line
// inputs, each file expanded by its kind — a STEP assembly to its instances (cad/assembly_scene.h,
// with the nominal-fit rule), an FE model to its bodies and displacement steps (fem/bodies.h), a
// glTF scene to its nodes (scene/io.h), any other mesh file to one body — in the working unit,
// posed and range-checked. One loader for the CLI and Python (library interfere::scene_load,
// which links interfere::fem and, when built with OpenCASCADE, interfere::cad).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/io.h"

namespace interfere::scene {

struct LoadOptions {
  std::string units = "mm";  ///< the working unit
  double linear_deflection = 0;    ///< STEP tessellation (cad::ImportOptions; 0: 0.1 % of each part's diagonal)
  double angular_deflection = 0.5;
  std::string fem_split = "auto";  ///< FE inputs: FemSceneOptions::split
  bool fem_linear_faces = false;
  std::string fem_field;           ///< displacement field (steps become frames)
  std::string fem_disp;            ///< or a displacement CSV
  double fem_scale = 1;            ///< displacement scale
  /// Called before each file is read (progress lines).
  std::function<void(const std::string& file)> reading;
};

struct LoadedScene {
  Scene scene;                     ///< bodies, frames of an FE input's steps, warnings
  std::vector<std::string> files;  ///< the files read
  /// The nominal-fit check of the STEP assemblies read (SceneClashOptions::nominal_fit); unset
  /// without any. Refers to `keep_alive`.
  std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&, const ClashResult&, double)> nominal_fit;
  /// The zero-clearance fits of the STEP assemblies read (SceneClashOptions::zero_clearance_fits,
  /// cad::zero_clearance_fit_check: the classification assembly-clash makes; issue #29); unset
  /// without any. Refers to `keep_alive`.
  SceneClashOptions::ZeroClearanceFits zero_clearance_fits;
  std::shared_ptr<void> keep_alive;
};

/// Reads the bodies of every spec, in order, into one scene in `options.units`. Ids: a
/// single-body file's is the spec's id, else the file's stem; the bodies of a multi-body file get
/// "<id or stem>/<path>". Duplicate ids are made unique ("#2") with a warning (give ids in a
/// scene file to make them independent of the order). Units: the spec's, else by format (glTF
/// metres, STEP its own — giving one is an error —, mm otherwise). Errors name the file (and the
/// spec's `where`): unreadable files, STEP without OpenCASCADE, a `select` that selects nothing, a
/// body without triangles, a coordinate outside the supported range once converted and posed, two
/// inputs with displacement steps.
Expected<LoadedScene> load_scene(const std::vector<BodySpec>& specs, const LoadOptions& options);

/// Whether this build reads STEP files (OpenCASCADE).
bool load_supports_step();

}  // namespace interfere::scene
