// Bench-only CalculiX .frd writer (issue #26, item 7: the "read a 10^6-element .frd with 10 steps
// <= 2 s" target needs large files; the library reads .frd but writes none). It writes what ccx
// 2.20 writes (the record layouts of the CalculiX GraphiX manual, "Result Format", as
// src/fem/io/frd_read.cpp and docs/fem.md describe them):
//   ASCII: 1C / 1U headers, 1UMAT per material, node block "2C" in long format (1: " -1" I10
//   3E12.5), element block "3C" long format (" -1" I10 type group material, " -2" node ids I10, 10 a
//   record), per step a 1PSTEP record and a "100CL" DISP block (-4 DISP with 4 components, -5 D1
//   D2 D3 stored and ALL computed) with " -1" I10 3E12.5 node records, each block closed by -3; end
//   9999.
//   Binary (*NODE OUTPUT): the same header records as text, the data in native little-endian
//   binary without -3: nodes format 3 (int32 id, 3 float64), elements format 2 (int32 id, type,
//   group, material, node ids), results format 2 (int32 node, 3 float32), as ccx writes them.
// Materials are the mesh's groups (material number = group index + 1, named by the group); an
// element without group gets material 1. Linear solids only (tet4, wedge6, hex8: the frd order of
// these is VTK's). Not a library feature: bench code only.
#pragma once
#include <filesystem>
#include <string>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"

namespace interfere::bench_frd {

struct FrdWriteOptions {
  bool binary = false;
  std::string title = "interfere benchmark model (issue #26)";
};

/// Writes `mesh` with the displacement steps of `disp` (may be null: no result blocks) to `path`
/// (through `path`.tmp and a rename, so that an interrupted run leaves no partial file).
Status write_frd(const FemMesh& mesh, const NodalSeries* disp, const std::filesystem::path& path,
                 const FrdWriteOptions& options = {});

}  // namespace interfere::bench_frd
