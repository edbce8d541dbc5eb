// Internal: what the legacy VTK and the VTU readers share once their arrays are decoded: turning
// points / connectivity / offsets / cell types / point and cell arrays into a FemMesh (ids from
// GlobalNodeId-like arrays, groups from an integer cell array, 3-component point vectors as
// fields), and the writers' choice of arrays. Node order is VTK's, so no reordering happens here.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scan.h"

namespace interfere::fem_io {

struct VtkArray {
  std::string name;
  int components = 1;
  bool integer = false;
  std::vector<double> reals;       ///< when !integer
  std::vector<std::int64_t> ints;  ///< when integer
  std::int64_t where = -1;         ///< line or byte offset of the array (for errors)
  std::size_t size() const { return integer ? ints.size() : reals.size(); }
};

struct VtkData {
  std::vector<double> points;              ///< 3 per point
  std::vector<std::int64_t> connectivity;  ///< point indices
  std::vector<std::int64_t> offsets;       ///< end offset of each cell into connectivity
  std::vector<std::int64_t> types;         ///< VTK cell type of each cell
  std::vector<VtkArray> point_arrays, cell_arrays;
  std::int64_t cells_where = -1, types_where = -1;  ///< locations for errors
  /// Names of our "group" array's values in increasing value order (VTU FieldData "group_names").
  std::vector<std::string> group_names;
};

/// Builds the mesh; `bytes` tells whether `where` values are byte offsets (else lines).
Expected<FemMesh> build_vtk_mesh(const std::string& file, VtkData&& d, bool bytes);

/// Names of the arrays the readers interpret.
bool is_node_id_array(const std::string& name);
bool is_elem_id_array(const std::string& name);
/// Priority of an integer cell array as the group array (lower is better); -1 if not a group array.
int group_array_rank(const std::string& name);

/// The per-cell / per-point arrays a writer emits: element ids ("element_id"), node ids
/// ("node_id"), groups ("group": FemGroup::id when positive and unique, else index + 1; -1 =
/// none), the caller's FemWriteOptions arrays, and the fields' last step.
struct VtkOutArrays {
  std::vector<VtkArray> point, cell;
  std::vector<std::string> group_names;  ///< in increasing order of the "group" values
};
VtkOutArrays vtk_out_arrays(const FemMesh& m, const FemWriteOptions& o);

}  // namespace interfere::fem_io
