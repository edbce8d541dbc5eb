// Guigue & Devillers, "Fast and Robust Triangle-Triangle Overlap Test Using Orientation
// Predicates", JGT 8(1), 2003, evaluated with plain double determinants (NOT robust:
// near-degenerate and coplanar configurations may be misjudged). Kept as the paper's baseline
// strategy; the engine uses tri_tri_exact, which is the same decision structure on exact
// predicates.
//  §3: reject when one triangle's corners are strictly on one side of the other's plane; rotate so
//      that corner 0 is alone on its side; the intervals on the planes' intersection line overlap
//      iff two 4-point orientations have the right sign (written here with the side signs folded
//      in instead of GD's swap of corners, see tri_tri_exact.cpp step 3).
//  §4 (coplanar): double orient2d in the projection dropping the normal's dominant axis; the
//      triangles overlap unless an edge line of one has the other strictly outside (SAT on edges),
//      a simpler decision than GD's region tree with the same result in exact arithmetic.
#include <cmath>

#include "interfere/np/tri_tri.h"
#include "tri_tri_internal.h"

namespace interfere {
namespace {

using Tri = std::array<Vec3, 3>;
using np_detail::alone_index;

inline int sign_of(double v) {
  return (v > 0) - (v < 0);
}

/// sign det[q-p, r-p, s-p] in double.
inline int orient_o(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  return sign_of(dot(cross(q - p, r - p), s - p));
}

inline double orient2(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j) {
  return (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
}

bool coplanar_2d(const Tri& a, const Tri& b, const Vec3& n) {
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  const int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  auto separated = [i, j](const Tri& t, const Tri& u) {
    const double ot = orient2(t[0], t[1], t[2], i, j);
    for (int e = 0; e < 3; ++e) {
      const Vec3& e0 = t[e];
      const Vec3& e1 = t[(e + 1) % 3];
      if (orient2(e0, e1, u[0], i, j) * ot < 0 && orient2(e0, e1, u[1], i, j) * ot < 0 &&
          orient2(e0, e1, u[2], i, j) * ot < 0)
        return true;
    }
    return false;
  };
  return !separated(a, b) && !separated(b, a);
}

}  // namespace

bool tri_tri_guigue_devillers(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  // Heights of B's corners against plane(A) (normal computed once, as in the paper).
  const Vec3 na = cross(a[1] - a[0], a[2] - a[0]);
  int hb[3];
  for (int i = 0; i < 3; ++i) hb[i] = sign_of(dot(na, b[i] - a[0]));
  if (hb[0] == hb[1] && hb[1] == hb[2] && hb[0] != 0) return false;
  const Vec3 nb = cross(b[1] - b[0], b[2] - b[0]);
  int ha[3];
  for (int i = 0; i < 3; ++i) ha[i] = sign_of(dot(nb, a[i] - b[0]));
  if (ha[0] == ha[1] && ha[1] == ha[2] && ha[0] != 0) return false;
  if (ha[0] == 0 && ha[1] == 0 && ha[2] == 0) return coplanar_2d(a, b, na);
  if (hb[0] == 0 && hb[1] == 0 && hb[2] == 0) return coplanar_2d(a, b, na);

  const int ra = alone_index(ha), rb = alone_index(hb);
  const int sa = ha[ra] != 0 ? -ha[ra] : ha[(ra + 1) % 3];
  const int sb = hb[rb] != 0 ? -hb[rb] : hb[(rb + 1) % 3];
  const int sigma = sa * sb;
  const Vec3& a0 = a[ra];
  const Vec3& b0 = b[rb];
  const Vec3& low_a = a[(ra + (sa < 0 ? 2 : 1)) % 3];
  const Vec3& high_a = a[(ra + (sa < 0 ? 1 : 2)) % 3];
  const Vec3& low_b = b[(rb + (sb < 0 ? 1 : 2)) % 3];
  const Vec3& high_b = b[(rb + (sb < 0 ? 2 : 1)) % 3];
  if (orient_o(a0, low_a, b0, high_b) * sigma < 0) return false;
  if (orient_o(a0, high_a, b0, low_b) * sigma > 0) return false;
  return true;
}

}  // namespace interfere
