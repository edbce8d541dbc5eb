// Test helpers for rows of two rollers of a built assembly (issue #27; test_scarred_pairs_*.cpp,
// test_assembly_tapered_scars.cpp): a roller as a ScenePart at a pose, and the mesh engine's clash
// verdict of two posed meshes (the independent confirmation of a clash).
#pragma once
#include <cstddef>

#include "interfere/bearing/assembly.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere::bearing::test {

/// Part i of `as` (a roller: its intact cylinder or frustum, mesh, tree and solid) at `pose`.
inline ScenePart scene_part(const Assembly& as, std::size_t i, const Transform& pose) {
  const BearingSpec& b = as.spec.bearings[as.parts[i].bearing];
  ScenePart s;
  s.cylinder = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, pose);
  s.mesh = as.parts[i].roller.get(), s.tree = as.parts[i].tree.get(), s.solid = as.parts[i].solid.get();
  s.pose = pose;
  return s;
}

/// Whether the mesh engine finds the two posed meshes' interiors overlapping.
inline bool meshes_clash(const TriMesh& a, const Transform& pa, const TriMesh& b, const Transform& pb) {
  const Model ma = make_model(transformed(a, pa)), mb = make_model(transformed(b, pb));
  ClashRequest rq;
  rq.parallel = false;
  rq.regions = false;
  return clash(ma, mb, rq).verdict == Verdict::clash;
}

}  // namespace interfere::bearing::test
