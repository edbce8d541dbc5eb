// Tessellates a STEP file for tools/hole_truth/render_labels.py (issue #29, item 2: the truth set's
// labels "checked by rendering"). Like the labellers (label_holes.cpp, ../floor_truth/label_floors.cpp)
// it reads the file with STEPControl_Reader, walks the solids of OneShape() with TopExp_Explorer and
// numbers each solid's faces in TopExp::MapShapes order (0-based), so that the labels' solid and face
// indices address the same faces here; it shares no code with src/cad. Every face is meshed by
// BRepMesh_IncrementalMesh (linear deflection 0.1 % of the shape's diagonal unless given, 0.25 rad).
//
// Output (text, one record a line):
//   s SOLID NFACES
//   f SOLID FACE TYPE [cylinder: px py pz ax ay az r | cone: px py pz ax ay az r semi_angle]
//       (TYPE: plane cylinder cone sphere torus bspline other; a cone's r is its radius at p)
//   t SOLID FACE x0 y0 z0 x1 y1 z1 x2 y2 z2   (world mm, counter-clockwise seen from outside the solid)
// Exit status 0 on success, 1 on an unreadable file or a face without triangulation (named), 2 on usage.
//
// Build (OCCT 7.6; also built by tests/CMakeLists.txt as interfere_tessellate_faces for the ctest):
//   g++ -O2 -std=c++17 -I/usr/include/opencascade tools/hole_truth/tessellate_faces.cpp -o /tmp/tessellate_faces \
//     -lTKSTEP -lTKSTEPBase -lTKSTEPAttr -lTKSTEP209 -lTKXSBase -lTKShHealing -lTKTopAlgo -lTKGeomAlgo \
//     -lTKMesh -lTKBRep -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel
// Run: /tmp/tessellate_faces FILE.stp OUT.txt [LINEAR_DEFLECTION_MM]
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

const char* type_name(GeomAbs_SurfaceType t) {
  switch (t) {
    case GeomAbs_Plane: return "plane";
    case GeomAbs_Cylinder: return "cylinder";
    case GeomAbs_Cone: return "cone";
    case GeomAbs_Sphere: return "sphere";
    case GeomAbs_Torus: return "torus";
    case GeomAbs_BSplineSurface: return "bspline";
    default: return "other";
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: tessellate_faces FILE.stp OUT.txt [LINEAR_DEFLECTION_MM]\n");
    return 2;
  }
  STEPControl_Reader reader;
  if (reader.ReadFile(argv[1]) != IFSelect_RetDone) {
    std::fprintf(stderr, "tessellate_faces: cannot read %s\n", argv[1]);
    return 1;
  }
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  if (box.IsVoid()) {
    std::fprintf(stderr, "tessellate_faces: %s: no geometry\n", argv[1]);
    return 1;
  }
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  const double diag = std::sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + (z1 - z0) * (z1 - z0));
  double lin = 1e-3 * diag;
  if (argc == 4) {
    char* end = nullptr;
    lin = std::strtod(argv[3], &end);
    if (end == argv[3] || *end != '\0' || !(lin > 0)) {
      std::fprintf(stderr, "tessellate_faces: LINEAR_DEFLECTION_MM: not a length > 0: %s\n", argv[3]);
      return 2;
    }
  }
  BRepMesh_IncrementalMesh mesh(shape, lin, Standard_False, 0.25, Standard_False);
  FILE* out = std::fopen(argv[2], "w");
  if (!out) {
    std::fprintf(stderr, "tessellate_faces: cannot write %s\n", argv[2]);
    return 1;
  }
  int solid_index = 0;
  for (TopExp_Explorer sx(shape, TopAbs_SOLID); sx.More(); sx.Next(), ++solid_index) {
    const TopoDS_Solid solid = TopoDS::Solid(sx.Current());
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(solid, TopAbs_FACE, faces);
    std::fprintf(out, "s %d %d\n", solid_index, faces.Extent());
    for (int fi = 1; fi <= faces.Extent(); ++fi) {
      const TopoDS_Face f = TopoDS::Face(faces(fi));
      BRepAdaptor_Surface s(f, Standard_True);
      std::fprintf(out, "f %d %d %s", solid_index, fi - 1, type_name(s.GetType()));
      if (s.GetType() == GeomAbs_Cylinder) {
        const gp_Cylinder c = s.Cylinder();
        const gp_Pnt p = c.Location();
        const gp_Dir a = c.Axis().Direction();
        std::fprintf(out, " %.9g %.9g %.9g %.9g %.9g %.9g %.9g", p.X(), p.Y(), p.Z(), a.X(), a.Y(), a.Z(), c.Radius());
      } else if (s.GetType() == GeomAbs_Cone) {
        const gp_Cone c = s.Cone();
        const gp_Pnt p = c.Location();
        const gp_Dir a = c.Axis().Direction();
        std::fprintf(out, " %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g", p.X(), p.Y(), p.Z(), a.X(), a.Y(), a.Z(),
                     c.RefRadius(), c.SemiAngle());
      }
      std::fprintf(out, "\n");
      TopLoc_Location loc;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(f, loc);
      if (tri.IsNull()) {
        std::fprintf(stderr, "tessellate_faces: %s: solid %d face %d has no triangulation (skipped)\n", argv[1],
                     solid_index, fi - 1);
        continue;
      }
      const gp_Trsf tr = loc.Transformation();
      const bool reversed = f.Orientation() == TopAbs_REVERSED;
      for (int k = 1; k <= tri->NbTriangles(); ++k) {
        int n[3];
        tri->Triangle(k).Get(n[0], n[1], n[2]);
        if (reversed) std::swap(n[1], n[2]);
        std::fprintf(out, "t %d %d", solid_index, fi - 1);
        for (int j = 0; j < 3; ++j) {
          const gp_Pnt q = tri->Node(n[j]).Transformed(tr);
          std::fprintf(out, " %.7g %.7g %.7g", q.X(), q.Y(), q.Z());
        }
        std::fprintf(out, "\n");
      }
    }
  }
  std::fclose(out);
  return 0;
}
