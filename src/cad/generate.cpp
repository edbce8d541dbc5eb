// Generated test and benchmark solids (issue #6, items 8-9): OCCT primitives (BRepPrimAPI) and
// Booleans (BRepAlgoAPI_Cut/Fuse, then ShapeUpgrade_UnifySameDomain), written to STEP with
// STEPCAFControl_Writer, each product named after its part. The casing is the paper's case (He & Xu, SJTU 2023, §4): a flanged ring (wall of
// revolution with a B-spline bulge) with counterbored bolt holes on the lower flange and plain bolt
// holes on the upper one.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopLoc_Location.hxx>
#include <XCAFApp_Application.hxx>
#include <Quantity_Color.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Trsf.hxx>
#include <ShapeUpgrade_ShapeDivideClosed.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopTools_ListOfShape.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include <cmath>
#include <numbers>
#include <utility>

#include "generate_floor_parts.h"
#include "generate_shapes.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

using detail::box;
using detail::cut;
using detail::cyl;
using detail::fuse;
using detail::unify;

// Body: a solid of revolution whose outer wall is a B-spline bulge (r 100 -> 112 -> 100 over the
// height; double curvature, so it tessellates into a fine grid like an aero-engine casing wall) around
// a cylindrical bore r = 88.
TopoDS_Shape casing_body(double h, double r_in, double r_out) {
  TColgp_Array1OfPnt pts(1, 5);
  pts.SetValue(1, gp_Pnt(r_out, 0, 0));
  pts.SetValue(2, gp_Pnt(r_out + 8, 0, 0.25 * h));
  pts.SetValue(3, gp_Pnt(r_out + 12, 0, 0.5 * h));
  pts.SetValue(4, gp_Pnt(r_out + 8, 0, 0.75 * h));
  pts.SetValue(5, gp_Pnt(r_out, 0, h));
  Handle(Geom_BSplineCurve) spline = GeomAPI_PointsToBSpline(pts).Curve();
  BRepBuilderAPI_MakeWire w;
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(r_in, 0, 0), gp_Pnt(r_out, 0, 0)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(spline).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(r_out, 0, h), gp_Pnt(r_in, 0, h)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(r_in, 0, h), gp_Pnt(r_in, 0, 0)).Edge());
  const TopoDS_Face profile = BRepBuilderAPI_MakeFace(w.Wire(), Standard_True).Face();
  return BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))).Shape();
}

TopoDS_Shape casing() {
  const double h = 60, r_out = 100, r_in = 88, r_flange = 130, t = 12;
  TopoDS_Shape s = casing_body(h, r_in, r_out);
  s = fuse(s, cut(cyl(0, 0, 0, r_flange, t), cyl(0, 0, -1, r_in, t + 2)));          // lower flange
  s = fuse(s, cut(cyl(0, 0, h - t, r_flange, t), cyl(0, 0, h - t - 1, r_in, t + 2)));  // upper flange
  const int n = 6;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * (i + 0.5) / n;
    const double x = 115 * std::cos(a), y = 115 * std::sin(a);
    s = cut(s, cyl(x, y, -1, 5, t + 2));            // lower: bolt hole r=5 ...
    s = cut(s, cyl(x, y, t - 4, 9, 5));             // ... counterbore r=9, depth 4 from the flange top
    s = cut(s, cyl(x, y, h - t - 1, 6, t + 2));     // upper: plain through hole r=6
  }
  return unify(s);
}

// He & Xu 2023 §4's casing (issue #29, item 4): "P1 screw tightening on the casing's working ring
// (its counterbored holes, FeatureE = {CounterboredHole, BottomFace}: the inner ring face, node 344),
// P2 bolting of the end flange (its circular through holes with the top and bottom faces)". The body
// of `casing()` with plain through holes r = 5 in both end flanges and 6 radial counterbored screw
// holes through the working ring at mid-height (outer wall r = 112 there): bore r = 3 from the inner
// ring face (r = 88) out, counterbore r = 6 from r = 104 out.
TopoDS_Shape paper_casing() {
  const double h = 60, r_out = 100, r_in = 88, r_flange = 130, t = 12;
  TopoDS_Shape s = casing_body(h, r_in, r_out);
  s = fuse(s, cut(cyl(0, 0, 0, r_flange, t), cyl(0, 0, -1, r_in, t + 2)));
  s = fuse(s, cut(cyl(0, 0, h - t, r_flange, t), cyl(0, 0, h - t - 1, r_in, t + 2)));
  const int n = 6;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * (i + 0.5) / n;
    const double x = 115 * std::cos(a), y = 115 * std::sin(a);
    s = cut(s, cyl(x, y, -1, 5, t + 2));         // lower end flange: bolt hole r = 5
    s = cut(s, cyl(x, y, h - t - 1, 5, t + 2));  // upper end flange: bolt hole r = 5
    const double b = 2 * std::numbers::pi * i / n;
    const gp_Dir radial(std::cos(b), std::sin(b), 0);
    s = cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(80 * radial.X(), 80 * radial.Y(), h / 2), radial), 3, 50).Shape());
    s = cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(104 * radial.X(), 104 * radial.Y(), h / 2), radial), 6, 30).Shape());
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
    case TestPart::paper_casing: return paper_casing();
    case TestPart::slot_features_block:
    case TestPart::filleted_pocket_block:
    case TestPart::filleted_step_block: return detail::floor_feature_part(p);
    case TestPart::perforated_plate: return perforated_plate();
    case TestPart::single_face:
      return BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 0, 10, 0, 10).Face();
    case TestPart::box_through_hole_split: {
      ShapeUpgrade_ShapeDivideClosed split(build(TestPart::box_through_hole));
      split.SetNbSplitPoints(1);
      split.Perform();
      return split.Result();
    }
    case TestPart::box_through_hole_nurbs:
      return BRepBuilderAPI_NurbsConvert(build(TestPart::box_through_hole)).Shape();
    case TestPart::countersunk_plate_nurbs:
      return BRepBuilderAPI_NurbsConvert(build(TestPart::countersunk_plate)).Shape();
    case TestPart::pocket_block: {
      // Pocket 15..45 x 10..30 from z 12 up, corners rounded r = 4; a through slot along y at x 5..13
      // whose ends are half cylinders r = 4.
      const double r = 4;
      TopoDS_Shape tool = fuse(box(15 + r, 10, 12, 45 - r, 30, 21), box(15, 10 + r, 12, 45, 30 - r, 21));
      for (double x : {15 + r, 45 - r})
        for (double y : {10 + r, 30 - r}) tool = fuse(tool, cyl(x, y, 12, r, 9));
      TopoDS_Shape slot = fuse(box(5, 8, -1, 13, 32, 21), fuse(cyl(9, 8, -1, 4, 22), cyl(9, 32, -1, 4, 22)));
      return unify(cut(cut(box(0, 0, 0, 60, 40, 20), tool), slot));
    }
    case TestPart::inclined_entry_block: {
      gp_Trsf t;
      t.SetRotation(gp_Ax1(gp_Pnt(0, 15, 14), gp_Dir(1, 0, 0)), 30.0 * std::numbers::pi / 180);
      const TopoDS_Shape wedge = BRepBuilderAPI_Transform(box(-1, -10, 14, 41, 60, 40), t).Shape();
      return unify(cut(cut(box(0, 0, 0, 40, 30, 20), wedge), cyl(20, 15, -1, 4, 30)));
    }
    case TestPart::shaft_cross_hole: {
      const TopoDS_Shape shaft = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 15, 60).Shape();
      return unify(cut(shaft, cyl(30, 0, -20, 3, 40)));
    }
    case TestPart::blind_split_floor: {
      ShapeUpgrade_ShapeDivideClosed split(build(TestPart::box_blind_hole));
      split.SetNbSplitPoints(1);
      split.Perform();
      return split.Result();
    }
    case TestPart::counterdrilled_plate: {
      // The drill point's cone: 118 degrees, from r = 6 at z = 6 down to r = 3, 3 / tan(59 deg) lower.
      const double h = 3 / std::tan(59.0 * std::numbers::pi / 180);
      const TopoDS_Shape cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(20, 15, 6 - h), gp_Dir(0, 0, 1)), 3, 6, h).Shape();
      return unify(cut(cut(cut(box(0, 0, 0, 40, 30, 10), cyl(20, 15, -1, 3, 12)), cyl(20, 15, 6, 6, 5)), cone));
    }
    case TestPart::crossing_holes: {
      const TopoDS_Shape hx = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-1, 20, 10), gp_Dir(1, 0, 0)), 4, 42).Shape();
      const TopoDS_Shape hy = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, -1, 10), gp_Dir(0, 1, 0)), 3, 42).Shape();
      return unify(cut(cut(box(0, 0, 0, 40, 40, 20), hx), hy));
    }
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
    case TestPart::box_through_hole_split: return "box_through_hole_split";
    case TestPart::single_face: return "single_face";
    case TestPart::countersunk_plate_nurbs: return "countersunk_plate_nurbs";
    case TestPart::pocket_block: return "pocket_block";
    case TestPart::inclined_entry_block: return "inclined_entry_block";
    case TestPart::shaft_cross_hole: return "shaft_cross_hole";
    case TestPart::blind_split_floor: return "blind_split_floor";
    case TestPart::crossing_holes: return "crossing_holes";
    case TestPart::counterdrilled_plate: return "counterdrilled_plate";
    case TestPart::paper_casing: return "paper_casing";
    case TestPart::slot_features_block: return "slot_features_block";
    case TestPart::filleted_pocket_block: return "filleted_pocket_block";
    case TestPart::filleted_step_block: return "filleted_step_block";
  }
  return "?";
}

namespace {

// Writes an XCAF document filled by `fill` (shapes and their names) with STEPCAFControl_Writer, so
// that products carry those names; `length_unit` (write.step.unit's names) is the file's length
// unit, the shapes' millimetres converted to it (default: mm).
template <class Fill>
Status write_xcaf(const std::filesystem::path& step_file, Fill&& fill, const char* schema = nullptr,
                  const char* length_unit = nullptr) {
  try {
    // The writer's transfer statistics go to the default messenger's stdout printer: mute it.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    if (const Status s = fill(XCAFDoc_DocumentTool::ShapeTool(doc->Main())); !s.ok())
      return Error{.file = step_file.string(), .reason = s.error().reason};
    // The schema ("AP203", "AP214CD", ...) and the length unit ("MM", "M", "INCH", ...) are
    // process-wide settings of OCCT's STEP interface: set for this writer (registered by
    // STEPControl_Controller::Init), then restored.
    STEPControl_Controller::Init();
    struct Setting {
      const char* name;
      std::string before;
      bool set = false;
      ~Setting() {
        if (set) Interface_Static::SetCVal(name, before.c_str());
      }
    };
    Setting restore_schema{"write.step.schema", Interface_Static::CVal("write.step.schema")};
    Setting restore_unit{"write.step.unit", Interface_Static::CVal("write.step.unit")};
    for (auto [setting, value] :
         {std::pair{&restore_schema, schema}, std::pair{&restore_unit, length_unit}}) {
      if (!value) continue;
      if (!Interface_Static::SetCVal(setting->name, value))
        return Error{.file = step_file.string(),
                     .reason = std::string(setting->name) + ": unknown value '" + value + "'"};
      setting->set = true;
    }
    STEPCAFControl_Writer w;
    w.SetNameMode(Standard_True);
    if (!w.Transfer(doc, STEPControl_AsIs)) return Error{.file = step_file.string(), .reason = "STEP transfer failed"};
    if (w.Write(step_file.string().c_str()) != IFSelect_RetDone)
      return Error{.file = step_file.string(), .reason = "cannot write the STEP file"};
    return {};
  } catch (const Standard_Failure& e) {
    return Error{.file = step_file.string(), .reason = std::string("OpenCASCADE failure: ") + e.GetMessageString()};
  }
}

// One product named `name` (null: after the part, test_part_name), in `length_unit` (null: OCCT's
// setting, mm).
Status write_part(TestPart part, const std::filesystem::path& step_file, const char* length_unit,
                  const char* name = nullptr) {
  return write_xcaf(
      step_file,
      [&](const Handle(XCAFDoc_ShapeTool)& st) -> Status {
        const TopoDS_Shape s = build(part);
        if (s.IsNull()) return Error{.reason = "solid construction failed"};
        TDataStd_Name::Set(st->AddShape(s, Standard_False), name ? name : test_part_name(part));
        return {};
      },
      nullptr, length_unit);
}

}  // namespace

Status write_test_part(TestPart part, const std::filesystem::path& step_file) {
  return write_part(part, step_file, nullptr);
}

Status write_test_part(TestPart part, const std::filesystem::path& step_file,
                       const std::string& length_unit) {
  return write_part(part, step_file, length_unit.c_str());
}

Status write_test_part_named(TestPart part, const std::filesystem::path& step_file, const std::string& product_name) {
  return write_part(part, step_file, nullptr, product_name.c_str());
}

Status write_test_assembly(const std::filesystem::path& step_file) {
  return write_xcaf(step_file, [](const Handle(XCAFDoc_ShapeTool)& st) -> Status {
    const TDF_Label plate = st->AddShape(build(TestPart::counterbored_plate), Standard_False);
    TDataStd_Name::Set(plate, "plate");
    const TDF_Label shaft = st->AddShape(build(TestPart::stepped_shaft), Standard_False);
    TDataStd_Name::Set(shaft, "shaft");
    // Surface colours (issue #29: kept in the glTF of `interfere simplify`).
    const Handle(XCAFDoc_ColorTool) colours = XCAFDoc_DocumentTool::ColorTool(st->Label());
    colours->SetColor(plate, Quantity_Color(0.8, 0.2, 0.1, Quantity_TOC_RGB), XCAFDoc_ColorSurf);
    colours->SetColor(shaft, Quantity_Color(0.1, 0.3, 0.9, Quantity_TOC_RGB), XCAFDoc_ColorSurf);
    const TDF_Label assembly = st->NewShape();
    TDataStd_Name::Set(assembly, "assembly");
    gp_Trsf t2, r2, t3;
    r2.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), std::numbers::pi / 2);
    t2.SetTranslation(gp_Vec(0, 0, 20));
    t2.Multiply(r2);  // rotate 90 degrees about z, then lift by 20
    t3.SetTranslation(gp_Vec(100, 0, 0));
    TDataStd_Name::Set(st->AddComponent(assembly, plate, TopLoc_Location(gp_Trsf())), "plate_1");
    TDataStd_Name::Set(st->AddComponent(assembly, plate, TopLoc_Location(t2)), "plate_2");
    TDataStd_Name::Set(st->AddComponent(assembly, shaft, TopLoc_Location(t3)), "shaft_1");
    st->UpdateAssemblies();
    return {};
  });
}

// A bolted joint with known mates (issue #29, items 2 and 4): the mates are the construction's,
// independent of any recognition. Plate 60x40x10 (z 0..10) and cover 60x40x6 (z 10..16 + gap), each
// with through holes r = 4 at (+-15, 0); a bolt (shank r = 4 from z = -8 to the cover's top, head
// r = 7, 5 high, on the cover) in each hole pair; a nut (r = 7, 6 high, bore r = 4) on each bolt under
// the plate (z -6..0).
Status write_bolted_test_assembly(const std::filesystem::path& step_file, double cover_gap) {
  return write_xcaf(step_file, [cover_gap](const Handle(XCAFDoc_ShapeTool)& st) -> Status {
    const double top = 16 + cover_gap;
    TopoDS_Shape plate = box(-30, -20, 0, 30, 20, 10), cover = box(-30, -20, 10 + cover_gap, 30, 20, top);
    for (double x : {-15.0, 15.0}) {
      plate = cut(plate, cyl(x, 0, -1, 4, 12));
      cover = cut(cover, cyl(x, 0, 9 + cover_gap, 4, 8));
    }
    const TopoDS_Shape bolt = unify(fuse(cyl(0, 0, -8, 4, top + 8), cyl(0, 0, top, 7, 5)));
    const TopoDS_Shape nut = cut(cyl(0, 0, -6, 7, 6), cyl(0, 0, -7, 4, 8));
    const TDF_Label lp = st->AddShape(plate, Standard_False), lc = st->AddShape(cover, Standard_False);
    const TDF_Label lb = st->AddShape(bolt, Standard_False), ln = st->AddShape(nut, Standard_False);
    TDataStd_Name::Set(lp, "plate");
    TDataStd_Name::Set(lc, "cover");
    TDataStd_Name::Set(lb, "bolt");
    TDataStd_Name::Set(ln, "nut");
    const TDF_Label assembly = st->NewShape();
    TDataStd_Name::Set(assembly, "joint");
    st->AddComponent(assembly, lp, TopLoc_Location(gp_Trsf()));  // (one instance each: named by its product)
    st->AddComponent(assembly, lc, TopLoc_Location(gp_Trsf()));
    int k = 0;
    for (double x : {-15.0, 15.0}) {
      gp_Trsf t;
      t.SetTranslation(gp_Vec(x, 0, 0));
      ++k;
      TDataStd_Name::Set(st->AddComponent(assembly, lb, TopLoc_Location(t)), ("bolt_" + std::to_string(k)).c_str());
      TDataStd_Name::Set(st->AddComponent(assembly, ln, TopLoc_Location(t)), ("nut_" + std::to_string(k)).c_str());
    }
    st->UpdateAssemblies();
    return {};
  });
}

// AP203 (CONFIG_CONTROL_DESIGN), shaped as CAD systems export it (as1_pe_203.stp): the product
// PLATE holds its solid as a nameless sub-shape, no instance has a name of its own.
Status write_test_assembly_ap203(const std::filesystem::path& step_file) {
  return write_xcaf(
      step_file,
      [](const Handle(XCAFDoc_ShapeTool)& st) -> Status {
        const TDF_Label solid = st->AddShape(build(TestPart::counterbored_plate), Standard_False);
        const TDF_Label plate = st->NewShape();
        TDataStd_Name::Set(plate, "PLATE");
        st->AddComponent(plate, solid, TopLoc_Location(gp_Trsf()));
        const TDF_Label rod = st->AddShape(build(TestPart::stepped_shaft), Standard_False);
        TDataStd_Name::Set(rod, "ROD");
        const TDF_Label assembly = st->NewShape();
        TDataStd_Name::Set(assembly, "ASM");
        gp_Trsf right, left;
        right.SetTranslation(gp_Vec(100, 0, 0));
        left.SetTranslation(gp_Vec(-100, 0, 0));
        st->AddComponent(assembly, plate, TopLoc_Location(gp_Trsf()));
        st->AddComponent(assembly, rod, TopLoc_Location(right));
        st->AddComponent(assembly, rod, TopLoc_Location(left));
        st->UpdateAssemblies();
        return {};
      },
      "AP203");
}

}  // namespace interfere::cad
