// Exact triangle–triangle intersection with cross/touch classification and exact endpoint features.
//
// Method (decision structure of Guigue & Devillers, "Fast and Robust Triangle-Triangle Overlap Test
// Using Orientation Predicates", JGT 8(1), 2003, §3), every sign from the exact filtered predicates
// of core/predicates.h, so no epsilon anywhere. h_X(p) is the signed height of p over plane(X),
// the sign of det[x1-x0, x2-x0, p-x0] (= -orient3d), and nX = (x1-x0)x(x2-x0).
//  1. Signs of B's corners against plane(A) (one Orient3dPlane: the cross product and the filter's
//     permanent terms are shared), then of A's against plane(B); all equal and nonzero on either
//     side: disjoint (GD §3, first rejection).
//  2. If one side is all zero, the pair is coplanar or a triangle is degenerate (collinear or
//     repeated corners). If B's corners are all on plane(A) and A is certified non-degenerate, A's
//     corners are all on plane(B) too and are not evaluated (three exact zeros saved). Degenerate
//     triangles are replaced by their support, the segment between their lexicographic min and max
//     corners (a point if all equal; lexicographic order is the order along a line), and tested
//     exactly as segment/point vs triangle or segment (segments: coplanar, and overlapping in all
//     three coordinate projections, one of which is injective on their plane). Coplanar pairs are
//     tested in a coordinate projection where A is exactly non-degenerate, by the separating-edge
//     criterion: closed convex polygons are disjoint iff all corners of one lie strictly outside an
//     edge line of the other (the edges of their Minkowski difference). These pairs are never
//     cross.
//  3. Otherwise both planes cut the other triangle. Each triangle is rotated cyclically
//  (orientation
//     kept) so that corner 0 is alone on its side of the other plane; A ∩ plane(B) is then the
//     interval between X1 on edge a0a1 and X2 on edge a0a2, and B ∩ plane(A) between Y1 on b0b1 and
//     Y2 on b0b2, all on the line L = plane(A) ∩ plane(B) with direction d = nA x nB.
//     Ordering lemma (GD §3 in closed form): for X on edge p->q of A and Y on edge r->s of B,
//       det[q-p, r-p, s-p] = ((Y-X).d / |d|^2) (nB.(q-p)) (nA.(s-r)),
//     so sign((Y-X).d) = sign(det) * sA * sB with sA = sign(hB(q)-hB(p)), sB = sign(hA(s)-hA(r))
//     known from step 1. Within A, X2 precedes X1 along d iff a0 is above B (sA < 0); within B,
//     Y1 precedes Y2 iff b0 is above A. The triangles meet iff the intervals overlap: two orient3d
//     (GD's final test, with the side signs folded in instead of swapping corners).
//  4. Classification: cross iff each triangle has corners strictly on both sides of the other's
//     plane and both overlap inequalities are strict; otherwise touch. For cross pairs the segment
//     is [max(lowA, lowB), min(highA, highB)]; two more orient3d compare the lower ends and the
//     upper ends. An end that belongs to one interval only is on that triangle's boundary and in
//     the other's interior (face); equal ends lie on both boundaries. On a triangle, an end on edge
//     p->q is the vertex q when h(q) == 0 (p is strictly off the plane for cross pairs), else the
//     edge. All of this follows from predicate signs, so neighbouring pairs agree on features.
//  5. Endpoint coordinates (double, constructions only): a vertex feature is the exact corner; an
//     edge ∩ plane point interpolates accurate heights (Orient3dPlane::value: relative error
//     <= 2^-40 even for nearly coplanar input, where plain double heights are rounding noise), an
//     edge ∩ edge point accurate 2D heights. Both are computed from canonically ordered input (edge
//     ends sorted lexicographically, the plane's triangle in input order, the two edges sorted), so
//     pairs that share the edge produce bit-identical points.
#include <algorithm>
#include <utility>

#include "interfere/core/predicates.h"
#include "interfere/np/tri_tri.h"
#include "tri_tri_internal.h"

namespace interfere {
namespace {

using Tri = std::array<Vec3, 3>;
using np_detail::alone_index;

bool lex_less(const Vec3& a, const Vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

/// det[q-p, r-p, s-p]: positive when s is on the side of plane (p,q,r) the normal points to.
inline int orient_o(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  return -orient3d(p, q, r, s);
}

/// Support of a degenerate (collinear) triangle: its two extreme corners along the line.
std::pair<Vec3, Vec3> support(const Tri& t) {
  Vec3 lo = t[0], hi = t[0];
  for (int i = 1; i < 3; ++i) {
    if (lex_less(t[i], lo)) lo = t[i];
    if (lex_less(hi, t[i])) hi = t[i];
  }
  return {lo, hi};
}

bool is_degenerate(const Tri& t, const Orient3dPlane& plane) {
  if (plane.certainly_nondegenerate()) return false;
  return collinear(t[0], t[1], t[2]);
}

/// A coordinate axis along which the non-degenerate triangle t projects to a non-degenerate
/// triangle (exactly); the dominant normal component is tried first.
int projection_axis(const Tri& t, const Vec3& normal_hint) {
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3,
            [&](int i, int j) { return std::fabs(normal_hint[i]) > std::fabs(normal_hint[j]); });
  for (int k : order)
    if (orient2d_projected(t[0], t[1], t[2], k) != 0) return k;
  return order[0];  // unreachable for a non-degenerate triangle
}

inline int o2(const Vec3& a, const Vec3& b, const Vec3& c, int axis) {
  return orient2d_projected(a, b, c, axis);
}

/// Closed segment [p,q] (p == q allowed) vs closed non-degenerate triangle t, all in one plane,
/// in the projection `axis` (injective on that plane). Separating lines: t's edges, line pq.
bool coplanar_segment_triangle(const Vec3& p, const Vec3& q, const Tri& t, int axis) {
  const int ot = o2(t[0], t[1], t[2], axis);
  for (int i = 0; i < 3; ++i) {
    const Vec3& e0 = t[i];
    const Vec3& e1 = t[(i + 1) % 3];
    if (o2(e0, e1, p, axis) * ot < 0 && o2(e0, e1, q, axis) * ot < 0) return false;
  }
  const int s0 = o2(p, q, t[0], axis), s1 = o2(p, q, t[1], axis), s2 = o2(p, q, t[2], axis);
  if (s0 == s1 && s1 == s2 && s0 != 0) return false;
  return true;
}

/// Closed segment [p,q] (p == q allowed) vs closed non-degenerate triangle t in 3D.
bool segment_triangle(const Vec3& p, const Vec3& q, const Tri& t) {
  const Orient3dPlane plane(t[0], t[1], t[2]);
  const int sp = plane.side(p), sq = plane.side(q);
  if (sp == sq && sp != 0) return false;
  if (sp == 0 && sq == 0)
    return coplanar_segment_triangle(p, q, t, projection_axis(t, plane.normal()));
  // pq meets the plane in one point; it is in t iff pq passes on one side of all edges (or on
  // them).
  const int e0 = orient3d(p, q, t[0], t[1]);
  const int e1 = orient3d(p, q, t[1], t[2]);
  const int e2 = orient3d(p, q, t[2], t[0]);
  const bool pos = e0 > 0 || e1 > 0 || e2 > 0;
  const bool neg = e0 < 0 || e1 < 0 || e2 < 0;
  return !(pos && neg);
}

/// Projected closed segments [p,q], [r,s] (points allowed) intersect in projection `axis`.
bool segment_segment_2d(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int axis) {
  const int sr = o2(p, q, r, axis), ss = o2(p, q, s, axis);
  if (sr == ss && sr != 0) return false;
  const int sp = o2(r, s, p, axis), sq = o2(r, s, q, axis);
  if (sp == sq && sp != 0) return false;
  if (sr != 0 || ss != 0 || sp != 0 || sq != 0) return true;
  // Collinear in projection: overlap of the projected 1D ranges in lexicographic order.
  const int i = axis == 0 ? 1 : (axis == 1 ? 2 : 0);
  const int j = axis == 0 ? 2 : (axis == 1 ? 0 : 1);
  auto less = [&](const Vec3& a, const Vec3& b) {
    return a[i] != b[i] ? a[i] < b[i] : a[j] < b[j];
  };
  const Vec3& lo1 = less(q, p) ? q : p;
  const Vec3& hi1 = less(q, p) ? p : q;
  const Vec3& lo2 = less(s, r) ? s : r;
  const Vec3& hi2 = less(s, r) ? r : s;
  return !less(hi1, lo2) && !less(hi2, lo1);
}

/// Closed 3D segments (points allowed): coplanar and intersecting in all three projections (one of
/// them is injective on a plane containing both, and projecting never separates).
bool segment_segment(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  if (orient3d(p, q, r, s) != 0) return false;
  return segment_segment_2d(p, q, r, s, 2) && segment_segment_2d(p, q, r, s, 0) &&
         segment_segment_2d(p, q, r, s, 1);
}

/// Coplanar non-degenerate triangles, closed: not separated by any of the six edge lines.
bool coplanar_triangles(const Tri& a, const Tri& b, const Vec3& normal_hint_a) {
  const int axis = projection_axis(a, normal_hint_a);
  auto separated_by_edges_of = [axis](const Tri& t, const Tri& u) {
    const int ot = o2(t[0], t[1], t[2], axis);
    for (int i = 0; i < 3; ++i) {
      const Vec3& e0 = t[i];
      const Vec3& e1 = t[(i + 1) % 3];
      if (o2(e0, e1, u[0], axis) * ot < 0 && o2(e0, e1, u[1], axis) * ot < 0 &&
          o2(e0, e1, u[2], axis) * ot < 0)
        return true;
    }
    return false;
  };
  return !separated_by_edges_of(a, b) && !separated_by_edges_of(b, a);
}

/// Step 2 of the method: at least one triangle's corners all lie on the other's plane.
/// b_on_plane_a: all corners of b have orient3d 0 against a (a degenerate or b in plane(a)).
bool flat_case(const Tri& a, const Tri& b, bool b_on_plane_a, bool a_on_plane_b,
               const Orient3dPlane& pa, const Orient3dPlane& pb) {
  bool a_deg, b_deg;
  if (b_on_plane_a && a_on_plane_b) {
    a_deg = is_degenerate(a, pa);
    b_deg = is_degenerate(b, pb);
  } else {
    // One side only: the triangle whose plane zeroes the other's corners is degenerate (if it
    // were not, the other would lie in its plane and vice versa) and the other is not.
    a_deg = b_on_plane_a;
    b_deg = a_on_plane_b;
  }
  if (!a_deg && !b_deg) return coplanar_triangles(a, b, pa.normal());
  if (a_deg && b_deg) {
    const auto [p, q] = support(a);
    const auto [r, s] = support(b);
    return segment_segment(p, q, r, s);
  }
  if (a_deg) {
    const auto [p, q] = support(a);
    return segment_triangle(p, q, b);
  }
  const auto [r, s] = support(b);
  return segment_triangle(r, s, a);
}


/// Point where edge {p,q} crosses the plane of triangle t (the plane built from t's corners in
/// input order); canonical in the edge's ends. The heights are accurate values
/// (Orient3dPlane::value), so the point stays accurate when the edge is nearly parallel to the
/// plane.
Vec3 edge_plane_point(Vec3 p, Vec3 q, const Orient3dPlane& t) {
  if (lex_less(q, p)) std::swap(p, q);
  const double hp = t.value(p);
  const double hq = t.value(q);
  const double den = hp - hq;
  double alpha = den != 0 ? hp / den : 0.5;
  alpha = std::clamp(alpha, 0.0, 1.0);
  return p + (q - p) * alpha;
}

/// Point where the (coplanar, crossing) edges {p,q} and {r,s} meet; canonical in the two edges:
/// the first edge (lexicographically) is cut by the second edge's line, with accurate 2D heights
/// in the coordinate projection where the edges' plane is widest.
Vec3 edge_edge_point(Vec3 p, Vec3 q, Vec3 r, Vec3 s) {
  if (lex_less(q, p)) std::swap(p, q);
  if (lex_less(s, r)) std::swap(r, s);
  if (lex_less(r, p) || (r == p && lex_less(s, q))) {
    std::swap(p, r);
    std::swap(q, s);
  }
  // The projection in which the two edges are least parallel, judged on the accurate heights, not
  // on a double cross product, which is rounding noise for nearly parallel edges (fuzzing found a
  // case where the cross product picked a plane in which both edges project exactly parallel).
  double hp = 0, den = 0;
  for (int drop = 0; drop < 3; ++drop) {
    const int i = (drop + 1) % 3, j = (drop + 2) % 3;
    const double h_p = orient2d_value(r[i], r[j], s[i], s[j], p[i], p[j]);
    const double h_q = orient2d_value(r[i], r[j], s[i], s[j], q[i], q[j]);
    if (std::fabs(h_p - h_q) > std::fabs(den)) hp = h_p, den = h_p - h_q;
  }
  double alpha = den != 0 ? hp / den : 0.5;
  alpha = std::clamp(alpha, 0.0, 1.0);
  return p + (q - p) * alpha;
}

/// One end of the cross segment, expressed on a triangle rotated by `rot` (corner 0 alone):
/// it lies on edge 0 -> k (k = 1 or 2). `h` are the original-index heights against the other plane.
struct EdgeEnd {
  int rot, k;
};

Feature feature_of(const EdgeEnd& e, const int h[3]) {
  const int corner = (e.rot + e.k) % 3;
  if (h[corner] == 0) return {Feature::vertex, static_cast<std::uint8_t>(corner)};
  // Edge (rot, rot+1) is edge index rot; edge (rot, rot+2) is edge index rot+2.
  const int edge = e.k == 1 ? e.rot : (e.rot + 2) % 3;
  return {Feature::edge, static_cast<std::uint8_t>(edge)};
}

/// How much of the method to run: the yes/no answer, the kind, or the kind with the segment.
enum class Mode { intersects, kind, segment };

template <Mode kMode>
TriTriResult evaluate(const Tri& a, const Tri& b) {
  TriTriResult res;
  // Step 1: heights (signs of det[b-a, c-a, d-a], i.e. -orient3d) of B's corners against A.
  const Orient3dPlane pa(a[0], a[1], a[2]);
  int hb[3];
  for (int i = 0; i < 3; ++i) hb[i] = -pa.side(b[i]);
  if (hb[0] == hb[1] && hb[1] == hb[2] && hb[0] != 0) return res;
  const Orient3dPlane pb(b[0], b[1], b[2]);
  const bool b_flat = hb[0] == 0 && hb[1] == 0 && hb[2] == 0;
  if (b_flat && pa.certainly_nondegenerate()) {
    // B lies in plane(A) with A non-degenerate: A's corners are all on plane(B) as well (B is
    // coplanar with A, or degenerate and then every orient3d against it vanishes). This skips
    // three exact zero certifications per coplanar pair.
    if (flat_case(a, b, true, true, pa, pb)) res.kind = ContactKind::touch;
    return res;
  }
  int ha[3];
  for (int i = 0; i < 3; ++i) ha[i] = -pb.side(a[i]);
  if (ha[0] == ha[1] && ha[1] == ha[2] && ha[0] != 0) return res;

  const bool a_flat = ha[0] == 0 && ha[1] == 0 && ha[2] == 0;
  if (b_flat || a_flat) {
    if (flat_case(a, b, b_flat, a_flat, pa, pb)) res.kind = ContactKind::touch;
    return res;
  }

  // Step 3: rotate so that corner 0 is alone; intervals [lowA, highA], [lowB, highB] along d.
  const int ra = alone_index(ha), rb = alone_index(hb);
  const Vec3& a0 = a[ra];
  const Vec3& b0 = b[rb];
  const int sa = ha[ra] != 0 ? -ha[ra] : ha[(ra + 1) % 3];  // sign(hB(a1) - hB(a0))
  const int sb = hb[rb] != 0 ? -hb[rb] : hb[(rb + 1) % 3];  // sign(hA(b1) - hA(b0))
  const int sigma = sa * sb;
  // Ends of the intervals as edges 0 -> k of the rotated triangles.
  const EdgeEnd low_a{ra, sa < 0 ? 2 : 1}, high_a{ra, sa < 0 ? 1 : 2};
  const EdgeEnd low_b{rb, sb < 0 ? 1 : 2}, high_b{rb, sb < 0 ? 2 : 1};
  auto corner = [](const Tri& t, const EdgeEnd& e) -> const Vec3& { return t[(e.rot + e.k) % 3]; };
  // sign(t(Y) - t(X)) for X = end of A, Y = end of B.
  auto compare = [&](const EdgeEnd& x, const EdgeEnd& y) {
    return orient_o(a0, corner(a, x), b0, corner(b, y)) * sigma;
  };
  const int c1 = compare(low_a, high_b);  // highB - lowA
  if (c1 < 0) return res;
  const int c2 = -compare(high_a, low_b);  // highA - lowB
  if (c2 < 0) return res;
  res.kind = ContactKind::touch;
  if constexpr (kMode == Mode::intersects) return res;

  // Step 4: classification.
  const bool a_strict =
      (ha[0] > 0 || ha[1] > 0 || ha[2] > 0) && (ha[0] < 0 || ha[1] < 0 || ha[2] < 0);
  const bool b_strict =
      (hb[0] > 0 || hb[1] > 0 || hb[2] > 0) && (hb[0] < 0 || hb[1] < 0 || hb[2] < 0);
  if (!(a_strict && b_strict && c1 > 0 && c2 > 0)) return res;
  res.kind = ContactKind::cross;
  if constexpr (kMode == Mode::kind) return res;

  auto point_on_a = [&](const EdgeEnd& x, const Feature& f) -> Vec3 {
    if (f.type == Feature::vertex) return a[f.index];
    return edge_plane_point(a0, corner(a, x), pb);
  };
  auto point_on_b = [&](const EdgeEnd& y, const Feature& f) -> Vec3 {
    if (f.type == Feature::vertex) return b[f.index];
    return edge_plane_point(b0, corner(b, y), pa);
  };
  const Feature face{Feature::face, 0};
  auto set_end = [&](int slot, const EdgeEnd& x, const EdgeEnd& y, int which) {
    // which > 0: the end of B's interval (A interior); < 0: A's end (B interior); 0: both.
    if (which > 0) {
      res.feature_a[slot] = face;
      res.feature_b[slot] = feature_of(y, hb);
      res.segment[slot] = point_on_b(y, res.feature_b[slot]);
    } else if (which < 0) {
      res.feature_a[slot] = feature_of(x, ha);
      res.feature_b[slot] = face;
      res.segment[slot] = point_on_a(x, res.feature_a[slot]);
    } else {
      const Feature fa = feature_of(x, ha), fb = feature_of(y, hb);
      res.feature_a[slot] = fa;
      res.feature_b[slot] = fb;
      if (fa.type == Feature::vertex) {
        res.segment[slot] = a[fa.index];
      } else if (fb.type == Feature::vertex) {
        res.segment[slot] = b[fb.index];
      } else {
        res.segment[slot] = edge_edge_point(a0, corner(a, x), b0, corner(b, y));
      }
    }
  };
  // Lower end: max(lowA, lowB); B's is larger when t(lowB) - t(lowA) > 0.
  set_end(0, low_a, low_b, compare(low_a, low_b));
  // Upper end: min(highA, highB); B's is smaller when t(highB) - t(highA) < 0.
  set_end(1, high_a, high_b, -compare(high_a, high_b));
  return res;
}

}  // namespace

TriTriResult tri_tri_exact(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  return evaluate<Mode::segment>(a, b);
}

bool tri_tri_exact_intersects(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  return evaluate<Mode::intersects>(a, b).kind != ContactKind::none;
}

ContactKind tri_tri_exact_kind(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  return evaluate<Mode::kind>(a, b).kind;
}

}  // namespace interfere
