// STEP import (issue #6, item 1) with OpenCASCADE 7.6: STEPCAFControl_Reader into an XCAF
// document (names, assembly structure, instance locations), BRepMesh_IncrementalMesh tessellation
// per part with every triangle tagged by its B-Rep face (vertices duplicated along face boundaries,
// taken per face from Poly_Triangulation; a face meshed as angular sectors, sector_split.cpp, gives
// its sectors' triangles its id), then the part's AAG (aag_build.cpp, on the part as read).
// Malformed files (step_guard.h): OCCT's translator dereferences null handles on some (a reference
// to a missing or mistyped entity: SIGSEGV in StepToGeom) and recurses along reference cycles, so
// the file is parsed in XSControl_Reader's steps with a cycle check before OCCT's entity checks,
// and signals become Standard_Failure exceptions at OCC_CATCH_SIGNALS during the import (OSD, the
// OCCT mechanism for Linux: OCC_CONVERT_SIGNALS below, before Standard_ErrorHandler.hxx).
#ifndef OCC_CONVERT_SIGNALS
#define OCC_CONVERT_SIGNALS
#endif
#include <Bnd_Box.hxx>
#include <BRep_Tool.hxx>
#include <BRepBndLib.hxx>
#include <BRepMesh_Context.hxx>
#include <BRepMesh_DelabellaMeshAlgoFactory.hxx>
#include <BRepMesh_FaceDiscret.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IFSelect_WorkLibrary.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_Graph.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Protocol.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDF_Tool.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XCAFApp_Application.hxx>
#include <Quantity_Color.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <tbb/task_group.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <set>

#include "interfere/core/coordinate_range.h"
#include "occt_internal.h"
#include "step_guard.h"

namespace interfere::cad {
namespace {

constexpr double kMinDeflection = 1e-7;  // mm: Precision::Confusion()

std::string label_name(const TDF_Label& l) {
  Handle(TDataStd_Name) n;
  if (l.FindAttribute(TDataStd_Name::GetID(), n)) {
    TCollection_AsciiString s(n->Get());
    return s.ToCString();
  }
  return {};
}

// The label's name as the file gives it, or "" where it is a name OCCT made up: XCAFDoc_ShapeTool's
// automatic names, "=>[0:1:1:3]" for a component (its link) and a shape type ("SOLID",
// "COMPOUND") for a shape (also when an OCCT writer put them in the file: its type may differ once
// read back), and a name of digits only, the NEXT_ASSEMBLY_USAGE_OCCURRENCE id that
// STEPCAFControl_Reader gives a component whose NAUO has no name. AP203 exports (as1_pe_203.stp)
// hold each product's solid as such a nameless sub-shape of the product.
std::string real_name(const TDF_Label& l) {
  std::string n = label_name(l);
  if (n.size() > 3 && n.compare(0, 3, "=>[") == 0 && n.back() == ']') return {};
  if (!n.empty() && std::all_of(n.begin(), n.end(), [](char c) { return c >= '0' && c <= '9'; })) return {};
  for (const char* type : {"COMPOUND", "COMPSOLID", "SOLID", "SHELL", "FACE", "WIRE", "EDGE", "VERTEX", "SHAPE"})
    if (n == type) return {};
  return n;
}

Transform to_transform(const TopLoc_Location& loc) {
  const gp_Trsf t = loc.Transformation();
  Transform r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.r[i][j] = t.Value(i + 1, j + 1);
  }
  r.t = {t.Value(1, 4), t.Value(2, 4), t.Value(3, 4)};
  return r;
}

Part make_part(const TopoDS_Shape& shape, const std::string& name, const ImportOptions& o,
               std::vector<std::string>& warnings) {
  Part p;
  p.name = name;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) ++p.solids;
  for (TopExp_Explorer x(shape, TopAbs_SHELL); x.More(); x.Next()) ++p.shells;
  p.faces = static_cast<std::uint32_t>(faces.Extent());
  double lin = o.linear_deflection;
  if (!(lin > 0)) {
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    if (!box.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      lin = 1e-3 * std::sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + (z1 - z0) * (z1 - z0));
    }
    if (!(lin > 0)) lin = 1e-3;
    lin = std::max(lin, kMinDeflection);
  }
  p.linear_deflection = lin;
  // Expensive faces meshed as angular sectors (sector_split.cpp); `mesh_shape` is the part itself
  // where none is split. The triangles of a face's sectors are the face's, tagged with its id.
  detail::SectorSplit split;
  if (o.sector_split) {
    split = detail::split_for_meshing(shape, faces);
  } else {
    split.shape = shape;
    for (int i = 1; i <= faces.Extent(); ++i) split.faces.push_back({TopoDS::Face(faces(i))});
  }
  const TopoDS_Shape& mesh_shape = split.shape;
  // (ImportOptions::delabella: the same parameters, OCCT's Delabella Delaunay per face; sectors are
  // always meshed with it, sector_split.cpp)
  if (o.delabella || split.split_faces > 0) {
    IMeshTools_Parameters params;
    params.Deflection = lin, params.Angle = o.angular_deflection, params.Relative = Standard_False;
    params.InParallel = Standard_True;
    Handle(IMeshTools_Context) context = new BRepMesh_Context();
    context->SetFaceDiscret(new BRepMesh_FaceDiscret(
        o.delabella ? Handle(IMeshTools_MeshAlgoFactory)(new BRepMesh_DelabellaMeshAlgoFactory())
                    : detail::sector_algo_factory(split)));
    BRepMesh_IncrementalMesh mesher;
    mesher.SetShape(mesh_shape);
    mesher.ChangeParameters() = params;
    mesher.Perform(context);
  } else {
    BRepMesh_IncrementalMesh mesher(mesh_shape, lin, Standard_False, o.angular_deflection, Standard_True);
  }
  // The AAG (on the part as read) is built while the triangles are collected and measured: after
  // BRepMesh both only read the B-Rep (issue #29: the casing's import, AAG 12 ms beside the
  // collection's 25 ms). OCCT's failures and signals in it are caught there and rethrown here.
  Aag aag;
  std::exception_ptr aag_failed;
  tbb::task_group aag_task;
  if (o.build_aag)
    aag_task.run([&] {
      try {
        OCC_CATCH_SIGNALS
        aag = detail::build_aag(shape, faces, o.canonical_tolerance);
      } catch (...) {
        aag_failed = std::current_exception();
      }
    });
  bool unmeasured = false;  // a face without UV nodes
  p.tessellation_deviation = 0;
  for (int i = 1; i <= faces.Extent(); ++i) {
    const std::vector<TopoDS_Face>& pieces = split.faces[static_cast<std::size_t>(i - 1)];
    const bool any = std::any_of(pieces.begin(), pieces.end(), [](const TopoDS_Face& f) {
      TopLoc_Location l;
      const Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(f, l);
      return !t.IsNull() && t->NbTriangles() > 0;
    });
    if (!any) {
      p.untessellated_faces.push_back(static_cast<std::uint32_t>(i - 1));
      warnings.push_back("part '" + name + "': face " + std::to_string(i - 1) + " failed to tessellate");
      continue;
    }
    for (const TopoDS_Face& f : pieces) {  // (one piece: the face itself)
      TopLoc_Location loc;
      Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(f, loc);
      if (tri.IsNull() || tri->NbTriangles() == 0) {  // (a sector failed: the face counts as tessellated)
        warnings.push_back("part '" + name + "': a sector of face " + std::to_string(i - 1) + " failed to tessellate");
        continue;
      }
      const gp_Trsf tr = loc.Transformation();
      const auto base = static_cast<std::uint32_t>(p.mesh.positions.size());
      for (int n = 1; n <= tri->NbNodes(); ++n) {
        gp_Pnt q = tri->Node(n);
        q.Transform(tr);
        p.mesh.positions.push_back({q.X(), q.Y(), q.Z()});
      }
      const bool reversed = f.Orientation() == TopAbs_REVERSED;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int a, b, c;
        tri->Triangle(t).Get(a, b, c);
        if (reversed) std::swap(b, c);
        p.mesh.triangles.push_back({base + std::uint32_t(a - 1), base + std::uint32_t(b - 1), base + std::uint32_t(c - 1)});
        p.face_ids.push_back(static_cast<std::uint32_t>(i - 1));
      }
      if (o.measure_deviation) {
        const double d = detail::tessellation_deviation(f, *tri, tr, lin);
        if (d < 0) unmeasured = true;
        p.tessellation_deviation = std::max(p.tessellation_deviation, d);
      }
    }
  }
  if (!o.measure_deviation || unmeasured) p.tessellation_deviation = -1;
  aag_task.wait();
  if (aag_failed) std::rethrow_exception(aag_failed);
  if (!o.build_aag) return p;
  p.aag = std::move(aag);
  for (std::size_t t = 0; t < p.face_ids.size(); ++t) ++p.aag.nodes[p.face_ids[t]].triangles;
  return p;
}

struct Walker {
  Handle(XCAFDoc_ShapeTool) tool;
  const ImportOptions& o;
  CadModel& model;
  std::map<int, std::uint32_t> part_of_label;  // by label tag path hash
  std::map<std::string, std::uint32_t> part_by_entry;
  std::set<std::string> skipped;  ///< labels without faces, warned about once
  Handle(XCAFDoc_ColorTool) colors;  ///< the document's colours (issue #29: kept in glTF)

  // `inst_name`: the component's own name ("" when it has none); `parent`: the name of the
  // product whose structure holds `label` ("" at the top).
  // `suffix`: "#k" for the k-th instance (k > 1) named alike in its assembly, added to its path level.
  void walk(const TDF_Label& label, const TopLoc_Location& loc, const std::string& path, const std::string& inst_name,
            const std::string& parent, const std::string& suffix = "") {
    TDF_Label ref = label;
    TopLoc_Location here = loc;
    if (XCAFDoc_ShapeTool::IsReference(label)) {
      XCAFDoc_ShapeTool::GetReferredShape(label, ref);
      here = loc * XCAFDoc_ShapeTool::GetLocation(label);
    }
    // The product's name; a nameless shape inside a product (an AP203 product's solid) is that
    // product, and adds no level to the path.
    std::string name = real_name(ref);
    if (name.empty() && ref != label) name = real_name(label);
    const bool sub_shape = name.empty() && inst_name.empty() && !parent.empty();
    if (name.empty()) name = parent.empty() ? "part" + std::to_string(model.parts.size()) : parent;
    const std::string my_path = sub_shape ? path : path + "/" + (inst_name.empty() ? name : inst_name) + suffix;
    if (XCAFDoc_ShapeTool::IsAssembly(ref)) {
      TDF_LabelSequence comps;
      XCAFDoc_ShapeTool::GetComponents(ref, comps);
      // Unnamed instances of one product in one assembly (AP203: NAUOs without names) are told
      // apart at their own level, "#2", "#3", ... (issue #29, item 5: before, AS1's two bracket
      // sub-assemblies shared one path level and only the leaves got "#2".."#6").
      std::map<std::string, int> seen;
      for (int i = 1; i <= comps.Length(); ++i) {
        const std::string inst = real_name(comps(i));
        TDF_Label cref = comps(i);
        if (XCAFDoc_ShapeTool::IsReference(comps(i))) XCAFDoc_ShapeTool::GetReferredShape(comps(i), cref);
        const std::string level = inst.empty() ? real_name(cref) : inst;
        const int k = level.empty() ? 1 : ++seen[level];
        walk(comps(i), here, my_path, inst, name, k > 1 ? "#" + std::to_string(k) : std::string());
      }
      return;
    }
    TCollection_AsciiString entry;
    TDF_Tool::Entry(ref, entry);
    std::uint32_t part_index;
    auto it = part_by_entry.find(entry.ToCString());
    if (it != part_by_entry.end()) {
      part_index = it->second;
    } else {
      const TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(ref);
      if (shape.IsNull()) return;
      TopExp_Explorer fx(shape, TopAbs_FACE);
      if (!fx.More()) {  // once per shape, however many instances refer to it
        if (skipped.insert(entry.ToCString()).second)
          model.warnings.push_back("'" + name + "' at " + my_path + " (XCAF label " + entry.ToCString() +
                                   ") has no faces (not a solid or shell): skipped");
        return;
      }
      part_index = static_cast<std::uint32_t>(model.parts.size());
      model.parts.push_back(make_part(shape, name, o, model.warnings));
      // Its colour: the product's or the shape's surface colour, else its generic one.
      Quantity_Color c;
      if (!colors.IsNull() &&
          (colors->GetColor(ref, XCAFDoc_ColorSurf, c) || colors->GetColor(ref, XCAFDoc_ColorGen, c) ||
           colors->GetColor(shape, XCAFDoc_ColorSurf, c) || colors->GetColor(shape, XCAFDoc_ColorGen, c))) {
        Part& p = model.parts.back();
        p.has_color = true;
        p.color[0] = static_cast<float>(c.Red()), p.color[1] = static_cast<float>(c.Green()),
        p.color[2] = static_cast<float>(c.Blue());
      }
      if (model.parts.back().solids == 0)
        model.warnings.push_back("part '" + name + "' has no solid (open shell or faces only)");
      part_by_entry[entry.ToCString()] = part_index;
    }
    Instance inst;
    inst.name = inst_name.empty() ? name : inst_name;
    inst.part = part_index;
    inst.placement = to_transform(here);
    inst.path = my_path;
    model.instances.push_back(inst);
  }
};

}  // namespace

Expected<CadModel> import_step(const std::filesystem::path& path, const ImportOptions& options) {
  const std::string file = path.string();
  // BRepMesh refuses deflections below Precision::Confusion() / Precision::Angular().
  if (!(options.linear_deflection == 0 || (options.linear_deflection >= kMinDeflection &&
                                           std::isfinite(options.linear_deflection))))
    return Error{.file = file, .reason = "linear deflection " + short_number(options.linear_deflection) +
                                         ": give 0 (0.1 % of each part's diagonal) or at least 1e-7 mm"};
  if (!(options.angular_deflection >= 1e-6 && options.angular_deflection <= std::numbers::pi))
    return Error{.file = file, .reason = "angular deflection " + short_number(options.angular_deflection) +
                                         ": give radians in [1e-6, pi]"};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{.file = file, .reason = "cannot open the STEP file"};
    in.seekg(0, std::ios::end);
    if (in.tellg() <= 0) return Error{.file = file, .reason = "empty STEP file"};
  }
  // One import at a time: the signal handlers and the messenger's printers are process-wide, and
  // OCCT's XCAF application is shared (Python threads call this with the GIL released).
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> lock(one_at_a_time);
  const detail::OcctSignals signals;
  const detail::QuietOcct quiet;
  try {
    OCC_CATCH_SIGNALS
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    STEPCAFControl_Reader reader;
    reader.SetNameMode(true);
    reader.SetColorMode(true);
    // XSControl_Reader::ReadFile, in its steps, so that the reference graph is checked for cycles
    // before the session checks the entities (which follows cycles until the stack overflows).
    STEPControl_Reader& step = reader.ChangeReader();
    const Handle(XSControl_WorkSession)& ws = step.WS();
    Handle(Interface_InterfaceModel) parsed;
    int status = -1;
    std::string failure;
    try {
      OCC_CATCH_SIGNALS
      if (!ws->WorkLibrary().IsNull()) status = ws->WorkLibrary()->ReadFile(file.c_str(), parsed, ws->Protocol());
    } catch (const Standard_Failure& e) {
      failure = std::string("parser failure: ") + e.GetMessageString();
    }
    if (status != 0 || parsed.IsNull()) {
      const std::string said = quiet.fails();
      std::string why = said.empty() ? failure : said;
      return Error{.file = file, .reason = "not a readable STEP file" + (why.empty() ? "" : " (" + why + ")")};
    }
    if (const std::string e = detail::reference_cycle(Interface_Graph(parsed, ws->Protocol()), parsed); !e.empty())
      return Error{.file = file,
                   .reason = "malformed STEP file: entity " + e + " refers to itself through a cycle of references"};
    ws->SetModel(parsed);
    ws->SetLoadedFile(file.c_str());
    ws->InitTransferReader(4);
    CadModel model;
    model.file = file;
    // A syntax error or an unresolved reference: a corrupt or truncated file, an error. Schema
    // check failures of single entities are common in files from CAD systems (NIST test parts)
    // and tolerated by the reader: warnings, as are entities that fail to translate.
    const Interface_CheckIterator checks = step.WS()->ModelCheckList();
    if (const detail::Fails bad = detail::fails_of(checks, step.Model(), true); bad.count > 0)
      return Error{.file = file, .reason = "malformed STEP file: " + bad.text()};
    if (const detail::Fails f = detail::fails_of(checks, step.Model(), false); f.count > 0)
      model.warnings.push_back(std::to_string(f.count) + " schema check failures in the STEP data, read anyway (" +
                               f.text() + ")");
    if (!reader.Transfer(doc)) return Error{.file = file, .reason = "STEP transfer failed (no shape)"};
    if (const auto& tr = step.WS()->TransferReader(); !tr.IsNull() && !tr->TransientProcess().IsNull())
      if (const detail::Fails f = detail::fails_of(tr->TransientProcess()->CheckList(Standard_True), step.Model(), false); f.count > 0)
        model.warnings.push_back(std::to_string(f.count) + " STEP entities failed to translate (" + f.text() +
                                 "): parts may be missing or incomplete");
    Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    TDF_LabelSequence free;
    tool->GetFreeShapes(free);
    {
      TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
      reader.ChangeReader().FileUnits(lengths, angles, solid_angles);
      for (int i = 1; i <= lengths.Length(); ++i) {
        const std::string u = lengths(i).ToCString();
        if (std::find(model.file_length_units.begin(), model.file_length_units.end(), u) == model.file_length_units.end())
          model.file_length_units.push_back(u);
      }
    }
    Walker w{tool, options, model, {}, {}, {}, XCAFDoc_DocumentTool::ColorTool(doc->Main())};
    for (int i = 1; i <= free.Length(); ++i) w.walk(free(i), TopLoc_Location(), "", "", "");
    // Instances named alike in one assembly (unnamed instances of one product): "#2", "#3", ...
    // in order, so that every path names one instance.
    {
      std::map<std::string, int> seen;
      for (const Instance& in : model.instances) ++seen[in.path];
      std::map<std::string, int> next;
      for (Instance& in : model.instances)
        if (seen[in.path] > 1)
          if (const int k = ++next[in.path]; k > 1) {
            std::string p = in.path + "#" + std::to_string(k);
            while (seen.count(p)) p += "#";  // (a path of the file that already ends so)
            seen[p] = 1;
            in.path = std::move(p);
          }
    }
    if (model.parts.empty()) return Error{.file = file, .reason = "no solid or shell with faces in the STEP file"};
    std::size_t tris = 0;
    for (const Part& p : model.parts) tris += p.mesh.num_triangles();
    if (tris == 0) return Error{.file = file, .reason = "no face could be tessellated"};
    // The coordinate range of the exact predicates (issue #23, item 7), on the parts' own
    // tessellations (instances are placed later by their transforms).
    for (const Part& p : model.parts)
      if (const std::size_t i = first_out_of_range(p.mesh.positions); i < p.mesh.positions.size())
        return Error{.file = file, .reason = "part '" + p.name + "': tessellation vertex " + std::to_string(i) + ": " +
                                             coordinate_range_reason(p.mesh.positions[i])};
    return model;
  } catch (const Standard_Failure& e) {
    return Error{.file = file, .reason = std::string("OpenCASCADE failure: ") + e.GetMessageString()};
  } catch (const std::exception& e) {
    return Error{.file = file, .reason = e.what()};
  }
}

}  // namespace interfere::cad
