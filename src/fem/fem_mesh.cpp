// Element type table and the structural check of a FemMesh (fem_mesh.h).
#include "interfere/fem/fem_mesh.h"

#include <array>
#include <string>
#include <unordered_set>

namespace interfere {
namespace {

// Indexed by ElemType. VTK cell types: VTK_VERTEX 1, VTK_LINE 3, VTK_QUADRATIC_EDGE 21,
// VTK_TRIANGLE 5, VTK_QUADRATIC_TRIANGLE 22, VTK_QUAD 9, VTK_QUADRATIC_QUAD 23,
// VTK_BIQUADRATIC_QUAD 28, VTK_TETRA 10, VTK_QUADRATIC_TETRA 24, VTK_PYRAMID 14,
// VTK_QUADRATIC_PYRAMID 27, VTK_WEDGE 13, VTK_QUADRATIC_WEDGE 26, VTK_HEXAHEDRON 12,
// VTK_QUADRATIC_HEXAHEDRON 25, VTK_TRIQUADRATIC_HEXAHEDRON 29.
constexpr std::array<ElemInfo, kNumElemTypes> kInfo{{
    {"point1", 1, 1, 0, 1, 1},
    {"line2", 2, 2, 1, 1, 3},
    {"line3", 3, 2, 1, 2, 21},
    {"tri3", 3, 3, 2, 1, 5},
    {"tri6", 6, 3, 2, 2, 22},
    {"quad4", 4, 4, 2, 1, 9},
    {"quad8", 8, 4, 2, 2, 23},
    {"quad9", 9, 4, 2, 2, 28},
    {"tet4", 4, 4, 3, 1, 10},
    {"tet10", 10, 4, 3, 2, 24},
    {"pyr5", 5, 5, 3, 1, 14},
    {"pyr13", 13, 5, 3, 2, 27},
    {"wedge6", 6, 6, 3, 1, 13},
    {"wedge15", 15, 6, 3, 2, 26},
    {"hex8", 8, 8, 3, 1, 12},
    {"hex20", 20, 8, 3, 2, 25},
    {"hex27", 27, 8, 3, 2, 29},
}};

}  // namespace

const ElemInfo& elem_info(ElemType t) { return kInfo[static_cast<std::size_t>(t)]; }

bool elem_type_from_name(const std::string& name, ElemType& out) {
  for (std::size_t i = 0; i < kInfo.size(); ++i) {
    if (name == kInfo[i].name) {
      out = static_cast<ElemType>(i);
      return true;
    }
  }
  return false;
}

Status validate_fem_mesh(const FemMesh& m) {
  auto fail = [&](std::string reason) { return Status(Error{.file = m.file, .reason = std::move(reason)}); };
  const std::size_t nn = m.nodes.size(), ne = m.elem_types.size();
  if (m.node_ids.size() != nn) return fail("node_ids has " + std::to_string(m.node_ids.size()) + " entries for " + std::to_string(nn) + " nodes");
  if (m.elem_ids.size() != ne || m.elem_groups.size() != ne || m.elem_offsets.size() != ne + 1) {
    return fail("element arrays disagree in size (types " + std::to_string(ne) + ", ids " + std::to_string(m.elem_ids.size()) +
                ", groups " + std::to_string(m.elem_groups.size()) + ", offsets " + std::to_string(m.elem_offsets.size()) + ")");
  }
  if (m.elem_offsets.front() != 0 || m.elem_offsets.back() != m.elem_nodes.size()) return fail("element offsets do not span elem_nodes");
  {
    std::unordered_set<std::int64_t> seen;
    seen.reserve(nn);
    for (std::size_t i = 0; i < nn; ++i) {
      if (!is_finite(m.nodes[i])) return fail("node " + std::to_string(m.node_ids[i]) + ": non-finite coordinate");
      if (!seen.insert(m.node_ids[i]).second) return fail("duplicate node id " + std::to_string(m.node_ids[i]));
    }
  }
  std::unordered_set<std::int64_t> seen;
  seen.reserve(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::string name = "element " + std::to_string(m.elem_ids[e]);
    if (static_cast<int>(m.elem_types[e]) >= kNumElemTypes) return fail(name + ": unknown type");
    if (m.elem_offsets[e + 1] < m.elem_offsets[e]) return fail(name + ": offsets decrease");
    const ElemInfo& info = elem_info(m.elem_types[e]);
    if (m.element_size(e) != info.nodes) {
      return fail(name + ": " + info.name + " needs " + std::to_string(info.nodes) + " nodes, has " + std::to_string(m.element_size(e)));
    }
    const std::uint32_t* v = m.element_nodes(e);
    for (int k = 0; k < info.nodes; ++k) {
      if (v[k] >= nn) return fail(name + ": node index " + std::to_string(v[k]) + " out of range (" + std::to_string(nn) + " nodes)");
    }
    if (m.elem_groups[e] < -1 || m.elem_groups[e] >= static_cast<std::int64_t>(m.groups.size())) {
      return fail(name + ": group index " + std::to_string(m.elem_groups[e]) + " out of range");
    }
    if (!seen.insert(m.elem_ids[e]).second) return fail("duplicate element id " + std::to_string(m.elem_ids[e]));
  }
  for (const FemSet& s : m.node_sets) {
    for (std::uint32_t i : s.members) {
      if (i >= nn) return fail("node set " + s.name + ": index out of range");
    }
  }
  for (const FemSet& s : m.elem_sets) {
    for (std::uint32_t i : s.members) {
      if (i >= ne) return fail("element set " + s.name + ": index out of range");
    }
  }
  for (const NodalSeries& f : m.fields) {
    if (f.times.size() != f.values.size()) return fail("field " + f.name + ": " + std::to_string(f.times.size()) + " times for " + std::to_string(f.values.size()) + " steps");
    for (std::size_t s = 0; s < f.values.size(); ++s) {
      if (f.values[s].size() != nn) return fail("field " + f.name + " step " + std::to_string(s) + ": " + std::to_string(f.values[s].size()) + " values for " + std::to_string(nn) + " nodes");
      for (const Vec3& v : f.values[s]) {
        if (!is_finite(v)) return fail("field " + f.name + " step " + std::to_string(s) + ": non-finite value");
      }
    }
  }
  return {};
}

}  // namespace interfere
