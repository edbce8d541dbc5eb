// Mates inferred from an assembly's geometry (issue #29, item 4; He & Xu 2023 §3: the assembly
// constraint of a step decides which features it keeps). OCCT-free.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {

struct Mate {
  enum class Kind : std::uint8_t {
    insertion,       ///< a boss-sense cylinder of instance b coaxial with a hole of instance a, of the hole's radius
    planar_contact,  ///< planes of a and b back to back (opposite normals, one plane) whose face boxes overlap
  };
  Kind kind = Kind::insertion;
  std::uint32_t instance_a = 0, instance_b = 0;  ///< indices into CadModel::instances
  /// insertion: the hole's feature type (through_hole, blind_hole, ...) and the constraint it implies
  /// (through_hole/stepped_hole: "bolt", blind_hole: "pin", counterbored_hole: "screw",
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

}  // namespace interfere::cad
