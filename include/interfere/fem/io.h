// Finite-element file input/output (issue #3, item 1): Gmsh MSH 2.2 / 4.1 (ASCII, binary), Nastran
// bulk data (small, large, free field), legacy VTK unstructured grids, VTK XML .vtu (ASCII, binary,
// appended, zlib), Abaqus/CalculiX .inp, nodal displacements as CSV; read only: CalculiX .frd results
// (ASCII and binary, issue #26) and Exodus II (.e/.exo, when built with libexodusII). Every error names the file,
// the line (text) or byte offset (binary) and the reason. The format-by-format details (supported
// keywords, element types, how bodies become groups) are in docs/fem.md.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"

namespace interfere {

enum class FemFormat { automatic, msh, nastran, vtk_legacy, vtu, abaqus, frd, exodus };

/// "msh", "nastran" (also "bdf", "nas"), "vtk", "vtu", "inp" (also "abaqus"), "frd" (also
/// "calculix"), "exodus" (also "exo", "e"), "auto";
/// automatic if unknown.
FemFormat fem_format_from_name(const std::string& name);
const char* fem_format_name(FemFormat f);
/// By extension: .msh, .bdf/.nas/.dat/.blk, .vtk, .vtu, .inp, .frd, .e/.exo; automatic when it is
/// none of them.
FemFormat fem_format_from_path(const std::filesystem::path& path);

struct FemReadOptions {
  FemFormat format = FemFormat::automatic;  ///< automatic: by extension, then by content
};

/// Reads a volume (or shell) mesh with its groups, sets and, where the format holds them, nodal
/// vector fields (VTU point data with 3 components, Gmsh $NodeData views with 3 components, the
/// DISP blocks of a .frd, the DISPL_X/Y/Z variables of an Exodus file; several time steps become
/// one NodalSeries). The result passes validate_fem_mesh.
Expected<FemMesh> read_fem(const std::filesystem::path& path, const FemReadOptions& options = {});

/// True when this build reads Exodus II files (built with libexodusII: INTERFERE_WITH_EXODUS).
bool fem_has_exodus_reader();

/// Nodal displacements from CSV (docs/fem.md): a header row, then one row per node and step.
///   node_id,ux,uy,uz            one step
///   step,node_id,ux,uy,uz       several steps (also `time` instead of `step`), any row order
/// Node ids are the mesh's solver ids; an id the mesh does not have is an error naming the row;
/// nodes absent from a step get zero displacement (reported in `missing_nodes`).
struct CsvDisplacementInfo {
  std::size_t rows = 0;
  std::size_t missing_nodes = 0;  ///< (node, step) entries not in the file, set to zero
};
Expected<NodalSeries> read_displacements_csv(const std::filesystem::path& path, const FemMesh& mesh,
                                             CsvDisplacementInfo* info = nullptr);

/// An extra per-cell or per-point array for the writers (e.g. the source element id of each
/// surface triangle). Integer arrays are written as Int64, real ones as Float64 with `components`.
struct FemArray {
  std::string name;
  int components = 1;
  std::vector<std::int64_t> ints;  ///< used when `reals` is empty
  std::vector<double> reals;
};

enum class VtuEncoding { ascii, binary, appended, zlib };

struct FemWriteOptions {
  FemFormat format = FemFormat::automatic;  ///< automatic: by extension
  bool binary = false;                      ///< MSH 4.1 binary / legacy VTK binary
  int msh_version = 41;                     ///< 41 or 22
  VtuEncoding vtu_encoding = VtuEncoding::appended;
  std::vector<FemArray> cell_data;   ///< one value (tuple) per element
  std::vector<FemArray> point_data;  ///< one value (tuple) per node
  bool write_fields = true;          ///< also write mesh.fields (last step, or every step in MSH)
};

/// Writes the mesh (node and element ids, groups as physical groups / property ids / cell data
/// "group"), atomically: the file appears complete or not at all. The element ids are written as
/// cell data "element_id" in VTK formats.
Status write_fem(const FemMesh& mesh, const std::filesystem::path& path, const FemWriteOptions& options = {});

}  // namespace interfere
