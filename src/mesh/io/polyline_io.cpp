// Intersection-curve writers: OBJ polylines (`l` statements) and legacy VTK POLYDATA (LINES).
#include <cstdio>
#include <string>

#include "interfere/core/atomic_file.h"
#include "interfere/mesh/polyline.h"

namespace interfere {
namespace {

void append_point(std::string& s, const char* prefix, const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s%.17g %.17g %.17g\n", prefix, p.x, p.y, p.z);
  s += buf;
}

std::string to_obj(const std::vector<Polyline>& curves) {
  std::string s = "# interfere intersection curves: one 'l' polyline per curve\n";
  for (const Polyline& c : curves) {
    for (const Vec3& p : c.points) append_point(s, "v ", p);
  }
  std::size_t base = 1;
  for (const Polyline& c : curves) {
    s += "l";
    for (std::size_t i = 0; i < c.points.size(); ++i) s += " " + std::to_string(base + i);
    if (c.closed && !c.points.empty()) s += " " + std::to_string(base);
    s += "\n";
    base += c.points.size();
  }
  return s;
}

std::string to_vtk(const std::vector<Polyline>& curves) {
  std::size_t npoints = 0, nindices = 0;
  for (const Polyline& c : curves) {
    npoints += c.points.size();
    nindices += 1 + c.points.size() + (c.closed ? 1 : 0);
  }
  std::string s = "# vtk DataFile Version 3.0\ninterfere intersection curves\nASCII\nDATASET POLYDATA\n";
  s += "POINTS " + std::to_string(npoints) + " double\n";
  for (const Polyline& c : curves) {
    for (const Vec3& p : c.points) append_point(s, "", p);
  }
  s += "LINES " + std::to_string(curves.size()) + " " + std::to_string(nindices) + "\n";
  std::size_t base = 0;
  for (const Polyline& c : curves) {
    s += std::to_string(c.points.size() + (c.closed ? 1 : 0));
    for (std::size_t i = 0; i < c.points.size(); ++i) s += " " + std::to_string(base + i);
    if (c.closed) s += " " + std::to_string(base);
    s += "\n";
    base += c.points.size();
  }
  s += "CELL_DATA " + std::to_string(curves.size()) + "\nSCALARS curve_id int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < curves.size(); ++i) s += std::to_string(i) + "\n";
  return s;
}

}  // namespace

Status write_polylines(const std::filesystem::path& path, const std::vector<Polyline>& curves) {
  const std::string ext = path.extension().string();
  if (ext == ".obj" || ext == ".OBJ") return write_file_atomic(path, to_obj(curves));
  if (ext == ".vtk" || ext == ".VTK") return write_file_atomic(path, to_vtk(curves));
  return Error{.file = path.string(), .reason = "unknown curve format '" + ext + "' (use .obj or .vtk)"};
}

}  // namespace interfere
