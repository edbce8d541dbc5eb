// Abaqus / CalculiX input writer (Abaqus Keywords Reference): *HEADING, *NODE, one *ELEMENT block
// per run of elements with equal type and group (ELSET = the group's name, so a read back keeps
// the element order and the groups), *NSET / *ELSET for the mesh's sets. Node order is VTK's,
// which equals Abaqus's for every type written. Types: C3D4, C3D10, C3D5, C3D6, C3D15, C3D8,
// C3D20, C3D27, S3, S6, S4, S8R.
#include "scan.h"

namespace interfere::fem_io {
namespace {

const char* abaqus_name(ElemType t) {
  switch (t) {
    case ElemType::tet4: return "C3D4";
    case ElemType::tet10: return "C3D10";
    case ElemType::pyr5: return "C3D5";
    case ElemType::wedge6: return "C3D6";
    case ElemType::wedge15: return "C3D15";
    case ElemType::hex8: return "C3D8";
    case ElemType::hex20: return "C3D20";
    case ElemType::hex27: return "C3D27";
    case ElemType::tri3: return "S3";
    case ElemType::tri6: return "S6";
    case ElemType::quad4: return "S4";
    case ElemType::quad8: return "S8R";
    default: return nullptr;
  }
}

std::string set_name(const std::string& n) {
  std::string r;
  for (char c : n) r += (c == ',' || c == '=' || c == '"' || c == '*' || is_space(c) || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '_' : c;
  return r.empty() ? "unnamed" : r;
}

void put_list(std::string& out, const std::vector<std::int64_t>& ids) {
  for (std::size_t i = 0; i < ids.size(); ++i) {
    put_int(out, ids[i]);
    out += (i + 1) % 16 == 0 || i + 1 == ids.size() ? "\n" : ", ";
  }
}

}  // namespace

Status write_abaqus(const FemMesh& m, const FemWriteOptions&, std::string& out) {
  for (ElemType t : m.elem_types) {
    if (!abaqus_name(t)) return Error{.reason = std::string("Abaqus writer: no element type for ") + elem_info(t).name};
  }
  out += "*HEADING\nwritten by interfere\n*NODE\n";
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    put_int(out, m.node_ids[i]);
    for (int k = 0; k < 3; ++k) {
      out += ", ";
      put_double(out, m.nodes[i][static_cast<std::size_t>(k)]);
    }
    out += '\n';
  }
  for (std::size_t e = 0; e < m.num_elements();) {
    std::size_t f = e + 1;
    while (f < m.num_elements() && m.elem_types[f] == m.elem_types[e] && m.elem_groups[f] == m.elem_groups[e]) ++f;
    out += "*ELEMENT, TYPE=";
    out += abaqus_name(m.elem_types[e]);
    if (m.elem_groups[e] >= 0) out += ", ELSET=" + set_name(m.groups[static_cast<std::size_t>(m.elem_groups[e])].name);
    out += '\n';
    for (std::size_t x = e; x < f; ++x) {
      put_int(out, m.elem_ids[x]);
      const int n = m.element_size(x);
      for (int k = 0; k < n; ++k) {
        out += (k + 1) % 16 == 0 ? ",\n" : ", ";
        put_int(out, m.node_ids[m.element_nodes(x)[k]]);
      }
      out += '\n';
    }
    e = f;
  }
  for (const FemSet& s : m.node_sets) {
    out += "*NSET, NSET=" + set_name(s.name) + "\n";
    std::vector<std::int64_t> ids;
    for (std::uint32_t i : s.members) ids.push_back(m.node_ids[i]);
    put_list(out, ids);
  }
  for (const FemSet& s : m.elem_sets) {
    out += "*ELSET, ELSET=" + set_name(s.name) + "\n";
    std::vector<std::int64_t> ids;
    for (std::uint32_t i : s.members) ids.push_back(m.elem_ids[i]);
    put_list(out, ids);
  }
  return {};
}

}  // namespace interfere::fem_io
