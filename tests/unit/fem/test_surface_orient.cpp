// Issue #23, items 1 and 2: every extracted FEM body is a closed, consistently outward surface
// whose enclosed volume equals the volume of its elements, on warped hexes whose opposite-corner
// votes tie, on mixed linear/quadratic bodies, on every generated mesh, on the committed test files
// and on every shared FEM file (when present).
//
// The oracle is independent of the surface code: the bodies are found here (groups, or a union-find
// over corner nodes), and each element's volume is the volume of the polyhedron bounded by its own
// faces (cones from its centroid over every face, faces triangulated as docs/fem.md documents:
// shorter diagonal, mid-side subdivision), summed over the body's elements. Interior faces cancel
// between the two elements sharing them, so the sum is the body's volume whatever the orientation
// and face matching of the extraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "interfere/fem/generate.h"
#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"
#include "interfere/mesh/validate.h"

namespace interfere {
namespace {

namespace fs = std::filesystem;

// Faces of the volume types (corner lists, any consistent orientation per element), from the
// Abaqus face numbering in docs/fem.md.
struct Face {
  int n;
  std::array<int, 4> c;
};
std::vector<Face> faces_of(ElemType t) {
  switch (t) {
    case ElemType::tet4:
    case ElemType::tet10:
      return {{3, {0, 1, 2}}, {3, {0, 3, 1}}, {3, {1, 3, 2}}, {3, {2, 3, 0}}};
    case ElemType::pyr5:
    case ElemType::pyr13:
      return {{4, {0, 1, 2, 3}}, {3, {0, 4, 1}}, {3, {1, 4, 2}}, {3, {2, 4, 3}}, {3, {3, 4, 0}}};
    case ElemType::wedge6:
    case ElemType::wedge15:
      return {
          {3, {0, 1, 2}}, {3, {3, 5, 4}}, {4, {0, 3, 4, 1}}, {4, {1, 4, 5, 2}}, {4, {2, 5, 3, 0}}};
    case ElemType::hex8:
    case ElemType::hex20:
    case ElemType::hex27:
      return {{4, {0, 1, 2, 3}}, {4, {4, 7, 6, 5}}, {4, {0, 4, 5, 1}},
              {4, {1, 5, 6, 2}}, {4, {2, 6, 7, 3}}, {4, {3, 7, 4, 0}}};
    default:
      return {};
  }
}

// Mid-edge node (local index) of each corner pair, from the node orders of fem_mesh.h.
std::map<std::pair<int, int>, int> mid_nodes(ElemType t) {
  std::vector<std::pair<int, int>> edges;
  int first = 0;
  switch (t) {
    case ElemType::tet10:
      edges = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}, first = 4;
      break;
    case ElemType::pyr13:
      edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}}, first = 5;
      break;
    case ElemType::wedge15:
      edges = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}}, first = 6;
      break;
    case ElemType::hex20:
    case ElemType::hex27:
      edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
               {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      first = 8;
      break;
    default:
      break;
  }
  std::map<std::pair<int, int>, int> m;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    m[{std::min(edges[i].first, edges[i].second), std::max(edges[i].first, edges[i].second)}] =
        first + static_cast<int>(i);
  }
  return m;
}

// hex27 face-centre node of a face (by its sorted corners).
int hex27_centre(std::array<int, 4> c) {
  std::sort(c.begin(), c.end());
  const std::array<std::array<int, 4>, 6> centres{
      {{0, 3, 4, 7}, {1, 2, 5, 6}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};
  for (int i = 0; i < 6; ++i) {
    if (centres[i] == c) return 20 + i;
  }
  return -1;
}

using Tri3 = std::array<std::uint32_t, 3>;

// Quad (a, b, c, d) (cyclic, node indices) split along the shorter diagonal, the one through the
// smaller node index on a tie.
void split_quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                const FemMesh& m, std::vector<Tri3>& out) {
  auto d2 = [&](std::uint32_t i, std::uint32_t j) {
    const Vec3 u = m.nodes[i] - m.nodes[j];
    return dot(u, u);
  };
  const double ac = d2(a, c), bd = d2(b, d);
  if (ac < bd || (ac == bd && std::min(a, c) < std::min(b, d))) {
    out.push_back({a, b, c}), out.push_back({a, c, d});
  } else {
    out.push_back({b, c, d}), out.push_back({b, d, a});
  }
}

// Volume of element e as the polyhedron of its triangulated faces (cones from the centroid).
double element_volume(const FemMesh& m, std::size_t e, bool subdivide) {
  const ElemType t = m.elem_types[e];
  const std::uint32_t* v = m.element_nodes(e);
  const int corners = elem_info(t).corners;
  Vec3 o{0, 0, 0};
  for (int i = 0; i < corners; ++i) o = o + m.nodes[v[i]];
  o = o * (1.0 / corners);
  const auto mids = mid_nodes(t);
  const bool quadratic = subdivide && !mids.empty();
  std::vector<Tri3> tris;
  for (const Face& f : faces_of(t)) {
    std::array<std::uint32_t, 4> c{}, md{};
    for (int i = 0; i < f.n; ++i) {
      c[i] = v[f.c[i]];
      if (quadratic) {
        const int a = f.c[i], b = f.c[(i + 1) % f.n];
        md[i] = v[mids.at({std::min(a, b), std::max(a, b)})];
      }
    }
    if (!quadratic) {
      if (f.n == 3)
        tris.push_back({c[0], c[1], c[2]});
      else
        split_quad(c[0], c[1], c[2], c[3], m, tris);
    } else if (f.n == 3) {
      tris.push_back({c[0], md[0], md[2]}), tris.push_back({md[0], c[1], md[1]});
      tris.push_back({md[2], md[1], c[2]}), tris.push_back({md[0], md[1], md[2]});
    } else if (t == ElemType::hex27) {
      const std::uint32_t x = v[hex27_centre(f.c)];
      for (int i = 0; i < 4; ++i)
        tris.push_back({c[i], md[i], x}), tris.push_back({md[i], c[(i + 1) % 4], x});
    } else {
      for (int i = 0; i < 4; ++i) tris.push_back({c[i], md[i], md[(i + 3) % 4]});
      split_quad(md[0], md[1], md[2], md[3], m, tris);
    }
  }
  double s = 0;
  for (const Tri3& tr : tris) {
    const Vec3 a = m.nodes[tr[0]] - o, b = m.nodes[tr[1]] - o, c = m.nodes[tr[2]] - o;
    s += dot(a, cross(b, c));
  }
  return std::fabs(s) / 6.0;
}

double signed_volume(const TriMesh& m) {
  // Relative to the first vertex (smaller terms).
  if (m.positions.empty()) return 0;
  const Vec3 r = m.positions[0];
  double s = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    s += dot(c[0] - r, cross(c[1] - r, c[2] - r));
  }
  return s / 6.0;
}

// Body key of every element (the oracle's own part assignment, as docs/fem.md defines
// `automatic`): by group when some surface element has one, else connected by corner nodes.
std::vector<std::int64_t> body_keys(const FemMesh& m) {
  const std::size_t ne = m.num_elements();
  bool grouped = false;
  for (std::size_t e = 0; e < ne; ++e)
    grouped |= elem_info(m.elem_types[e]).dim >= 2 && m.elem_groups[e] >= 0;
  std::vector<std::int64_t> key(ne, -2);
  if (grouped) {
    for (std::size_t e = 0; e < ne; ++e) key[e] = m.elem_groups[e];
    return key;
  }
  std::vector<std::uint32_t> parent(m.num_nodes());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t e = 0; e < ne; ++e) {
    const std::uint32_t* v = m.element_nodes(e);
    for (int i = 1; i < elem_info(m.elem_types[e]).corners; ++i) parent[find(v[i])] = find(v[0]);
  }
  for (std::size_t e = 0; e < ne; ++e) key[e] = find(m.element_nodes(e)[0]);
  return key;
}

// The check of items 1 and 2: every body with volume elements is closed, consistently oriented,
// and its signed volume (positive: outward) equals its elements' volume to 1e-9.
void expect_bodies_closed_outward(const FemMesh& m, const SurfaceOptions& options,
                                  const std::string& what) {
  SCOPED_TRACE(what);
  auto r = extract_surface(m, options);
  ASSERT_TRUE(r) << r.error().message();
  std::vector<std::int64_t> key = body_keys(m);
  if (options.split == PartSplit::single) std::fill(key.begin(), key.end(), 0);
  std::map<std::int64_t, double> volume;
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    if (elem_info(m.elem_types[e]).dim == 3)
      volume[key[e]] += element_volume(m, e, options.subdivide_quadratic);
  }
  std::size_t checked = 0;
  for (const SurfacePart& p : r->parts) {
    SCOPED_TRACE("body '" + p.name + "'");
    if (p.volume_elements == 0) continue;  // shells only: no solid
    ASSERT_GT(p.mesh.num_triangles(), 0u);
    const std::int64_t k = key[p.tri_element[0]];
    for (std::uint32_t e : p.tri_element) ASSERT_EQ(key[e], k) << "a triangle of another body";
    const MeshStats s = mesh_stats(p.mesh);
    EXPECT_TRUE(s.closed()) << s.open_edges << " open, " << s.nonmanifold_edges << " non-manifold, "
                            << s.inconsistent_edges << " inconsistent edges";
    EXPECT_EQ(p.open_components, 0u);
    EXPECT_EQ(p.nonorientable_components, 0u);
    const double expected = volume.at(k);
    EXPECT_NEAR(signed_volume(p.mesh), expected, 1e-9 * expected);
    EXPECT_NEAR(p.enclosed_volume, expected, 1e-9 * expected);
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

// Two hexahedra (integer corners, positive Jacobian at every corner) whose face S1 resp. S2 is so
// warped that the opposite-corner vote of extract_surface ties (4 corners on each side of its two
// triangles' planes): the faces the can file has 22 of.
constexpr int kTiedHexes[2][8][3] = {
    {{-167, 284, -91},
     {770, -194, -95},
     {854, 1034, 295},
     {110, 746, -183},
     {204, -230, 193},
     {741, 221, 93},
     {803, 1218, 333},
     {56, 1209, 44}},
    {{-280, 43, -6},
     {1023, 152, 109},
     {1207, 777, 175},
     {-19, 1207, -56},
     {-133, -194, 47},
     {749, -233, 478},
     {849, 1198, 342},
     {22, 1182, 468}},
};

FemMesh tied_hexes(int copies) {
  FemMesh m;
  for (int k = 0; k < copies; ++k) {
    const int(&h)[8][3] = kTiedHexes[k % 2];
    std::uint32_t v[8];
    for (int i = 0; i < 8; ++i) {
      v[i] = static_cast<std::uint32_t>(m.nodes.size());
      m.nodes.push_back(
          {h[i][0] + 3000.0 * k, static_cast<double>(h[i][1]), static_cast<double>(h[i][2])});
      m.node_ids.push_back(static_cast<std::int64_t>(m.nodes.size()));
    }
    m.add_element(ElemType::hex8, k + 1, -1, v, 8);
  }
  return m;
}

TEST(FemSurfaceOrient, TiedVotesOnWarpedHexesGiveClosedOutwardBodies) {
  const FemMesh m = tied_hexes(4);
  ASSERT_TRUE(validate_fem_mesh(m));
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->tied_faces, 4u);  // the setup: every hex has one tied face
  EXPECT_EQ(r->parts.size(), 4u);
  expect_bodies_closed_outward(m, {}, "tied hexes");
  // One part of four components: each is oriented on its own.
  expect_bodies_closed_outward(m, {.split = PartSplit::single}, "tied hexes, one part");
  // Inverted node order (negative Jacobian everywhere): the same surfaces, outward all the same.
  FemMesh inv = m;
  for (std::size_t e = 0; e < inv.num_elements(); ++e) {
    std::uint32_t* v = inv.elem_nodes.data() + inv.elem_offsets[e];
    for (int i = 0; i < 4; ++i) std::swap(v[i], v[i + 4]);
  }
  expect_bodies_closed_outward(inv, {}, "inverted tied hexes");
}

const ElemType kTypes[] = {ElemType::tet4,  ElemType::tet10,  ElemType::hex8,    ElemType::hex20,
                           ElemType::hex27, ElemType::wedge6, ElemType::wedge15, ElemType::pyr5};

TEST(FemSurfaceOrient, EveryGeneratedMeshIsClosedOutwardWithTheElementsVolume) {
  for (ElemType type : kTypes) {
    for (bool subdivide : {true, false}) {
      const std::string name = std::string(elem_info(type).name) + (subdivide ? "" : " corners");
      const FemBoxOptions o{
          .type = type, .nx = 3, .ny = 2, .nz = 2, .lo = {-1, 0, 2}, .hi = {2, 1.5, 3}};
      const SurfaceOptions so{.subdivide_quadratic = subdivide};
      expect_bodies_closed_outward(make_fem_box(o).mesh, so, "box " + name);
      expect_bodies_closed_outward(make_fem_cylinder(o, 2.0, 3.0, {1, 2, 3}).mesh, so,
                                   "cylinder " + name);
      expect_bodies_closed_outward(make_fem_sphere(o, 1.5, {-1, 0, 1}).mesh, so, "sphere " + name);
      if (type == ElemType::tet4 || type == ElemType::tet10) {
        FemBoxOptions o5 = o;
        o5.tets_per_cell = 5;
        expect_bodies_closed_outward(make_fem_sphere(o5, 1.5).mesh, so,
                                     "sphere 5 tets/cell " + name);
      }
    }
  }
}

// A body of quadratic elements with every other element demoted to its linear type (mid-side
// nodes dropped; they stay on the straight edges, so the linear faces are flat through them).
FemMesh demote_every_other(const FemMesh& q, ElemType linear) {
  FemMesh m;
  m.nodes = q.nodes;
  m.node_ids = q.node_ids;
  for (std::size_t e = 0; e < q.num_elements(); ++e) {
    const bool demote = e % 2 == 1;
    const ElemType t = demote ? linear : q.elem_types[e];
    m.add_element(t, q.elem_ids[e], -1, q.element_nodes(e), elem_info(t).nodes);
  }
  return m;
}

TEST(FemSurfaceOrient, MixedLinearAndQuadraticBodiesAreClosed) {
  const std::pair<ElemType, ElemType> pairs[] = {{ElemType::tet10, ElemType::tet4},
                                                 {ElemType::hex20, ElemType::hex8},
                                                 {ElemType::wedge15, ElemType::wedge6}};
  for (const auto& [quadratic, linear] : pairs) {
    const GeneratedFem g = make_fem_box(
        {.type = quadratic, .nx = 3, .ny = 3, .nz = 2, .lo = {0, 0, 0}, .hi = {3, 2, 1}});
    const FemMesh m = demote_every_other(g.mesh, linear);
    ASSERT_TRUE(validate_fem_mesh(m));
    const std::string name =
        std::string(elem_info(quadratic).name) + " + " + elem_info(linear).name;
    expect_bodies_closed_outward(m, {}, name);
    expect_bodies_closed_outward(m, {.subdivide_quadratic = false}, name + " corners");
    auto r = extract_surface(m);
    ASSERT_TRUE(r);
    EXPECT_GT(r->split_faces, 0u) << name;
    const double v = signed_volume(r->parts[0].mesh);
    EXPECT_NEAR(v, g.volume, 1e-12 * g.volume)
        << name;  // the box's volume exactly (straight edges)
  }
}

TEST(FemSurfaceOrient, DegenerateFacesAndFlatBodiesAreReported) {
  // A flat tet (coplanar corners, three of them collinear): a closed surface enclosing nothing.
  FemMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  m.node_ids = {1, 2, 3, 4};
  const std::uint32_t v[4] = {0, 1, 2, 3};
  m.add_element(ElemType::tet4, 1, -1, v, 4);
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->parts.size(), 1u);
  EXPECT_EQ(r->degenerate_faces, 1u);  // face (0,1,2) has zero area
  EXPECT_EQ(r->parts[0].degenerate_components, 1u);
  EXPECT_EQ(r->parts[0].enclosed_volume, 0.0);
}

std::vector<fs::path> fem_files(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* e : {".msh", ".bdf", ".nas", ".dat", ".vtk", ".vtu", ".inp"}) {
      if (ext == e) out.push_back(entry.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void expect_files_closed_outward(const std::vector<fs::path>& files) {
  for (const fs::path& f : files) {
    // *INCLUDE fragments (no elements), and small_field.bdf: a tet glued on half of a hex's quad
    // face (non-conforming by design: the reader test of continuations and INCLUDE).
    const std::string name = f.filename().string();
    if (name == "hex20_nodes.inp" || name == "small_field_top.bdf" || name == "small_field.bdf")
      continue;
    auto m = read_fem(f);
    ASSERT_TRUE(m) << m.error().message();
    bool volumes = false;
    for (ElemType t : m->elem_types) volumes |= elem_info(t).dim == 3;
    if (!volumes) continue;  // shell models have no solid to close
    for (bool subdivide : {true, false}) {
      expect_bodies_closed_outward(*m, {.subdivide_quadratic = subdivide},
                                   f.filename().string() + (subdivide ? "" : " corners"));
    }
  }
}

TEST(FemSurfaceOrient, CommittedTestFilesAreClosedOutward) {
  const auto files = fem_files(fs::path(INTERFERE_SOURCE_DIR) / "tests" / "data" / "fem");
  ASSERT_FALSE(files.empty());
  expect_files_closed_outward(files);
}

TEST(FemSurfaceOrient, EverySharedFemFileIsClosedOutward) {
  fs::path dir = fs::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "fem";
  if (const char* env = std::getenv("INTERFERE_SHARED_DATA"); env && *env)
    dir = fs::path(env) / "fem";
  const auto files = fem_files(dir);
  if (files.empty()) GTEST_SKIP() << dir << " not present";
  expect_files_closed_outward(files);
}

}  // namespace
}  // namespace interfere
