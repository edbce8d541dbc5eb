// Generator of the review parts of tests/cad/test_review_sector_split.cpp (review of e5bad37, issue
// #29): surfaces of revolution with holes' rims as inner wires, other than the casing. Not built by
// CMake (tests/cad globs only its own folder's *.cpp); the STEP files it wrote are committed beside it.
// Build: g++ -std=c++17 -O1 -I/usr/include/opencascade make_parts.cpp -o make_parts \
//   -lTKSTEP -lTKSTEPBase -lTKSTEPAttr -lTKSTEP209 -lTKXSBase -lTKShHealing -lTKBool -lTKBO -lTKPrim \
//   -lTKTopAlgo -lTKGeomAlgo -lTKBRep -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel
// Run: ./make_parts OUT_DIR  (writes NAME.step and NAME.volume: the B-Rep volume by GProp)
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GProp_GProps.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {
struct Hole {
  double angle_deg, z, r, depth_from, depth_to;  // radial cylinder from radius depth_from to depth_to
};

TopoDS_Shape drill(TopoDS_Shape s, const std::vector<Hole>& holes, double cx = 0, double cy = 0) {
  for (const Hole& h : holes) {
    const double a = h.angle_deg * M_PI / 180;
    const gp_Dir d(std::cos(a), std::sin(a), 0);
    const gp_Pnt p(cx + h.depth_from * std::cos(a), cy + h.depth_from * std::sin(a), h.z);
    const TopoDS_Shape c = BRepPrimAPI_MakeCylinder(gp_Ax2(p, d), h.r, h.depth_to - h.depth_from).Shape();
    s = BRepAlgoAPI_Cut(s, c).Shape();
  }
  return s;
}

void write(const std::string& dir, const std::string& name, const TopoDS_Shape& s) {
  STEPControl_Writer w;
  Interface_Static::SetCVal("write.step.schema", "AP214");
  w.Transfer(s, STEPControl_AsIs);
  w.Write((dir + "/" + name + ".step").c_str());
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g);
  std::ofstream(dir + "/" + name + ".volume") << std::to_string(g.Mass()) << "\n";
  std::printf("%s: volume %.6f\n", name.c_str(), g.Mass());
}
}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  // 1. A tube (R 20, bore 15, height 30) with 5 radial through holes, one across the seam (u = 0),
  //    the others at irregular angles and heights.
  {
    TopoDS_Shape tube = BRepAlgoAPI_Cut(BRepPrimAPI_MakeCylinder(20, 30).Shape(), BRepPrimAPI_MakeCylinder(15, 30).Shape()).Shape();
    tube = drill(tube, {{0, 15, 2, 10, 25}, {71, 8, 2.5, 10, 25}, {152, 21, 1.5, 10, 25}, {213, 12, 3, 10, 25}, {289, 20, 2, 10, 25}});
    write(dir, "tube_seam_holes", tube);
  }
  // 2. A solid cone frustum (r 25 -> 12, height 30) with 4 blind radial holes at irregular angles.
  {
    TopoDS_Shape cone = BRepPrimAPI_MakeCone(25, 12, 30).Shape();
    cone = drill(cone, {{10, 10, 2, 10, 30}, {100, 18, 1.5, 5, 30}, {135, 6, 2, 12, 30}, {260, 14, 2.5, 8, 30}});
    write(dir, "cone_holes", cone);
  }
  // 3. A torus (R 30, r 8) with 4 radial holes into its outer side at irregular angles.
  {
    TopoDS_Shape torus = BRepPrimAPI_MakeTorus(30, 8).Shape();
    torus = drill(torus, {{17, 0, 2, 30, 45}, {95, 2, 1.5, 30, 45}, {181, -1.5, 2.5, 30, 45}, {302, 0.5, 2, 30, 45}});
    write(dir, "torus_holes", torus);
  }
  // 4. A cylinder whose 4 holes' rims form only 2 angular groups (overlapping in angle): not split.
  {
    TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(20, 40).Shape();
    cyl = drill(cyl, {{40, 10, 2, 10, 25}, {44, 30, 2, 10, 25}, {200, 12, 2.5, 10, 25}, {203, 28, 2, 10, 25}});
    write(dir, "cylinder_two_groups", cyl);
  }
  // 5. A sphere (r 20) with 3 blind radial holes near the equator at irregular angles.
  {
    TopoDS_Shape sph = BRepPrimAPI_MakeSphere(20).Shape();
    sph = drill(sph, {{33, 2, 2, 10, 25}, {140, -3, 2.5, 10, 25}, {251, 4, 1.5, 10, 25}});
    write(dir, "sphere_holes", sph);
  }
  // 6. A cylinder with 6 holes, two pairs nearly touching in angle (tiny gaps between groups) and one
  //    just beside the seam (not across it).
  {
    TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(20, 40).Shape();
    cyl = drill(cyl, {{8, 20, 2, 10, 25}, {20, 12, 1.5, 10, 25}, {25.2, 28, 1.5, 10, 25}, {120, 20, 3, 10, 25},
                      {240, 10, 2, 10, 25}, {352, 30, 2, 10, 25}});
    write(dir, "cylinder_tight_gaps", cyl);
  }
  // 7. A pointed cone (r 25 -> 0, height 30: its apex a degenerated edge) with 3 blind radial holes.
  {
    TopoDS_Shape cone = BRepPrimAPI_MakeCone(25, 0, 30).Shape();
    cone = drill(cone, {{20, 8, 2, 8, 30}, {150, 12, 1.5, 6, 30}, {265, 6, 2, 10, 30}});
    write(dir, "cone_apex_holes", cone);
  }
  // 8. A torus (R 30, r 8) with 4 vertical through holes at irregular angles, away from its V seam
  //    (the outer equator): 8 rims as inner wires, 4 angular groups.
  {
    TopoDS_Shape torus = BRepPrimAPI_MakeTorus(30, 8).Shape();
    for (const double deg : {12.0, 101.0, 188.0, 297.0}) {
      const double a = deg * M_PI / 180;
      const double rr = deg > 150 ? 29.0 : 31.5, rh = deg > 150 ? 2.5 : 1.8;
      const TopoDS_Shape c = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(rr * std::cos(a), rr * std::sin(a), -12), gp_Dir(0, 0, 1)), rh, 24).Shape();
      torus = BRepAlgoAPI_Cut(torus, c).Shape();
    }
    write(dir, "torus_top_holes", torus);
  }
  return 0;
}
