// Part assignment of the elements for surface extraction (fem/surface.h): by group, or by
// connectivity through shared corner nodes (union-find with path halving and union by index,
// Tarjan & van Leeuwen, "Worst-case analysis of set union algorithms", J. ACM 31(2), 1984).
#include "surface_internal.h"

#include <numeric>

#include "surface_faces.h"

namespace interfere::fem_detail {
namespace {

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

bool has_surface(ElemType t) { return elem_info(t).dim >= 2; }

}  // namespace

PartAssignment assign_parts(const FemMesh& mesh, PartSplit split) {
  PartAssignment r;
  const std::size_t ne = mesh.num_elements();
  r.part.assign(ne, kNoPart);
  if (split == PartSplit::automatic) {
    split = PartSplit::single;
    for (std::size_t e = 0; e < ne; ++e) {
      if (has_surface(mesh.elem_types[e]) && mesh.elem_groups[e] >= 0) {
        split = PartSplit::by_group;
        break;
      }
    }
    if (split == PartSplit::single) split = PartSplit::connectivity;
  }
  if (split == PartSplit::single) {
    for (std::size_t e = 0; e < ne; ++e) {
      if (has_surface(mesh.elem_types[e])) r.part[e] = 0;
    }
    r.names.push_back("all");
    r.groups.push_back(-1);
  } else if (split == PartSplit::by_group) {
    // Parts in group order, "ungrouped" last; groups without surface elements make no part.
    const std::size_t ng = mesh.groups.size();
    std::vector<std::uint32_t> index(ng + 1, kNoPart);
    std::vector<char> used(ng + 1, 0);
    for (std::size_t e = 0; e < ne; ++e) {
      if (has_surface(mesh.elem_types[e])) used[mesh.elem_groups[e] < 0 ? ng : mesh.elem_groups[e]] = 1;
    }
    for (std::size_t g = 0; g <= ng; ++g) {
      if (!used[g]) continue;
      index[g] = static_cast<std::uint32_t>(r.names.size());
      r.names.push_back(g < ng ? mesh.groups[g].name : std::string("ungrouped"));
      r.groups.push_back(g < ng ? static_cast<std::int32_t>(g) : -1);
    }
    for (std::size_t e = 0; e < ne; ++e) {
      if (has_surface(mesh.elem_types[e])) r.part[e] = index[mesh.elem_groups[e] < 0 ? ng : mesh.elem_groups[e]];
    }
  } else {
    std::vector<std::uint32_t> parent(mesh.num_nodes());
    std::iota(parent.begin(), parent.end(), 0u);
    for (std::size_t e = 0; e < ne; ++e) {
      const ElemType t = mesh.elem_types[e];
      if (!has_surface(t)) continue;
      const std::uint32_t* v = mesh.element_nodes(e);
      const int nc = elem_info(t).corners;
      std::uint32_t a = find(parent, v[0]);
      for (int k = 1; k < nc; ++k) {
        const std::uint32_t b = find(parent, v[k]);
        if (a == b) continue;
        // The smaller index becomes the root (deterministic).
        if (b < a) {
          parent[a] = b;
          a = b;
        } else {
          parent[b] = a;
        }
      }
    }
    // Components numbered by their smallest element index.
    std::vector<std::uint32_t> label(mesh.num_nodes(), kNoPart);
    for (std::size_t e = 0; e < ne; ++e) {
      if (!has_surface(mesh.elem_types[e])) continue;
      const std::uint32_t root = find(parent, mesh.element_nodes(e)[0]);
      if (label[root] == kNoPart) {
        label[root] = static_cast<std::uint32_t>(r.names.size());
        r.names.push_back("body " + std::to_string(r.names.size() + 1));
        r.groups.push_back(-1);
      }
      r.part[e] = label[root];
    }
  }
  return r;
}

}  // namespace interfere::fem_detail
