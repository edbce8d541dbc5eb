// Attributed adjacency graph of a B-Rep (issue #6, item 2), after Joshi & Chang, "Graph-based
// heuristics for recognition of machined features from a 3D solid model", CAD 20(2), 1988, as used
// by He & Xu (SJTU 2023) §2.1: a node per face (surface type and parameters), an arc per edge shared
// by two faces (curve type, convexity from the outward normals and the edge's orientation in the
// first face, inner/outer loop). B-spline faces that are geometrically planes, cylinders or cones
// are recognised by least-squares fits of sampled points (plane: PCA; cylinder: axis from the
// normals' PCA, then a circle fit (Kasa 1976) in the plane across it; cone: axis from the centred
// normals' PCA and the normal lines' meet, then a line fit of radius against height), accepted
// within a tolerance relative to the face's size.
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepGProp.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom2d_Curve.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListIteratorOfListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "occt_internal.h"

namespace interfere::cad::detail {
namespace {

Vec3 v3(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 v3(const gp_Dir& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return l > 0 ? v / l : v;
}

// Outward normal (face orientation applied) at (u, v).
bool face_normal(const TopoDS_Face& f, double u, double v, Vec3& p, Vec3& n) {
  BRepGProp_Face gf(f);
  gp_Pnt pt;
  gp_Vec nv;
  gf.Normal(u, v, pt, nv);
  if (nv.Magnitude() < 1e-300) return false;
  p = v3(pt);
  n = unit({nv.X(), nv.Y(), nv.Z()});
  return true;
}

// Sample points and normals on a grid over the face's parameter bounds (points outside the trimmed
// face are fine for an untrimmed analytic test of the underlying surface).
void sample_face(const TopoDS_Face& f, int n, std::vector<Vec3>& pts, std::vector<Vec3>& nrm) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      Vec3 p, nn;
      if (face_normal(f, u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n, p, nn)) pts.push_back(p), nrm.push_back(nn);
    }
}

// An orthonormal basis of the plane across unit axis a.
std::pair<Vec3, Vec3> across(const Vec3& a) {
  const Vec3 e1 = unit(std::abs(a.x) < 0.9 ? cross(a, {1, 0, 0}) : cross(a, {0, 1, 0}));
  return {e1, cross(a, e1)};
}

// Cone (a free-form face that is no plane or cylinder): its normals make one angle with the axis, so
// the axis is the direction in which the centred normals do not spread (PCA); every normal line
// meets the axis, which across the axis is a point, the least-squares meet of the projected normal
// lines; along the axis the distance to it grows linearly (the slope is tan of the half angle).
// Accepted when that line fits the samples within tol * size and the slope is not that of a
// cylinder. Like the analytic cones of describe_surface: axis_point on the axis (here at the
// samples' mean height), radius there; the axis is oriented towards growing radius.
void recognise_cone(const std::vector<Vec3>& pts, const std::vector<Vec3>& nrm, const Vec3& c, double size,
                    AagNode& node, double tol) {
  const double n = double(nrm.size());
  Vec3 mean{};
  for (const Vec3& v : nrm) mean += v;
  mean = mean / n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& v : nrm) {
    const Eigen::Vector3d e(v.x - mean.x, v.y - mean.y, v.z - mean.z);
    cov += e * e.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  if (es.eigenvalues()(0) > 1e-6 * n || !(es.eigenvalues()(1) > 1e-3 * n)) return;  // no spread at all: a plane
  const Eigen::Vector3d ev = es.eigenvectors().col(0);
  Vec3 a = unit({ev.x(), ev.y(), ev.z()});
  const auto [e1, e2] = across(a);
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d d(dot(nrm[i], e1), dot(nrm[i], e2));
    if (d.norm() < 1e-6) return;
    const Eigen::Vector2d q(dot(pts[i] - c, e1), dot(pts[i] - c, e2));
    const Eigen::Vector2d w = Eigen::Vector2d(-d.y(), d.x()) / d.norm();  // across the projected normal line
    m += w * w.transpose();
    rhs += w * w.dot(q);
  }
  if (!(std::abs(m.determinant()) > 1e-9 * n * n)) return;
  const Eigen::Vector2d x = m.ldlt().solve(rhs);
  const Vec3 axis_point = c + e1 * x.x() + e2 * x.y();
  // radius = r0 + slope * height, least squares.
  double sh = 0, sr = 0, shh = 0, shr = 0;
  std::vector<double> hs, rs;
  for (const Vec3& p : pts) {
    const Vec3 d = p - axis_point;
    const double h = dot(d, a), r = norm(d - a * h);
    hs.push_back(h), rs.push_back(r);
    sh += h, sr += r, shh += h * h, shr += h * r;
  }
  const double den = n * shh - sh * sh;
  if (!(den > 0)) return;
  double slope = (n * shr - sh * sr) / den;
  const double r0 = (sr - slope * sh) / n;
  double dev = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) dev = std::max(dev, std::abs(rs[i] - (r0 + slope * hs[i])));
  if (dev > tol * size || std::abs(slope) < 1e-3 || !(r0 > 0)) return;
  if (slope < 0) a = -a, slope = -slope;
  node.type = SurfaceType::cone;
  node.from_bspline = true;
  node.axis = a;
  node.axis_point = axis_point;
  node.radius = r0;
  node.half_angle = std::atan(slope);
  const Vec3 radial = pts[0] - axis_point;
  node.hole = dot(nrm[0], radial - a * dot(radial, a)) < 0;
}

// Canonical recognition of a free-form face: plane, then cylinder, then cone.
void recognise_canonical(const TopoDS_Face& f, AagNode& node, double tol) {
  std::vector<Vec3> pts, nrm;
  sample_face(f, 8, pts, nrm);
  if (pts.size() < 6) return;
  Vec3 c{};
  for (const Vec3& p : pts) c += p;
  c = c / double(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double size = 0;
  for (const Vec3& p : pts) {
    const Eigen::Vector3d d(p.x - c.x, p.y - c.y, p.z - c.z);
    cov += d * d.transpose();
    size = std::max(size, d.norm());
  }
  if (size == 0) return;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Eigen::Vector3d nrm0 = es.eigenvectors().col(0);
  const Vec3 pn{nrm0.x(), nrm0.y(), nrm0.z()};
  double dev = 0;
  for (const Vec3& p : pts) dev = std::max(dev, std::abs(dot(p - c, pn)));
  if (dev <= tol * size) {
    node.type = SurfaceType::plane;
    node.from_bspline = true;
    node.normal = dot(pn, nrm[pts.size() / 2]) >= 0 ? pn : -pn;
    node.axis_point = c;
    return;
  }
  // Cylinder: the normals are perpendicular to the axis.
  Eigen::Matrix3d nn = Eigen::Matrix3d::Zero();
  for (const Vec3& n : nrm) {
    const Eigen::Vector3d e(n.x, n.y, n.z);
    nn += e * e.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> en(nn);
  const Eigen::Vector3d ax = en.eigenvectors().col(0);
  if (en.eigenvalues()(0) > 1e-6 * double(nrm.size())) {
    recognise_cone(pts, nrm, c, size, node, tol);
    return;
  }
  const Vec3 a = unit({ax.x(), ax.y(), ax.z()});
  // Basis across the axis, Kasa circle fit: x^2 + y^2 + D x + E y + F = 0.
  const auto [e1, e2] = across(a);
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd b(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double x = dot(pts[i] - c, e1), y = dot(pts[i] - c, e2);
    A(i, 0) = x, A(i, 1) = y, A(i, 2) = 1;
    b(i) = -(x * x + y * y);
  }
  const Eigen::Vector3d s = A.colPivHouseholderQr().solve(b);
  const double cx = -s(0) / 2, cy = -s(1) / 2, r2 = cx * cx + cy * cy - s(2);
  if (!(r2 > 0)) return;
  const double r = std::sqrt(r2);
  double rdev = 0;
  for (const Vec3& p : pts) {
    const double x = dot(p - c, e1) - cx, y = dot(p - c, e2) - cy;
    rdev = std::max(rdev, std::abs(std::sqrt(x * x + y * y) - r));
  }
  if (rdev > tol * std::max(size, r)) return;
  node.type = SurfaceType::cylinder;
  node.from_bspline = true;
  node.axis = a;
  node.axis_point = c + e1 * cx + e2 * cy;
  node.radius = r;
  const Vec3 radial = pts[0] - node.axis_point;
  node.hole = dot(nrm[0], radial - a * dot(radial, a)) < 0;
}

void describe_surface(const TopoDS_Face& f, AagNode& node, double tol) {
  BRepAdaptor_Surface s(f, Standard_True);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  Vec3 p, n;
  const bool have_n = face_normal(f, 0.5 * (u0 + u1), 0.5 * (v0 + v1), p, n);
  auto sense = [&](const Vec3& axis_point, const Vec3& axis) {
    const Vec3 radial = p - axis_point;
    return have_n && dot(n, radial - axis * dot(radial, axis)) < 0;
  };
  switch (s.GetType()) {
    case GeomAbs_Plane: {
      node.type = SurfaceType::plane;
      node.normal = have_n ? n : v3(s.Plane().Axis().Direction());
      node.axis_point = v3(s.Plane().Location());
      break;
    }
    case GeomAbs_Cylinder: {
      const gp_Cylinder c = s.Cylinder();
      node.type = SurfaceType::cylinder;
      node.axis = v3(c.Axis().Direction()), node.axis_point = v3(c.Location());
      node.radius = c.Radius();
      node.hole = sense(node.axis_point, node.axis);
      break;
    }
    case GeomAbs_Cone: {
      const gp_Cone c = s.Cone();
      node.type = SurfaceType::cone;
      node.axis = v3(c.Axis().Direction()), node.axis_point = v3(c.Location());
      node.radius = c.RefRadius(), node.half_angle = c.SemiAngle();
      node.hole = sense(node.axis_point, node.axis);
      break;
    }
    case GeomAbs_Sphere: {
      const gp_Sphere c = s.Sphere();
      node.type = SurfaceType::sphere;
      node.axis_point = v3(c.Location()), node.radius = c.Radius();
      node.hole = have_n && dot(n, p - node.axis_point) < 0;
      break;
    }
    case GeomAbs_Torus: {
      const gp_Torus c = s.Torus();
      node.type = SurfaceType::torus;
      node.axis = v3(c.Axis().Direction()), node.axis_point = v3(c.Location());
      node.radius = c.MajorRadius(), node.minor_radius = c.MinorRadius();
      break;
    }
    case GeomAbs_BSplineSurface:
    case GeomAbs_BezierSurface:
      node.type = SurfaceType::bspline;
      recognise_canonical(f, node, tol);
      break;
    default:
      node.type = SurfaceType::other;
      recognise_canonical(f, node, tol);
      break;
  }
}

// Free-form edges (B-spline/Bezier/offset) that are geometrically lines or circular arcs, as exported
// files often carry them: 17 samples; a line when every sample lies within tol * length of the chord,
// a circle when they lie in a plane (PCA) and on a circle of that plane (Kasa fit) within tol * size.
CurveType canonical_curve(const BRepAdaptor_Curve& c, double tol) {
  std::vector<Vec3> pts;
  const double t0 = c.FirstParameter(), t1 = c.LastParameter();
  for (int i = 0; i <= 16; ++i) pts.push_back(v3(c.Value(t0 + (t1 - t0) * i / 16)));
  const Vec3 a = pts.front(), b = pts.back();
  double size = 0;
  Vec3 centre{};
  for (const Vec3& p : pts) centre += p;
  centre = centre / double(pts.size());
  for (const Vec3& p : pts) size = std::max(size, norm(p - centre));
  if (!(size > 0)) return CurveType::other;
  const Vec3 d = b - a;
  const double len = norm(d);
  if (len > 0) {
    double dev = 0;
    for (const Vec3& p : pts) dev = std::max(dev, norm(cross(p - a, d)) / len);
    if (dev <= tol * size) return CurveType::line;
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : pts) {
    const Eigen::Vector3d q(p.x - centre.x, p.y - centre.y, p.z - centre.z);
    cov += q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Eigen::Vector3d n0 = es.eigenvectors().col(0), e10 = es.eigenvectors().col(2);
  const Vec3 n{n0.x(), n0.y(), n0.z()}, e1{e10.x(), e10.y(), e10.z()};
  const Vec3 e2 = cross(n, e1);
  for (const Vec3& p : pts)
    if (std::abs(dot(p - centre, n)) > tol * size) return CurveType::other;
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd rhs(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double x = dot(pts[i] - centre, e1), y = dot(pts[i] - centre, e2);
    A(i, 0) = x, A(i, 1) = y, A(i, 2) = 1;
    rhs(i) = -(x * x + y * y);
  }
  const Eigen::Vector3d sol = A.colPivHouseholderQr().solve(rhs);
  const double cx = -sol(0) / 2, cy = -sol(1) / 2, r2 = cx * cx + cy * cy - sol(2);
  if (!(r2 > 0)) return CurveType::other;
  const double r = std::sqrt(r2);
  for (const Vec3& p : pts) {
    const double x = dot(p - centre, e1) - cx, y = dot(p - centre, e2) - cy;
    if (std::abs(std::sqrt(x * x + y * y) - r) > tol * std::max(size, r)) return CurveType::other;
  }
  return CurveType::circle;
}

CurveType curve_type(const TopoDS_Edge& e, double tol) {
  if (BRep_Tool::Degenerated(e)) return CurveType::other;
  BRepAdaptor_Curve c(e);
  switch (c.GetType()) {
    case GeomAbs_Line: return CurveType::line;
    case GeomAbs_Circle: return CurveType::circle;
    case GeomAbs_Ellipse: return CurveType::ellipse;
    default: return canonical_curve(c, tol);
  }
}

// Normal of `face` at the edge's parameter t (through the edge's p-curve on that face).
bool normal_on_edge(const TopoDS_Edge& e, const TopoDS_Face& f, double t, Vec3& p, Vec3& n) {
  double f0, f1;
  Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, f0, f1);
  if (pc.IsNull()) return false;
  const gp_Pnt2d uv = pc->Value(t);
  return face_normal(f, uv.X(), uv.Y(), p, n);
}


// Angular range and axial extent of a cylinder or cone face (issue #29): a hole's wall must close
// the full circle, summed over the faces it is split into. Analytic faces: the angle is the surface's
// u parameter, the range the face's u bounds (right-handed about node.axis: the end whose
// neighbourhood holds the middle of the range is its start). Recognised B-spline faces: the largest
// angular gap between 48 samples per boundary edge (a gap under 0.15 rad between samples counts as
// closed). The axial extent comes from the boundary samples in both cases.
void angular_range(const TopoDS_Face& f, AagNode& node) {
  const Vec3 a = node.axis;
  const auto [e1, e2] = across(a);
  auto angle_of = [&](const Vec3& q) {
    const Vec3 d = q - node.axis_point;
    return std::atan2(dot(d, e2), dot(d, e1));
  };
  std::vector<double> angles;
  double hmin = 1e300, hmax = -1e300;
  for (TopExp_Explorer x(f, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge e = TopoDS::Edge(x.Current());
    if (BRep_Tool::Degenerated(e)) continue;
    BRepAdaptor_Curve c(e);
    const double t0 = c.FirstParameter(), t1 = c.LastParameter();
    if (!std::isfinite(t0) || !std::isfinite(t1)) continue;
    for (int i = 0; i <= 48; ++i) {
      const Vec3 q = v3(c.Value(t0 + (t1 - t0) * i / 48));
      const double h = dot(q - node.axis_point, a);
      hmin = std::min(hmin, h), hmax = std::max(hmax, h);
      const Vec3 r = q - node.axis_point - a * h;
      if (norm(r) > 1e-9 * std::max(1.0, node.radius)) angles.push_back(angle_of(q));
    }
  }
  if (hmin > hmax) return;
  node.axial_min = hmin, node.axial_max = hmax;
  constexpr double two_pi = 2 * M_PI;
  auto dir_at = [&](double t) { return e1 * std::cos(t) + e2 * std::sin(t); };
  if (!node.from_bspline) {
    BRepAdaptor_Surface s(f, Standard_True);
    double u0, u1, v0, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    const double span = std::min(u1 - u0, two_pi);
    if (!(span > 0)) return;
    node.arc_span = span;
    const double vm = 0.5 * (v0 + v1);
    const double t0 = angle_of(v3(s.Value(u0, vm))), tm = angle_of(v3(s.Value(0.5 * (u0 + u1), vm)));
    double d = std::remainder(tm - t0, two_pi);
    if (d < 0) d += two_pi;
    // u runs right-handed about the axis when the middle lies half a span after u0.
    const bool forward = std::abs(d - 0.5 * span) < std::abs((two_pi - d) - 0.5 * span);
    node.arc_start = dir_at(forward ? t0 : angle_of(v3(s.Value(u1, vm))));
    return;
  }
  if (angles.size() < 2) return;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + two_pi - angles.back(), start = angles.front();
  for (std::size_t i = 1; i < angles.size(); ++i)
    if (angles[i] - angles[i - 1] > gap) gap = angles[i] - angles[i - 1], start = angles[i];
  node.arc_span = gap < 0.15 ? two_pi : two_pi - gap;
  node.arc_start = dir_at(start);
}
}  // namespace

Aag build_aag(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces, double tol) {
  Aag g;
  g.nodes.resize(faces.Extent());
  // Loops of each face: which edges lie on inner wires.
  std::vector<std::vector<TopoDS_Shape>> inner_edges(faces.Extent());
  for (int i = 1; i <= faces.Extent(); ++i) {
    const TopoDS_Face f = TopoDS::Face(faces(i));
    AagNode& node = g.nodes[i - 1];
    node.face = static_cast<std::uint32_t>(i - 1);
    describe_surface(f, node, tol);
    if (node.type == SurfaceType::cylinder || node.type == SurfaceType::cone) angular_range(f, node);
    GProp_GProps props;
    BRepGProp::SurfaceProperties(f, props);
    node.area = props.Mass();
    const TopoDS_Wire outer = BRepTools::OuterWire(f);
    for (TopExp_Explorer w(f, TopAbs_WIRE); w.More(); w.Next()) {
      if (!outer.IsNull() && w.Current().IsSame(outer)) {
        ++node.outer_loops;
        continue;
      }
      ++node.inner_loops;
      for (TopExp_Explorer e(w.Current(), TopAbs_EDGE); e.More(); e.Next()) inner_edges[i - 1].push_back(e.Current());
    }
  }
  auto on_inner = [&](int face, const TopoDS_Shape& e) {
    for (const TopoDS_Shape& s : inner_edges[face])
      if (s.IsSame(e)) return true;
    return false;
  };
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (int ei = 1; ei <= edge_faces.Extent(); ++ei) {
    const TopoDS_Edge e = TopoDS::Edge(edge_faces.FindKey(ei));
    if (BRep_Tool::Degenerated(e)) continue;
    std::vector<int> fids;
    for (TopTools_ListIteratorOfListOfShape it(edge_faces(ei)); it.More(); it.Next()) {
      const int id = faces.FindIndex(it.Value());
      if (id > 0 && std::find(fids.begin(), fids.end(), id - 1) == fids.end()) fids.push_back(id - 1);
    }
    if (fids.size() != 2) continue;  // seam edge (one face) or non-manifold
    AagArc arc;
    arc.a = static_cast<std::uint32_t>(std::min(fids[0], fids[1]));
    arc.b = static_cast<std::uint32_t>(std::max(fids[0], fids[1]));
    arc.edge = static_cast<std::uint32_t>(edges.FindIndex(e) - 1);
    arc.curve = curve_type(e, tol);
    arc.inner_loop_a = on_inner(int(arc.a), e);
    arc.inner_loop_b = on_inner(int(arc.b), e);
    GProp_GProps lp;
    BRepGProp::LinearProperties(e, lp);
    arc.length = lp.Mass();
    // Convexity: with T the edge tangent oriented as the edge runs in face A (material of A on the
    // left of T seen from A's outward normal nA), the edge is convex when (nA x nB) . T > 0.
    const TopoDS_Face fa = TopoDS::Face(faces(int(arc.a) + 1)), fb = TopoDS::Face(faces(int(arc.b) + 1));
    TopAbs_Orientation in_a = TopAbs_FORWARD;
    for (TopExp_Explorer x(fa, TopAbs_EDGE); x.More(); x.Next())
      if (x.Current().IsSame(e)) {
        in_a = x.Current().Orientation();
        break;
      }
    BRepAdaptor_Curve c(e);
    const double t = 0.5 * (c.FirstParameter() + c.LastParameter());
    gp_Pnt cp;
    gp_Vec tv;
    c.D1(t, cp, tv);
    arc.midpoint = v3(cp);
    Vec3 tan = unit({tv.X(), tv.Y(), tv.Z()});
    if (in_a == TopAbs_REVERSED) tan = -tan;
    Vec3 pa, na, pb, nb;
    if (normal_on_edge(e, fa, t, pa, na) && normal_on_edge(e, fb, t, pb, nb)) {
      const double cosang = std::clamp(dot(na, nb), -1.0, 1.0);
      arc.angle = std::acos(cosang);
      const double s = dot(cross(na, nb), tan);
      if (arc.angle < 1e-3) arc.convexity = Convexity::smooth;
      else arc.convexity = s > 0 ? Convexity::convex : Convexity::concave;
    }
    g.arcs.push_back(arc);
  }
  std::sort(g.arcs.begin(), g.arcs.end(), [](const AagArc& x, const AagArc& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.edge < y.edge);
  });
  return g;
}

}  // namespace interfere::cad::detail
