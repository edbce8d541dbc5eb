// What the truth-set labellers share (tools/hole_truth/label_holes.cpp, tools/floor_truth/
// label_floors.cpp; issue #29, item 2): a small vector type and the program's frame: the STEP file
// read with STEPControl_Reader, the JSON opening line, the solids in file order and their size.
// Header-only, OCCT only, nothing of src/cad: the labellers stay independent of the recognizer and
// build with one g++ line each (their headers).
#pragma once
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace truth {

struct V {
  double x = 0, y = 0, z = 0;
};
inline V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator*(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double len(V a) { return std::sqrt(dot(a, a)); }
inline V unit(V a) { return a * (1 / len(a)); }
inline V pv(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
inline V dv(const gp_Dir& p) { return {p.X(), p.Y(), p.Z()}; }
inline gp_Pnt to_pnt(V a) { return gp_Pnt(a.x, a.y, a.z); }

/// The solids of a STEP file, in TopExp_Explorer order; status: the program's exit status when it
/// must stop (2: no file given, 1: the file cannot be read), else 0.
struct StepSolids {
  std::vector<TopoDS_Solid> solids;
  int status = 0;
};

/// Reads argv[1] ("usage: TOOL FILE.stp" on stderr without it) and prints the JSON's opening
/// `{"file": "<base name>", "labeller": "<labeller>", "solids": [` on stdout.
inline StepSolids read_step_solids(int argc, char** argv, const char* tool, const char* labeller) {
  StepSolids r;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE.stp\n", tool);
    r.status = 2;
    return r;
  }
  STEPControl_Reader reader;
  if (reader.ReadFile(argv[1]) != IFSelect_RetDone) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    r.status = 1;
    return r;
  }
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  std::printf("{\"file\": \"%s\", \"labeller\": \"%s\", \"solids\": [\n",
              std::string(argv[1]).substr(std::string(argv[1]).find_last_of('/') + 1).c_str(), labeller);
  for (TopExp_Explorer sx(shape, TopAbs_SOLID); sx.More(); sx.Next()) r.solids.push_back(TopoDS::Solid(sx.Current()));
  return r;
}

/// The diagonal of the solid's bounding box (BRepBndLib).
inline double diagonal(const TopoDS_Solid& solid) {
  Bnd_Box box;
  BRepBndLib::Add(solid, box);
  double bx0, by0, bz0, bx1, by1, bz1;
  box.Get(bx0, by0, bz0, bx1, by1, bz1);
  return len(V{bx1 - bx0, by1 - by0, bz1 - bz0});
}

}  // namespace truth
