// Polylines (intersection curves) and their writers: OBJ `l` statements and legacy VTK POLYDATA.
#pragma once
#include <filesystem>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/vec.h"

namespace interfere {

struct Polyline {
  std::vector<Vec3> points;
  bool closed = false;  ///< the last point joins the first
  double length = 0;
};

/// Writes polylines by extension: ".obj" (v + l lines; a closed curve repeats its first index) or
/// ".vtk" (legacy ASCII POLYDATA with LINES and a cell array "curve_id"). Atomic like write_mesh.
Status write_polylines(const std::filesystem::path& path, const std::vector<Polyline>& curves);

}  // namespace interfere
