// Nastran bulk data writer, free field (MSC Nastran Quick Reference Guide, "Free Field Format"):
// BEGIN BULK, GRID (CP 0), CTETRA/CPYRAM/CPENTA/CHEXA (linear and quadratic), CTRIA3/CTRIA6,
// CQUAD4/CQUAD8, PSOLID/PSHELL stubs naming each PID, ENDDATA. PID = FemGroup::id when positive
// and unique, else the group index + 1 (0 for elements without a group). Reals always carry a
// decimal point; node order converted back from VTK's (scan.cpp, nastran_to_vtk).
#include <algorithm>
#include <charconv>
#include <set>

#include "scan.h"

namespace interfere::fem_io {
namespace {

void put_real(std::string& out, double v) {
  char b[40];
  const auto r = std::to_chars(b, b + 32, v);
  std::string_view s(b, static_cast<std::size_t>(r.ptr - b));
  if (s.find_first_of(".ni") != std::string_view::npos) {
    out += s;
    return;
  }
  const std::size_t e = s.find('e');
  if (e == std::string_view::npos) {
    out += s;
    out += '.';
  } else {
    out += s.substr(0, e);
    out += '.';
    out += s.substr(e);
  }
}

const char* card_of(ElemType t) {
  switch (t) {
    case ElemType::tet4: case ElemType::tet10: return "CTETRA";
    case ElemType::pyr5: case ElemType::pyr13: return "CPYRAM";
    case ElemType::wedge6: case ElemType::wedge15: return "CPENTA";
    case ElemType::hex8: case ElemType::hex20: return "CHEXA";
    case ElemType::tri3: return "CTRIA3";
    case ElemType::tri6: return "CTRIA6";
    case ElemType::quad4: return "CQUAD4";
    case ElemType::quad8: return "CQUAD8";
    default: return nullptr;
  }
}

}  // namespace

Status write_nastran(const FemMesh& m, const FemWriteOptions&, std::string& out) {
  std::vector<std::int64_t> pid(m.groups.size());
  {
    std::set<std::int64_t> seen;
    bool ok = true;
    for (const FemGroup& g : m.groups) ok &= g.id > 0 && seen.insert(g.id).second;
    for (std::size_t g = 0; g < pid.size(); ++g) pid[g] = ok ? m.groups[g].id : static_cast<std::int64_t>(g + 1);
  }
  for (ElemType t : m.elem_types) {
    if (!card_of(t)) return Error{.reason = std::string("Nastran writer: no card for ") + elem_info(t).name};
  }
  for (std::int64_t id : m.node_ids) {
    if (id <= 0) return Error{.reason = "Nastran needs positive GRID ids, found " + std::to_string(id)};
  }
  out += "$ written by interfere\nBEGIN BULK\n";
  for (std::size_t g = 0; g < m.groups.size(); ++g) {
    out += "$ PID ";
    put_int(out, pid[g]);
    out += ": ";
    out += one_line_name(m.groups[g].name);
    out += '\n';
    out += m.groups[g].dim == 3 ? "PSOLID," : "PSHELL,";
    put_int(out, pid[g]);
    out += ",1\n";
  }
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    out += "GRID,";
    put_int(out, m.node_ids[i]);
    out += ",,";
    put_real(out, m.nodes[i].x);
    out += ',';
    put_real(out, m.nodes[i].y);
    out += ',';
    put_real(out, m.nodes[i].z);
    out += '\n';
  }
  std::uint32_t v[32];
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    const ElemType t = m.elem_types[e];
    const int n = m.element_size(e);
    std::copy(m.element_nodes(e), m.element_nodes(e) + n, v);
    unpermute(nastran_to_vtk(t), v, n);
    out += card_of(t);
    out += ',';
    put_int(out, m.elem_ids[e]);
    out += ',';
    put_int(out, m.elem_groups[e] < 0 ? 0 : pid[static_cast<std::size_t>(m.elem_groups[e])]);
    int field = 4;  // next field number on this line (2..9 are data; EID and PID took 2 and 3)
    for (int k = 0; k < n; ++k) {
      if (field > 9) {
        out += "\n";
        field = 2;
      }
      out += ',';
      put_int(out, m.node_ids[v[k]]);
      ++field;
    }
    out += '\n';
  }
  out += "ENDDATA\n";
  return {};
}

}  // namespace interfere::fem_io
