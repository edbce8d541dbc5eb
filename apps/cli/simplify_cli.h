// `interfere simplify` (issue #6, items 5-7), split by stage: the options and their checks, the
// input (mesh or STEP) with its regions and features (simplify_input.cpp), the JSON report
// (simplify_report.cpp), the run and the outputs (cmd_simplify.cpp).
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common.h"
#include "view_output.h"
#include "interfere/mesh/io.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/qem.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/pipeline.h"
#endif

namespace interfere::cli {

struct SimplifyCliOptions {
  std::string input, output, json, regions, features, step, process, format = "auto", feature_mode = "weight", seams = "auto";
  std::string parts_dir;  ///< STEP input: each simplified part (prototype) also written here
  std::string units;      ///< --units: a mesh input's unit (default: m for glTF, mm otherwise; STEP: its own)
  std::string library, rules;  ///< --library, --rules: JSON files instead of the installed ones
  std::string lod;        ///< --lod R1,R2,...: glTF output, coarser levels (fractions of the budget) as MSFT_lod
  std::string mates = "auto";
  std::string mesher = "default";  ///< --mesher default|delabella: a STEP input's triangulation (cad::ImportOptions::delabella)  ///< --mates auto|off: a STEP input without --process keeps what the inferred mates pick
  std::size_t target = 0;
  double ratio = 0;
  double sharp_angle = 0;
  double crease_angle = 40;  ///< --crease-angle: glTF normals of a mesh without faces or regions
  double max_error = 0, max_error_rel = 0;  ///< --max-error (model units), --max-error-rel (of the diagonal)
  StepTessellation tessellation;  ///< (its `given`: resolve_step_tessellation, when the command runs)
  std::size_t renderer_max = 0;
  bool lock = false, check_self = false, no_error = false, no_guard = false, strict_guard = false;
  bool crease_given = false;      ///< --crease-angle on the command line
  int threads = 0;
  ViewOutputs views;  ///< --html, --glb, --pvd (issue #25): the original and the simplified mesh
};

/// How OUT is written: glTF, or a mesh format (automatic: by OUT's extension).
struct SimplifyOutput {
  bool glb = false;  ///< glTF: binary (.glb, --format glb) or JSON (.gltf, --format gltf) as `container` says
  GltfContainer container = GltfContainer::glb;
  MeshFormat format = MeshFormat::automatic;
};

/// Every check of the options that needs no file read: budgets, modes, angles, limits, the
/// options that go with a STEP input or a mesh only, the outputs (known formats, existing
/// directories, none equal to an input or to each other). Throws InputError; nothing is written.
SimplifyOutput check_simplify_options(const SimplifyCliOptions& o);

/// The library options of the command line (budget, modes, guard, error); the input's face ids,
/// features and limits are added by load_simplify_input.
SimplifyOptions simplify_options(const SimplifyCliOptions& o);

/// The input: a mesh (with its --regions or --sharp-angle regions as face ids and the --features
/// among them) or a STEP model prepared for the process step (its parts, instances and
/// features; the report's `cad` object and warnings). Then --max-error(-rel) and --renderer-max
/// set the limit and the budget. Throws InputError naming the file.
struct SimplifyInput {
  TriMesh mesh;
#ifdef INTERFERE_HAS_CAD
  std::unique_ptr<cad::Prepared> cad;
#endif
};
#ifdef INTERFERE_HAS_CAD
using ImportedModel = cad::CadModel;
#else
struct ImportedModel {};
#endif
/// `model`: the STEP input already imported (--step all imports it once for every step).
SimplifyInput load_simplify_input(const SimplifyCliOptions& o, const ImportedModel* model, SimplifyOptions& so,
                                  nlohmann::json& report);

/// The report's fields of a result (docs/simplify.md "simplify report"), added to `report`.
void add_result_report(nlohmann::json& report, const SimplifyResult& r, const SimplifyOptions& so,
                       const SimplifyCliOptions& o);
#ifdef INTERFERE_HAS_CAD
/// The report's parts_simplified: one entry per part simplified (a part's self-intersections
/// counted with `count_self`, their sum over the instances added to `self_total`).
nlohmann::json parts_report(const cad::Prepared& prep, const cad::AssemblySimplifyResult& a, bool count_self,
                            std::size_t& self_total);
#endif

}  // namespace interfere::cli
