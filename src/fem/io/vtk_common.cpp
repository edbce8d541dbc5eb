// Shared by the legacy VTK and VTU readers/writers (vtk_common.h): from decoded VTK arrays to a
// FemMesh and back. VTK file formats (Kitware, "VTK File Formats"): cell connectivity indexes
// the points, cell types VTK_TETRA = 10 ... VTK_TRIQUADRATIC_HEXAHEDRON = 29.
#include "vtk_common.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace interfere::fem_io {

bool is_node_id_array(const std::string& n) {
  return n == "GlobalNodeId" || n == "GlobalNodeIds" || n == "node_id" || n == "NodeId" || n == "node_ids" || n == "gmsh:node_id";
}
bool is_elem_id_array(const std::string& n) {
  return n == "GlobalElementId" || n == "GlobalElementIds" || n == "GlobalCellId" || n == "GlobalCellIds" || n == "element_id" ||
         n == "ElementId" || n == "element_ids" || n == "CellId";
}
int group_array_rank(const std::string& n) {
  static const char* const kNames[] = {"group", "gmsh:physical", "PartId", "part_id", "mat_id", "MaterialIds", "MaterialId",
                                       "material", "mat", "CellEntityIds", "region", "gmsh:geometrical"};
  for (int i = 0; i < static_cast<int>(std::size(kNames)); ++i) {
    if (n == kNames[i]) return i;
  }
  return -1;
}

Expected<FemMesh> build_vtk_mesh(const std::string& file, VtkData&& d, bool bytes) {
  auto err = [&](std::int64_t where, std::string r) { return bytes ? byte_error(file, where, std::move(r)) : line_error(file, where, std::move(r)); };
  FemMesh m;
  m.file = file;
  if (d.points.size() % 3 != 0) return err(-1, "points array is not a multiple of 3");
  const std::size_t np = d.points.size() / 3;
  const std::size_t nc = d.types.size();
  if (d.offsets.size() != nc) return err(d.cells_where, "cells: " + std::to_string(d.offsets.size()) + " offsets for " + std::to_string(nc) + " cell types");
  if (nc == 0) return file_error(file, "no cells");
  m.nodes.resize(np);
  for (std::size_t i = 0; i < np; ++i) {
    m.nodes[i] = {d.points[3 * i], d.points[3 * i + 1], d.points[3 * i + 2]};
    if (!is_finite(m.nodes[i])) return err(-1, "point " + std::to_string(i) + ": non-finite coordinate");
  }
  std::vector<double>().swap(d.points);
  // Ids.
  const VtkArray* node_ids = nullptr;
  const VtkArray* elem_ids = nullptr;
  const VtkArray* groups = nullptr;
  for (const VtkArray& a : d.point_arrays) {
    if (!node_ids && a.components == 1 && is_node_id_array(a.name) && a.size() == np) node_ids = &a;
  }
  for (const VtkArray& a : d.cell_arrays) {
    if (a.components != 1 || a.size() != nc) continue;
    if (!elem_ids && is_elem_id_array(a.name)) elem_ids = &a;
    const int r = group_array_rank(a.name);
    if (r >= 0 && (a.integer || std::all_of(a.reals.begin(), a.reals.end(), [](double x) { return x == std::floor(x) && std::abs(x) < 1e15; })) &&
        (!groups || r < group_array_rank(groups->name)))
      groups = &a;
  }
  auto int_at = [](const VtkArray& a, std::size_t i) { return a.integer ? a.ints[i] : static_cast<std::int64_t>(a.reals[i]); };
  m.node_ids.resize(np);
  for (std::size_t i = 0; i < np; ++i) m.node_ids[i] = node_ids ? int_at(*node_ids, i) : static_cast<std::int64_t>(i + 1);
  {
    std::int64_t first = -1;
    const std::int64_t dup = find_duplicate(m.node_ids, &first);
    if (dup >= 0) return err(node_ids ? node_ids->where : -1, "duplicate node id " + std::to_string(m.node_ids[static_cast<std::size_t>(dup)]) + " in " + (node_ids ? node_ids->name : std::string("points")));
  }
  // Cells.
  m.elem_types.reserve(nc);
  m.elem_ids.reserve(nc);
  m.elem_groups.reserve(nc);
  m.elem_offsets.reserve(nc + 1);
  m.elem_nodes.reserve(d.connectivity.size());
  std::int64_t prev = 0;
  std::uint32_t v[32];
  std::size_t poly_cells = 0;  // VTK_EMPTY_CELL 0, VTK_POLY_VERTEX 2, VTK_POLY_LINE 4: no surface
  for (std::size_t c = 0; c < nc; ++c) {
    ElemType t{};
    if (d.types[c] == 0 || d.types[c] == 2 || d.types[c] == 4) {
      const std::int64_t end = d.offsets[c];
      if (end < prev || end > static_cast<std::int64_t>(d.connectivity.size())) {
        return err(d.cells_where, "cell " + std::to_string(c) + ": offset " + std::to_string(end) + " out of range");
      }
      prev = end;
      ++poly_cells;
      continue;
    }
    if (!elem_type_from_vtk(static_cast<int>(d.types[c]), t) || d.types[c] < 0 || d.types[c] > 255) {
      return err(d.types_where, "cell " + std::to_string(c) + ": unsupported VTK cell type " + std::to_string(d.types[c]));
    }
    const std::int64_t end = d.offsets[c];
    const int need = elem_info(t).nodes;
    if (end < prev || end > static_cast<std::int64_t>(d.connectivity.size())) {
      return err(d.cells_where, "cell " + std::to_string(c) + ": offset " + std::to_string(end) + " out of range");
    }
    if (end - prev != need) {
      return err(d.cells_where, "cell " + std::to_string(c) + ": " + elem_info(t).name + " needs " + std::to_string(need) + " points, has " + std::to_string(end - prev));
    }
    for (int k = 0; k < need; ++k) {
      const std::int64_t p = d.connectivity[static_cast<std::size_t>(prev + k)];
      if (p < 0 || static_cast<std::uint64_t>(p) >= np) {
        return err(d.cells_where, "cell " + std::to_string(c) + ": point index " + std::to_string(p) + " out of range (" + std::to_string(np) + " points)");
      }
      v[k] = static_cast<std::uint32_t>(p);
    }
    prev = end;
    m.add_element(t, elem_ids ? int_at(*elem_ids, c) : static_cast<std::int64_t>(c + 1), -1, v, need);
  }
  {
    std::int64_t first = -1;
    const std::int64_t dup = find_duplicate(m.elem_ids, &first);
    if (dup >= 0) return err(elem_ids ? elem_ids->where : -1, "duplicate element id " + std::to_string(m.elem_ids[static_cast<std::size_t>(dup)]) + " in " + (elem_ids ? elem_ids->name : std::string("cells")));
  }
  // Mixed dimensions: keep the highest (like the other readers).
  drop_lower_dimension(m, nullptr);
  if (poly_cells > 0) {
    m.warnings.push_back("skipped " + std::to_string(poly_cells) +
                         " VTK empty, poly-vertex and poly-line cells (no surface)");
  }
  // Groups: distinct values of the group array, in increasing order; -1 in our "group" array = none.
  if (groups) {
    std::vector<std::int64_t> val(nc);
    for (std::size_t c = 0; c < nc; ++c) val[c] = int_at(*groups, c);
    // Map kept elements back: drop_lower_dimension kept the order, so walk both.
    std::vector<std::int64_t> kept;
    kept.reserve(m.num_elements());
    {
      int top = 0;
      for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
      for (std::size_t c = 0; c < nc; ++c) {
        ElemType t{};
        elem_type_from_vtk(static_cast<int>(d.types[c]), t);
        if (elem_info(t).dim == top) kept.push_back(val[c]);
      }
    }
    std::set<std::int64_t> distinct(kept.begin(), kept.end());
    const bool ours = groups->name == "group";
    if (ours) distinct.erase(-1);
    std::map<std::int64_t, std::int32_t> index;
    int top = 0;
    for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
    const bool named = ours && d.group_names.size() == distinct.size();
    std::size_t k = 0;
    for (std::int64_t x : distinct) {
      index[x] = static_cast<std::int32_t>(m.groups.size());
      m.groups.push_back(FemGroup{.name = named ? d.group_names[k] : groups->name + " " + std::to_string(x), .id = x, .dim = top});
      ++k;
    }
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      auto it = index.find(kept[e]);
      m.elem_groups[e] = it == index.end() ? -1 : it->second;
    }
  }
  // Fields: 3-component real point arrays (other than ids). Arrays named <base>_<digits> (u_0001,
  // u_0002, ...) are the steps of one series <base>, in numeric order, time = the number.
  std::map<std::string, std::map<std::int64_t, std::size_t>> steps;  // base -> number -> array
  std::vector<std::string> order;
  for (std::size_t k = 0; k < d.point_arrays.size(); ++k) {
    const VtkArray& a = d.point_arrays[k];
    if (a.integer || a.components != 3 || a.reals.size() != 3 * np) continue;
    for (std::size_t i = 0; i < a.reals.size(); ++i) {
      if (!std::isfinite(a.reals[i])) return err(a.where, "point data '" + a.name + "': non-finite value at point " + std::to_string(i / 3));
    }
    std::string base = a.name;
    std::int64_t number = -1;
    const std::size_t us = a.name.rfind('_');
    std::int64_t x = 0;
    if (us != std::string::npos && us > 0 && us + 1 < a.name.size() &&
        a.name.find_first_not_of("0123456789", us + 1) == std::string::npos && parse_int(std::string_view(a.name).substr(us + 1), x)) {
      base = a.name.substr(0, us);
      number = x;
    }
    if (number < 0 || steps[base].count(number)) {  // plain array (or a repeated number): its own series
      base = a.name;
      number = 0;
    }
    if (!steps.count(base) || steps[base].empty()) order.push_back(base);
    steps[base][number] = k;
  }
  for (const std::string& base : order) {
    NodalSeries f{.name = base};
    const bool numbered = base != d.point_arrays[steps[base].begin()->second].name;
    for (auto [number, k] : steps[base]) {
      const VtkArray& a = d.point_arrays[k];
      std::vector<Vec3> vals(np);
      for (std::size_t i = 0; i < np; ++i) vals[i] = {a.reals[3 * i], a.reals[3 * i + 1], a.reals[3 * i + 2]};
      f.values.push_back(std::move(vals));
      f.times.push_back(numbered ? static_cast<double>(number) : 0.0);
    }
    m.fields.push_back(std::move(f));
  }
  return m;
}

VtkOutArrays vtk_out_arrays(const FemMesh& m, const FemWriteOptions& o) {
  VtkOutArrays out;
  VtkArray eid{.name = "element_id", .integer = true, .ints = m.elem_ids};
  out.cell.push_back(std::move(eid));
  if (!m.groups.empty()) {
    std::set<std::int64_t> seen;
    bool ok = true;
    for (const FemGroup& g : m.groups) ok &= g.id > 0 && seen.insert(g.id).second;
    VtkArray g{.name = "group", .integer = true};
    g.ints.resize(m.num_elements());
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      const std::int32_t k = m.elem_groups[e];
      g.ints[e] = k < 0 ? -1 : (ok ? m.groups[static_cast<std::size_t>(k)].id : k + 1);
    }
    out.cell.push_back(std::move(g));
    std::vector<std::pair<std::int64_t, std::string>> named;
    for (std::size_t k = 0; k < m.groups.size(); ++k) named.emplace_back(ok ? m.groups[k].id : static_cast<std::int64_t>(k + 1), m.groups[k].name);
    std::sort(named.begin(), named.end());
    for (auto& [v, n] : named) out.group_names.push_back(n);
  }
  VtkArray nid{.name = "node_id", .integer = true, .ints = m.node_ids};
  out.point.push_back(std::move(nid));
  auto from = [](const FemArray& a) {
    VtkArray v{.name = a.name, .components = a.components, .integer = a.reals.empty()};
    if (v.integer) {
      v.ints = a.ints;
    } else {
      v.reals = a.reals;
    }
    return v;
  };
  for (const FemArray& a : o.cell_data) out.cell.push_back(from(a));
  for (const FemArray& a : o.point_data) out.point.push_back(from(a));
  if (o.write_fields) {
    for (const NodalSeries& f : m.fields) {
      if (f.values.empty()) continue;
      VtkArray v{.name = f.name, .components = 3};
      v.reals.reserve(3 * m.num_nodes());
      for (const Vec3& u : f.values.back()) {
        v.reals.push_back(u.x);
        v.reals.push_back(u.y);
        v.reals.push_back(u.z);
      }
      out.point.push_back(std::move(v));
    }
  }
  return out;
}

}  // namespace interfere::fem_io
