// FemMesh: a finite-element mesh as the solver wrote it (issue #3): nodes with the solver's ids,
// elements with type, id and body, node/element sets, and nodal vector fields per load step.
// Every reader (fem/io.h) produces one; fem/surface.h turns it into the TriMesh the engine checks.
//
// Node order inside an element is VTK's (the same as Gmsh's for every linear type; readers of other
// conventions reorder on input):
//   tet10  : corners 0-3, mid-edge nodes on (0,1) (1,2) (2,0) (0,3) (1,3) (2,3)
//   hex20  : corners 0-7 (bottom 0-3, top 4-7, counter-clockwise seen from the top), mid-edge nodes
//            on (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5) (2,6) (3,7)
//   hex27  : hex20 + face centres (0,3,7,4) (1,2,6,5) (0,1,5,4) (3,2,6,7) (0,1,2,3) (4,5,6,7) + body
//   wedge6 : triangle 0-2 and triangle 3-5 (3 above 0)
//   wedge15: corners 0-5, mid-edge (0,1) (1,2) (2,0) (3,4) (4,5) (5,3) (0,3) (1,4) (2,5)
//   pyr5   : base quad 0-3, apex 4;  pyr13: mid-edge (0,1) (1,2) (2,3) (3,0) (0,4) (1,4) (2,4) (3,4)
//   tri6, quad8, quad9: corners first, then mid-edge nodes in edge order, then the face centre.
// Linear volume elements are positively oriented (positive Jacobian, VTK convention); readers do
// not flip them: surface extraction orients faces outward by geometry, not by trust in the input.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/vec.h"

namespace interfere {

enum class ElemType : std::uint8_t {
  point1,
  line2,
  line3,
  tri3,
  tri6,
  quad4,
  quad8,
  quad9,
  tet4,
  tet10,
  pyr5,
  pyr13,
  wedge6,
  wedge15,
  hex8,
  hex20,
  hex27,
};
inline constexpr int kNumElemTypes = 17;

struct ElemInfo {
  const char* name;   ///< "tet4", "hex20", ... (as above)
  int nodes;          ///< nodes per element
  int corners;        ///< corner (vertex) nodes
  int dim;            ///< 0 point, 1 line, 2 shell, 3 volume
  int order;          ///< 1 linear, 2 quadratic
  int vtk_cell_type;  ///< VTK_TETRA = 10, VTK_QUADRATIC_HEXAHEDRON = 25, ...
};
const ElemInfo& elem_info(ElemType t);
/// By name as in ElemInfo::name; false if unknown.
bool elem_type_from_name(const std::string& name, ElemType& out);

/// A body of the model: a Gmsh physical group, an Abaqus *ELEMENT ELSET / instance, a Nastran
/// property id (PID), or a VTK cell-data id. Every element belongs to at most one group.
struct FemGroup {
  std::string name;     ///< the solver's name ("PSOLID 3", "Part-1-1", "steel"); unique in a mesh
  std::int64_t id = 0;  ///< the solver's number (physical tag, PID, material id; 0 if none)
  int dim = 3;          ///< dimension of its elements (2 for shell groups)
};

/// Named node or element set (Abaqus *NSET/*ELSET, Gmsh physical groups of lower dimension):
/// indices into FemMesh::nodes or the element arrays. Sets may overlap.
struct FemSet {
  std::string name;
  std::vector<std::uint32_t> members;
};

/// A nodal vector field over load steps / time (displacements): values[step][node index].
struct NodalSeries {
  std::string name;                      ///< "DISPL", "displacement", the CSV's file name, ...
  std::vector<double> times;             ///< one per step (step numbers when the file has none)
  std::vector<std::vector<Vec3>> values;  ///< values[s].size() == FemMesh::nodes.size()
  std::size_t num_steps() const { return values.size(); }
};

struct FemMesh {
  std::string file;  ///< where it was read from (for messages)

  // Nodes: reference positions and the solver's ids (unique within a mesh; Abaqus instances get
  // their nodes copied per instance, the element's group then tells which instance a node is in).
  std::vector<Vec3> nodes;
  std::vector<std::int64_t> node_ids;

  // Elements, in file order: type, the solver's id, group (index into groups, -1 = none), and their
  // nodes (indices into `nodes`, VTK order) in a CSR layout: element e uses
  // elem_nodes[elem_offsets[e] .. elem_offsets[e + 1]).
  std::vector<ElemType> elem_types;
  std::vector<std::int64_t> elem_ids;
  std::vector<std::int32_t> elem_groups;
  std::vector<std::uint64_t> elem_offsets{0};
  std::vector<std::uint32_t> elem_nodes;

  std::vector<FemGroup> groups;
  std::vector<FemSet> node_sets;
  std::vector<FemSet> elem_sets;

  /// Nodal vector fields read with the mesh (VTU point data, Gmsh NodeData); a CSV read separately
  /// (fem/io.h read_displacements) is not stored here.
  std::vector<NodalSeries> fields;

  /// What the reader left out or changed, for the user (e.g. "skipped 12 1-D elements (T3D2 12)").
  std::vector<std::string> warnings;

  std::size_t num_nodes() const { return nodes.size(); }
  std::size_t num_elements() const { return elem_types.size(); }
  const std::uint32_t* element_nodes(std::size_t e) const { return elem_nodes.data() + elem_offsets[e]; }
  int element_size(std::size_t e) const {
    return static_cast<int>(elem_offsets[e + 1] - elem_offsets[e]);
  }
  /// Appends an element (nodes already as indices, VTK order).
  void add_element(ElemType t, std::int64_t id, std::int32_t group, const std::uint32_t* nodes_of,
                   int count) {
    elem_types.push_back(t);
    elem_ids.push_back(id);
    elem_groups.push_back(group);
    elem_nodes.insert(elem_nodes.end(), nodes_of, nodes_of + count);
    elem_offsets.push_back(elem_nodes.size());
  }
};

/// Structural check of a mesh built by hand or by a reader: array sizes agree, node counts match
/// the element types, node indices are in range, node and element ids are unique, group indices
/// are valid, fields have one value per node. Returns the first problem (Error::reason names the
/// element or node by the solver's id), or success.
Status validate_fem_mesh(const FemMesh& mesh);

}  // namespace interfere
