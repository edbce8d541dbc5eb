// Independent labeller of pockets, slots, blind slots and steps for the floor-feature truth set
// (issue #29, item 2). It shares no code and no method with src/cad (no AAG, no arc convexity, no
// surface-type tests of walls or fillets): it reads the STEP file with STEPControl_Reader and, for
// every planar face of each solid (a candidate floor), casts rays just above the floor across its
// outer boundary (IntCurvesFace_ShapeIntersector against the solid):
//   - samples: points along the outer wire's edges in wire order (BRepTools_WireExplorer), each with
//     the in-face direction d (perpendicular to the edge, into the face: checked by classifying a point
//     against the face);
//   - a sample is walled when a ray from just inside the floor (h = 1e-4 of the part's diagonal, and at
//     least 4 times the solid's largest edge tolerance, above it) going out across the edge (-d) meets the
//     solid within 2 % of the diagonal and a ray at one
//     of the heights h, 2h, ..., 1024h meets, within 10 %, a face standing on the floor there (its normal perpendicular
//     to the floor's): a wall, directly or after a fillet; open when the lowest ray meets nothing (the
//     floor meets the outside there); a floor where material rises but stands nowhere (an inclined
//     wall, a round curving over) is not labelled; the faces the rays meet are the feature's walls and
//     fillets;
//   - type, from the walled samples: every one walled: pocket (unless the outer wire is one circle:
//     a hole's floor or a seat, the hole truth set's); else the maximal runs of walled samples along
//     the wire: one straight run (every sample's d parallel, the points on one line): step; two
//     straight runs facing each other (opposite d): slot; one run turning by half a turn whose ends
//     face each other: blind slot (closed at one end); anything else: not labelled.
//   - a step must be mutual (the paper's two planes meeting at one concave edge): its wall, taken as a
//     floor, is a step too whose faces are this floor (and a fillet between), nothing more;
//   - one feature per face set: candidates are taken pockets first, then blind slots, slots, steps;
//     a candidate whose floor is a face of a taken one (a face its rays met), or a taken one's floor one
//     of its faces, is dropped (features sharing only walls are both kept), unless
//     it is of the same type and the same feature seen from its other face (each floor among the
//     other's faces: a step's floor and wall, a blind slot's floor and end), which is merged into it.
// Output per feature: type, floor points (an interior point of each merged floor), floor normals, the
// walled samples' boundary points (for matching to recognised features' triangles) and the faces (this
// tool's numbering: TopExp::MapShapes order of each solid).
//
// Build (OCCT 7.6, not part of the CMake build so that it stays independent of it):
//   g++ -O2 -std=c++17 -I/usr/include/opencascade tools/floor_truth/label_floors.cpp -o /tmp/label_floors \
//     -lTKSTEP -lTKSTEPBase -lTKSTEPAttr -lTKSTEP209 -lTKXSBase -lTKShHealing -lTKTopAlgo -lTKGeomAlgo \
//     -lTKBRep -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel
// Run: /tmp/label_floors FILE.stp > truth.json
#include <BRepAdaptor_Curve.hxx>
#include <BRep_Tool.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <ElSLib.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Lin.hxx>
#include <gp_Pln.hxx>

#include "../truth_common/step_solids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace truth;

struct Sample {
  V p, d;  // boundary point, in-face direction
  bool walled = false;
};

struct Cand {
  std::string type;
  int rank = 0;
  std::vector<int> floors;
  std::vector<V> floor_points, normals, walled;
  std::set<int> faces;  // floor(s) and the faces the rays met
  double area = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const StepSolids step = read_step_solids(argc, argv, "label_floors", "tools/floor_truth/label_floors.cpp");
  if (step.status) return step.status;
  for (int solid_index = 0; solid_index < static_cast<int>(step.solids.size()); ++solid_index) {
    const TopoDS_Solid& solid = step.solids[solid_index];
    const double diag = diagonal(solid);
    // h above the B-Rep's edge tolerance: a ray closer to the floor's edge than that grazes the wall's
    // boundary and reads as a wall where there is none (gmsh_Zylkopf: edge tolerance 4.4e-3 mm > 1e-4 of
    // its 42 mm diagonal; its bolt seats, open to the outside through a notch, were labelled pockets;
    // found by rendering the labels, tools/hole_truth/render_labels.py).
    double edge_tol = 0;
    for (TopExp_Explorer ex(solid, TopAbs_EDGE); ex.More(); ex.Next())
      edge_tol = std::max(edge_tol, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
    const double h = std::max(1e-4 * diag, 4 * edge_tol), reach = 2e-2 * diag, far = 1e-1 * diag, step = diag / 400;
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(solid, TopAbs_FACE, faces);
    IntCurvesFace_ShapeIntersector rays;
    rays.Load(solid, 1e-7);
    std::vector<Cand> cands;
    for (int fi = 1; fi <= faces.Extent(); ++fi) {
      const TopoDS_Face F = TopoDS::Face(faces(fi));
      BRepAdaptor_Surface s(F, Standard_True);
      if (s.GetType() != GeomAbs_Plane) continue;
      const gp_Pln pl = s.Plane();
      V n = pv(gp_Pnt(pl.Axis().Direction().XYZ()));
      if (F.Orientation() == TopAbs_REVERSED) n = n * -1;
      BRepTopAdaptor_FClass2d in_face(F, 1e-7);
      auto on_face = [&](V q) {
        double u, v;
        ElSLib::Parameters(pl, to_pnt(q), u, v);
        return in_face.Perform(gp_Pnt2d(u, v)) == TopAbs_IN;
      };
      const TopoDS_Wire outer = BRepTools::OuterWire(F);
      if (outer.IsNull()) continue;
      std::vector<Sample> samples;
      std::set<int> met;
      bool all_circles = true, rising = false;
      V circle_centre;
      double circle_r = -1;
      for (BRepTools_WireExplorer we(outer, F); we.More(); we.Next()) {
        const TopoDS_Edge& e = we.Current();
        BRepAdaptor_Curve c(e);
        if (c.GetType() == GeomAbs_Circle) {
          const V ctr = pv(c.Circle().Location());
          if (circle_r < 0) circle_r = c.Circle().Radius(), circle_centre = ctr;
          all_circles = all_circles && std::abs(c.Circle().Radius() - circle_r) <= 1e-6 * diag && len(ctr - circle_centre) <= 1e-6 * diag;
        } else {
          all_circles = false;
        }
        const double t0 = c.FirstParameter(), t1 = c.LastParameter();
        const double L = GCPnts_AbscissaPoint::Length(c);
        const int k = std::clamp(int(L / step), 2, 24);
        std::vector<Sample> edge_samples;
        for (int i = 0; i < k; ++i) {
          const double t = t0 + (t1 - t0) * (i + 0.5) / k;
          gp_Pnt p;
          gp_Vec tv;
          c.D1(t, p, tv);
          if (tv.Magnitude() < 1e-12) continue;
          Sample sm;
          sm.p = pv(p);
          V d = unit(cross(n, V{tv.X(), tv.Y(), tv.Z()}));
          const double eps = std::max(1e-3 * L, 4 * h);
          if (!on_face(sm.p + d * eps)) {
            d = d * -1;
            if (!on_face(sm.p + d * eps)) continue;
          }
          sm.d = d;
          // Rays from just inside the floor, at heights h, 2h, ..., 1024h above it, out across the edge:
          // walled when the lowest meets the solid within reach and one of them meets a face standing
          // on the floor there (its normal perpendicular to n: a wall, whatever fillet leads to it);
          // material that rises but never stands (an inclined face, a round curving over) is neither.
          bool first = true, stands = false;
          std::set<int> hits;
          for (double H = h; H <= 1024 * h * (1 + 1e-9); H *= 2) {
            const V o = sm.p + d * h + n * H;
            rays.Perform(gp_Lin(to_pnt(o), gp_Dir(-d.x, -d.y, -d.z)), 0, (first ? reach : far) + h);
            int best = 0;
            if (rays.IsDone())
              for (int j = 1; j <= rays.NbPnt(); ++j)
                if (!best || rays.WParameter(j) < rays.WParameter(best)) best = j;
            if (!best) {
              if (first) break;
              continue;
            }
            first = false;
            const int hit = faces.FindIndex(rays.Face(best));
            if (hit == fi) break;
            hits.insert(hit);
            BRepAdaptor_Surface hs(rays.Face(best), Standard_True);
            gp_Pnt hp;
            gp_Vec du, dv;
            hs.D1(rays.UParameter(best), rays.VParameter(best), hp, du, dv);
            const gp_Vec hn = du.Crossed(dv);
            if (hn.Magnitude() > 1e-12 && std::abs(dot(V{hn.X(), hn.Y(), hn.Z()}, n)) <= 1e-3 * hn.Magnitude()) {
              stands = true;
              break;
            }
          }
          if (!first) {
            if (!stands) {
              rising = true;  // material rises here but stands on no wall: no floor of these features
              continue;
            }
            sm.walled = true;
            met.insert(hits.begin(), hits.end());
          }
          edge_samples.push_back(sm);
        }
        // Wire order: the explorer gives the edges in order; an edge used reversed is walked backwards.
        if (we.Orientation() == TopAbs_REVERSED) std::reverse(edge_samples.begin(), edge_samples.end());
        samples.insert(samples.end(), edge_samples.begin(), edge_samples.end());
      }
      if (rising) continue;
      const std::size_t m = samples.size();
      std::size_t walled = 0;
      for (const Sample& sm : samples) walled += sm.walled;
      if (m < 3 || walled == 0) continue;
      Cand c;
      c.floors = {fi - 1};
      // Faces in this tool's numbering, 0-based.
      std::set<int> zero_based;
      for (int f : met) zero_based.insert(f - 1);
      zero_based.insert(fi - 1);
      c.faces = zero_based;
      for (const Sample& sm : samples)
        if (sm.walled) c.walled.push_back(sm.p);
      if (walled == m) {
        if (all_circles) continue;  // a hole's floor or a counterbore's seat
        c.type = "pocket", c.rank = 0;
      } else {
        // Runs of walled samples, cyclic, starting after an open one.
        std::size_t start = 0;
        while (samples[start].walled) ++start;
        std::vector<std::vector<const Sample*>> runs;
        for (std::size_t i = 1; i <= m; ++i) {
          const Sample& sm = samples[(start + i) % m];
          if (!sm.walled) continue;
          if (runs.empty() || !samples[(start + i - 1) % m].walled) runs.emplace_back();
          runs.back().push_back(&sm);
        }
        auto straight = [&](const std::vector<const Sample*>& r) {
          for (const Sample* q : r) {
            if (dot(q->d, r[0]->d) < 1 - 1e-6) return false;
            if (std::abs(dot(q->p - r[0]->p, r[0]->d)) > 1e-6 * diag) return false;
          }
          return true;
        };
        if (runs.size() == 1 && straight(runs[0])) {
          c.type = "through_step", c.rank = 3;
        } else if (runs.size() == 2 && straight(runs[0]) && straight(runs[1]) && dot(runs[0][0]->d, runs[1][0]->d) < -1 + 1e-6 &&
                   dot(runs[1][0]->p - runs[0][0]->p, runs[0][0]->d) > 0) {
          c.type = "slot", c.rank = 2;
        } else if (runs.size() == 1) {
          // Turning of d along the run, about n.
          const auto& r = runs[0];
          double turn = 0;
          for (std::size_t i = 1; i < r.size(); ++i)
            turn += std::atan2(dot(cross(r[i - 1]->d, r[i]->d), n), dot(r[i - 1]->d, r[i]->d));
          const bool ends_face = dot(r.front()->d, r.back()->d) < -1 + 1e-6 && dot(r.back()->p - r.front()->p, r.front()->d) > 0;
          if (std::abs(std::abs(turn) - M_PI) < 1e-3 && ends_face) c.type = "blind_slot", c.rank = 1;
          else continue;
        } else {
          continue;
        }
      }
      // Interior point of the floor: the first point of a grid over its UV bounds inside it.
      double u0, u1, v0, v1;
      BRepTools::UVBounds(F, u0, u1, v0, v1);
      bool found = false;
      for (int i = 0; i <= 16 && !found; ++i)
        for (int j = 0; j <= 16 && !found; ++j) {
          const double u = u0 + (u1 - u0) * (0.5 + ((i + 1) / 2) * (i % 2 ? 1 : -1) / 17.0);
          const double v = v0 + (v1 - v0) * (0.5 + ((j + 1) / 2) * (j % 2 ? 1 : -1) / 17.0);
          if (in_face.Perform(gp_Pnt2d(u, v)) == TopAbs_IN) c.floor_points.push_back(pv(ElSLib::Value(u, v, pl))), found = true;
        }
      if (!found) continue;
      c.normals.push_back(n);
      cands.push_back(std::move(c));
    }
    // One feature per face set: by rank; same rank merged, lower rank dropped.
    std::stable_sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.rank < b.rank; });
    // A step is the paper's (two planes meeting at one concave edge, open elsewhere): its wall, taken
    // as a floor, is a step whose one wall is this floor.
    {
      std::vector<Cand> kept;
      for (const Cand& c : cands) {
        bool ok = c.type != "through_step";
        for (const Cand& o : cands)
          ok = ok || (o.type == "through_step" && &o != &c && c.faces.count(o.floors[0]) && o.faces.count(c.floors[0]) &&
                      c.faces.size() <= 3 && o.faces.size() <= 3);
        if (ok) kept.push_back(c);
      }
      cands.swap(kept);
    }
    std::vector<Cand> taken;
    for (Cand& c : cands) {
      Cand* hit = nullptr;
      bool drop = false;
      for (Cand& t : taken) {
        // Features that only share walls (two slots either side of one rib, the gaps above and below one
        // cooling fin) are two features; one overlaps another when a floor of either is a face of the other
        // (before: any shared face dropped one: gmsh_Block's fin gaps were labelled one in two, found by
        // rendering the labels, tools/hole_truth/render_labels.py).
        bool share = false;
        for (int f : c.floors) share = share || t.faces.count(f);
        for (int f : t.floors) share = share || c.faces.count(f);
        if (!share) continue;
        // The same feature seen from its other face: each floor is among the other's faces.
        const bool mutual = t.faces.count(c.floors[0]) && c.faces.count(t.floors[0]);
        if (t.rank == c.rank && t.type == c.type && mutual && !hit) hit = &t;
        else drop = true;
      }
      if (drop) continue;
      if (hit) {
        hit->floors.insert(hit->floors.end(), c.floors.begin(), c.floors.end());
        hit->floor_points.insert(hit->floor_points.end(), c.floor_points.begin(), c.floor_points.end());
        hit->normals.insert(hit->normals.end(), c.normals.begin(), c.normals.end());
        hit->walled.insert(hit->walled.end(), c.walled.begin(), c.walled.end());
        hit->faces.insert(c.faces.begin(), c.faces.end());
      } else {
        taken.push_back(std::move(c));
      }
    }
    std::printf("%s  {\"index\": %d, \"faces\": %d, \"features\": [", solid_index ? ",\n" : "", solid_index, faces.Extent());
    for (std::size_t i = 0; i < taken.size(); ++i) {
      const Cand& c = taken[i];
      auto pts = [](const std::vector<V>& v) {
        std::string s = "[";
        for (std::size_t k = 0; k < v.size(); ++k) {
          char b[128];
          std::snprintf(b, sizeof b, "%s[%.6f, %.6f, %.6f]", k ? ", " : "", v[k].x, v[k].y, v[k].z);
          s += b;
        }
        return s + "]";
      };
      std::string fs = "[";
      for (int f : c.faces) fs += (fs.size() > 1 ? ", " : "") + std::to_string(f);
      fs += "]";
      std::string fl = "[";
      for (int f : c.floors) fl += (fl.size() > 1 ? ", " : "") + std::to_string(f);
      fl += "]";
      std::printf("%s\n   {\"type\": \"%s\", \"floors\": %s, \"faces\": %s, \"floor_points\": %s, \"normals\": %s, \"walled\": %s}",
                  i ? "," : "", c.type.c_str(), fl.c_str(), fs.c_str(), pts(c.floor_points).c_str(), pts(c.normals).c_str(),
                  pts(c.walled).c_str());
    }
    std::printf("]}");
  }
  std::printf("\n]}\n");
  return 0;
}
