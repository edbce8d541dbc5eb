// Assembly semantics (issue #6, item 4), after He & Xu (SJTU 2023) §3: rules (JSON) map a
// constraint type of an assembly step to the feature types and the feature roles whose faces take
// part in it (bolt connection -> through hole + top and bottom faces; gear on shaft -> outer
// cylinder + adjacent ring face; screw tightening -> counterbored hole + seat face); a process
// description (JSON) lists the steps with their parts and constraint type, so the assembly features
// of step P_i are selected automatically. OCCT-free.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "interfere/cad/features.h"

namespace interfere::cad {

struct SemanticRule {
  std::string name;        ///< e.g. "bolt_connection"
  std::string constraint;  ///< the constraint type it applies to
  struct Need {
    std::string feature;             ///< feature type (must exist in the library)
    std::vector<std::string> roles;  ///< roles whose faces are assembly features (empty = all)
    /// He & Xu §3's added faces, "feature.Add(TopFace and BottomFace)": "TopFace" (the face the
    /// hole enters from: role "top"), "BottomFace" (the face it leaves on: role "bottom", else the
    /// AAG neighbours of its innermost bore, "bore" or "wall", that are not the feature's own faces,
    /// e.g. the casing's inner ring face under a counterbored screw hole). Issue #29, item 3.
    std::vector<std::string> add;
    /// The added faces are kept only within this multiple of the hole's radius (TopFace: its largest
    /// radius, the counterbore's; BottomFace: its smallest, the bore's) from its axis: the clamped
    /// region under a washer or a head (ISO 7089 washers: outer diameter about 2 d). 0: whole faces.
    double clamp_radius_factor = 2.0;
    /// A hole whose planar top or bottom face (when added) is smaller than the clamped annulus
    /// (pi ((k r)^2 - r^2)) is no clamped hole and is skipped for this rule, with a warning (the
    /// casing's main bore, r = 88, in a flange ring of 28,000 mm^2: no washer fits).
    bool require_clamp_fit = true;
  };
  std::vector<Need> needs;
};
struct SemanticRules {
  std::vector<SemanticRule> rules;
};

struct ProcessStep {
  std::string id;
  std::vector<std::string> parts;  ///< part names ("*" = every part)
  std::string constraint;
};
struct Process {
  std::vector<ProcessStep> steps;
};

/// Parses rules and checks every feature type and role against `library`: a rule referring to an
/// unknown feature type or role, naming no feature, or named twice is an error naming the rule.
Expected<SemanticRules> parse_semantic_rules(const std::string& json_text, const FeatureLibrary& library,
                                             const std::string& source = "");
Expected<SemanticRules> load_semantic_rules(const std::filesystem::path& path, const FeatureLibrary& library);
Expected<SemanticRules> default_semantic_rules(const FeatureLibrary& library);
Expected<Process> parse_process(const std::string& json_text, const std::string& source = "");
Expected<Process> load_process(const std::filesystem::path& path);

/// Part of a face kept as an assembly feature: its points within `radius` of the axis line (the
/// clamped annulus around a hole on its TopFace/BottomFace).
struct Annulus {
  std::uint32_t face = 0;
  Vec3 axis_point, axis;  ///< the hole's axis (unit direction)
  double radius = 0;      ///< the clamped region's outer radius
};

struct Selection {
  std::vector<std::uint32_t> faces;  ///< sorted face ids that are assembly features of the step (whole faces)
  std::vector<Annulus> annuli;       ///< parts of other faces that are (Need::add with a clamp)
  std::vector<const Feature*> features_used;
  std::vector<std::string> warnings;  ///< e.g. a constraint with no rule, a rule with no feature found
};

/// Warnings for the parts step `step_id` names that are none of `part_names` ("*" matches every
/// part): such a step would silently keep no feature of a misspelt part. Each names the step, the
/// part and the parts there are. Unknown step ids give nothing here (select_assembly_features
/// reports them as errors).
std::vector<std::string> unknown_step_parts(const Process& process, const std::string& step_id,
                                            const std::vector<std::string>& part_names);

/// Whether step `step_id` names `name` (a part or an instance) or "*"; false for an unknown step.
bool step_includes(const Process& process, const std::string& step_id, const std::string& name);

/// The faces step `step_id`'s rules select on a part with `features`, whatever the step's part
/// list says (for a part of which only some instances take part). Errors: unknown step id, a
/// step constraint no rule knows (a misspelt constraint would leave the features unprotected).
/// `aag`: the part's graph, for BottomFace where the feature has no "bottom" role and for the
/// clamp-fit test (without it: role faces only, no fit test).
Expected<Selection> select_step_features(const Process& process, const std::string& step_id,
                                         const SemanticRules& rules, const std::string& part_name,
                                         const std::vector<Feature>& features, const Aag* aag = nullptr);

/// Assembly-feature faces of `part_name` (with its recognised `features`) in step `step_id`.
/// Errors as select_step_features. A part not in the step selects nothing.
Expected<Selection> select_assembly_features(const Process& process, const std::string& step_id,
                                             const SemanticRules& rules, const std::string& part_name,
                                             const std::vector<Feature>& features, const Aag* aag = nullptr);

/// The triangles of `mesh` (per-triangle `face_ids`) inside the selection's annuli: on the annulus'
/// face with every corner within its radius of its axis line. Sorted. (BRepMesh puts no vertex
/// inside a planar face: its triangles fan the hole's rim out to the face's far border and few lie
/// inside; the rim itself is kept by the hole's wall. Curved faces, and finer meshes, have them.)
std::vector<std::uint32_t> annulus_triangles(const TriMesh& mesh, const std::vector<std::uint32_t>& face_ids,
                                             const std::vector<Annulus>& annuli);

}  // namespace interfere::cad
