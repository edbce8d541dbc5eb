// Nominal fits of an assembly's instance pairs (include/interfere/cad/assembly_clash.h,
// InstancePairResult::nominal_fit): tessellations that cross only where B-Rep faces coincide (a
// bolt in a hole of its own diameter), recognised from the faces' AAG parameters (issue #6, item 2)
// placed by the instances' transforms.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "assembly_clash_internal.h"
#include "interfere/np/distance.h"

namespace interfere::cad::detail {
namespace {

// The face node of a part, placed in the world.
struct PlacedFace {
  SurfaceType type = SurfaceType::other;
  Vec3 normal, axis_point, axis;
  double radius = 0, offset = 0;  // plane: normal . p
  bool hole = false;
};

PlacedFace placed(const AagNode& n, const Transform& t) {
  PlacedFace f;
  f.type = n.type, f.radius = n.radius, f.hole = n.hole;
  f.normal = t.rotate(n.normal);
  f.axis = t.rotate(n.axis);
  f.axis_point = t.apply(n.axis_point);
  return f;  // (a plane's offset is set by the caller, through a placed triangle of the face)
}

// Whether faces fa (of one instance) and fb (of the other) are one surface (within tol: lengths;
// angles in radians): planes back to back (material on opposite sides), a sphere in a seat, and
// coaxial cylinders of one radius, back to back (a bolt in its hole) or on the same side (two
// bores in line, as a nut's on a plate's: their walls meet at the rim).
bool coincide(const PlacedFace& fa, const PlacedFace& fb, double tol, double angle) {
  if (fa.type != fb.type) return false;
  const auto unit = [](const Vec3& v) { return v / norm(v); };
  switch (fa.type) {
    case SurfaceType::plane:
      return norm(unit(fa.normal) + unit(fb.normal)) <= angle &&
             std::fabs(fa.offset + fb.offset) <= tol;
    case SurfaceType::cylinder: {
      if (std::fabs(fa.radius - fb.radius) > tol) return false;
      const Vec3 a = unit(fa.axis), b = unit(fb.axis);
      if (norm(cross(a, b)) > angle) return false;
      const Vec3 d = fb.axis_point - fa.axis_point;
      return norm(d - a * dot(d, a)) <= tol;  // b's axis point on a's axis
    }
    case SurfaceType::sphere:
      return fa.hole != fb.hole && std::fabs(fa.radius - fb.radius) <= tol &&
             norm(fa.axis_point - fb.axis_point) <= tol;
    default:
      return false;
  }
}

}  // namespace

bool nominal_fit(const Part& part_a, const Transform& place_a, const Part& part_b, const Transform& place_b,
                 const Model& wa, const Model& wb, const ClashResult& r, double depth, double tessellation_error) {
  if (part_a.face_ids.empty() || part_b.face_ids.empty() || part_a.aag.nodes.empty() || part_b.aag.nodes.empty())
    return false;
  const double size = norm(wa.mesh.bounds().extent()) + norm(wb.mesh.bounds().extent());
  const double tol = kFitTolerance * size, angle = kFitTolerance;
  const auto face_of = [&](const Part& part, const Transform& placement, std::uint32_t t, const TriMesh& w) {
    PlacedFace f = placed(part.aag.nodes[part.face_ids[t]], placement);
    if (f.type == SurfaceType::plane) {  // the plane through the placed triangle
      const auto c = w.corners(t);
      f.offset = dot(f.normal / norm(f.normal), (c[0] + c[1] + c[2]) / 3.0);
    }
    return f;
  };
  // The faces of A and of B that coincide back to back with a face of the other, among the
  // pairs (crossing or touching); a crossing pair is explained when one of its faces is one.
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> coincident;  // (face of A, face of B)
  std::set<std::uint32_t> fit_a, fit_b;
  for (const TrianglePair& q : r.pairs) {
    if (q.a >= part_a.face_ids.size() || q.b >= part_b.face_ids.size()) continue;
    const auto key = std::make_pair(part_a.face_ids[q.a], part_b.face_ids[q.b]);
    auto it = coincident.find(key);
    if (it == coincident.end())
      it = coincident
               .emplace(key, coincide(face_of(part_a, place_a, q.a, wa.mesh), face_of(part_b, place_b, q.b, wb.mesh),
                                      tol, angle))
               .first;
    if (it->second) fit_a.insert(key.first), fit_b.insert(key.second);
  }
  // A face crossing the other part may coincide with one of its faces that it does not meet
  // (a nut's seat a hair inside the plate's top face: parallel, so no pair): each face of the
  // crossing pairs, not yet explained, against every face of the other part (a triangle of
  // each face places it).
  const auto first_triangles = [](const Part& part) {
    std::vector<std::uint32_t> first(part.aag.nodes.size(), 0xffffffffu);
    for (std::uint32_t t = static_cast<std::uint32_t>(part.face_ids.size()); t-- > 0;)
      if (part.face_ids[t] < first.size()) first[part.face_ids[t]] = t;
    return first;
  };
  const std::vector<std::uint32_t> first_a = first_triangles(part_a),
                                   first_b = first_triangles(part_b);
  std::set<std::uint32_t> crossing_a, crossing_b;
  for (const TrianglePair& q : r.pairs)
    if (q.kind == ContactKind::cross && q.a < part_a.face_ids.size() &&
        q.b < part_b.face_ids.size())
      crossing_a.insert(part_a.face_ids[q.a]), crossing_b.insert(part_b.face_ids[q.b]);
  const auto explain = [&](const std::set<std::uint32_t>& crossing, bool of_a) {
    for (const std::uint32_t f : crossing) {
      if ((of_a ? fit_a : fit_b).count(f)) continue;
      const std::vector<std::uint32_t>& others = of_a ? first_b : first_a;
      for (std::uint32_t g = 0; g < others.size(); ++g) {
        const std::uint32_t fa = of_a ? f : g, fb = of_a ? g : f;
        if (others[g] != 0xffffffffu &&
            coincide(face_of(part_a, place_a, first_a[fa], wa.mesh), face_of(part_b, place_b, first_b[fb], wb.mesh),
                     tol, angle)) {
          fit_a.insert(fa), fit_b.insert(fb);
          break;
        }
      }
    }
  };
  explain(crossing_a, true);
  explain(crossing_b, false);
  bool fit = !fit_a.empty() && depth <= tessellation_error;
  for (const TrianglePair& q : r.pairs) {
    if (!fit) break;
    if (q.kind != ContactKind::cross) continue;
    fit = (q.a < part_a.face_ids.size() && fit_a.count(part_a.face_ids[q.a])) ||
          (q.b < part_b.face_ids.size() && fit_b.count(part_b.face_ids[q.b]));
  }
  return fit;
}

// Zero-clearance fits from the B-Rep (issue #29, item 4: "zero-clearance fits classified from the
// B-Rep as contacts ... whatever the tessellation"): a pair whose tessellations neither cross nor
// touch (an AP203 export's placements rounded to 1e-12 mm apart, a tessellation whose rims miss)
// is still in contact where two of its B-Rep faces are one surface back to back (coincide(), the
// same test as the nominal fit's) and their regions meet: the faces' triangles come within `reach`.
bool zero_clearance_fit(const Part& part_a, const Transform& place_a, const Part& part_b, const Transform& place_b,
                        double tol, double reach, double* gap) {
  if (part_a.face_ids.empty() || part_b.face_ids.empty() || part_a.aag.nodes.empty() || part_b.aag.nodes.empty())
    return false;
  struct FaceTris {
    PlacedFace face;
    std::vector<std::array<Vec3, 3>> tris;
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  };
  const auto faces_of = [](const Part& part, const Transform& t) {
    std::map<std::uint32_t, FaceTris> out;
    for (std::size_t i = 0; i < part.face_ids.size() && i < part.mesh.num_triangles(); ++i) {
      const std::uint32_t f = part.face_ids[i];
      if (f >= part.aag.nodes.size()) continue;
      const SurfaceType type = part.aag.nodes[f].type;
      if (type != SurfaceType::plane && type != SurfaceType::cylinder && type != SurfaceType::sphere) continue;
      auto [it, fresh] = out.try_emplace(f);
      FaceTris& ft = it->second;
      std::array<Vec3, 3> c;
      for (int k = 0; k < 3; ++k) {
        c[k] = t.apply(part.mesh.positions[part.mesh.triangles[i][k]]);
        ft.lo = {std::min(ft.lo.x, c[k].x), std::min(ft.lo.y, c[k].y), std::min(ft.lo.z, c[k].z)};
        ft.hi = {std::max(ft.hi.x, c[k].x), std::max(ft.hi.y, c[k].y), std::max(ft.hi.z, c[k].z)};
      }
      if (fresh) {
        ft.face = placed(part.aag.nodes[f], t);
        if (type == SurfaceType::plane) ft.face.offset = dot(ft.face.normal / norm(ft.face.normal), (c[0] + c[1] + c[2]) / 3.0);
      }
      ft.tris.push_back(c);
    }
    return out;
  };
  const auto fa_all = faces_of(part_a, place_a), fb_all = faces_of(part_b, place_b);
  const double angle = kFitTolerance;
  bool found = false;
  double best = reach;
  for (const auto& [ia, fa] : fa_all)
    for (const auto& [ib, fb] : fb_all) {
      if (fa.face.type != fb.face.type) continue;
      // Curved faces in contact lie back to back (a bolt's shank in a bore), not on one side (two
      // bores in line, which meet at a rim only where their planes touch).
      if (fa.face.type != SurfaceType::plane && fa.face.hole == fb.face.hole) continue;
      if (fa.lo.x > fb.hi.x + reach || fb.lo.x > fa.hi.x + reach || fa.lo.y > fb.hi.y + reach ||
          fb.lo.y > fa.hi.y + reach || fa.lo.z > fb.hi.z + reach || fb.lo.z > fa.hi.z + reach)
        continue;
      if (!coincide(fa.face, fb.face, tol, angle)) continue;
      for (const auto& ta : fa.tris) {
        if (std::min({ta[0].x, ta[1].x, ta[2].x}) > fb.hi.x + reach || std::max({ta[0].x, ta[1].x, ta[2].x}) < fb.lo.x - reach ||
            std::min({ta[0].y, ta[1].y, ta[2].y}) > fb.hi.y + reach || std::max({ta[0].y, ta[1].y, ta[2].y}) < fb.lo.y - reach ||
            std::min({ta[0].z, ta[1].z, ta[2].z}) > fb.hi.z + reach || std::max({ta[0].z, ta[1].z, ta[2].z}) < fb.lo.z - reach)
          continue;
        for (const auto& tb : fb.tris) {
          const double d = triangle_triangle_closest(ta, tb).distance;
          if (d <= best) best = d, found = true;
          if (found && (!gap || best == 0)) {
            if (gap) *gap = best;
            return true;
          }
        }
      }
    }
  if (found && gap) *gap = best;
  return found;
}

}  // namespace interfere::cad::detail
