// Shared by bench_fem_io.cpp and its gmsh peer (peer_gmsh.cpp): the generated 10^6-tet box and
// the files written from it once per run.
#pragma once
#include <filesystem>
#include <map>
#include <string>

#include "interfere/fem/fem_mesh.h"

namespace interfere::bench_fem {
/// n^3 cubes, 6 tets each.
FemMesh tet_box(int n);
/// The box written as ".msh" (4.1 binary), ".vtu" (appended) or ".bdf" (free field).
const std::filesystem::path& bench_file(const std::string& ext);
}  // namespace interfere::bench_fem
