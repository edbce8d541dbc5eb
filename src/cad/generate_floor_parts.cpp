// Generated parts with slots, blind slots, steps and pockets, with floor fillets and corner rounds
// (issue #29, item 1: floor features and fillets that must not be reported). OCCT primitives, Booleans
// and BRepFilletAPI_MakeFillet (real rolling-ball fillets, as CAD systems make them). Sizes in mm; the
// construction parameters are in model.h's TestPart comments and are what the tests check against.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <functional>

#include "generate_floor_parts.h"
#include "generate_shapes.h"

namespace interfere::cad::detail {
namespace {

// Fillets of radius r on the straight edges whose middle point and direction `pick` accepts.
using EdgePick = std::function<bool(const gp_Pnt& mid, const gp_Dir& dir)>;
TopoDS_Shape fillet(const TopoDS_Shape& s, double r, const EdgePick& pick) {
  BRepFilletAPI_MakeFillet mk(s);
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  int n = 0;
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edges(i));
    BRepAdaptor_Curve c(e);
    if (c.GetType() != GeomAbs_Line) continue;
    const double m = 0.5 * (c.FirstParameter() + c.LastParameter());
    if (pick(c.Value(m), c.Line().Direction())) mk.Add(r, e), ++n;
  }
  if (n == 0) throw Standard_Failure("no edge to fillet");
  mk.Build();
  if (!mk.IsDone()) throw Standard_Failure("fillet failed");
  return mk.Shape();
}

bool near(double a, double b) { return std::abs(a - b) < 1e-6; }
bool along_z(const gp_Dir& d) { return std::abs(d.Z()) > 1 - 1e-9; }
bool along_x(const gp_Dir& d) { return std::abs(d.X()) > 1 - 1e-9; }

// Block 80 x 60 x 30, its four vertical edges rounded r = 4 (convex corner rounds); a through slot
// along x, y 5..17, floor z = 22, floor fillets r = 2; a blind slot from x = 0 along x, y 25..35,
// floor z = 24, closed by a round end (half cylinder r = 5 about (40, 30)); a blind slot from x = 80
// back to x = 50, y 43..55, floor z = 20, square end at x = 50 with corner rounds r = 2.
TopoDS_Shape slot_features_block() {
  TopoDS_Shape b = fillet(box(0, 0, 0, 80, 60, 30), 4, [](const gp_Pnt&, const gp_Dir& d) { return along_z(d); });
  // Through slot with a rounded floor: the tool's bottom edges along x rounded r = 2.
  const TopoDS_Shape t1 = fillet(box(-1, 5, 22, 81, 17, 31), 2,
                                 [](const gp_Pnt& m, const gp_Dir& d) { return along_x(d) && near(m.Z(), 22); });
  b = cut(b, t1);
  b = cut(b, fuse(box(-1, 25, 24, 40, 35, 31), cyl(40, 30, 24, 5, 7)));
  const TopoDS_Shape t3 = fillet(box(50, 43, 20, 81, 55, 31), 2,
                                 [](const gp_Pnt& m, const gp_Dir& d) { return along_z(d) && near(m.X(), 50); });
  return unify(cut(b, t3));
}

// Block 70 x 50 x 25; a pocket x 15..55, y 10..40, floor z = 15, vertical corner rounds r = 5 and
// floor fillets r = 2 all round (the tool: a box with its vertical edges, then its bottom edges,
// rounded); the block's top outer edges rounded r = 1.5 (convex fillets).
TopoDS_Shape filleted_pocket_block() {
  TopoDS_Shape tool = fillet(box(15, 10, 15, 55, 40, 26), 5, [](const gp_Pnt&, const gp_Dir& d) { return along_z(d); });
  tool = fillet(tool, 2, [](const gp_Pnt& m, const gp_Dir&) { return near(m.Z(), 15); });
  TopoDS_Shape b = fillet(box(0, 0, 0, 70, 50, 25), 1.5,
                          [](const gp_Pnt& m, const gp_Dir& d) { return !along_z(d) && near(m.Z(), 25); });
  return unify(cut(b, tool));
}

// Block 60 x 40 x 30; a through step along x at y 0..12, floor z = 20, wall y = 12, the concave edge
// between them filleted r = 3 and the wall's top edge rounded r = 2 (a convex fillet); a plain
// through step at y 30..40, floor z = 22, wall y = 30.
TopoDS_Shape filleted_step_block() {
  TopoDS_Shape b = cut(box(0, 0, 0, 60, 40, 30), box(-1, -1, 20, 61, 12, 31));
  b = cut(b, box(-1, 30, 22, 61, 41, 31));
  b = fillet(b, 3, [](const gp_Pnt& m, const gp_Dir& d) { return along_x(d) && near(m.Y(), 12) && near(m.Z(), 20); });
  b = fillet(b, 2, [](const gp_Pnt& m, const gp_Dir& d) { return along_x(d) && near(m.Y(), 12) && near(m.Z(), 30); });
  return unify(b);
}

}  // namespace

TopoDS_Shape floor_feature_part(TestPart p) {
  switch (p) {
    case TestPart::slot_features_block: return slot_features_block();
    case TestPart::filleted_pocket_block: return filleted_pocket_block();
    case TestPart::filleted_step_block: return filleted_step_block();
    default: break;
  }
  throw Standard_Failure("not a floor-feature test part");
}

}  // namespace interfere::cad::detail
