// Legacy VTK writer (VTK File Formats, "Simple Legacy Formats"): "# vtk DataFile Version 4.2",
// ASCII or BINARY (big-endian), DATASET UNSTRUCTURED_GRID with POINTS (double), CELLS in the
// classic "n size" layout, CELL_TYPES, and CELL_DATA / POINT_DATA as FIELD arrays (element_id,
// group, node_id, the options' arrays, the fields' last step). Array names have blanks replaced by
// '_' (legacy VTK names are single tokens).
#include <algorithm>
#include <limits>

#include "vtk_common.h"

namespace interfere::fem_io {
namespace {

std::string token_name(const std::string& n) {
  std::string r = n.empty() ? std::string("unnamed") : n;
  for (char& c : r) {
    if (is_space(c)) c = '_';
  }
  return r;
}

void put_array(std::string& out, const VtkArray& a, bool bin) {
  const std::size_t tuples = a.size() / static_cast<std::size_t>(a.components);
  bool fits32 = true;
  for (std::int64_t v : a.ints) fits32 &= v >= std::numeric_limits<std::int32_t>::min() && v <= std::numeric_limits<std::int32_t>::max();
  out += token_name(a.name) + " " + std::to_string(a.components) + " " + std::to_string(tuples) + " ";
  out += a.integer ? (fits32 ? "int\n" : "vtktypeint64\n") : "double\n";
  if (bin) {
    if (a.integer) {
      for (std::int64_t v : a.ints) {
        if (fits32) put_raw<std::int32_t>(out, static_cast<std::int32_t>(v), true); else put_raw<std::int64_t>(out, v, true);
      }
    } else {
      for (double v : a.reals) put_raw(out, v, true);
    }
    out += '\n';
    return;
  }
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (a.integer) put_int(out, a.ints[i]); else put_double(out, a.reals[i]);
    out += (i + 1) % 9 == 0 || i + 1 == n ? '\n' : ' ';
  }
}

}  // namespace

Status write_vtk_legacy(const FemMesh& m, const FemWriteOptions& o, std::string& out) {
  const bool bin = o.binary;
  for (const Vec3& p : m.nodes) (void)p;
  out += "# vtk DataFile Version 4.2\ninterfere FEM mesh\n";
  out += bin ? "BINARY\n" : "ASCII\n";
  out += "DATASET UNSTRUCTURED_GRID\nPOINTS " + std::to_string(m.num_nodes()) + " double\n";
  if (bin) {
    for (const Vec3& p : m.nodes) {
      put_raw(out, p.x, true);
      put_raw(out, p.y, true);
      put_raw(out, p.z, true);
    }
    out += '\n';
  } else {
    for (const Vec3& p : m.nodes) {
      put_double(out, p.x);
      out += ' ';
      put_double(out, p.y);
      out += ' ';
      put_double(out, p.z);
      out += '\n';
    }
  }
  const std::size_t ne = m.num_elements();
  out += "CELLS " + std::to_string(ne) + " " + std::to_string(ne + m.elem_nodes.size()) + "\n";
  for (std::size_t e = 0; e < ne; ++e) {
    const int n = m.element_size(e);
    if (bin) {
      put_raw<std::int32_t>(out, n, true);
      for (int k = 0; k < n; ++k) put_raw<std::int32_t>(out, static_cast<std::int32_t>(m.element_nodes(e)[k]), true);
    } else {
      put_int(out, n);
      for (int k = 0; k < n; ++k) {
        out += ' ';
        put_int(out, m.element_nodes(e)[k]);
      }
      out += '\n';
    }
  }
  if (bin) out += '\n';
  out += "CELL_TYPES " + std::to_string(ne) + "\n";
  for (std::size_t e = 0; e < ne; ++e) {
    const int t = elem_info(m.elem_types[e]).vtk_cell_type;
    if (bin) {
      put_raw<std::int32_t>(out, t, true);
    } else {
      put_int(out, t);
      out += '\n';
    }
  }
  if (bin) out += '\n';
  const VtkOutArrays arrays = vtk_out_arrays(m, o);
  out += "CELL_DATA " + std::to_string(ne) + "\nFIELD FieldData " + std::to_string(arrays.cell.size()) + "\n";
  for (const VtkArray& a : arrays.cell) put_array(out, a, bin);
  out += "POINT_DATA " + std::to_string(m.num_nodes()) + "\nFIELD FieldData " + std::to_string(arrays.point.size()) + "\n";
  for (const VtkArray& a : arrays.point) put_array(out, a, bin);
  return {};
}

}  // namespace interfere::fem_io
