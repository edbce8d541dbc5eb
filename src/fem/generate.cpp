// Structured FEM meshes (fem/generate.h). Tet splits: Kuhn/Freudenthal (H. W. Kuhn, "Some
// combinatorial lemmas in topology", IBM J. Res. Dev. 4(5), 1960) and the 5-tet split with
// alternating parity; cube-to-ball map: Nowell, "Mapping a cube to a sphere" (2005), the disc map
// its two-dimensional case.
#include "interfere/fem/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "interfere/core/predicates.h"

namespace interfere {
namespace {

constexpr std::array<std::array<int, 3>, 8> kCorner{{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
constexpr std::array<std::array<int, 2>, 12> kHexEdges{{
    {0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
constexpr std::array<std::array<int, 4>, 6> kHexCentres{{
    {0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};
// Faces of the cell (Abaqus hex order, normals into the cell): pyramid bases.
constexpr std::array<std::array<int, 4>, 6> kCellFaces{{
    {0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}}};

struct Grid {
  int gx, gy, gz;  // doubled-grid points per axis
  std::uint32_t at(int i, int j, int k) const {
    return static_cast<std::uint32_t>(i + gx * (j + static_cast<std::int64_t>(gy) * k));
  }
};

using P3 = std::array<int, 3>;  // doubled-grid coordinates

P3 mid(const P3& a, const P3& b) { return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}; }

void check(const FemBoxOptions& o) {
  if (o.nx < 1 || o.ny < 1 || o.nz < 1) throw std::invalid_argument("make_fem_box: cells per axis must be >= 1");
  if (o.tets_per_cell != 5 && o.tets_per_cell != 6) throw std::invalid_argument("make_fem_box: tets_per_cell is 5 or 6");
  const ElemType t = o.type;
  if (elem_info(t).dim != 3 || t == ElemType::pyr13) {
    throw std::invalid_argument(std::string("make_fem_box: unsupported element type ") + elem_info(t).name);
  }
}

// Grid of (2n+1)^3 points (every type uses a subset); elements in doubled-grid coordinates.
FemMesh build(const FemBoxOptions& o, const Vec3& lo, const Vec3& hi) {
  check(o);
  const Grid g{2 * o.nx + 1, 2 * o.ny + 1, 2 * o.nz + 1};
  FemMesh m;
  const std::size_t total = static_cast<std::size_t>(g.gx) * g.gy * g.gz;
  std::vector<Vec3> grid(total);
  for (int k = 0; k < g.gz; ++k) {
    for (int j = 0; j < g.gy; ++j) {
      for (int i = 0; i < g.gx; ++i) {
        grid[g.at(i, j, k)] = {lo.x + (hi.x - lo.x) * i / (2.0 * o.nx), lo.y + (hi.y - lo.y) * j / (2.0 * o.ny),
                               lo.z + (hi.z - lo.z) * k / (2.0 * o.nz)};
      }
    }
  }
  auto pt = [&](const P3& p) { return grid[g.at(p[0], p[1], p[2])]; };
  const int group = o.group.empty() ? -1 : 0;
  if (group == 0) m.groups.push_back({.name = o.group, .id = 1, .dim = 3});
  std::vector<std::uint32_t> v;
  std::int64_t id = o.first_element_id;
  auto add = [&](ElemType t, const std::vector<P3>& nodes) {
    v.clear();
    for (const P3& p : nodes) v.push_back(g.at(p[0], p[1], p[2]));
    m.add_element(t, id++, group, v.data(), static_cast<int>(v.size()));
  };
  const ElemType t = o.type;
  for (int ck = 0; ck < o.nz; ++ck) {
    for (int cj = 0; cj < o.ny; ++cj) {
      for (int ci = 0; ci < o.nx; ++ci) {
        std::array<P3, 8> c;
        for (int q = 0; q < 8; ++q) c[q] = {2 * (ci + kCorner[q][0]), 2 * (cj + kCorner[q][1]), 2 * (ck + kCorner[q][2])};
        auto corner_index = [&](int a, int b, int d) {
          for (int q = 0; q < 8; ++q) {
            if (kCorner[q][0] == a && kCorner[q][1] == b && kCorner[q][2] == d) return q;
          }
          return 0;
        };
        auto tet = [&](P3 a, P3 b, P3 cc, P3 d) {
          if (orient3d(pt(a), pt(b), pt(cc), pt(d)) > 0) std::swap(b, cc);  // make (b-a)x(c-a)·(d-a) > 0
          std::vector<P3> n{a, b, cc, d};
          if (t == ElemType::tet10) {
            for (auto [x, y] : {std::pair{a, b}, {b, cc}, {cc, a}, {a, d}, {b, d}, {cc, d}}) n.push_back(mid(x, y));
          }
          add(t, n);
        };
        switch (t) {
          case ElemType::hex8:
          case ElemType::hex20:
          case ElemType::hex27: {
            std::vector<P3> n(c.begin(), c.end());
            if (t != ElemType::hex8) {
              for (const auto& e : kHexEdges) n.push_back(mid(c[e[0]], c[e[1]]));
            }
            if (t == ElemType::hex27) {
              for (const auto& f : kHexCentres) n.push_back(mid(c[f[0]], c[f[2]]));
              n.push_back(mid(c[0], c[6]));
            }
            add(t, n);
            break;
          }
          case ElemType::tet4:
          case ElemType::tet10:
            if (o.tets_per_cell == 6) {
              const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
              for (const auto& p : perm) {
                std::array<int, 3> a{0, 0, 0};
                const int q0 = 0;
                a[p[0]] = 1;
                const int q1 = corner_index(a[0], a[1], a[2]);
                a[p[1]] = 1;
                const int q2 = corner_index(a[0], a[1], a[2]);
                tet(c[q0], c[q1], c[q2], c[6]);
              }
            } else {
              const int parity = (ci + cj + ck) % 2;
              std::vector<int> even;
              for (int q = 0; q < 8; ++q) {
                if ((kCorner[q][0] + kCorner[q][1] + kCorner[q][2]) % 2 == parity) even.push_back(q);
              }
              tet(c[even[0]], c[even[1]], c[even[2]], c[even[3]]);
              for (int q = 0; q < 8; ++q) {
                if ((kCorner[q][0] + kCorner[q][1] + kCorner[q][2]) % 2 == parity) continue;
                std::vector<int> nb;
                for (int s = 0; s < 3; ++s) {
                  std::array<int, 3> a = kCorner[q];
                  a[s] ^= 1;
                  nb.push_back(corner_index(a[0], a[1], a[2]));
                }
                tet(c[q], c[nb[0]], c[nb[1]], c[nb[2]]);
              }
            }
            break;
          case ElemType::wedge6:
          case ElemType::wedge15:
            for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
              std::vector<P3> n{c[tri[0]], c[tri[1]], c[tri[2]], c[tri[0] + 4], c[tri[1] + 4], c[tri[2] + 4]};
              if (t == ElemType::wedge15) {
                for (auto [x, y] : {std::pair{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}}) {
                  n.push_back(mid(n[x], n[y]));
                }
              }
              add(t, n);
            }
            break;
          case ElemType::pyr5: {
            const P3 centre = mid(c[0], c[6]);
            for (const auto& f : kCellFaces) add(t, {c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre});
            break;
          }
          default: break;
        }
      }
    }
  }
  // Keep the grid points in use (grid order), renumber.
  std::vector<std::uint32_t> index(total, ~0u);
  for (std::uint32_t n : m.elem_nodes) index[n] = 0;
  std::int64_t nid = o.first_node_id;
  for (std::size_t i = 0; i < total; ++i) {
    if (index[i] == ~0u) continue;
    index[i] = static_cast<std::uint32_t>(m.nodes.size());
    m.nodes.push_back(grid[i]);
    m.node_ids.push_back(nid++);
  }
  for (std::uint32_t& n : m.elem_nodes) n = index[n];
  return m;
}

// Pyramids: put each apex at the centroid of its cell's mapped corners (the mapped cell centre
// can lie outside a strongly distorted cell, e.g. at the corners of the cube-to-ball map).
void recentre_apexes(FemMesh& m) {
  if (m.num_elements() == 0 || m.elem_types[0] != ElemType::pyr5) return;
  for (std::size_t e = 0; e + 6 <= m.num_elements(); e += 6) {
    Vec3 s{};
    const std::uint32_t* bottom = m.element_nodes(e);      // cell face (0,1,2,3)
    const std::uint32_t* top = m.element_nodes(e + 1);     // cell face (4,7,6,5)
    for (int k = 0; k < 4; ++k) s += m.nodes[bottom[k]] + m.nodes[top[k]];
    m.nodes[bottom[4]] = s / 8.0;
  }
}

}  // namespace

int fem_elements_per_cell(const FemBoxOptions& o) {
  switch (o.type) {
    case ElemType::tet4:
    case ElemType::tet10: return o.tets_per_cell;
    case ElemType::wedge6:
    case ElemType::wedge15: return 2;
    case ElemType::pyr5: return 6;
    default: return 1;
  }
}

GeneratedFem make_fem_box(const FemBoxOptions& o) {
  GeneratedFem r;
  r.mesh = build(o, o.lo, o.hi);
  const Vec3 d = o.hi - o.lo;
  r.volume = d.x * d.y * d.z;
  r.area = 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
  return r;
}

GeneratedFem make_fem_cylinder(const FemBoxOptions& o, double radius, double height, const Vec3& base) {
  GeneratedFem r;
  r.mesh = build(o, {-1, -1, 0}, {1, 1, 1});
  for (Vec3& p : r.mesh.nodes) {
    const double x = p.x, y = p.y;
    p = {base.x + radius * x * std::sqrt(1 - y * y / 2), base.y + radius * y * std::sqrt(1 - x * x / 2),
         base.z + height * p.z};
  }
  recentre_apexes(r.mesh);
  const double pi = std::numbers::pi;
  r.volume = pi * radius * radius * height;
  r.area = 2 * pi * radius * radius + 2 * pi * radius * height;
  return r;
}

GeneratedFem make_fem_sphere(const FemBoxOptions& o, double radius, const Vec3& center) {
  GeneratedFem r;
  r.mesh = build(o, {-1, -1, -1}, {1, 1, 1});
  for (Vec3& p : r.mesh.nodes) {
    const double x2 = p.x * p.x, y2 = p.y * p.y, z2 = p.z * p.z;
    p = {center.x + radius * p.x * std::sqrt(std::max(0.0, 1 - y2 / 2 - z2 / 2 + y2 * z2 / 3)),
         center.y + radius * p.y * std::sqrt(std::max(0.0, 1 - z2 / 2 - x2 / 2 + z2 * x2 / 3)),
         center.z + radius * p.z * std::sqrt(std::max(0.0, 1 - x2 / 2 - y2 / 2 + x2 * y2 / 3))};
  }
  recentre_apexes(r.mesh);
  const double pi = std::numbers::pi;
  r.volume = 4.0 / 3.0 * pi * radius * radius * radius;
  r.area = 4 * pi * radius * radius;
  return r;
}

}  // namespace interfere
