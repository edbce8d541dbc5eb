// Extended checks on the public models in ../shared/data (skipped cleanly when that folder is absent):
// readers and validation against the counts published in shared/data/SOURCES.md, and the clash of
// each model against a rotated and a translated copy of itself against CGAL's exact do_intersect
// (degenerate triangles as CGAL segments or points).
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <type_traits>
#include <variant>

#include "interfere/core/predicates.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/clash.h"

namespace interfere {
namespace {

std::filesystem::path shared_mesh_dir() {
  return std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "mesh";
}

struct Published {
  const char* file;
  std::size_t welded_vertices, triangles, open_edges, nonmanifold_edges;
};

// From shared/data/SOURCES.md (V welded, triangles, boundary / non-manifold edges).
constexpr Published kPublished[] = {
    {"armadillo_closed_odedstein.obj", 14587, 29170, 0, 0},
    {"bunny_closed_odedstein.obj", 3301, 6598, 0, 0},
    {"fandisk.obj", 6475, 12946, 0, 0},
    {"fcl_env.obj", 2072, 2180, 1856, 0},
    {"fcl_rob.obj", 141, 216, 96, 27},
    {"gmsh_lever.stl", 377, 774, 0, 0},
    {"gmsh_netgen_hinge.stl", 598, 1212, 0, 0},
    {"rocker_arm.obj", 10044, 20088, 0, 0},
    {"teapot_newell.obj", 3241, 6320, 160, 0},
    {"trimesh_1002_tray_bottom.STL", 2216, 4520, 0, 0},
    {"trimesh_angle_block.STL", 398, 704, 166, 0},
    {"trimesh_featuretype.STL", 2010, 3476, 576, 0},
    {"trimesh_plate_holes.STL", 618, 1252, 0, 0},
    {"vtkdata_gears.stl", 9723, 19426, 0, 0},
    {"wingnut_odedstein.obj", 3047, 6090, 0, 0},
};

TEST(SharedData, ReadersAndValidationMatchPublishedCounts) {
  if (!std::filesystem::is_directory(shared_mesh_dir())) GTEST_SKIP() << "../shared/data not present";
  for (const Published& p : kPublished) {
    const auto path = shared_mesh_dir() / p.file;
    auto mesh = read_mesh(path);
    ASSERT_TRUE(mesh) << mesh.error().message();
    const MeshStats s = mesh_stats(*mesh);
    EXPECT_EQ(s.vertices, p.welded_vertices) << p.file;
    EXPECT_EQ(s.triangles, p.triangles) << p.file;
    EXPECT_EQ(s.open_edges, p.open_edges) << p.file;
    EXPECT_EQ(s.nonmanifold_edges, p.nonmanifold_edges) << p.file;
  }
}

using K = CGAL::Exact_predicates_exact_constructions_kernel;

// A triangle as CGAL sees it: a triangle, or, when degenerate (collinear corners), the segment
// between its two farthest corners, or a point. Degenerate triangles are tested as such by the
// engine too (they used to be left out of both sides of the comparison: issue #23, item 14).
using Simplex = std::variant<K::Triangle_3, K::Segment_3, K::Point_3>;

Simplex cgal_simplex(const TriMesh& m, std::uint32_t i) {
  const auto c = m.corners(i);
  const K::Point_3 p[3] = {{c[0].x, c[0].y, c[0].z}, {c[1].x, c[1].y, c[1].z}, {c[2].x, c[2].y, c[2].z}};
  if (!CGAL::collinear(p[0], p[1], p[2])) return K::Triangle_3(p[0], p[1], p[2]);
  if (p[0] == p[1] && p[1] == p[2]) return p[0];
  int u = 0, v = 1;  // the farthest pair (exact squared distances)
  for (const auto [i0, i1] : {std::pair{0, 2}, std::pair{1, 2}})
    if (CGAL::squared_distance(p[i0], p[i1]) > CGAL::squared_distance(p[u], p[v])) u = i0, v = i1;
  return K::Segment_3(p[u], p[v]);
}

bool meets(const Simplex& x, const Simplex& y) {
  return std::visit(
      [](const auto& s, const auto& t) {
        using S = std::decay_t<decltype(s)>;
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<S, K::Point_3> && std::is_same_v<T, K::Point_3>) return s == t;
        else if constexpr (std::is_same_v<S, K::Point_3>) return t.has_on(s);
        else if constexpr (std::is_same_v<T, K::Point_3>) return s.has_on(t);
        else return static_cast<bool>(CGAL::do_intersect(s, t));
      },
      x, y);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> cgal_pairs(const TriMesh& a, const TriMesh& b) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
  auto boxes = [](const TriMesh& m) {
    std::vector<Box> out;
    for (std::uint32_t i = 0; i < m.num_triangles(); ++i) {
      // CGAL's boxes (enclosing), not the library's Aabb that the engine's broad phase uses.
      const auto c = m.corners(i);
      CGAL::Bbox_3 b;
      for (const Vec3& v : c) b += K::Point_3(v.x, v.y, v.z).bbox();
      double lo[3] = {b.xmin(), b.ymin(), b.zmin()}, hi[3] = {b.xmax(), b.ymax(), b.zmax()};
      out.emplace_back(lo, hi, i);
    }
    return out;
  };
  std::vector<Box> ba = boxes(a), bb = boxes(b);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  CGAL::box_intersection_d(ba.begin(), ba.end(), bb.begin(), bb.end(), [&](const Box& x, const Box& y) {
    if (meets(cgal_simplex(a, x.info()), cgal_simplex(b, y.info()))) out.emplace_back(x.info(), y.info());
  });  // default topology: CLOSED boxes, so touching boxes are reported
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SharedData, SelfCopiesMatchCgal) {
  if (!std::filesystem::is_directory(shared_mesh_dir())) GTEST_SKIP() << "../shared/data not present";
  for (const char* file : {"gmsh_lever.stl", "trimesh_plate_holes.STL", "fcl_rob.obj", "bunny_closed_odedstein.obj"}) {
    auto mesh = read_mesh(shared_mesh_dir() / file);
    ASSERT_TRUE(mesh) << mesh.error().message();
    const Aabb box = mesh->bounds();
    Transform quarter;  // a quarter turn about z through the box centre: exact in double
    quarter.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
    const Vec3 c = box.center();
    quarter.t = {c.x + c.y, c.y - c.x, 0};
    const Transform shift{.t = {box.extent().x * 0.25, 0, 0}};
    for (const Transform& t : {quarter, shift, Transform{}}) {
      const TriMesh b = transformed(*mesh, t);
      const ClashResult r = clash(make_model(*mesh), make_model(b));
      std::vector<std::pair<std::uint32_t, std::uint32_t>> ours;
      for (const TrianglePair& p : r.pairs) ours.emplace_back(p.a, p.b);
      const auto theirs = cgal_pairs(*mesh, b);
      EXPECT_FALSE(theirs.empty()) << file;  // every pose overlaps the original
      EXPECT_EQ(ours, theirs) << file;
    }
  }
}

}  // namespace
}  // namespace interfere
