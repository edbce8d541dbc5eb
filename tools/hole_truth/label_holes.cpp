// Independent hole labeller for the recognition truth set (issue #29, item 2). It shares no code and
// no method with src/cad (no AAG, no arcs, no convexity, no loops): it reads the STEP file with
// STEPControl_Reader, takes every analytic cylinder and cone surface of each solid, and decides by
// point classification against the solid (BRepClass3d_SolidClassifier, "ray casting into the
// solid") whether the surface is the wall of a hole:
//   - a wall: at some height along the axis, for every one of 72 directions around the axis, the
//     point just outside the surface's radius is material and the point just inside is not (the
//     wall closes a full circle, whatever faces and edges it is split into);
//   - a hole: coaxial walls (cylinders and cones) whose axial extents touch, ordered along the axis;
//   - an end is closed (blind) when material lies on the axis within one radius beyond the last wall
//     (a flat, filleted, conical or spherical floor), else open;
//   - type: counterdrilled_hole (a larger cylinder at an open end, a cone narrowing inwards, then the
//     bore: one radius to the end), counterbored_hole (a larger cylinder at an open end followed by a smaller one),
//     countersunk_hole (a cone at an open end narrowing inwards: countersinks and entry chamfers),
//     stepped_hole (other multi-diameter holes), blind_hole (one closed end), through_hole.
// B-spline faces are not labelled (the tool has no surface recognition of its own).
//
// Build (OCCT 7.6, not part of the CMake build so that it stays independent of it):
//   g++ -O2 -std=c++17 -I/usr/include/opencascade tools/hole_truth/label_holes.cpp -o /tmp/label_holes \
//     -lTKSTEP -lTKSTEPBase -lTKSTEPAttr -lTKSTEP209 -lTKXSBase -lTKShHealing -lTKTopAlgo -lTKGeomAlgo \
//     -lTKBRep -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel
// Run: /tmp/label_holes FILE.stp > truth.json
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTools.hxx>
#include <Bnd_Box.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>

#include "../truth_common/step_solids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace truth;

// One analytic surface: cylinder (half_angle 0) or cone; radius at axis_point; axis unit.
struct Surf {
  bool cone = false;
  V p, a;
  double r = 0, half = 0;  // cone: r(h) = r + h * tan(half)
  double h0 = 1e300, h1 = -1e300;  // axial extent of its faces (from sampled face points)
  int faces = 0;
};

double radius_at(const Surf& s, double h) { return s.r + h * std::tan(s.half); }

struct Element {
  Surf s;
  bool wall = false;
};

}  // namespace

int main(int argc, char** argv) {
  const StepSolids step = read_step_solids(argc, argv, "label_holes", "tools/hole_truth/label_holes.cpp");
  if (step.status) return step.status;
  for (int solid_index = 0; solid_index < static_cast<int>(step.solids.size()); ++solid_index) {
    const TopoDS_Solid& solid = step.solids[solid_index];
    const double diag = diagonal(solid);
    BRepClass3d_SolidClassifier cls(solid);
    auto inside = [&](V q) {
      cls.Perform(gp_Pnt(q.x, q.y, q.z), 1e-7);
      return cls.State() == TopAbs_IN;
    };
    // 1. Distinct analytic cylinder and cone surfaces with their faces' axial extents.
    std::vector<Surf> surfs;
    for (TopExp_Explorer fx(solid, TopAbs_FACE); fx.More(); fx.Next()) {
      const TopoDS_Face f = TopoDS::Face(fx.Current());
      BRepAdaptor_Surface s(f, Standard_True);
      Surf c;
      if (s.GetType() == GeomAbs_Cylinder) {
        const gp_Cylinder g = s.Cylinder();
        c.p = pv(g.Location()), c.a = dv(g.Axis().Direction()), c.r = g.Radius();
      } else if (s.GetType() == GeomAbs_Cone) {
        const gp_Cone g = s.Cone();
        c.cone = true, c.p = pv(g.Location()), c.a = dv(g.Axis().Direction()), c.r = g.RefRadius(), c.half = g.SemiAngle();
      } else {
        continue;
      }
      // Normalise: axis pointing to +x/+y/+z first non-zero, axis point the foot of the origin.
      if (c.a.x < -1e-9 || (std::abs(c.a.x) <= 1e-9 && (c.a.y < -1e-9 || (std::abs(c.a.y) <= 1e-9 && c.a.z < 0)))) {
        c.a = c.a * -1;
        c.half = -c.half;
      }
      const double t = -dot(c.p, c.a);
      c.r = radius_at(c, t);
      c.p = c.p + c.a * t;
      // Axial extent from a grid of face points (inside the trimmed face: UV bounds of the face).
      double u0, u1, v0, v1;
      BRepTools::UVBounds(f, u0, u1, v0, v1);
      double h0 = 1e300, h1 = -1e300;
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) {
          const V q = pv(s.Value(u0 + (u1 - u0) * i / 8, v0 + (v1 - v0) * j / 8));
          const double h = dot(q - c.p, c.a);
          h0 = std::min(h0, h), h1 = std::max(h1, h);
        }
      const double tol = 1e-6 * std::max(1.0, diag);
      bool merged = false;
      for (Surf& o : surfs) {
        if (o.cone != c.cone || len(cross(o.a, c.a)) > 1e-7 || len(o.p - c.p) > tol || std::abs(o.r - c.r) > tol ||
            std::abs(o.half - c.half) > 1e-7)
          continue;
        // Same surface: one element only where the extents touch (two holes on one axis stay two).
        if (h0 > o.h1 + tol || h1 < o.h0 - tol) continue;
        o.h0 = std::min(o.h0, h0), o.h1 = std::max(o.h1, h1), ++o.faces, merged = true;
        break;
      }
      if (!merged) c.h0 = h0, c.h1 = h1, c.faces = 1, surfs.push_back(c);
    }
    // Extents of one surface that touch after later merges.
    for (bool again = true; again;) {
      again = false;
      for (std::size_t i = 0; i < surfs.size() && !again; ++i)
        for (std::size_t j = i + 1; j < surfs.size() && !again; ++j) {
          Surf &a = surfs[i], &b = surfs[j];
          const double tol = 1e-6 * std::max(1.0, diag);
          if (a.cone != b.cone || len(cross(a.a, b.a)) > 1e-7 || len(a.p - b.p) > tol || std::abs(a.r - b.r) > tol ||
              std::abs(a.half - b.half) > 1e-7 || b.h0 > a.h1 + tol || b.h1 < a.h0 - tol)
            continue;
          a.h0 = std::min(a.h0, b.h0), a.h1 = std::max(a.h1, b.h1), a.faces += b.faces;
          surfs.erase(surfs.begin() + long(j));
          again = true;
        }
    }
    // 2. Walls: full circle of material outside the radius and none inside, at some height.
    std::vector<Element> walls;
    for (const Surf& s : surfs) {
      V e1 = unit(std::abs(s.a.x) < 0.9 ? cross(s.a, {1, 0, 0}) : cross(s.a, {0, 1, 0}));
      const V e2 = cross(s.a, e1);
      bool wall = false;
      for (double f : {0.5, 0.3, 0.7, 0.15, 0.85, 0.05, 0.95}) {
        const double h = s.h0 + (s.h1 - s.h0) * f;
        const double r = radius_at(s, h);
        if (!(r > 1e-6)) continue;
        const double d = std::min(0.02 * r, 0.05);
        bool full = true;
        for (int k = 0; k < 72 && full; ++k) {
          const double t = 2 * M_PI * k / 72;
          const V dir = e1 * std::cos(t) + e2 * std::sin(t);
          const V c = s.p + s.a * h;
          full = inside(c + dir * (r + d)) && !inside(c + dir * (r - d));
        }
        if (full) {
          wall = true;
          break;
        }
      }
      if (wall) walls.push_back({s, true});
    }
    // 3. Holes: coaxial walls whose extents touch (tolerance 1e-4 of the part's size).
    const double gap = 1e-4 * std::max(1.0, diag);
    std::vector<int> hole_of(walls.size(), -1);
    std::vector<std::vector<int>> holes;
    for (std::size_t i = 0; i < walls.size(); ++i) {
      if (hole_of[i] >= 0) continue;
      hole_of[i] = int(holes.size());
      holes.push_back({int(i)});
      for (std::size_t q = 0; q < holes.back().size(); ++q) {
        const Surf& a = walls[std::size_t(holes.back()[q])].s;
        for (std::size_t j = 0; j < walls.size(); ++j) {
          if (hole_of[j] >= 0) continue;
          const Surf& b = walls[j].s;
          if (len(cross(a.a, b.a)) > 1e-7 || len(a.p - b.p) > 1e-6 * std::max(1.0, diag)) continue;
          if (b.h0 > a.h1 + gap || b.h1 < a.h0 - gap) continue;
          hole_of[j] = hole_of[i];
          holes.back().push_back(int(j));
        }
      }
    }
    std::printf("%s {\"index\": %d, \"holes\": [\n", solid_index ? "," : "", solid_index);
    bool first = true;
    for (const auto& h : holes) {
      std::vector<Surf> el;
      for (int i : h) el.push_back(walls[std::size_t(i)].s);
      std::sort(el.begin(), el.end(), [](const Surf& a, const Surf& b) { return a.h0 + a.h1 < b.h0 + b.h1; });
      const V a = el[0].a, p = el[0].p;
      const double lo = el.front().h0, hi = el.back().h1;
      double rmax = 0;
      for (const Surf& s : el) rmax = std::max({rmax, radius_at(s, s.h0), radius_at(s, s.h1)});
      // 4. Ends: material on the axis within one radius beyond the last wall = closed.
      auto closed = [&](double h_end, double sgn, const Surf& end) {
        const double r = std::max(radius_at(end, h_end), 1e-3);
        for (double t : {std::min(0.02 * r, 0.05), 0.25 * r, 0.5 * r, 1.0 * r})
          if (inside(p + a * (h_end + sgn * t))) return true;
        return false;
      };
      const bool closed_lo = closed(lo, -1, el.front()), closed_hi = closed(hi, +1, el.back());
      // Ordered from an open end inwards (the one with the larger entry radius when both are open).
      bool from_hi = closed_lo && !closed_hi;
      if (!closed_lo && !closed_hi) from_hi = radius_at(el.back(), hi) > radius_at(el.front(), lo);
      std::vector<Surf> in = el;
      if (from_hi) std::reverse(in.begin(), in.end());
      // seq ordered from an open end; outer_hi: that end is the high end of the axis.
      auto narrowing_cone_at_open_end = [&](const std::vector<Surf>& seq, bool outer_hi) {
        if (seq.size() < 2 || !seq[0].cone) return false;
        const Surf& c = seq[0];
        return radius_at(c, outer_hi ? c.h1 : c.h0) > radius_at(c, outer_hi ? c.h0 : c.h1);
      };
      std::vector<Surf> rev(in.rbegin(), in.rend());
      const bool both_open = !closed_lo && !closed_hi;
      // counterbore: first cylinder (from an open end) larger than the next cylinder.
      auto counterbored = [](const std::vector<Surf>& seq) {
        std::vector<double> cyl;
        for (const Surf& s : seq)
          if (!s.cone) cyl.push_back(s.r);
        return cyl.size() >= 2 && !seq[0].cone ? cyl[0] > cyl[1] * (1 + 1e-6) : false;
      };
      // counterdrill (issue #29, item 3): a counterbore whose seat is a cone narrowing inwards to the
      // bore, the rest of the hole one cylinder radius.
      auto counterdrilled = [&](const std::vector<Surf>& seq, bool outer_hi) {
        if (!counterbored(seq) || seq.size() < 3 || !seq[1].cone || seq[2].cone) return false;
        const Surf& c = seq[1];
        if (!(radius_at(c, outer_hi ? c.h1 : c.h0) > radius_at(c, outer_hi ? c.h0 : c.h1))) return false;
        for (std::size_t i = 3; i < seq.size(); ++i)
          if (seq[i].cone || std::abs(seq[i].r - seq[2].r) > 1e-6 * std::max(1.0, seq[2].r)) return false;
        return true;
      };
      std::string type;
      if (closed_lo && closed_hi) type = "closed_cavity";
      else if (counterdrilled(in, from_hi) || (both_open && counterdrilled(rev, !from_hi))) type = "counterdrilled_hole";
      else if (counterbored(in) || (both_open && counterbored(rev))) type = "counterbored_hole";
      else if (narrowing_cone_at_open_end(in, from_hi) || (both_open && narrowing_cone_at_open_end(rev, !from_hi))) type = "countersunk_hole";
      else {
        std::vector<double> radii;
        for (const Surf& s : el)
          if (!s.cone && std::none_of(radii.begin(), radii.end(), [&](double r) { return std::abs(r - s.r) < 1e-6 * std::max(1.0, s.r); }))
            radii.push_back(s.r);
        if (radii.size() >= 2) type = "stepped_hole";
        else type = (closed_lo || closed_hi) ? "blind_hole" : "through_hole";
      }
      std::printf("%s  {\"type\": \"%s\", \"axis_point\": [%.6f, %.6f, %.6f], \"axis\": [%.9f, %.9f, %.9f], "
                  "\"extent\": [%.6f, %.6f], \"ends\": [\"%s\", \"%s\"], \"max_radius\": %.6f, \"elements\": [",
                  first ? "" : ",\n", type.c_str(), p.x, p.y, p.z, a.x, a.y, a.z, lo, hi, closed_lo ? "closed" : "open",
                  closed_hi ? "closed" : "open", rmax);
      for (std::size_t i = 0; i < el.size(); ++i)
        std::printf("%s{\"kind\": \"%s\", \"r0\": %.6f, \"r1\": %.6f, \"h0\": %.6f, \"h1\": %.6f, \"faces\": %d}",
                    i ? ", " : "", el[i].cone ? "cone" : "cylinder", radius_at(el[i], el[i].h0),
                    radius_at(el[i], el[i].h1), el[i].h0, el[i].h1, el[i].faces);
      std::printf("]}");
      first = false;
    }
    std::printf("\n ]}\n");
  }
  std::printf("]}\n");
  return 0;
}
