// Mates inferred from an assembly's geometry (issue #29, item 4; He & Xu 2023 §3: the assembly
// constraint of a step decides which features it keeps). OCCT-free.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/semantics.h"

namespace interfere::cad {

struct Mate {
  enum class Kind : std::uint8_t {
    insertion,       ///< a boss-sense cylinder of instance b coaxial with a hole of instance a, of the hole's radius
    planar_contact,  ///< planes of a and b back to back (opposite normals, one plane) whose face boxes overlap
  };
  Kind kind = Kind::insertion;
  std::uint32_t instance_a = 0, instance_b = 0;  ///< indices into CadModel::instances
  /// insertion: the hole's feature type (through_hole, blind_hole, ...) and the constraint it implies
  /// (through_hole/stepped_hole: "bolt", blind_hole: "pin", counterbored_hole and counterdrilled_hole: "screw",
  /// countersunk_hole: "countersunk_screw"); planar_contact: "plane" and "".
  std::string feature_type, constraint;
  std::vector<std::uint32_t> faces_a, faces_b;  ///< part face ids (a: the hole's faces; b: the cylinder / the planes)
  Vec3 axis_point, axis;                        ///< insertion, world
  double radius = 0;                            ///< insertion
};

/// Every insertion and planar contact between two different instances. Tolerance: lengths within
/// `relative_tolerance` of the assembly's bounding-box diagonal, directions within 1e-3 rad; a
/// cylinder's radius must equal one of the hole's cylinder radii (zero clearance) and their axial
/// extents overlap. Planar contacts compare the faces' triangle boxes (not the exact face regions).
std::vector<Mate> infer_mates(const CadModel& model, const FeatureLibrary& library, double relative_tolerance = 1e-6);

const char* mate_kind_name(Mate::Kind k);

/// The assembly features the inferred mates pick, per part (issue #29, item 4: "the assembly features
/// are found without a hand-written process file"), as a process step would select them:
/// - an insertion's hole: the rule of the mate's constraint (a through hole with a bolt in it: the
///   `bolt` rule, wall + TopFace/BottomFace annuli; counterbored: `screw`; ...) applied to that hole
///   alone; where the rule keeps nothing of it (a type the rule does not name, a face too small for
///   the clamped annulus: the rule's warning is kept) the hole's own faces;
/// - an insertion's inserted cylinder (a bolt's shank, a rod): its faces;
/// - a planar contact: the contact faces of the side whose faces are smaller in total (a nut's or a
///   head's seat, a bracket's foot; both sides when equal): the larger side's face around a hole is
///   kept as the hole's annulus, not whole.
/// A part used by several instances is simplified once: its selection is the union over the mates
/// of all its instances. `instances[k]`: whether instance k takes part in a mate.
struct MateSelection {
  std::vector<Mate> mates;
  std::vector<Selection> parts;       ///< per CadModel::parts (features_used left empty)
  std::vector<std::uint8_t> instances;
  std::vector<std::string> warnings;
};
/// Errors: none but the rules' (a mate's constraint without a rule falls back to the hole's faces).
MateSelection select_mate_features(const CadModel& model, const FeatureLibrary& library, const SemanticRules& rules);

}  // namespace interfere::cad
