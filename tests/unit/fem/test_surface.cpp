// Boundary surface extraction (fem/surface.h) on generated meshes of every element type: closed,
// outward (signed volume = volume of the elements, computed here independently by a tet
// decomposition), area = analytic area, identical for 1 and 2 threads, triangles name their face.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>

#include "interfere/core/predicates.h"
#include "interfere/fem/deform.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"
#include "interfere/mesh/validate.h"

namespace interfere {
namespace {

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(b - a, cross(c - a, d - a)) / 6.0;
}

// Volume of the elements by a decomposition into tets of their corners (exact for elements with
// planar faces; for curved ones it is the volume of the straight-sided element).
double element_volume(const FemMesh& m, std::size_t e) {
  const std::uint32_t* v = m.element_nodes(e);
  auto p = [&](int i) { return m.nodes[v[i]]; };
  auto t = [&](int a, int b, int c, int d) { return std::fabs(tet_volume(p(a), p(b), p(c), p(d))); };
  switch (m.elem_types[e]) {
    case ElemType::tet4:
    case ElemType::tet10: return t(0, 1, 2, 3);
    case ElemType::pyr5:
    case ElemType::pyr13: return t(0, 1, 2, 4) + t(0, 2, 3, 4);
    case ElemType::wedge6:
    case ElemType::wedge15: return t(0, 1, 2, 3) + t(1, 2, 3, 4) + t(2, 3, 4, 5);
    case ElemType::hex8:
    case ElemType::hex20:
    case ElemType::hex27:
      return t(0, 1, 2, 6) + t(0, 2, 3, 6) + t(0, 3, 7, 6) + t(0, 7, 4, 6) + t(0, 4, 5, 6) + t(0, 5, 1, 6);
    default: return 0;
  }
}

double mesh_volume(const FemMesh& m) {
  double s = 0;
  for (std::size_t e = 0; e < m.num_elements(); ++e) s += element_volume(m, e);
  return s;
}

double signed_volume(const TriMesh& m) {
  double s = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    s += dot(c[0], cross(c[1], c[2])) / 6.0;
  }
  return s;
}

double area(const TriMesh& m) {
  double s = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    s += norm(cross(c[1] - c[0], c[2] - c[0])) / 2.0;
  }
  return s;
}

const ElemType kVolumeTypes[] = {ElemType::tet4,   ElemType::tet10,   ElemType::hex8,
                                 ElemType::hex20,  ElemType::hex27,   ElemType::wedge6,
                                 ElemType::wedge15, ElemType::pyr5};

// Every triangle's corners are nodes of the element face it names, and every face's triangles
// together have the face's area sign convention (outward checked by the volume).
void expect_faces_named(const SurfacePart& p, const FemMesh& m) {
  ASSERT_EQ(p.tri_element.size(), p.mesh.num_triangles());
  ASSERT_EQ(p.tri_face.size(), p.mesh.num_triangles());
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {
    const std::vector<std::uint32_t> nodes = element_face_nodes(m, p.tri_element[t], p.tri_face[t]);
    for (std::uint32_t v : p.mesh.triangles[t]) {
      ASSERT_NE(std::find(nodes.begin(), nodes.end(), p.vertex_node[v]), nodes.end())
          << "triangle " << t << " element " << p.tri_element[t] << " face " << int(p.tri_face[t]);
    }
  }
  for (std::size_t i = 0; i < p.vertex_node.size(); ++i) EXPECT_EQ(p.mesh.positions[i], m.nodes[p.vertex_node[i]]);
}

TEST(FemSurface, BoxOfEveryElementTypeIsClosedOutwardWithExactArea) {
  for (ElemType type : kVolumeTypes) {
    for (bool subdivide : {true, false}) {
      for (int tets : {6, 5}) {
        if (tets == 5 && type != ElemType::tet4 && type != ElemType::tet10) continue;
        SCOPED_TRACE(std::string(elem_info(type).name) + (subdivide ? " subdivided" : " corners") + " tets/cell " +
                     std::to_string(tets));
        const GeneratedFem g = make_fem_box(
            {.type = type, .nx = 3, .ny = 4, .nz = 2, .lo = {-1, 0.5, 2}, .hi = {2, 3, 4.5}, .tets_per_cell = tets});
        ASSERT_TRUE(validate_fem_mesh(g.mesh));
        auto r = extract_surface(g.mesh, {.subdivide_quadratic = subdivide});
        ASSERT_TRUE(r) << r.error().message();
        ASSERT_EQ(r->parts.size(), 1u);
        const SurfacePart& p = r->parts[0];
        const MeshStats s = mesh_stats(p.mesh);
        EXPECT_TRUE(s.closed()) << "open " << s.open_edges << " nonmanifold " << s.nonmanifold_edges
                                << " inconsistent " << s.inconsistent_edges;
        EXPECT_EQ(s.components, 1u);
        EXPECT_EQ(s.degenerate_triangles, 0u);
        EXPECT_EQ(r->nonmanifold_faces, 0u);
        EXPECT_EQ(r->inverted_faces, 0u);
        EXPECT_EQ(r->degenerate_faces, 0u);
        const double vol = mesh_volume(g.mesh);
        EXPECT_NEAR(vol, g.volume, 1e-12 * g.volume);
        EXPECT_NEAR(signed_volume(p.mesh), vol, 1e-9 * vol);
        EXPECT_NEAR(area(p.mesh), g.area, 1e-12 * g.area);
        // boundary faces: cell faces on the box surface, split as the element type splits them
        const int cell_faces = 2 * (3 * 4 + 4 * 2 + 2 * 3);
        std::size_t expected = cell_faces;  // hexes, pyramids: one face per cell face
        if (type == ElemType::tet4 || type == ElemType::tet10) expected = 2 * cell_faces;
        if (type == ElemType::wedge6 || type == ElemType::wedge15) expected = cell_faces + 2 * 3 * 4;  // xy faces halved
        EXPECT_EQ(r->boundary_faces, expected);
        expect_faces_named(p, g.mesh);
        EXPECT_EQ(p.volume_elements, g.mesh.num_elements());
      }
    }
  }
}

TEST(FemSurface, QuadraticFacesAreSubdividedThroughTheirMidNodes) {
  // One element of each quadratic type: the counts of triangles per face follow surface.h.
  struct Case {
    ElemType type;
    std::size_t subdivided, corners;
  };
  for (const Case& c : {Case{ElemType::tet10, 4 * 4, 4}, Case{ElemType::hex20, 6 * 6, 12},
                        Case{ElemType::hex27, 6 * 8, 12}, Case{ElemType::wedge15, 4 * 4 + 4 * 6, 4 + 4 * 2}}) {
    const GeneratedFem g = make_fem_box({.type = c.type, .nx = 1, .ny = 1, .nz = 1, .tets_per_cell = 5});
    // tet10 with 5 per cell: take one element only
    FemMesh one = g.mesh;
    if (c.type == ElemType::tet10) {
      one.elem_types.resize(1), one.elem_ids.resize(1), one.elem_groups.resize(1), one.elem_offsets.resize(2);
      one.elem_nodes.resize(10);
    }
    auto sub = extract_surface(one, {.subdivide_quadratic = true});
    auto lin = extract_surface(one, {.subdivide_quadratic = false});
    ASSERT_TRUE(sub && lin);
    std::size_t nsub = 0, nlin = 0;
    for (const auto& p : sub->parts) nsub += p.mesh.num_triangles();
    for (const auto& p : lin->parts) nlin += p.mesh.num_triangles();
    // (the cell of wedge15 is 2 wedges: 4 triangle faces and 4 quads on its boundary)
    EXPECT_EQ(nsub, c.subdivided) << elem_info(c.type).name;
    EXPECT_EQ(nlin, c.corners) << elem_info(c.type).name;
  }
}

TEST(FemSurface, MappedCylinderAndSphereAreClosedWithAnalyticAreaWithinDiscretisationError) {
  for (ElemType type : kVolumeTypes) {
    for (int shape = 0; shape < 2; ++shape) {
      SCOPED_TRACE(std::string(elem_info(type).name) + (shape ? " sphere" : " cylinder"));
      const FemBoxOptions o{.type = type, .nx = 8, .ny = 8, .nz = 8};
      const GeneratedFem g = shape ? make_fem_sphere(o, 2.0, {1, 2, 3}) : make_fem_cylinder(o, 1.5, 3.0, {1, -1, 0});
      auto r = extract_surface(g.mesh);
      ASSERT_TRUE(r) << r.error().message();
      ASSERT_EQ(r->parts.size(), 1u);
      const TriMesh& m = r->parts[0].mesh;
      const MeshStats s = mesh_stats(m);
      EXPECT_TRUE(s.closed());
      EXPECT_EQ(s.components, 1u);
      EXPECT_EQ(r->inverted_faces, 0u);
      // Chordal error of a surface triangulated with edges h on curvature radius R: relative
      // volume/area error O((h/R)^2); h/R <= 0.3 here (8 cells over the diameter, doubled for
      // quadratic faces), so a few percent for straight faces, much less through mid-side nodes.
      const double vol = signed_volume(m);
      EXPECT_NEAR(vol, g.volume, 0.03 * g.volume);
      EXPECT_NEAR(area(m), g.area, 0.03 * g.area);
      if (type == ElemType::tet4) {
        const double elements = mesh_volume(g.mesh);  // linear tets: the surface encloses them exactly
        EXPECT_NEAR(vol, elements, 1e-9 * elements);
      }
      if (elem_info(type).order == 2) {  // through the mid-side nodes: closer to the smooth shape
        auto lin = extract_surface(g.mesh, {.subdivide_quadratic = false});
        ASSERT_TRUE(lin);
        EXPECT_LT(std::fabs(vol - g.volume), std::fabs(signed_volume(lin->parts[0].mesh) - g.volume));
      }
    }
  }
}

TEST(FemSurface, OneAndTwoThreadsAndSequentialGiveIdenticalSurfaces) {
  const GeneratedFem g = make_fem_sphere({.type = ElemType::tet10, .nx = 14, .ny = 14, .nz = 14}, 1.0);
  auto run = [&](int threads, bool parallel) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    auto r = extract_surface(g.mesh, {.parallel = parallel});
    EXPECT_TRUE(r);
    return std::move(*r);
  };
  const SurfaceResult a = run(1, true), b = run(2, true), c = run(2, false);
  for (const SurfaceResult* x : {&b, &c}) {
    ASSERT_EQ(x->parts.size(), a.parts.size());
    for (std::size_t p = 0; p < a.parts.size(); ++p) {
      EXPECT_EQ(x->parts[p].mesh.triangles, a.parts[p].mesh.triangles);
      EXPECT_EQ(x->parts[p].mesh.positions, a.parts[p].mesh.positions);
      EXPECT_EQ(x->parts[p].vertex_node, a.parts[p].vertex_node);
      EXPECT_EQ(x->parts[p].tri_element, a.parts[p].tri_element);
      EXPECT_EQ(x->parts[p].tri_face, a.parts[p].tri_face);
    }
    EXPECT_EQ(x->boundary_faces, a.boundary_faces);
    EXPECT_EQ(x->interior_faces, a.interior_faces);
  }
}

// Two boxes in one mesh: glued (sharing the nodes of the face x = 1) or apart.
FemMesh two_boxes(bool glued, bool groups) {
  FemMesh m = make_fem_box({.type = ElemType::hex8, .nx = 2, .ny = 2, .nz = 2}).mesh;
  const FemMesh b = make_fem_box({.type = ElemType::hex8, .nx = 2, .ny = 2, .nz = 2, .lo = {glued ? 1.0 : 3.0, 0, 0},
                                  .hi = {glued ? 2.0 : 4.0, 1, 1}})
                        .mesh;
  const std::size_t n0 = m.num_nodes(), e0 = m.num_elements();
  std::vector<std::uint32_t> index(b.num_nodes());
  for (std::size_t i = 0; i < b.num_nodes(); ++i) {
    index[i] = static_cast<std::uint32_t>(m.num_nodes());
    if (glued) {
      for (std::size_t j = 0; j < n0; ++j) {
        if (m.nodes[j] == b.nodes[i]) index[i] = static_cast<std::uint32_t>(j);
      }
    }
    if (index[i] == m.num_nodes()) {
      m.nodes.push_back(b.nodes[i]);
      m.node_ids.push_back(static_cast<std::int64_t>(1000 + i));
    }
  }
  if (groups) {
    m.groups = {{.name = "left", .id = 1}, {.name = "right", .id = 2}};
    for (auto& g : m.elem_groups) g = 0;
  }
  for (std::size_t e = 0; e < b.num_elements(); ++e) {
    std::vector<std::uint32_t> v;
    for (int k = 0; k < 8; ++k) v.push_back(index[b.element_nodes(e)[k]]);
    m.add_element(ElemType::hex8, static_cast<std::int64_t>(100 + e), groups ? 1 : -1, v.data(), 8);
  }
  EXPECT_EQ(m.num_elements(), e0 + b.num_elements());
  return m;
}

TEST(FemSurface, BodiesBecomePartsByGroupOrByConnectivity) {
  {
    const FemMesh m = two_boxes(false, false);
    ASSERT_TRUE(validate_fem_mesh(m));
    auto r = extract_surface(m);  // automatic: no groups -> connectivity
    ASSERT_TRUE(r);
    ASSERT_EQ(r->parts.size(), 2u);
    EXPECT_EQ(r->parts[0].name, "body 1");
    for (const auto& p : r->parts) {
      EXPECT_TRUE(mesh_stats(p.mesh).closed());
      EXPECT_NEAR(signed_volume(p.mesh), 1.0, 1e-12);
      EXPECT_EQ(p.volume_elements, 8u);
    }
    auto one = extract_surface(m, {.split = PartSplit::single});
    ASSERT_TRUE(one);
    ASSERT_EQ(one->parts.size(), 1u);
    EXPECT_EQ(mesh_stats(one->parts[0].mesh).components, 2u);
  }
  {
    const FemMesh m = two_boxes(true, true);
    ASSERT_TRUE(validate_fem_mesh(m));
    auto r = extract_surface(m);  // automatic: groups
    ASSERT_TRUE(r);
    ASSERT_EQ(r->parts.size(), 2u);
    EXPECT_EQ(r->parts[0].name, "left");
    EXPECT_EQ(r->parts[1].name, "right");
    EXPECT_EQ(r->parts[1].group, 1);
    for (const auto& p : r->parts) {  // the glued face is a boundary of both parts
      EXPECT_TRUE(mesh_stats(p.mesh).closed());
      EXPECT_NEAR(signed_volume(p.mesh), 1.0, 1e-12);
      EXPECT_NEAR(area(p.mesh), 6.0, 1e-12);
    }
    auto whole = extract_surface(m, {.split = PartSplit::connectivity});  // glued: one body
    ASSERT_TRUE(whole);
    ASSERT_EQ(whole->parts.size(), 1u);
    EXPECT_NEAR(signed_volume(whole->parts[0].mesh), 2.0, 1e-12);
    EXPECT_NEAR(area(whole->parts[0].mesh), 10.0, 1e-12);
  }
}

TEST(FemSurface, InvertedElementsAreOrientedOutwardByGeometry) {
  GeneratedFem g = make_fem_box({.type = ElemType::tet10, .nx = 2, .ny = 2, .nz = 2});
  FemMesh& m = g.mesh;
  std::size_t inverted = 0;
  for (std::size_t e = 0; e < m.num_elements(); e += 3) {  // swap corners 1,2 and their mid nodes
    std::uint32_t* v = m.elem_nodes.data() + m.elem_offsets[e];
    std::swap(v[1], v[2]);
    std::swap(v[4], v[6]);  // (0,1) <-> (2,0)
    std::swap(v[8], v[9]);  // (1,3) <-> (2,3)
    ++inverted;
  }
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  EXPECT_GT(r->inverted_faces, 0u);
  EXPECT_TRUE(mesh_stats(r->parts[0].mesh).closed());
  EXPECT_NEAR(signed_volume(r->parts[0].mesh), 1.0, 1e-12);
}

TEST(FemSurface, ShellsAreTakenAsTheyAre) {
  FemMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {0.5, 0, 0}, {1, 0.5, 0},
             {0.5, 1, 0}, {0, 0.5, 0}};
  for (std::size_t i = 0; i < m.nodes.size(); ++i) m.node_ids.push_back(static_cast<std::int64_t>(i + 1));
  const std::uint32_t q8[8] = {0, 1, 2, 3, 6, 7, 8, 9};
  const std::uint32_t t3[3] = {1, 4, 5};
  m.add_element(ElemType::quad8, 1, -1, q8, 8);
  m.add_element(ElemType::tri3, 2, -1, t3, 3);
  const std::uint32_t line[2] = {4, 5};
  m.add_element(ElemType::line2, 3, -1, line, 2);
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->parts.size(), 1u);
  const SurfacePart& p = r->parts[0];
  EXPECT_EQ(p.mesh.num_triangles(), 6u + 1u);
  EXPECT_EQ(r->skipped_elements, 1u);
  EXPECT_EQ(p.shell_elements, 2u);
  EXPECT_NEAR(area(p.mesh), 1.5, 1e-12);
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {  // the shells' own orientation (+z) kept
    const auto c = p.mesh.corners(t);
    EXPECT_GT(cross(c[1] - c[0], c[2] - c[0]).z, 0);
  }
  expect_faces_named(p, m);
}

TEST(FemSurface, ShellsOnVolumeFacesAreDroppedLikeGmshBoundaryElements) {
  // A hex box plus quad4 shells on its boundary faces (as Gmsh writes them) and one free shell.
  GeneratedFem g = make_fem_box({.type = ElemType::hex8, .nx = 2, .ny = 2, .nz = 2});
  FemMesh& m = g.mesh;
  auto solid = extract_surface(m);
  ASSERT_TRUE(solid);
  const std::size_t boundary_tris = solid->parts[0].mesh.num_triangles();
  std::size_t shells = 0;
  for (std::size_t e = 0, ne = m.num_elements(); e < ne; ++e) {
    for (int f = 1; f <= 6; ++f) {
      std::vector<std::uint32_t> q = element_face_nodes(m, e, f);
      bool on_boundary = false;
      for (std::size_t t = 0; t < solid->parts[0].mesh.num_triangles(); ++t) {
        on_boundary |= solid->parts[0].tri_element[t] == e && solid->parts[0].tri_face[t] == f;
      }
      if (!on_boundary) continue;
      m.add_element(ElemType::quad4, static_cast<std::int64_t>(1000 + shells++), -1, q.data(), 4);
    }
  }
  const std::uint32_t on_face[4] = {0, 1, 4, 3};  // the bottom face of cell (0,0,0) again
  m.add_element(ElemType::quad4, 5000, -1, on_face, 4);
  const auto n0 = static_cast<std::uint32_t>(m.num_nodes());  // a free shell touching the box at node 0
  m.nodes.insert(m.nodes.end(), {{-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}});
  m.node_ids.insert(m.node_ids.end(), {9001, 9002, 9003});
  const std::uint32_t free_quad[4] = {0, n0 + 2, n0 + 1, n0};
  m.add_element(ElemType::quad4, 5001, -1, free_quad, 4);
  EXPECT_EQ(shells, 24u);
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->parts.size(), 1u);  // connected through node 0
  EXPECT_EQ(r->dropped_shells, 25u);
  EXPECT_EQ(r->parts[0].mesh.num_triangles(), boundary_tris + 2);
  EXPECT_EQ(r->parts[0].shell_elements, 1u);
  auto kept = extract_surface(m, {.drop_boundary_shells = false});
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->parts[0].mesh.num_triangles(), boundary_tris + 2 * 26);
  EXPECT_EQ(kept->parts[0].shell_elements, 26u);
}

TEST(FemSurface, QuadsAreSplitAlongTheShorterDiagonal) {
  FemMesh m;
  m.nodes = {{0, 0, 0}, {3, 0, 0}, {1, 1, 0}, {0, 1, 0}};  // diagonal 1-3 is longer than 0-2
  m.node_ids = {1, 2, 3, 4};
  const std::uint32_t q[4] = {0, 1, 2, 3};
  m.add_element(ElemType::quad4, 1, -1, q, 4);
  auto r = extract_surface(m);
  ASSERT_TRUE(r);
  const SurfacePart& p = r->parts[0];
  ASSERT_EQ(p.mesh.num_triangles(), 2u);
  auto has_edge = [&](std::uint32_t a, std::uint32_t b) {
    int n = 0;
    for (const Tri& t : p.mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t x = p.vertex_node[t[k]], y = p.vertex_node[t[(k + 1) % 3]];
        n += (x == a && y == b) || (x == b && y == a);
      }
    }
    return n;
  };
  EXPECT_EQ(has_edge(0, 2), 2);
  EXPECT_EQ(has_edge(1, 3), 0);
}

TEST(FemSurface, BadNodeIndexIsAnErrorNamingTheElement) {
  GeneratedFem g = make_fem_box({.type = ElemType::hex8, .nx = 2, .ny = 1, .nz = 1, .first_element_id = 41});
  g.mesh.elem_nodes[8 + 3] = 999;
  g.mesh.file = "bad.msh";
  auto r = extract_surface(g.mesh);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, "bad.msh");
  EXPECT_NE(r.error().reason.find("element 42"), std::string::npos) << r.error().reason;
}

}  // namespace
}  // namespace interfere
