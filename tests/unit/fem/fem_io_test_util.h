// Helpers shared by the FEM reader/writer tests: a mesh holding every element type, bit-exact
// mesh comparison, a private temporary directory, and running the gmsh CLI on a .geo written by
// the test (GTEST_SKIP when gmsh is not on PATH).
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/io.h"

namespace interfere::fem_test {

namespace fs = std::filesystem;

/// A private temporary directory, removed at exit.
inline fs::path temp_dir() {
  static fs::path dir = [] {
    std::string t = (fs::temp_directory_path() / "interfere_fem_io_XXXXXX").string();
    if (!::mkdtemp(t.data())) std::abort();
    return fs::path(t);
  }();
  // Registered after `dir` is constructed, so it runs before `dir` is destroyed.
  static const bool cleanup = (std::atexit([] {
                                 std::error_code ec;
                                 fs::remove_all(temp_dir(), ec);
                               }),
                               true);
  (void)cleanup;
  return dir;
}

inline void write_text(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
}
inline std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

inline bool have_gmsh() { return std::system("gmsh --version > /dev/null 2>&1") == 0; }

/// Writes `geo` and meshes it with gmsh (`args` e.g. "-3 -format msh41 -bin"); returns the .msh.
inline fs::path gmsh_mesh(const std::string& name, const std::string& geo, const std::string& args) {
  const fs::path g = temp_dir() / (name + ".geo");
  const fs::path out = temp_dir() / (name + ".msh");
  write_text(g, geo);
  const std::string cmd = "gmsh " + g.string() + " " + args + " -o " + out.string() + " > " + (temp_dir() / (name + ".log")).string() + " 2>&1";
  if (std::system(cmd.c_str()) != 0 || !fs::exists(out)) return {};
  return out;
}

/// Mid-edge node pairs (corner indices) of each quadratic type in VTK order (fem_mesh.h header /
/// VTK documentation), and face-centre corner quadruples of hex27.
inline std::vector<std::array<int, 2>> vtk_edges(ElemType t) {
  switch (t) {
    case ElemType::tri6: return {{0, 1}, {1, 2}, {2, 0}};
    case ElemType::quad8:
    case ElemType::quad9: return {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    case ElemType::tet10: return {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    case ElemType::hex20:
    case ElemType::hex27:
      return {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    case ElemType::wedge15: return {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
    case ElemType::pyr13: return {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
    case ElemType::line3: return {{0, 1}};
    default: return {};
  }
}
inline std::vector<std::array<int, 4>> vtk_hex27_faces() {
  return {{0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}};
}

/// Largest distance of a mid-edge (face-centre) node from the midpoint (centroid) of its corners,
/// relative to the element size, over all quadratic elements; counts the elements checked.
inline double midside_error(const FemMesh& m, std::size_t* checked = nullptr) {
  double worst = 0;
  std::size_t n = 0;
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    const ElemType t = m.elem_types[e];
    const auto edges = vtk_edges(t);
    if (edges.empty()) continue;
    ++n;
    const std::uint32_t* v = m.element_nodes(e);
    const int corners = elem_info(t).corners;
    double size = 0;
    for (int k = 1; k < corners; ++k) size = std::max(size, distance(m.nodes[v[0]], m.nodes[v[k]]));
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const Vec3 mid = (m.nodes[v[edges[k][0]]] + m.nodes[v[edges[k][1]]]) * 0.5;
      worst = std::max(worst, distance(mid, m.nodes[v[corners + static_cast<int>(k)]]) / size);
    }
    if (t == ElemType::hex27 || t == ElemType::quad9) {
      const auto faces = t == ElemType::hex27 ? vtk_hex27_faces() : std::vector<std::array<int, 4>>{{0, 1, 2, 3}};
      for (std::size_t f = 0; f < faces.size(); ++f) {
        Vec3 c{};
        for (int q : faces[f]) c += m.nodes[v[q]];
        worst = std::max(worst, distance(c * 0.25, m.nodes[v[corners + static_cast<int>(edges.size() + f)]]) / size);
      }
    }
  }
  if (checked) *checked = n;
  return worst;
}

/// A mesh with one element of every volume type (shell = false) or every shell type (shell =
/// true), mid-side nodes at midpoints, non-contiguous ids, two groups and a field with 2 steps.
inline FemMesh every_type_mesh(bool shell) {
  FemMesh m;
  std::vector<ElemType> types = shell ? std::vector<ElemType>{ElemType::tri3, ElemType::tri6, ElemType::quad4, ElemType::quad8, ElemType::quad9}
                                      : std::vector<ElemType>{ElemType::tet4, ElemType::tet10, ElemType::pyr5, ElemType::pyr13, ElemType::wedge6,
                                                              ElemType::wedge15, ElemType::hex8, ElemType::hex20, ElemType::hex27};
  m.groups = {{.name = "steel", .id = 3, .dim = shell ? 2 : 3}, {.name = "alu", .id = 7, .dim = shell ? 2 : 3}};
  std::int64_t next_node = 101;
  double x0 = 0;
  auto add_node = [&](Vec3 p) {
    m.nodes.push_back(p);
    m.node_ids.push_back(next_node);
    next_node += 3;
    return static_cast<std::uint32_t>(m.nodes.size() - 1);
  };
  for (std::size_t i = 0; i < types.size(); ++i) {
    const ElemType t = types[i];
    const ElemInfo& info = elem_info(t);
    std::vector<Vec3> c;
    switch (elem_info(t).corners) {
      case 3: c = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}; break;
      case 4: c = info.dim == 2 ? std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}} : std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; break;
      case 5: c = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}}; break;
      case 6: c = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}; break;
      case 8: c = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}; break;
    }
    std::vector<std::uint32_t> v;
    for (Vec3& p : c) {
      p.x += x0 + 0.1 * static_cast<double>(i) / 3.0;  // inexact decimal values
      v.push_back(add_node(p));
    }
    for (auto [a, b] : vtk_edges(t)) v.push_back(add_node((m.nodes[v[a]] + m.nodes[v[b]]) * 0.5));
    if (t == ElemType::hex27) {
      for (auto f : vtk_hex27_faces()) {
        Vec3 s{};
        for (int q : f) s += m.nodes[v[q]];
        v.push_back(add_node(s * 0.25));
      }
      Vec3 s{};
      for (int q = 0; q < 8; ++q) s += m.nodes[v[q]];
      v.push_back(add_node(s * 0.125));
    }
    if (t == ElemType::quad9) {
      Vec3 s{};
      for (int q = 0; q < 4; ++q) s += m.nodes[v[q]];
      v.push_back(add_node(s * 0.25));
    }
    EXPECT_EQ(static_cast<int>(v.size()), info.nodes) << info.name;
    m.add_element(t, 1000 + 7 * static_cast<std::int64_t>(i), static_cast<std::int32_t>(i % 2), v.data(), info.nodes);
    x0 += 2;
  }
  NodalSeries f{.name = "DISPL", .times = {0.0, 0.25}};
  for (int s = 0; s < 2; ++s) {
    std::vector<Vec3> vals;
    for (std::size_t k = 0; k < m.nodes.size(); ++k) vals.push_back(Vec3{0.001 * static_cast<double>(k), -1.0 / 3.0 * s, 1e-7 * s});
    f.values.push_back(vals);
  }
  m.fields.push_back(f);
  return m;
}

/// Bit-exact comparison (nodes, ids, types, node order, groups by name and id, fields).
inline void expect_same_mesh(const FemMesh& a, const FemMesh& b, bool groups = true, bool group_ids = true, bool fields = true) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.num_elements(), b.num_elements());
  EXPECT_EQ(a.node_ids, b.node_ids);
  for (std::size_t i = 0; i < a.num_nodes(); ++i) {
    ASSERT_EQ(0, std::memcmp(&a.nodes[i], &b.nodes[i], sizeof(Vec3))) << "node " << a.node_ids[i];
  }
  EXPECT_EQ(a.elem_ids, b.elem_ids);
  EXPECT_EQ(a.elem_types, b.elem_types);
  EXPECT_EQ(a.elem_offsets, b.elem_offsets);
  EXPECT_EQ(a.elem_nodes, b.elem_nodes);
  if (groups) {
    ASSERT_EQ(a.groups.size(), b.groups.size());
    for (std::size_t g = 0; g < a.groups.size(); ++g) {
      EXPECT_EQ(a.groups[g].name, b.groups[g].name);
      if (group_ids) EXPECT_EQ(a.groups[g].id, b.groups[g].id);
    }
    EXPECT_EQ(a.elem_groups, b.elem_groups);
  }
  if (fields) {
    ASSERT_EQ(a.fields.size(), b.fields.size());
    for (std::size_t f = 0; f < a.fields.size(); ++f) {
      EXPECT_EQ(a.fields[f].name, b.fields[f].name);
      EXPECT_EQ(a.fields[f].times, b.fields[f].times);
      ASSERT_EQ(a.fields[f].values.size(), b.fields[f].values.size());
      for (std::size_t s = 0; s < a.fields[f].values.size(); ++s) {
        EXPECT_TRUE(a.fields[f].values[s] == b.fields[f].values[s]) << a.fields[f].name << " step " << s;
      }
    }
  }
}

/// Reads `text` written to a file named `name`; expects an error whose message contains `what`
/// and that names the file and a line or byte.
inline ::testing::AssertionResult bad_input(const std::string& name, const std::string& text, const std::string& what, bool location = true) {
  const fs::path p = temp_dir() / name;
  write_text(p, text);
  Expected<FemMesh> m = read_fem(p);
  if (m) return ::testing::AssertionFailure() << name << ": read succeeded, expected '" << what << "'";
  const Error& e = m.error();
  if (e.file != p.string()) return ::testing::AssertionFailure() << "error file '" << e.file << "'";
  if (e.reason.find(what) == std::string::npos) return ::testing::AssertionFailure() << name << ": " << e.message() << " (expected '" << what << "')";
  if (location && e.line < 0 && e.byte < 0) return ::testing::AssertionFailure() << name << ": no line or byte: " << e.message();
  return ::testing::AssertionSuccess() << e.message();
}

}  // namespace interfere::fem_test
