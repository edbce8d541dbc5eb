// §3.4 of Li, Zhou & Zheng 2008, as written (issue #28, deliverable 3): the cylinder and a triangle
// are declared to intersect when their orthographic projections (formula (1): onto the plane
// through the origin normal to the projection direction) overlap in all three of
//   §3.4.1 along the cylinder axis: the end circle projects to an ellipse O1 (here a circle of
//          radius r: its minor axis r |A.B| = r); overlap when (1) a triangle vertex is in the
//          ellipse, (2) the ellipse meets a triangle edge or (3) its centre is in the triangle;
//   §3.4.2 along one edge of the triangle: the triangle projects to a segment AB, the cylinder to
//          the ellipses O1, O2 of its end circles (major axis A x B of length r, minor axis
//          r |A.B|, formula (2)) and the rectangle between their major axes (sides EF, GH);
//          overlap when (1) A or B is in O1 or O2, (2) AB meets O1 or O2, (3) A or B is in the
//          rectangle or (4) AB meets the rectangle;
//   §3.4.3 along a diameter of the end circle: the cylinder projects to the rectangle DEFG (the
//          projected axis times the diameter perpendicular to both), the triangle to a triangle;
//          overlap when (1) a triangle vertex is in the rectangle, (2) a rectangle vertex is in the
//          triangle or (3) an edge of one crosses an edge of the other.
// Double precision like the paper; boundaries count as overlapping. Incomplete (false contacts):
// paper_tests.h, docs/probe.md.
#include <algorithm>
#include <cmath>

#include "interfere/probe/paper_tests.h"

namespace interfere::probe {
namespace {

struct P2 {
  double x = 0, y = 0;
};
P2 operator-(const P2& a, const P2& b) { return {a.x - b.x, a.y - b.y}; }
P2 operator+(const P2& a, const P2& b) { return {a.x + b.x, a.y + b.y}; }
P2 operator*(const P2& a, double s) { return {a.x * s, a.y * s}; }
double dot2(const P2& a, const P2& b) { return a.x * b.x + a.y * b.y; }
double cross2(const P2& a, const P2& b) { return a.x * b.y - a.y * b.x; }
double orient(const P2& a, const P2& b, const P2& c) { return cross2(b - a, c - a); }

/// Orthographic projection onto the plane normal to the unit `dir`, in coordinates of a basis of
/// that plane (formula (1) followed by a change of basis inside the plane).
struct Projector {
  Vec3 e1, e2;
  explicit Projector(const Vec3& dir) {
    const Vec3 h = std::fabs(dir.x) < 0.6 ? Vec3{1, 0, 0} : (std::fabs(dir.y) < 0.6 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    e1 = cross(dir, h);
    e1 = e1 / norm(e1);
    e2 = cross(dir, e1);
  }
  P2 operator()(const Vec3& p) const { return {dot(p, e1), dot(p, e2)}; }
  P2 vec(const Vec3& v) const { return {dot(v, e1), dot(v, e2)}; }
};

bool on_segment(const P2& p, const P2& a, const P2& b) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

/// Closed segments [a, b] and [c, d] share a point (collinear overlaps included).
bool segments_cross(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  if (o1 == 0 && on_segment(c, a, b)) return true;
  if (o2 == 0 && on_segment(d, a, b)) return true;
  if (o3 == 0 && on_segment(a, c, d)) return true;
  if (o4 == 0 && on_segment(b, c, d)) return true;
  return false;
}

/// Point in the closed convex polygon `v` (n corners in order, either orientation; a degenerate
/// polygon contains the points of its sides).
bool in_convex(const P2& p, const P2* v, int n) {
  bool pos = false, neg = false;
  double area = 0;
  for (int i = 0; i < n; ++i) area += cross2(v[i], v[(i + 1) % n]);
  if (area == 0) {
    for (int i = 0; i < n; ++i)
      if (segments_cross(p, p, v[i], v[(i + 1) % n])) return true;
    return false;
  }
  for (int i = 0; i < n; ++i) {
    const double o = orient(v[i], v[(i + 1) % n], p);
    pos |= o > 0, neg |= o < 0;
  }
  return !(pos && neg);
}

/// Ellipse with centre c, unit major direction k (semi-axis a) and the perpendicular minor
/// direction (semi-axis b >= 0).
struct Ellipse {
  P2 c, k;
  double a = 0, b = 0;
  /// Coordinates in which the ellipse is the unit disk (b > 0).
  P2 unit(const P2& p) const {
    const P2 d = p - c;
    const P2 m{-k.y, k.x};
    return {dot2(d, k) / a, dot2(d, m) / b};
  }
};

bool in_ellipse(const P2& p, const Ellipse& e) {
  if (e.b > 0) {
    const P2 u = e.unit(p);
    return u.x * u.x + u.y * u.y <= 1;
  }
  // Degenerate (projection along a diameter): the major diameter segment.
  return segments_cross(p, p, e.c - e.k * e.a, e.c + e.k * e.a);
}

/// Segment [p, q] meets the closed ellipse.
bool segment_meets_ellipse(const P2& p, const P2& q, const Ellipse& e) {
  if (!(e.b > 0)) return segments_cross(p, q, e.c - e.k * e.a, e.c + e.k * e.a);
  const P2 a = e.unit(p), b = e.unit(q);
  const P2 d = b - a;
  const double dd = dot2(d, d);
  double s = dd > 0 ? -dot2(a, d) / dd : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  const P2 c = a + d * s;
  return dot2(c, c) <= 1;
}

/// Triangle (or the segment a degenerate one becomes) overlaps the convex polygon `v`: a vertex of
/// either inside the other, or two sides crossing.
bool triangle_polygon(const P2 t[3], const P2* v, int n) {
  for (int i = 0; i < 3; ++i)
    if (in_convex(t[i], v, n)) return true;
  for (int i = 0; i < n; ++i)
    if (in_convex(v[i], t, 3)) return true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < n; ++j)
      if (segments_cross(t[i], t[(i + 1) % 3], v[j], v[(j + 1) % n])) return true;
  return false;
}

Vec3 unit(const Vec3& v) { return v / norm(v); }

}  // namespace

PaperProjections paper_projections(const Cylinder& c, const std::array<Vec3, 3>& t, int edge, const Vec3& diameter) {
  PaperProjections out;
  const Vec3 B = unit(c.c1 - c.c0);  // axis (l, m, n)
  const double r = c.radius;

  // §3.4.1 along the axis: the end circles project to one circle of radius r about the axis point.
  {
    const Projector P(B);
    const Ellipse o1{P(c.c0), {1, 0}, r, r};
    const P2 tri[3] = {P(t[0]), P(t[1]), P(t[2])};
    bool hit = false;
    for (int i = 0; i < 3 && !hit; ++i) hit = in_ellipse(tri[i], o1);                                // (1)
    for (int i = 0; i < 3 && !hit; ++i) hit = segment_meets_ellipse(tri[i], tri[(i + 1) % 3], o1);  // (2)
    if (!hit) hit = in_convex(o1.c, tri, 3);                                                        // (3)
    out.along_axis = hit;
  }

  // §3.4.2 along the edge t[edge] -> t[edge + 1]: the triangle becomes the segment A B.
  {
    const int i0 = ((edge % 3) + 3) % 3;
    const Vec3 ev = t[(i0 + 1) % 3] - t[i0];
    if (!(norm(ev) > 0)) {
      out.along_edge = true;  // no direction: nothing to separate with
    } else {
      const Vec3 A = unit(ev);
      const Projector P(A);
      const P2 a = P(t[i0]), b = P(t[(i0 + 2) % 3]);  // t[i0] and t[i0 + 1] project to one point
      // Major axis along A x B (length r), minor r |A.B| (§3.4, formula (2)).
      Vec3 kx = cross(A, B);
      const double sk = norm(kx);
      P2 k;
      if (sk > 0) {
        k = P.vec(kx / sk);
      } else {
        k = {1, 0};  // projecting along the axis: circles
      }
      const double minor = r * std::min(1.0, std::fabs(dot(A, B)));
      const Ellipse o1{P(c.c0), k, r, minor}, o2{P(c.c1), k, r, minor};
      const P2 rect[4] = {o1.c + k * r, o2.c + k * r, o2.c - k * r, o1.c - k * r};  // D E F G
      const bool hit = in_ellipse(a, o1) || in_ellipse(b, o1) || in_ellipse(a, o2) || in_ellipse(b, o2) ||  // (1)
                       segment_meets_ellipse(a, b, o1) || segment_meets_ellipse(a, b, o2) ||                 // (2)
                       in_convex(a, rect, 4) || in_convex(b, rect, 4) ||                                     // (3)
                       [&] {                                                                                 // (4)
                         for (int j = 0; j < 4; ++j)
                           if (segments_cross(a, b, rect[j], rect[(j + 1) % 4])) return true;
                         return false;
                       }();
      out.along_edge = hit;
    }
  }

  // §3.4.3 along a diameter D (perpendicular to the axis): the cylinder becomes the rectangle of the
  // projected axis and the diameter B x D (length 2r), the triangle a triangle.
  {
    Vec3 D = diameter - B * dot(diameter, B);
    if (!(norm(D) > 1e-12 * std::max(1.0, norm(diameter)))) {
      const Projector fixed(B);  // a fixed diameter: the first basis direction of the axis-normal plane
      D = fixed.e1;
    }
    D = unit(D);
    const Projector P(D);
    const P2 k = P.vec(cross(B, D));
    const P2 p0 = P(c.c0), p1 = P(c.c1);
    const P2 rect[4] = {p0 + k * r, p1 + k * r, p1 - k * r, p0 - k * r};
    const P2 tri[3] = {P(t[0]), P(t[1]), P(t[2])};
    out.along_diameter = triangle_polygon(tri, rect, 4);
  }
  return out;
}

bool three_projection_test(const Cylinder& c, const std::array<Vec3, 3>& t, int edge) {
  return paper_projections(c, t, edge).all();
}

}  // namespace interfere::probe
