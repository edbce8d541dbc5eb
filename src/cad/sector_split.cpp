// Angular sectors of expensive faces before meshing (issue #29: the casing's whole command).
// BRepMesh meshes one face on one thread, and its initial grid on a face
// (BRepMesh_BoundaryParamsRangeSplitter) takes a grid line at the parameter of every boundary node,
// the inner wires' included: on a closed surface of revolution with several holes' rims as inner
// wires (the paper's casing, He & Xu 2023 §4: the working-ring wall, six counterbore rims, 27,843
// of 35,552 triangles) the grid and the Delaunay insertion into it grow about quadratically with the
// rims' nodes, 0.45-0.9 s for that one face. Split into angular sectors, one rim each, between the
// rims, the faces mesh in 0.2 s together on one thread (and in parallel with InParallel), within the
// same deflection, and with fewer triangles (the grid is no longer over-dense).
//
// Rule (SectorSplit, documented in docs/simplify.md, "Whole command on the casing"): a face is split
// when its surface is a surface of revolution, cylinder, cone or torus, U-periodic (the angle), the
// face covers the whole turn, has no degenerated edge (a pole or an apex: split lines through it
// left a sphere's sectors unwelded there), with at least kMinRims inner wires; the split lines are
// isoparametric U lines in the middle of the angular gaps between the inner wires (rims overlapping
// in angle form one group), away from every vertex of the face. Faces that do not qualify, or whose
// division fails any check below, are meshed as before. Only the face and the edges the split lines
// cross change (ShapeUpgrade_FaceDivide with a ShapeBuild_ReShape context applied to the whole part:
// a neighbour sharing a crossed edge gets that edge in two pieces, so the shared edge is discretised
// once and the meshes weld).
//
// The sectors of surfaces of revolution and cylinders are triangulated by OCCT's Delabella Delaunay
// (BRepMesh_DelabellaMeshAlgoFactory, the same deflection control), every other face by BRepMesh's
// default algorithm as before (SectorAlgoFactory): on the casing's sectors it halves the meshing time on one thread (0.50 ->
// 0.27 s CPU, load 6), closed, measured deviation 0.01690 at 0.01694 (docs/simplify.md).
#ifndef OCC_CONVERT_SIGNALS
#define OCC_CONVERT_SIGNALS
#endif
#include <BRepAdaptor_Surface.hxx>
#include <BRepMesh_DelabellaMeshAlgoFactory.hxx>
#include <BRepMesh_MeshAlgoFactory.hxx>
#include <IMeshData_Face.hxx>
#include <IMeshTools_MeshAlgo.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeExtend.hxx>
#include <ShapeUpgrade_FaceDivide.hxx>
#include <ShapeUpgrade_SplitSurface.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HSequenceOfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "occt_internal.h"

namespace interfere::cad::detail {
namespace {

constexpr int kMinRims = 3;  // inner wires (angular groups) a face needs to be split

// ShapeUpgrade_SplitSurface that splits in U at given values (its own Compute finds none).
class USplit : public ShapeUpgrade_SplitSurface {
 public:
  explicit USplit(Handle(TColStd_HSequenceOfReal) values) : values_(std::move(values)) {}
  void Compute(const Standard_Boolean) override { SetUSplitValues(values_); }

 private:
  Handle(TColStd_HSequenceOfReal) values_;
};

bool revolution_type(GeomAbs_SurfaceType t) {
  return t == GeomAbs_SurfaceOfRevolution || t == GeomAbs_Cylinder || t == GeomAbs_Cone || t == GeomAbs_Torus;
}

// The sectors' algorithm: Delabella where it was measured within the deflection (the casing's wall,
// tubes), BRepMesh's default on cones and tori (Delabella's sectors of a cone with holes: 0.076
// off at a deflection of 0.05, the default's 0.056, unsplit 0.049).
bool delabella_type(GeomAbs_SurfaceType t) { return t == GeomAbs_SurfaceOfRevolution || t == GeomAbs_Cylinder; }

// The U values where `face` is split, empty where the rule does not apply.
std::vector<double> split_values(const TopoDS_Face& face) {
  const BRepAdaptor_Surface surface(face, false);
  if (!revolution_type(surface.GetType()) || !surface.IsUPeriodic()) return {};
  const double period = surface.UPeriod();
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (!(u1 - u0 > period * (1 - 1e-9))) return {};  // (not the whole turn)
  // (a degenerated edge: a pole or an apex, where every split line would meet the others)
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next())
    if (BRep_Tool::Degenerated(TopoDS::Edge(x.Current()))) return {};
  const TopoDS_Wire outer = BRepTools::OuterWire(face);
  std::vector<std::pair<double, double>> rims;  // U ranges of the inner wires
  for (TopoDS_Iterator it(face); it.More(); it.Next()) {
    if (it.Value().ShapeType() != TopAbs_WIRE || it.Value().IsSame(outer)) continue;
    double a0, a1, b0, b1;
    BRepTools::UVBounds(face, TopoDS::Wire(it.Value()), a0, a1, b0, b1);
    if (!(a0 >= u0 && a1 <= u1 && a1 - a0 < 0.5 * period)) return {};  // (a wire across the seam, or around)
    rims.emplace_back(a0, a1);
  }
  if (rims.size() < static_cast<std::size_t>(kMinRims)) return {};
  std::sort(rims.begin(), rims.end());
  std::vector<std::pair<double, double>> groups{rims.front()};  // rims overlapping in angle merged
  for (std::size_t i = 1; i < rims.size(); ++i)
    if (rims[i].first <= groups.back().second) groups.back().second = std::max(groups.back().second, rims[i].second);
    else groups.push_back(rims[i]);
  if (groups.size() < static_cast<std::size_t>(kMinRims)) return {};
  // The vertices' U (a split line through a vertex would leave a degenerate piece).
  std::vector<double> vertex_u;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(x.Current());
    for (TopExp_Explorer y(e, TopAbs_VERTEX); y.More(); y.Next()) {
      const gp_Pnt2d uv = BRep_Tool::Parameters(TopoDS::Vertex(y.Current()), face);
      vertex_u.push_back(uv.X());
    }
  }
  std::vector<double> values;
  for (std::size_t i = 1; i < groups.size(); ++i) {
    const double gap = groups[i].first - groups[i - 1].second;
    const double u = 0.5 * (groups[i].first + groups[i - 1].second);
    const bool clear = std::all_of(vertex_u.begin(), vertex_u.end(), [&](double w) {
      const double d = std::remainder(w - u, period);
      return std::abs(d) > 0.1 * gap;
    });
    if (gap > 1e-3 * period && clear) values.push_back(u);
  }
  return values;
}

// Per face: Delabella for the sectors, the default algorithm for the rest. BRepMesh asks the factory
// for an algorithm per face (BRepMesh_FaceDiscret), so each face gets its own pair.
class SectorAlgo : public IMeshTools_MeshAlgo {
 public:
  SectorAlgo(Handle(IMeshTools_MeshAlgo) plain, Handle(IMeshTools_MeshAlgo) sector,
             const TopTools_IndexedMapOfShape& sectors)
      : plain_(std::move(plain)), sector_(std::move(sector)), sectors_(sectors) {}
  void Perform(const IMeshData::IFaceHandle& face, const IMeshTools_Parameters& parameters,
               const Message_ProgressRange& range) override {
    (sectors_.Contains(face->GetFace()) ? sector_ : plain_)->Perform(face, parameters, range);
  }

 private:
  Handle(IMeshTools_MeshAlgo) plain_, sector_;
  const TopTools_IndexedMapOfShape& sectors_;
};

class SectorAlgoFactory : public IMeshTools_MeshAlgoFactory {
 public:
  explicit SectorAlgoFactory(TopTools_IndexedMapOfShape sectors) : sectors_(std::move(sectors)) {}
  Handle(IMeshTools_MeshAlgo) GetAlgo(const GeomAbs_SurfaceType type,
                                      const IMeshTools_Parameters& parameters) const override {
    if (!delabella_type(type)) return plain_->GetAlgo(type, parameters);
    return new SectorAlgo(plain_->GetAlgo(type, parameters), sector_->GetAlgo(type, parameters), sectors_);
  }

 private:
  TopTools_IndexedMapOfShape sectors_;
  Handle(IMeshTools_MeshAlgoFactory) plain_ = new BRepMesh_MeshAlgoFactory();
  Handle(IMeshTools_MeshAlgoFactory) sector_ = new BRepMesh_DelabellaMeshAlgoFactory();
};

}  // namespace

Handle(IMeshTools_MeshAlgoFactory) sector_algo_factory(const SectorSplit& split) {
  TopTools_IndexedMapOfShape sectors;
  for (const std::vector<TopoDS_Face>& pieces : split.faces)
    if (pieces.size() > 1)
      for (const TopoDS_Face& f : pieces) sectors.Add(f);
  return new SectorAlgoFactory(std::move(sectors));
}

SectorSplit split_for_meshing(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces) {
  SectorSplit r;
  r.shape = shape;
  r.faces.resize(static_cast<std::size_t>(faces.Extent()));
  for (int i = 1; i <= faces.Extent(); ++i) r.faces[i - 1].push_back(TopoDS::Face(faces(i)));
  try {
    OCC_CATCH_SIGNALS
    Handle(ShapeBuild_ReShape) context = new ShapeBuild_ReShape();
    int split = 0;
    for (int i = 1; i <= faces.Extent(); ++i) {
      const TopoDS_Face& face = TopoDS::Face(faces(i));
      const std::vector<double> u = split_values(face);
      if (u.empty()) continue;
      Handle(TColStd_HSequenceOfReal) values = new TColStd_HSequenceOfReal();
      for (double x : u) values->Append(x);
      ShapeUpgrade_FaceDivide divide(face);
      divide.SetContext(context);
      divide.SetSplitSurfaceTool(new USplit(values));
      divide.SetSurfaceSegmentMode(Standard_True);
      if (!divide.Perform() || divide.Status(ShapeExtend_FAIL)) return r;
      const TopoDS_Shape pieces = divide.Result();
      int n = 0;
      for (TopExp_Explorer x(pieces, TopAbs_FACE); x.More(); x.Next()) ++n;
      if (n != static_cast<int>(u.size()) + 1) return r;  // (not the sectors asked for: the part unsplit)
      context->Replace(face, pieces);
      ++split;
    }
    if (split == 0) return r;
    const TopoDS_Shape result = context->Apply(shape);
    TopTools_IndexedMapOfShape out;
    TopExp::MapShapes(result, TopAbs_FACE, out);
    std::vector<int> owner(static_cast<std::size_t>(out.Extent()) + 1, 0);
    std::vector<std::vector<TopoDS_Face>> mapped(r.faces.size());
    for (int i = 1; i <= faces.Extent(); ++i) {
      for (TopExp_Explorer x(context->Apply(faces(i)), TopAbs_FACE); x.More(); x.Next()) {
        const int k = out.FindIndex(x.Current());
        if (k == 0 || owner[k] != 0) return r;  // (every face of the result from one face of the part)
        owner[k] = i;
        mapped[i - 1].push_back(TopoDS::Face(out(k)));  // (with its orientation in the result)
      }
      if (mapped[i - 1].empty()) return r;
    }
    if (std::find(owner.begin() + 1, owner.end(), 0) != owner.end()) return r;
    r.shape = result;
    r.faces = std::move(mapped);
    r.split_faces = split;
  } catch (const Standard_Failure&) {
    // (the part meshed unsplit)
  }
  return r;
}

}  // namespace interfere::cad::detail
