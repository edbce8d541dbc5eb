// STEP -> features -> assembly features of a step -> one mesh with face ids ready for
// interfere::simplify (issue #6): the glue used by `interfere simplify` and `interfere features`.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/semantics.h"

namespace interfere::cad {

struct PipelineOptions {
  double linear_deflection = 0, angular_deflection = 0.5;
  std::string library_file, rules_file;  ///< empty = installed defaults
  std::string process_file, step;        ///< both empty = no semantics (no features kept, unless `mates`)
  /// Without a process (issue #29, item 4): the assembly features are those the mates inferred from
  /// the geometry pick (select_mate_features with the rules of rules_file or the installed ones);
  /// nothing is kept where the model has no mates. Ignored with a process.
  bool mates = false;
  bool delabella = false;  ///< ImportOptions::delabella
};

struct PreparedPart {
  std::string name;
  TriMesh mesh;                              ///< part coordinates
  std::vector<std::uint32_t> face_ids;       ///< per triangle, the part's B-Rep face
  std::vector<std::uint32_t> feature_faces;  ///< assembly-feature faces of the step (part's ids)
  std::uint32_t faces = 0;
  std::size_t instances = 0;
  /// Index of the CAD part (a part whose instances differ in taking part in the step is prepared
  /// twice, with and without the step's features; the first is named "<part> [<step>]").
  std::uint32_t model_part = 0;
  /// How far the tessellation may lie from the B-Rep: Part::tessellation_error (its deviation
  /// measured on import). A simplification's error bound is relative to the tessellation; relative
  /// to the B-Rep add this.
  double tessellation_error = 0;
  /// Triangles (part indices) kept as assembly features besides those of `feature_faces`: the
  /// clamped annuli of the step's TopFace/BottomFace (Selection::annuli, issue #29), for
  /// SimplifyOptions::feature_triangles.
  std::vector<std::uint32_t> feature_triangles;
  bool has_color = false;  ///< Part::has_color, color
  float color[3] = {0, 0, 0};
};
struct PreparedInstance {
  std::string name;
  std::uint32_t part = 0;  ///< index into Prepared::parts
  Transform placement;
  std::uint32_t face_offset = 0;  ///< added to the part's face ids in the world mesh
  std::string path;               ///< product-tree path (Instance::path)
};

struct Prepared {
  std::vector<PreparedPart> parts;  ///< for per-part simplification
  std::vector<PreparedInstance> instances;
  TriMesh mesh;                         ///< every instance in world coordinates
  std::vector<std::uint32_t> face_ids;  ///< unique per instance
  std::vector<std::uint32_t> feature_faces;
  std::string report_json;              ///< parts, instances, features, selection
  std::vector<std::string> warnings;
};

/// The feature library, semantic rules and process of the options' files (the installed defaults
/// where library_file or rules_file is empty; no rules without a process, unless `mates`), read before a STEP file
/// so that a mistake there is reported without the import's wait. With a process, options.step
/// ("all": every step of it) is checked too: a step of the process whose constraint a rule knows.
struct Semantics {
  FeatureLibrary library;
  SemanticRules rules;
  std::optional<Process> process;
};
Expected<Semantics> load_semantics(const PipelineOptions& options);

/// Imports `step_file` (options' deflections) and prepares it for process step options.step. The
/// library, rules and process files are read first.
Expected<Prepared> prepare_for_simplify(const std::string& step_file, const PipelineOptions& options);
/// The same for a model already imported (one import for several process steps: `--step all`).
Expected<Prepared> prepare_for_simplify(const CadModel& model, const PipelineOptions& options);

/// Adds faces to keep, named by their ids in the world mesh (a part's face id plus its instance's
/// face_offset, as Prepared::face_ids and the written outputs number them; for a one-part file the
/// ids `interfere features` lists): each goes to the simplified part its instance uses, so it is kept
/// on every instance sharing that part, and `feature_faces` is rebuilt. Errors: an id no instance
/// has (naming it and the range there is); nothing is changed then.
Status add_feature_faces(Prepared& prepared, const std::vector<std::uint32_t>& world_ids);

/// Whether process step `step` takes in instance `k` of `model`: it names the instance, its part
/// or "*".
bool instance_in_step(const Process& process, const std::string& step, const CadModel& model, std::size_t k);
/// Whether it takes in part `part`: it names the part, "*", or one of the part's instances.
bool part_in_step(const Process& process, const std::string& step, const CadModel& model, std::uint32_t part);
/// The assembly-feature faces process step `step` selects on part `part` of `model` (recognised
/// `features`): select_step_features when the step takes the part in (part_in_step: by its name,
/// "*" or one of its instances), else an empty selection. Errors as select_step_features.
Expected<Selection> part_step_selection(const Process& process, const std::string& step, const SemanticRules& rules,
                                        const CadModel& model, std::uint32_t part,
                                        const std::vector<Feature>& features);
/// unknown_step_parts against the names of the model's parts and instances.
std::vector<std::string> unknown_step_names(const Process& process, const std::string& step, const CadModel& model);

}  // namespace interfere::cad
