// Plain helpers of the CAD model (issue #6, item 1): names of the AAG attributes, instances merged
// into one world mesh with per-instance face ids.
#include "interfere/cad/model.h"

namespace interfere::cad {

const char* surface_type_name(SurfaceType t) {
  switch (t) {
    case SurfaceType::plane: return "plane";
    case SurfaceType::cylinder: return "cylinder";
    case SurfaceType::cone: return "cone";
    case SurfaceType::sphere: return "sphere";
    case SurfaceType::torus: return "torus";
    case SurfaceType::bspline: return "bspline";
    case SurfaceType::other: return "other";
  }
  return "other";
}
const char* curve_type_name(CurveType t) {
  switch (t) {
    case CurveType::line: return "line";
    case CurveType::circle: return "circle";
    case CurveType::ellipse: return "ellipse";
    case CurveType::other: return "other";
  }
  return "other";
}
const char* convexity_name(Convexity c) {
  switch (c) {
    case Convexity::convex: return "convex";
    case Convexity::concave: return "concave";
    case Convexity::smooth: return "smooth";
  }
  return "smooth";
}

TriMesh world_mesh(const CadModel& model, std::vector<std::uint32_t>* face_ids) {
  TriMesh out;
  if (face_ids) face_ids->clear();
  std::uint32_t face_base = 0;
  for (const Instance& inst : model.instances) {
    const Part& p = model.parts[inst.part];
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (const Vec3& v : p.mesh.positions) out.positions.push_back(inst.placement.apply(v));
    for (const Tri& t : p.mesh.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    if (face_ids)
      for (std::uint32_t f : p.face_ids) face_ids->push_back(f + face_base);
    face_base += p.faces;
  }
  return out;
}

}  // namespace interfere::cad
