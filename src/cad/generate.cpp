// Generated test and benchmark solids (issue #6, items 8-9): OCCT primitives (BRepPrimAPI) and
// Booleans (BRepAlgoAPI_Cut/Fuse, then ShapeUpgrade_UnifySameDomain), written to STEP with
// STEPControl_Writer. The casing is the paper's case (He & Xu, SJTU 2023, §4): a flanged ring with
// counterbored bolt holes on the lower flange and plain bolt holes on the upper one.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopTools_ListOfShape.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <numbers>

#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

TopoDS_Shape cyl(double x, double y, double z0, double r, double h) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z0), gp_Dir(0, 0, 1)), r, h).Shape();
}
TopoDS_Shape box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), gp_Pnt(x1, y1, z1)).Shape();
}
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Cut(a, b).Shape(); }
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Fuse(a, b).Shape(); }
TopoDS_Shape unify(const TopoDS_Shape& s) {
  ShapeUpgrade_UnifySameDomain u(s, Standard_True, Standard_True, Standard_False);
  u.Build();
  return u.Shape();
}

TopoDS_Shape casing() {
  const double h = 60, r_out = 100, r_in = 88, r_flange = 130, t = 12;
  TopoDS_Shape s = cyl(0, 0, 0, r_out, h);
  s = fuse(s, cyl(0, 0, 0, r_flange, t));           // lower flange
  s = fuse(s, cyl(0, 0, h - t, r_flange, t));       // upper flange
  s = cut(s, cyl(0, 0, -1, r_in, h + 2));           // bore
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * (i + 0.5) / n;
    const double x = 115 * std::cos(a), y = 115 * std::sin(a);
    s = cut(s, cyl(x, y, -1, 5, t + 2));            // lower: bolt hole r=5 ...
    s = cut(s, cyl(x, y, t - 4, 9, 5));             // ... counterbore r=9, depth 4 from the flange top
    s = cut(s, cyl(x, y, h - t - 1, 6, t + 2));     // upper: plain through hole r=6
  }
  return unify(s);
}

// 400 x 400 x 10 plate with a 13 x 13 grid of counterbored holes (169 x 3 + 6 = 513 faces), cut
// in one Boolean with all tools as arguments.
TopoDS_Shape perforated_plate() {
  TopTools_ListOfShape args, tools;
  args.Append(box(0, 0, 0, 400, 400, 10));
  for (int i = 0; i < 13; ++i)
    for (int j = 0; j < 13; ++j) {
      const double x = 20 + 30 * i, y = 20 + 30 * j;
      tools.Append(cyl(x, y, -1, 4, 12));
      tools.Append(cyl(x, y, 6, 8, 5));
    }
  BRepAlgoAPI_Cut c;
  c.SetArguments(args);
  c.SetTools(tools);
  c.Build();
  return unify(c.Shape());
}

TopoDS_Shape build(TestPart p) {
  switch (p) {
    case TestPart::box_through_hole: return cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, -1, 4, 12));
    case TestPart::box_blind_hole: return cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, 4, 4, 7));
    case TestPart::counterbored_plate:
      return unify(cut(cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, -1, 3, 12)), cyl(20, 15, 6, 6, 5)));
    case TestPart::countersunk_plate: {
      const TopoDS_Shape cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(20, 15, 7), gp_Dir(0, 0, 1)), 3, 7, 4).Shape();
      return unify(cut(cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, -1, 3, 12)), cone));
    }
    case TestPart::stepped_shaft: return unify(fuse(cyl(0, 0, 0, 10, 30), cyl(0, 0, 30, 6, 25)));
    case TestPart::slot_block: return unify(cut(box(0, 0, 0, 40, 30, 20), box(-1, 10, 12, 41, 20, 21)));
    case TestPart::step_block: return unify(cut(box(0, 0, 0, 40, 30, 20), box(-1, 20, 12, 41, 31, 21)));
    case TestPart::near_miss_plate:
      return unify(cut(cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, -1, 3, 12)), cyl(22, 15, 6, 6, 5)));
    case TestPart::casing: return casing();
    case TestPart::perforated_plate: return perforated_plate();
    case TestPart::box_through_hole_nurbs:
      return BRepBuilderAPI_NurbsConvert(build(TestPart::box_through_hole)).Shape();
  }
  return {};
}

}  // namespace

const char* test_part_name(TestPart p) {
  switch (p) {
    case TestPart::box_through_hole: return "box_through_hole";
    case TestPart::box_blind_hole: return "box_blind_hole";
    case TestPart::counterbored_plate: return "counterbored_plate";
    case TestPart::countersunk_plate: return "countersunk_plate";
    case TestPart::stepped_shaft: return "stepped_shaft";
    case TestPart::slot_block: return "slot_block";
    case TestPart::step_block: return "step_block";
    case TestPart::near_miss_plate: return "near_miss_plate";
    case TestPart::casing: return "casing";
    case TestPart::box_through_hole_nurbs: return "box_through_hole_nurbs";
    case TestPart::perforated_plate: return "perforated_plate";
  }
  return "?";
}

Status write_test_part(TestPart part, const std::filesystem::path& step_file) {
  try {
    const TopoDS_Shape s = build(part);
    if (s.IsNull()) return Error{.file = step_file.string(), .reason = "solid construction failed"};
    // The writer's transfer statistics go to the default messenger's stdout printer: mute it.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    STEPControl_Writer w;
    if (w.Transfer(s, STEPControl_AsIs) != IFSelect_RetDone)
      return Error{.file = step_file.string(), .reason = "STEP transfer failed"};
    if (w.Write(step_file.string().c_str()) != IFSelect_RetDone)
      return Error{.file = step_file.string(), .reason = "cannot write the STEP file"};
    return {};
  } catch (const Standard_Failure& e) {
    return Error{.file = step_file.string(), .reason = std::string("OpenCASCADE failure: ") + e.GetMessageString()};
  }
}

}  // namespace interfere::cad
