// FE assembly parts for the paper's strategy table on FE surfaces (issue #26, item 6; Deng et al.
// 2018, §2: "two adjacent CFETR parts", finite-element models whose surfaces are triangulated).
// Generated with the gmsh SDK (built-in kernel, structured extrusion: fast at any size), written as
// MSH 4.1 binary into a cache folder, then loaded the way a user's model is: read_fem ->
// extract_surface (one part per physical group).
//
//   vacuum_vessel  a 22.5° sector of a torus shell (major radius 6 m, wall between minor radii
//                  2.0 and 2.2 m): the annular cross-section as 4 transfinite quad patches,
//                  revolved about z with recombined layers -> hex8 elements
//   port           a rectangular duct (outer 1.6 × 2.0 m, wall 0.15 m, 2.5 m long) on the
//                  outboard side, tilted 3° about y, crossing the vessel wall all around: the
//                  hollow-rectangle cross-section as 4 transfinite triangle patches, extruded
//                  along its axis without recombination -> tet4 elements
//
// `n` is the target of surface triangles per part; the meshes come within a few percent of it.
// Every load checks both parts: one closed component each (no open, degenerate or non-orientable
// component; mesh_stats closed), outward (positive enclosed volume), and the enclosed volume
// against the analytic solid (port: exact up to rounding; vessel: the polygonal cross-section and
// chords of the revolution, relative error < 0.5%). A failed check throws std::runtime_error.
//
// Cache folder: INTERFERE_BENCH_FEM_CACHE, default <build>/bench_cache/fem_strategies.
#pragma once
#include <cstddef>
#include <filesystem>

#include "interfere/mesh/tri_mesh.h"
#include "interfere/mesh/validate.h"

namespace interfere::bench {

struct FemAssembly {
  std::filesystem::path file;  ///< the .msh
  TriMesh vessel, port;        ///< the surfaces of the two bodies (extract_surface)
  MeshStats vessel_stats, port_stats;  ///< mesh_stats of the surfaces (both closed)
  std::size_t hex_elements = 0, tet_elements = 0, nodes = 0;
  double vessel_volume = 0, port_volume = 0;                  ///< enclosed by the surfaces
  double vessel_volume_analytic = 0, port_volume_analytic = 0;
  double generate_seconds = 0;  ///< gmsh, when the file was written (kept beside it; 0 if unknown)
  double read_seconds = 0, extract_seconds = 0;
};

/// The assembly at scale n (surface triangles per part), generated on first use (cached file,
/// then once per process).
const FemAssembly& fem_assembly(std::size_t n);

/// Loads an assembly file: read_fem + extract_surface + the checks above (no caching).
FemAssembly load_fem_assembly(const std::filesystem::path& file);

}  // namespace interfere::bench
