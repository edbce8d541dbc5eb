// Touching parts whose interiors overlap all the same (query/clash.h, ClashResult::touching_overlap):
// faces that coincide while the solids interpenetrate, such as two blocks shifted along a face or a
// part seated inside another on a common face. Their surfaces meet only in touching pairs, so the
// crossing pairs (paper 1's clash) miss them. Decided exactly: a point of one surface that is not
// on the other and lies inside it (exact ray parity, containment.cpp) proves the overlap.
//
// Probes of part X against the closed part Y: one vertex of each connected set of X's triangles
// that touch nothing of Y (such a set lies wholly inside or outside Y, and its vertices are
// exactly off Y's surface), and the centroid of each triangle of X that touches Y (a triangle
// touching Y along an edge, as the sides of a part seated on a face, has its centroid inside Y
// when the part is). A centroid exactly on Y's surface, strictly inside a coplanar triangle of Y,
// compares their orientations instead: the same outward side means both solids lie on the same
// side of the common face (an instance placed twice, a part seated in another), the opposite one
// a face contact (even where a part fills a cavity of the other exactly).
#include <algorithm>
#include <numeric>

#include "clash_internal.h"
#include "interfere/core/predicates.h"
#include "interfere/mesh/validate.h"

namespace interfere::detail {
namespace {

// An apex off the plane of t (exactly): with it, orient3d gives the in-plane side of p for each
// edge. false for a degenerate triangle (a segment or a point).
bool apex_of(const std::array<Vec3, 3>& t, Vec3& apex) {
  apex = t[0] + cross(t[1] - t[0], t[2] - t[0]);
  if (orient3d(t[0], t[1], t[2], apex) != 0) return true;
  for (const Vec3& d : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    apex = t[0] + d;
    if (orient3d(t[0], t[1], t[2], apex) != 0) return true;
  }
  return false;
}

// Where p lies with respect to the surface of m, for a probe of the triangle tx through which p is
// taken: off it (0), on it (1), or strictly inside a triangle of it coplanar with tx, whose outward
// side is tx's (2: the two solids lie on the same side of a common face, so their interiors
// overlap there) or the opposite one (3: a face contact).
int on_surface(const Model& m, const Vec3& p, const std::array<Vec3, 3>& tx) {
  int found = 0;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const BvhNode& n = m.bvh.nodes[stack.back()];
    stack.pop_back();
    bool inside_box = true;  // (float boxes rounded outwards: conservative)
    for (int k = 0; k < 3; ++k) inside_box = inside_box && double(n.box.lo[k]) <= p[k] && p[k] <= double(n.box.hi[k]);
    if (!inside_box) continue;
    if (!n.is_leaf()) {
      stack.push_back(n.first);
      stack.push_back(n.first + 1);
      continue;
    }
    for (std::uint32_t k = 0; k < n.count; ++k) {
      const auto t = m.mesh.corners(m.bvh.prims[n.first + k]);
      Vec3 apex;
      if (orient3d(t[0], t[1], t[2], p) != 0 || !apex_of(t, apex)) continue;
      const int s0 = orient3d(t[0], t[1], apex, p), s1 = orient3d(t[1], t[2], apex, p), s2 = orient3d(t[2], t[0], apex, p);
      if ((s0 < 0 || s1 < 0 || s2 < 0) && (s0 > 0 || s1 > 0 || s2 > 0)) continue;  // in the plane, outside
      found = std::max(found, 1);
      const bool strictly = s0 != 0 && s1 != 0 && s2 != 0;
      const bool coplanar = orient3d(t[0], t[1], t[2], tx[0]) == 0 && orient3d(t[0], t[1], t[2], tx[1]) == 0 &&
                            orient3d(t[0], t[1], t[2], tx[2]) == 0;
      Vec3 ax;
      if (!strictly || !coplanar || !apex_of(tx, ax)) continue;
      // tx's outward side (where its normal points) against t's: the sign of t's orientation at it.
      const bool same = (orient3d(t[0], t[1], t[2], ax) > 0) == (orient3d(tx[0], tx[1], tx[2], ax) > 0);
      return same ? 2 : 3;
    }
  }
  return found;
}

// +1: a probe of x lies inside y; 0: every probe decided outside (or on y); -1: a probe undecided.
int probe(const Model& x, const Model& y, const std::vector<char>& touches) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  // Connected sets of the triangles that touch nothing (shared edges of the welded mesh).
  std::vector<char> free_of(nt);
  for (std::uint32_t t = 0; t < nt; ++t) free_of[t] = !touches[t];
  const std::vector<std::uint32_t> set = edge_connected_sets(m, free_of);
  int result = 0;
  const auto test = [&](const Vec3& p) {
    const int in = point_in_closed_mesh(y, p);
    if (in == 1) return true;
    if (in < 0) result = -1;
    return false;
  };
  for (std::uint32_t t = 0; t < nt; ++t)
    if (!touches[t] && set[t] == t && test(m.positions[m.triangles[t][0]])) return 1;
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (!touches[t]) continue;
    const auto c = m.corners(t);
    const Vec3 p = (c[0] + c[1] + c[2]) / 3.0;
    const int where = on_surface(y, p, c);
    if (where == 2 || (where == 0 && test(p))) return 1;
  }
  return result;
}

}  // namespace

int touching_overlap(const Model& a, const Model& b, const std::vector<TrianglePair>& pairs) {
  std::vector<char> ta(a.mesh.num_triangles(), 0), tb(b.mesh.num_triangles(), 0);
  for (const TrianglePair& p : pairs) ta[p.a] = 1, tb[p.b] = 1;
  const int ab = probe(a, b, ta);
  if (ab == 1) return 1;
  const int ba = probe(b, a, tb);
  if (ba == 1) return 1;
  return ab < 0 || ba < 0 ? -1 : 0;
}

}  // namespace interfere::detail
