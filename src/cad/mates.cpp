// Mates from geometry (issue #29, item 4): holes recognised per part (hole_recognition.cpp through
// recognize_features), boss-sense cylinders per part, both placed by the instances' transforms;
// an insertion is a cylinder coaxial with a hole, of one of its radii, overlapping it along the axis
// (a bolt or rod in a plate's hole, a nut on a bolt); a planar contact is two planes back to back
// whose faces' regions overlap with a positive area (their tessellations, exact 2D predicates).
#include "interfere/cad/mates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "interfere/core/predicates.h"

namespace interfere::cad {
namespace {

using Tri = std::array<Vec3, 3>;

/// Do two triangles lying (within rounding) in one plane of normal n overlap with a positive area?
/// Projected along n's largest coordinate, both oriented counter-clockwise; their interiors are
/// disjoint iff an edge line of one has the other entirely on its outer closed side (two convex
/// polygons: a separating line can be taken through an edge). orient2d is exact on the projected
/// coordinates: triangles touching along an edge or at a point do not overlap.
bool triangles_overlap_2d(const Tri& a, const Tri& b, int drop) {
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  double pa[3][2], pb[3][2];
  for (int i = 0; i < 3; ++i) {
    pa[i][0] = a[i][u], pa[i][1] = a[i][v];
    pb[i][0] = b[i][u], pb[i][1] = b[i][v];
  }
  const auto ccw = [](double (&p)[3][2]) {
    const int o = orient2d(p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1]);
    if (o < 0) std::swap(p[1], p[2]);
    return o != 0;
  };
  if (!ccw(pa) || !ccw(pb)) return false;  // a degenerate triangle has no area
  const auto separates = [](const double (&p)[3][2], const double (&q)[3][2]) {
    for (int e = 0; e < 3; ++e) {
      const double* s = p[e];
      const double* t = p[(e + 1) % 3];
      bool all_out = true;
      for (int k = 0; k < 3 && all_out; ++k) all_out = orient2d(s[0], s[1], t[0], t[1], q[k][0], q[k][1]) <= 0;
      if (all_out) return true;
    }
    return false;
  };
  return !separates(pa, pb) && !separates(pb, pa);
}

/// Do two faces' triangles (world) in one plane of normal n overlap with a positive area?
bool regions_overlap(const std::vector<Tri>& fa, const std::vector<Tri>& fb, const Vec3& n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  for (const Tri& a : fa) {
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min({a[0][d], a[1][d], a[2][d]});
      hi[d] = std::max({a[0][d], a[1][d], a[2][d]});
    }
    for (const Tri& b : fb) {
      bool apart = false;
      for (int d = 0; d < 3 && !apart; ++d) {
        if (d == drop) continue;
        apart = std::max({b[0][d], b[1][d], b[2][d]}) <= lo[d] || std::min({b[0][d], b[1][d], b[2][d]}) >= hi[d];
      }
      if (!apart && triangles_overlap_2d(a, b, drop)) return true;
    }
  }
  return false;
}

struct Cyl {  // a boss-sense cylinder face, placed
  std::uint32_t face = 0;
  Vec3 p, a;
  double r = 0, lo = 0, hi = 0;  // extent along a from p
};
struct Hole {
  const Feature* f = nullptr;
  Vec3 p, a;
  double lo = 0, hi = 0;
};
struct Box {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3& q) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
  }
  bool overlaps(const Box& o, double tol) const {
    return lo.x <= o.hi.x + tol && o.lo.x <= hi.x + tol && lo.y <= o.hi.y + tol && o.lo.y <= hi.y + tol &&
           lo.z <= o.hi.z + tol && o.lo.z <= hi.z + tol;
  }
};

Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return l > 0 ? v / l : v;
}

std::string constraint_of(const std::string& hole_type) {
  if (hole_type == "blind_hole") return "pin";
  if (hole_type == "counterbored_hole" || hole_type == "counterdrilled_hole") return "screw";
  if (hole_type == "countersunk_hole") return "countersunk_screw";
  return "bolt";
}

}  // namespace

const char* mate_kind_name(Mate::Kind k) { return k == Mate::Kind::insertion ? "insertion" : "planar_contact"; }

std::vector<Mate> infer_mates(const CadModel& model, const FeatureLibrary& library, double relative_tolerance) {
  std::vector<std::vector<Feature>> features(model.parts.size());
  for (std::size_t i = 0; i < model.parts.size(); ++i) features[i] = recognize_features(model.parts[i].aag, library);
  Box all;
  // Per instance: holes, cylinders, plane face boxes, all in world coordinates.
  struct Placed {
    Box box;  // the instance's placed triangles
    std::vector<Hole> holes;
    std::vector<Cyl> cyls;
    std::map<std::uint32_t, Box> plane_box;
    std::map<std::uint32_t, Vec3> plane_point;  // a vertex of the face, world
    std::map<std::uint32_t, std::vector<Tri>> plane_tris;  // the face's triangles, world
  };
  std::vector<Placed> placed(model.instances.size());
  for (std::size_t k = 0; k < model.instances.size(); ++k) {
    const Instance& inst = model.instances[k];
    const Part& part = model.parts[inst.part];
    const Transform& t = inst.placement;
    for (std::size_t tri = 0; tri < part.mesh.num_triangles(); ++tri) {
      const std::uint32_t f = tri < part.face_ids.size() ? part.face_ids[tri] : 0;
      const bool plane = f < part.aag.nodes.size() && part.aag.nodes[f].type == SurfaceType::plane;
      Tri placed_tri;
      for (int c = 0; c < 3; ++c) {
        const Vec3 q = t.apply(part.mesh.positions[part.mesh.triangles[tri][c]]);
        placed_tri[c] = q;
        all.add(q);
        placed[k].box.add(q);
        if (plane) {
          placed[k].plane_box[f].add(q);
          placed[k].plane_point.emplace(f, q);
        }
      }
      if (plane) placed[k].plane_tris[f].push_back(placed_tri);
    }
    for (const Feature& f : features[inst.part]) {
      if (f.type.find("hole") == std::string::npos || norm(f.axis) == 0) continue;
      Hole h;
      h.f = &f;
      h.p = t.apply(f.axis_point), h.a = unit(t.rotate(f.axis));
      h.lo = 1e300, h.hi = -1e300;
      for (std::uint32_t x : f.faces) {
        const AagNode& n = part.aag.nodes[x];
        if (n.type != SurfaceType::cylinder && n.type != SurfaceType::cone) continue;
        for (double s : {n.axial_min, n.axial_max}) {
          const double h_s = dot(t.apply(n.axis_point + n.axis * s) - h.p, h.a);
          h.lo = std::min(h.lo, h_s), h.hi = std::max(h.hi, h_s);
        }
      }
      if (h.lo <= h.hi) placed[k].holes.push_back(h);
    }
    for (const AagNode& n : part.aag.nodes)
      if (n.type == SurfaceType::cylinder && !n.hole) {
        Cyl c;
        c.face = n.face;
        c.p = t.apply(n.axis_point), c.a = unit(t.rotate(n.axis)), c.r = n.radius;
        c.lo = std::min(n.axial_min, n.axial_max), c.hi = std::max(n.axial_min, n.axial_max);
        placed[k].cyls.push_back(c);
      }
  }
  const double tol = relative_tolerance * std::max(1.0, norm(all.hi - all.lo));
  constexpr double angle = 1e-3;
  std::vector<Mate> out;
  for (std::uint32_t ka = 0; ka < placed.size(); ++ka)
    for (std::uint32_t kb = 0; kb < placed.size(); ++kb) {
      // Instances whose boxes are apart have no mate (a broad phase: an assembly of many instances
      // is not tried face by face for every pair).
      if (ka == kb || !placed[ka].box.overlaps(placed[kb].box, tol)) continue;
      // Insertions: a hole of a, a cylinder of b.
      for (const Hole& h : placed[ka].holes) {
        Mate m;
        for (const Cyl& c : placed[kb].cyls) {
          if (norm(cross(h.a, c.a)) > angle) continue;
          const Vec3 d = c.p - h.p;
          if (norm(d - h.a * dot(d, h.a)) > tol) continue;
          if (std::none_of(h.f->radii.begin(), h.f->radii.end(), [&](double r) { return std::abs(r - c.r) <= tol; })) continue;
          const double s = dot(c.a, h.a) > 0 ? 1.0 : -1.0, off = dot(c.p - h.p, h.a);
          const double c0 = off + s * c.lo, c1 = off + s * c.hi;
          if (std::max(c0, c1) <= h.lo + tol || std::min(c0, c1) >= h.hi - tol) continue;  // no axial overlap
          m.faces_b.push_back(c.face);
          m.radius = c.r;
        }
        if (m.faces_b.empty()) continue;
        m.kind = Mate::Kind::insertion;
        m.instance_a = ka, m.instance_b = kb;
        m.feature_type = h.f->type, m.constraint = constraint_of(h.f->type);
        m.faces_a = h.f->faces;
        m.axis_point = h.p, m.axis = h.a;
        out.push_back(std::move(m));
      }
      if (kb < ka) continue;  // planar contacts once per pair
      const Part& pa = model.parts[model.instances[ka].part];
      const Part& pb = model.parts[model.instances[kb].part];
      Mate m;
      for (const auto& [fa, ba] : placed[ka].plane_box) {
        const AagNode& na = pa.aag.nodes[fa];
        const Vec3 nA = unit(model.instances[ka].placement.rotate(na.normal));
        const Vec3 qA = placed[ka].plane_point.at(fa);
        for (const auto& [fb, bb] : placed[kb].plane_box) {
          const AagNode& nb = pb.aag.nodes[fb];
          const Vec3 nB = unit(model.instances[kb].placement.rotate(nb.normal));
          if (norm(nA + nB) > angle || !ba.overlaps(bb, tol)) continue;
          // One plane: a vertex of b on a's plane; and the faces' regions overlap (not only their
          // boxes: a face around a pocket or hole, an L-shaped face).
          if (std::abs(dot(placed[kb].plane_point.at(fb) - qA, nA)) > tol) continue;
          if (!regions_overlap(placed[ka].plane_tris.at(fa), placed[kb].plane_tris.at(fb), nA)) continue;
          if (std::find(m.faces_a.begin(), m.faces_a.end(), fa) == m.faces_a.end()) m.faces_a.push_back(fa);
          if (std::find(m.faces_b.begin(), m.faces_b.end(), fb) == m.faces_b.end()) m.faces_b.push_back(fb);
        }
      }
      if (m.faces_a.empty()) continue;
      m.kind = Mate::Kind::planar_contact;
      m.instance_a = ka, m.instance_b = kb;
      m.feature_type = "plane";
      std::sort(m.faces_a.begin(), m.faces_a.end()), std::sort(m.faces_b.begin(), m.faces_b.end());
      out.push_back(std::move(m));
    }
  return out;
}

}  // namespace interfere::cad
