// Gmsh MSH writer: 4.1 ASCII and binary, 2.2 ASCII (Gmsh reference manual, "MSH file format").
// Each group becomes one elementary entity (tag = group index + 1) carrying one physical group
// (tag = FemGroup::id when positive and unique, else the group index + 1; its name in
// $PhysicalNames); elements without a group go to one more entity without a physical group.
// Elements are written in mesh order (one block per run of equal entity and type), nodes in Gmsh
// order, doubles as shortest round-trip text (ASCII) or raw IEEE (binary): a read back is
// bit-exact. Fields become $NodeData views, one block per step. Node sets are not written.
#include <algorithm>
#include <set>

#include "scan.h"

namespace interfere::fem_io {
namespace {

int gmsh_number(ElemType t) {
  switch (t) {
    case ElemType::point1: return 15;
    case ElemType::line2: return 1;
    case ElemType::line3: return 8;
    case ElemType::tri3: return 2;
    case ElemType::tri6: return 9;
    case ElemType::quad4: return 3;
    case ElemType::quad8: return 16;
    case ElemType::quad9: return 10;
    case ElemType::tet4: return 4;
    case ElemType::tet10: return 11;
    case ElemType::pyr5: return 7;
    case ElemType::pyr13: return 19;
    case ElemType::wedge6: return 6;
    case ElemType::wedge15: return 18;
    case ElemType::hex8: return 5;
    case ElemType::hex20: return 17;
    case ElemType::hex27: return 12;
  }
  return 0;
}

}  // namespace

Status write_msh(const FemMesh& m, const FemWriteOptions& o, std::string& out) {
  if (o.msh_version != 41 && o.msh_version != 22) return Error{.reason = "msh_version must be 41 or 22"};
  const bool v4 = o.msh_version == 41;
  const bool bin = o.binary && v4;
  if (o.binary && !v4) return Error{.reason = "binary MSH is written as 4.1 only"};
  for (std::int64_t id : m.node_ids) {
    if (id <= 0 || id > 2147483647) return Error{.reason = "MSH needs node ids in 1..2^31-1, found " + std::to_string(id)};
  }
  for (std::int64_t id : m.elem_ids) {
    if (id <= 0) return Error{.reason = "MSH needs positive element ids, found " + std::to_string(id)};
  }
  int top = 0;
  for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
  const std::size_t ng = m.groups.size();
  // Physical tags.
  std::vector<int> ptag(ng);
  {
    std::set<std::int64_t> seen;
    bool ok = true;
    for (const FemGroup& g : m.groups) ok &= g.id > 0 && g.id < 2147483647 && seen.insert(g.id).second;
    for (std::size_t g = 0; g < ng; ++g) ptag[g] = ok ? static_cast<int>(m.groups[g].id) : static_cast<int>(g + 1);
  }
  const bool any_ungrouped = std::find(m.elem_groups.begin(), m.elem_groups.end(), -1) != m.elem_groups.end();
  const std::size_t nent = ng + (any_ungrouped ? 1 : 0);
  auto entity_of = [&](std::size_t e) { return m.elem_groups[e] < 0 ? static_cast<int>(ng + 1) : m.elem_groups[e] + 1; };

  out.reserve(m.nodes.size() * (bin ? 32 : 60) + m.elem_nodes.size() * (bin ? 8 : 8));
  out += "$MeshFormat\n";
  out += v4 ? "4.1 " : "2.2 ";
  out += bin ? "1 8\n" : "0 8\n";
  if (bin) {
    put_raw<std::int32_t>(out, 1);
    out += "\n";
  }
  out += "$EndMeshFormat\n";
  if (ng > 0) {
    out += "$PhysicalNames\n";
    put_int(out, static_cast<std::int64_t>(ng));
    out += "\n";
    for (std::size_t g = 0; g < ng; ++g) {
      put_int(out, top);
      out += " ";
      put_int(out, ptag[g]);
      out += " \"";
      out += one_line_name(m.groups[g].name);
      out += "\"\n";
    }
    out += "$EndPhysicalNames\n";
  }
  if (!v4) {
    out += "$Nodes\n";
    put_int(out, static_cast<std::int64_t>(m.nodes.size()));
    out += "\n";
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
      put_int(out, m.node_ids[i]);
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        put_double(out, m.nodes[i][static_cast<std::size_t>(k)]);
      }
      out += '\n';
    }
    out += "$EndNodes\n$Elements\n";
    put_int(out, static_cast<std::int64_t>(m.num_elements()));
    out += "\n";
    std::uint32_t v[32];
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      const ElemInfo& info = elem_info(m.elem_types[e]);
      put_int(out, m.elem_ids[e]);
      out += ' ';
      put_int(out, gmsh_number(m.elem_types[e]));
      out += " 2 ";
      put_int(out, m.elem_groups[e] < 0 ? 0 : ptag[static_cast<std::size_t>(m.elem_groups[e])]);
      out += ' ';
      put_int(out, entity_of(e));
      std::copy(m.element_nodes(e), m.element_nodes(e) + info.nodes, v);
      unpermute(gmsh_to_vtk(m.elem_types[e]), v, info.nodes);
      for (int k = 0; k < info.nodes; ++k) {
        out += ' ';
        put_int(out, m.node_ids[v[k]]);
      }
      out += '\n';
    }
    out += "$EndElements\n";
  } else {
    // Entities: one per group (+ ungrouped) of dimension `top`, bounding box of its nodes.
    std::vector<Vec3> lo(nent, Vec3{1e300, 1e300, 1e300}), hi(nent, Vec3{-1e300, -1e300, -1e300});
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      const std::size_t k = static_cast<std::size_t>(entity_of(e) - 1);
      for (int q = 0; q < m.element_size(e); ++q) {
        lo[k] = min(lo[k], m.nodes[m.element_nodes(e)[q]]);
        hi[k] = max(hi[k], m.nodes[m.element_nodes(e)[q]]);
      }
    }
    for (std::size_t k = 0; k < nent; ++k) {
      if (lo[k].x > hi[k].x) lo[k] = hi[k] = Vec3{};
    }
    out += "$Entities\n";
    std::uint64_t counts[4] = {0, 0, 0, 0};
    counts[top] = nent;
    if (bin) {
      for (std::uint64_t c : counts) put_raw(out, c);
    } else {
      for (int d = 0; d < 4; ++d) {
        put_int(out, static_cast<std::int64_t>(counts[d]));
        out += d < 3 ? " " : "\n";
      }
    }
    for (std::size_t k = 0; k < nent; ++k) {
      const double box[6] = {lo[k].x, lo[k].y, lo[k].z, hi[k].x, hi[k].y, hi[k].z};
      const bool has_phys = k < ng;
      if (bin) {
        put_raw<std::int32_t>(out, static_cast<std::int32_t>(k + 1));
        if (top == 0) {
          for (int q = 0; q < 3; ++q) put_raw(out, box[q]);
        } else {
          for (double x : box) put_raw(out, x);
        }
        put_raw<std::uint64_t>(out, has_phys ? 1 : 0);
        if (has_phys) put_raw<std::int32_t>(out, ptag[k]);
        if (top > 0) put_raw<std::uint64_t>(out, 0);
      } else {
        put_int(out, static_cast<std::int64_t>(k + 1));
        for (int q = 0; q < (top == 0 ? 3 : 6); ++q) {
          out += ' ';
          put_double(out, box[q]);
        }
        out += has_phys ? " 1 " + std::to_string(ptag[k]) : std::string(" 0");
        out += top > 0 ? " 0\n" : "\n";
      }
    }
    if (bin) out += "\n";
    out += "$EndEntities\n$Nodes\n";
    std::int64_t nmin = 0, nmax = 0;
    if (!m.node_ids.empty()) {
      nmin = *std::min_element(m.node_ids.begin(), m.node_ids.end());
      nmax = *std::max_element(m.node_ids.begin(), m.node_ids.end());
    }
    const std::uint64_t nn = m.nodes.size();
    if (bin) {
      for (std::uint64_t x : {std::uint64_t{nn > 0 ? 1u : 0u}, nn, static_cast<std::uint64_t>(nmin), static_cast<std::uint64_t>(nmax)}) put_raw(out, x);
      if (nn > 0) {
        put_raw<std::int32_t>(out, top);
        put_raw<std::int32_t>(out, 1);
        put_raw<std::int32_t>(out, 0);
        put_raw<std::uint64_t>(out, nn);
        for (std::int64_t id : m.node_ids) put_raw<std::uint64_t>(out, static_cast<std::uint64_t>(id));
        for (const Vec3& p : m.nodes) {
          put_raw(out, p.x);
          put_raw(out, p.y);
          put_raw(out, p.z);
        }
      }
      out += "\n";
    } else {
      out += (nn > 0 ? "1 " : "0 ") + std::to_string(nn) + " " + std::to_string(nmin) + " " + std::to_string(nmax) + "\n";
      if (nn > 0) {
        out += std::to_string(top) + " 1 0 " + std::to_string(nn) + "\n";
        for (std::int64_t id : m.node_ids) {
          put_int(out, id);
          out += '\n';
        }
        for (const Vec3& p : m.nodes) {
          put_double(out, p.x);
          out += ' ';
          put_double(out, p.y);
          out += ' ';
          put_double(out, p.z);
          out += '\n';
        }
      }
    }
    out += "$EndNodes\n$Elements\n";
    // Blocks: runs of equal (entity, type).
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t e = 0; e < m.num_elements();) {
      std::size_t f = e + 1;
      while (f < m.num_elements() && m.elem_types[f] == m.elem_types[e] && entity_of(f) == entity_of(e)) ++f;
      runs.emplace_back(e, f);
      e = f;
    }
    std::int64_t emin = 0, emax = 0;
    if (!m.elem_ids.empty()) {
      emin = *std::min_element(m.elem_ids.begin(), m.elem_ids.end());
      emax = *std::max_element(m.elem_ids.begin(), m.elem_ids.end());
    }
    if (bin) {
      for (std::uint64_t x : {std::uint64_t{runs.size()}, std::uint64_t{m.num_elements()}, static_cast<std::uint64_t>(emin), static_cast<std::uint64_t>(emax)}) put_raw(out, x);
    } else {
      out += std::to_string(runs.size()) + " " + std::to_string(m.num_elements()) + " " + std::to_string(emin) + " " + std::to_string(emax) + "\n";
    }
    std::uint32_t v[32];
    for (auto [b, f] : runs) {
      const ElemType t = m.elem_types[b];
      const ElemInfo& info = elem_info(t);
      if (bin) {
        put_raw<std::int32_t>(out, info.dim);
        put_raw<std::int32_t>(out, entity_of(b));
        put_raw<std::int32_t>(out, gmsh_number(t));
        put_raw<std::uint64_t>(out, f - b);
      } else {
        out += std::to_string(info.dim) + " " + std::to_string(entity_of(b)) + " " + std::to_string(gmsh_number(t)) + " " + std::to_string(f - b) + "\n";
      }
      for (std::size_t e = b; e < f; ++e) {
        std::copy(m.element_nodes(e), m.element_nodes(e) + info.nodes, v);
        unpermute(gmsh_to_vtk(t), v, info.nodes);
        if (bin) {
          put_raw<std::uint64_t>(out, static_cast<std::uint64_t>(m.elem_ids[e]));
          for (int k = 0; k < info.nodes; ++k) put_raw<std::uint64_t>(out, static_cast<std::uint64_t>(m.node_ids[v[k]]));
        } else {
          put_int(out, m.elem_ids[e]);
          for (int k = 0; k < info.nodes; ++k) {
            out += ' ';
            put_int(out, m.node_ids[v[k]]);
          }
          out += '\n';
        }
      }
    }
    if (bin) out += "\n";
    out += "$EndElements\n";
  }
  if (o.write_fields) {
    for (const NodalSeries& f : m.fields) {
      for (std::size_t s = 0; s < f.values.size(); ++s) {
        out += "$NodeData\n1\n\"";
        out += one_line_name(f.name);
        out += "\"\n1\n";
        put_double(out, f.times[s]);
        out += "\n3\n" + std::to_string(s) + "\n3\n" + std::to_string(m.nodes.size()) + "\n";
        for (std::size_t i = 0; i < m.nodes.size(); ++i) {
          const Vec3& u = f.values[s][i];
          if (bin) {
            put_raw<std::int32_t>(out, static_cast<std::int32_t>(m.node_ids[i]));
            put_raw(out, u.x);
            put_raw(out, u.y);
            put_raw(out, u.z);
          } else {
            put_int(out, m.node_ids[i]);
            for (int k = 0; k < 3; ++k) {
              out += ' ';
              put_double(out, u[static_cast<std::size_t>(k)]);
            }
            out += '\n';
          }
        }
        if (bin) out += "\n";
        out += "$EndNodeData\n";
      }
    }
  }
  return {};
}

}  // namespace interfere::fem_io
