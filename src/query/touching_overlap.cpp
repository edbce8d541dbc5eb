// Touching parts whose interiors overlap all the same (query/clash.h, ClashResult::touching_overlap):
// faces that coincide while the solids interpenetrate, such as two blocks shifted along a face or a
// part seated inside another on a common face. Their surfaces meet only in touching pairs, so the
// crossing pairs (paper 1's clash) miss them. Decided exactly: a point of one surface that is not
// on the other and lies inside it (exact ray parity, containment.cpp) proves the overlap.
//
// Probes of part X against the closed part Y: one vertex of each connected set of X's triangles
// that touch nothing of Y (such a set lies wholly inside or outside Y, and its vertices are
// exactly off Y's surface), and, for each triangle of X that touches Y: where a triangle of Y lies
// in its plane with overlapping interiors (exact: orient3d), their outward sides compared (the
// same side means both solids lie on the same side of the common face: an instance placed twice,
// a part seated in another; the opposite one a face contact, even where a part fills a cavity of
// the other exactly); else its centroid (a triangle touching Y along an edge, as the sides of a
// part seated on a face, has its centroid inside Y when the part is; the centroid is rounded, so
// it is used only where Y's surface lies farther from it than that rounding).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "clash_internal.h"
#include "interfere/core/predicates.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/distance.h"

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

// Whether two triangles of one plane (apex: a point off it) have overlapping relative interiors:
// no edge line of either has the other wholly on its outer side or on it (the separating-axis test
// in the plane, exact with orient3d).
bool coplanar_interiors_overlap(const std::array<Vec3, 3>& t, const std::array<Vec3, 3>& u, const Vec3& apex) {
  const auto separates = [&](const std::array<Vec3, 3>& e, const std::array<Vec3, 3>& other) {
    for (int i = 0; i < 3; ++i) {
      const Vec3 &p = e[i], &q = e[(i + 1) % 3];
      const int in = orient3d(p, q, apex, e[(i + 2) % 3]);
      if (in == 0) return true;  // (a degenerate triangle has no interior)
      bool all_out = true;
      for (const Vec3& v : other) all_out = all_out && orient3d(p, q, apex, v) * in <= 0;
      if (all_out) return true;
    }
    return false;
  };
  return !separates(t, u) && !separates(u, t);
}

// The pair's triangles lie in one plane with overlapping interiors: 2 when they have the same
// outward side (the two solids lie on the same side of a common face: their interiors overlap
// there), 3 when opposite ones (a face contact), 0 otherwise.
int coplanar_side(const std::array<Vec3, 3>& t, const std::array<Vec3, 3>& tx) {
  Vec3 apex;
  if (!apex_of(tx, apex)) return 0;
  if (orient3d(tx[0], tx[1], tx[2], t[0]) != 0 || orient3d(tx[0], tx[1], tx[2], t[1]) != 0 ||
      orient3d(tx[0], tx[1], tx[2], t[2]) != 0 || !coplanar_interiors_overlap(t, tx, apex))
    return 0;
  // Outward sides compared at the apex (tx's normal side, or any point off the plane).
  return (orient3d(t[0], t[1], t[2], apex) > 0) == (orient3d(tx[0], tx[1], tx[2], apex) > 0) ? 2 : 3;
}

// +1: a probe of x lies inside y; 0: every probe decided outside (or on y); -1: a probe undecided.
// touches[t]: 0 touches nothing of y, 1 touches it, 2 shares a face with it (a coplanar triangle of
// y with overlapping interior and the opposite outward side: a face contact, no probe needed).
int probe(const Model& x, const Model& y, const std::vector<char>& touches) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  // Connected sets of the triangles that touch nothing (through shared vertices, which touch
  // nothing either).
  std::vector<char> free_of(nt);
  for (std::uint32_t t = 0; t < nt; ++t) free_of[t] = !touches[t];
  const std::vector<std::uint32_t> set = connected_sets(m, free_of);
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
    if (touches[t] == 2) continue;  // (a face contact there)
    const auto c = m.corners(t);
    const Vec3 p = (c[0] + c[1] + c[2]) / 3.0;
    // The rounded centroid stands for the exact one (within a few units in the last place of the
    // corners' largest coordinate) only where y's surface is farther than that: else no claim.
    double scale = 0;
    for (const Vec3& v : c) scale = std::max({scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    const double rounding = 64 * std::numeric_limits<double>::epsilon() * scale;
    if (surface_distance(y, p) > rounding && test(p)) return 1;
  }
  return result;
}

}  // namespace

int touching_overlap(const Model& a, const Model& b, const std::vector<TrianglePair>& pairs) {
  std::vector<char> ta(a.mesh.num_triangles(), 0), tb(b.mesh.num_triangles(), 0);
  // A triangle's coplanar partner is among the triangles it touches: the pairs decide common faces
  // (in parallel; the flags are merged in pair order).
  std::vector<char> side(pairs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i)
      side[i] = static_cast<char>(coplanar_side(b.mesh.corners(pairs[i].b), a.mesh.corners(pairs[i].a)));
  });
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (side[i] == 2) return 1;
    ta[pairs[i].a] = std::max<char>(ta[pairs[i].a], side[i] == 3 ? 2 : 1);
    tb[pairs[i].b] = std::max<char>(tb[pairs[i].b], side[i] == 3 ? 2 : 1);
  }
  const int ab = probe(a, b, ta);
  if (ab == 1) return 1;
  const int ba = probe(b, a, tb);
  if (ba == 1) return 1;
  return ab < 0 || ba < 0 ? -1 : 0;
}

}  // namespace interfere::detail
