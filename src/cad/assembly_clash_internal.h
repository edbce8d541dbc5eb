// Internal (src/cad): the parts of assembly_clash (assembly_clash.cpp) kept in their own files.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interfere/cad/assembly_clash.h"
#include "interfere/query/depth.h"
#include "interfere/query/model.h"

namespace interfere::cad::detail {


/// Whether the crossings of two placed parts (`r`, on their world models `wa` and `wb`, whose
/// triangles are the parts' in order, placed rigidly by `place_a` and `place_b`) are a nominal fit
/// (assembly_fit.cpp): every crossing pair has a face coinciding with one of the other part, and
/// the sampled depth is within the tessellation error. False for a part without faces or AAG.
bool nominal_fit(const Part& part_a, const Transform& place_a, const Part& part_b, const Transform& place_b,
                 const Model& wa, const Model& wb, const ClashResult& r, double depth, double tessellation_error);

/// Whether placed parts a and b meet on coincident B-Rep faces although their tessellations may not
/// (assembly_fit.cpp, issue #29): a plane of each back to back, a cylinder or sphere of each of one
/// radius back to back (coincide() within `tol`), whose placed triangles come within `reach`. `gap`:
/// the smallest such distance. False for a part without faces or AAG.
bool zero_clearance_fit(const Part& part_a, const Transform& place_a, const Part& part_b, const Transform& place_b,
                        double tol, double reach, double* gap = nullptr);

/// The same for instances a and b of `model`, world[i] the world model of instance i.
inline bool nominal_fit(const CadModel& model, std::uint32_t a, std::uint32_t b, const std::vector<Model>& world,
                        const ClashResult& r, double depth, double tessellation_error) {
  const Instance &ia = model.instances[a], &ib = model.instances[b];
  return nominal_fit(model.parts[ia.part], ia.placement, model.parts[ib.part], ib.placement, world[a], world[b], r,
                     depth, tessellation_error);
}

}  // namespace interfere::cad::detail
